//! An array of samples shared by parallel workers that touch disjoint samples.

/// Samples that several workers use at once, each writing samples no other worker touches
/// and reading only samples that nobody writes meanwhile. The caller states why its access
/// pattern is so where it makes one (`SAFETY` at the use); the type checks the bounds.
#[derive(Clone, Copy)]
pub(crate) struct SharedSamples {
    ptr: *mut f64,
    len: usize,
}

// SAFETY: the workers touch disjoint samples, except those that all only read (the type's
// contract, stated at each use); the pointer outlives them, as the slice it was taken from
// stays borrowed for the parallel section.
unsafe impl Send for SharedSamples {}
unsafe impl Sync for SharedSamples {}

impl SharedSamples {
    pub(crate) fn of(samples: &mut [f64]) -> Self {
        SharedSamples {
            ptr: samples.as_mut_ptr(),
            len: samples.len(),
        }
    }

    #[inline]
    pub(crate) fn read(self, index: usize) -> f64 {
        assert!(index < self.len, "a sample inside the array");
        // SAFETY: in bounds (checked); no worker writes a sample that another reads.
        unsafe { *self.ptr.add(index) }
    }

    #[inline]
    pub(crate) fn write(self, index: usize, value: f64) {
        assert!(index < self.len, "a sample inside the array");
        // SAFETY: in bounds (checked); each sample is written by one worker only.
        unsafe { *self.ptr.add(index) = value }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;

    /// Workers that each write their own samples from samples nobody writes leave what a
    /// serial loop leaves.
    #[test]
    fn disjoint_workers_write_what_a_serial_loop_writes() {
        let mut data: Vec<f64> = (0..10_000).map(|i| i as f64).collect();
        let shared = SharedSamples::of(&mut data);
        // odd samples from the even ones before them, in parallel chunks
        (0..5_000).into_par_iter().with_min_len(64).for_each(|k| {
            shared.write(2 * k + 1, 3.0 * shared.read(2 * k));
        });
        for k in 0..5_000 {
            assert_eq!(data[2 * k], (2 * k) as f64);
            assert_eq!(data[2 * k + 1], 6.0 * k as f64);
        }
    }

    #[test]
    #[should_panic(expected = "a sample inside the array")]
    fn an_index_past_the_end_panics() {
        let mut data = vec![0.0; 4];
        SharedSamples::of(&mut data).read(4);
    }
}
