//! The memory a run needs, estimated before it is allocated (docs/security.md, "Memory and
//! work").
//!
//! The rule: after the case is read and before the grid's arrays or the particles' are
//! allocated, the estimate is compared with the limit — the `-memory SIZE` given on the
//! command line, else the memory the kernel says is available (`MemAvailable` in
//! `/proc/meminfo`, skipped when unreadable), and always the process's address-space limit
//! (`ulimit -v`) — and a run that would not fit is refused with exit 2. Found later, an
//! allocation that fails would abort the process with no message.
//!
//! The estimate counts the arrays every run of the model holds, meant as a lower bound (the
//! Poisson solver's scratch, solver lists and output buffers come on top), so that a refused
//! run would not have fit.

use crate::case::{Case, CouplingModel};
use crate::error::FsimError;
use std::sync::atomic::{AtomicU64, Ordering};

/// Bytes per cell of the fluid solver's arrays on the padded grid (velocity, register,
/// right-hand side: six arrays of 8 bytes; FluidSolver::bytes_per_cell counts them built).
const FLUID_PADDED: f64 = 48.0;

/// Bytes per cell of the fluid solver's unpadded pressure (the Poisson solver's scratch and
/// the case's initial fields come on top: their size depends on the solver and the fields).
const FLUID_CELL: f64 = 8.0;

/// Bytes per cell of the drag-law model's own padded arrays (fraction, fluxes, drag
/// coefficients: 17 arrays; VolumeAveragedFluid::bytes_per_cell counts them built).
const DRAG_LAW_PADDED: f64 = 136.0;

/// Bytes per cell of the drag-law model's unpadded arrays (pressure system: 11 arrays).
const DRAG_LAW_CELL: f64 = 88.0;

/// Bytes per particle of the DEM's arrays (state, derived arrays, accelerations; what
/// Dem::memory_bytes reports per particle before any contact list).
pub const BYTES_PER_PARTICLE: f64 = 370.0;

/// The `-memory` limit in bytes; 0 when not given.
static USER_LIMIT: AtomicU64 = AtomicU64::new(0);

/// Sets the `-memory` limit (bytes) for this process's checks.
pub fn set_user_limit(bytes: Option<u64>) {
    USER_LIMIT.store(bytes.unwrap_or(0), Ordering::Relaxed);
}

/// Parses a size as `-memory` takes it: a number of bytes with an optional suffix `K`, `M`,
/// `G` or `T` (powers of 1024, `B` and `iB` allowed after it): `4G`, `512MiB`, `1.5T`.
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let t = t
        .strip_suffix("iB")
        .or_else(|| t.strip_suffix('B'))
        .unwrap_or(t);
    let (number, scale) = match t.chars().last().map(|c| c.to_ascii_uppercase()) {
        Some('K') => (&t[..t.len() - 1], 1u64 << 10),
        Some('M') => (&t[..t.len() - 1], 1 << 20),
        Some('G') => (&t[..t.len() - 1], 1 << 30),
        Some('T') => (&t[..t.len() - 1], 1 << 40),
        _ => (t, 1),
    };
    match number.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 && x * (scale as f64) < 1.8e19 => {
            Ok((x * scale as f64) as u64)
        }
        _ => Err("expected a positive size such as 4G, 512M or 1000000 (bytes)".to_string()),
    }
}

/// The bytes the grid's arrays need for the case's model (module docs: a lower bound).
pub fn grid_bytes(case: &Case) -> f64 {
    let n = case.mesh.grid.n;
    let cells = n.iter().map(|&k| k as f64).product::<f64>();
    let padded = n.iter().map(|&k| k as f64 + 2.0).product::<f64>();
    let mut bytes = FLUID_PADDED * padded + FLUID_CELL * cells;
    if case.coupling.model == CouplingModel::DragLaw {
        bytes += DRAG_LAW_PADDED * padded + DRAG_LAW_CELL * cells;
    }
    bytes
}

/// The limit a run must fit in, and what it is, for the message.
fn limit() -> Option<(f64, String)> {
    let user = USER_LIMIT.load(Ordering::Relaxed);
    let chosen = if user > 0 {
        Some((
            user as f64,
            format!(
                "the -memory limit of {} (raise it with -memory SIZE)",
                show(user as f64)
            ),
        ))
    } else {
        mem_available().map(|b| {
            (
                b as f64,
                format!(
                    "the {} of memory available (MemAvailable; give -memory SIZE to allow \
                     more)",
                    show(b as f64)
                ),
            )
        })
    };
    let address_space = address_space_limit().map(|b| {
        (
            b as f64,
            format!(
                "the process's address-space limit of {} (ulimit -v)",
                show(b as f64)
            ),
        )
    });
    match (chosen, address_space) {
        (Some(a), Some(b)) => Some(if b.0 < a.0 { b } else { a }),
        (a, b) => a.or(b),
    }
}

/// Refuses (exit 2) a run whose `what` needs `bytes`, more than the limit (module docs).
pub fn check(bytes: f64, what: &str) -> Result<(), FsimError> {
    shortfall(bytes, what).map_or(Ok(()), |m| Err(FsimError::input(m)))
}

/// The refusal of [`check`] as a message, `None` when `bytes` fit.
pub fn shortfall(bytes: f64, what: &str) -> Option<String> {
    match limit() {
        Some((limit, name)) if bytes.is_nan() || bytes > limit => Some(format!(
            "{what} needs at least {} of memory, more than {name}: use a coarser grid or \
             fewer particles, or run where more memory is free (docs/security.md, \"Memory \
             and work\")",
            show(bytes)
        )),
        _ => None,
    }
}

/// `MemAvailable` from `/proc/meminfo`, in bytes, as first read by this process (before the
/// run allocated: a later check of grid and particles together must not count the grid's
/// arrays twice); `None` when it does not read.
fn mem_available() -> Option<u64> {
    static FIRST: std::sync::OnceLock<Option<u64>> = std::sync::OnceLock::new();
    *FIRST.get_or_init(read_mem_available)
}

fn read_mem_available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb = line.split_whitespace().nth(1)?.parse::<u64>().ok()?;
    kb.checked_mul(1024)
}

/// The soft `RLIMIT_AS` in bytes; `None` when unlimited.
fn address_space_limit() -> Option<u64> {
    let mut limit = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    // SAFETY: getrlimit writes the struct it is given and nothing else.
    let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut limit) } == 0;
    (ok && limit.rlim_cur != libc::RLIM_INFINITY).then_some(limit.rlim_cur)
}

/// A byte count for people: `1.5 GB`, `120.0 MB`, `3.2 TB`.
pub fn show(bytes: f64) -> String {
    let units = [("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)];
    for (name, size) in units {
        if bytes >= size {
            return format!("{:.1} {name}", bytes / size);
        }
    }
    format!("{bytes:.0} bytes")
}

/// How the message of a failed allocation ([`zeros`]) begins: a caller that gets it as a
/// plain `String` error reports a failed run (exit 1), not bad input.
pub const ALLOCATION_FAILED: &str = "cannot allocate";

/// Whether `message` reports a failed allocation ([`ALLOCATION_FAILED`]).
pub fn is_allocation_failure(message: &str) -> bool {
    message.starts_with(ALLOCATION_FAILED)
}

/// Reserves `len` zeros, or says how much could not be had (exit 1 through the caller): a
/// large array that the estimate let through can still fail to allocate, and should say so
/// instead of aborting.
pub fn zeros(len: usize, what: &str) -> Result<Vec<f64>, String> {
    let mut v = Vec::new();
    returning_failure(|| v.try_reserve_exact(len)).map_err(|_| {
        format!(
            "{ALLOCATION_FAILED} {} for {what} ({len} values): not enough memory",
            show(len as f64 * 8.0)
        )
    })?;
    v.resize(len, 0.0);
    Ok(v)
}

thread_local! {
    /// Set while a caller that handles a failed allocation itself is allocating.
    static RETURN_FAILURE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `reserve` (a `try_reserve`) with a failed allocation returned to it as an error,
/// where [`ExitOnFailure`] would end the process: the caller's message names the array.
pub fn returning_failure<T>(reserve: impl FnOnce() -> T) -> T {
    let was = RETURN_FAILURE.with(|f| f.replace(true));
    let result = reserve();
    RETURN_FAILURE.with(|f| f.set(was));
    result
}

/// The global allocator of `fsimFoam`: the system's, except that an allocation that fails
/// ends the process with one line on stderr and exit code 1 (a failed run: time directories
/// appear whole or not at all, so none is half-written) instead of Rust's abort with
/// `SIGABRT`. An allocation inside [`returning_failure`] gets its failure returned instead.
pub struct ExitOnFailure;

impl ExitOnFailure {
    #[cold]
    fn failed(size: usize) -> ! {
        // No allocation here: the line is assembled on the stack.
        let mut line = [0u8; 256];
        let mut n = 0;
        let mut put = |bytes: &[u8]| {
            let k = bytes.len().min(line.len() - n);
            line[n..n + k].copy_from_slice(&bytes[..k]);
            n += k;
        };
        put(b"fsimFoam: error: out of memory: an allocation of ");
        let mut digits = [0u8; 20];
        let (mut i, mut v) = (digits.len(), size);
        loop {
            i -= 1;
            digits[i] = b'0' + (v % 10) as u8;
            v /= 10;
            if v == 0 {
                break;
            }
        }
        put(&digits[i..]);
        put(
            b" bytes failed (more than the estimate checked before the run): use a coarser \
              grid or fewer particles, or run where more memory is free (docs/security.md, \
              \"Memory and work\")\n",
        );
        // SAFETY: write(2) and _exit(2) are async-signal-safe and take a valid buffer.
        unsafe {
            libc::write(2, line.as_ptr().cast(), n);
            libc::_exit(1)
        }
    }

    fn checked(&self, p: *mut u8, size: usize) -> *mut u8 {
        if p.is_null() && !RETURN_FAILURE.try_with(|f| f.get()).unwrap_or(false) {
            Self::failed(size)
        }
        p
    }
}

// SAFETY: every call is forwarded to the system allocator with its arguments unchanged.
unsafe impl std::alloc::GlobalAlloc for ExitOnFailure {
    unsafe fn alloc(&self, layout: std::alloc::Layout) -> *mut u8 {
        self.checked(unsafe { std::alloc::System.alloc(layout) }, layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: std::alloc::Layout) -> *mut u8 {
        self.checked(
            unsafe { std::alloc::System.alloc_zeroed(layout) },
            layout.size(),
        )
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: std::alloc::Layout, new_size: usize) -> *mut u8 {
        self.checked(
            unsafe { std::alloc::System.realloc(ptr, layout, new_size) },
            new_size,
        )
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: std::alloc::Layout) {
        unsafe { std::alloc::System.dealloc(ptr, layout) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_binary_suffixes() {
        assert_eq!(parse_size("4G"), Ok(4 << 30));
        assert_eq!(parse_size("512MiB"), Ok(512 << 20));
        assert_eq!(parse_size("1.5k"), Ok(1536));
        assert_eq!(parse_size("1000"), Ok(1000));
        assert!(parse_size("0").is_err());
        assert!(parse_size("inf").is_err());
        assert!(parse_size("-1G").is_err());
        assert!(parse_size("G").is_err());
        assert!(parse_size("1e30").is_err());
    }

    #[test]
    fn a_limit_refuses_with_the_estimate_and_the_limit() {
        set_user_limit(Some(1 << 20));
        let err = check(5e6, "the grid of 10 cells").unwrap_err();
        set_user_limit(None);
        assert_eq!(err.exit_code(), 2);
        let text = err.to_string();
        assert!(
            text.contains("5.0 MB") && text.contains("-memory limit of 1.0 MB"),
            "{text}"
        );
    }
}
