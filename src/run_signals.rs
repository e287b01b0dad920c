//! OpenFOAM's `writeNowSignal` and `stopAtWriteNowSignal` (`OptimisationSwitches`, off by
//! default): a signal makes a run write the step after it, or write it and stop, as a batch
//! system's warning before its time limit asks. Set in the case's `system/controlDict`.

use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};

/// The signal numbers handled (-1: none) and whether each has come since the last look. A
/// handler may only touch such atomics.
static WRITE_NOW_SIGNAL: AtomicI32 = AtomicI32::new(-1);
static STOP_SIGNAL: AtomicI32 = AtomicI32::new(-1);
static WRITE_NOW_CAUGHT: AtomicBool = AtomicBool::new(false);
static STOP_CAUGHT: AtomicBool = AtomicBool::new(false);

extern "C" fn on_signal(signal: libc::c_int) {
    if signal == WRITE_NOW_SIGNAL.load(Ordering::Relaxed) {
        WRITE_NOW_CAUGHT.store(true, Ordering::Relaxed);
    }
    if signal == STOP_SIGNAL.load(Ordering::Relaxed) {
        STOP_CAUGHT.store(true, Ordering::Relaxed);
    }
}

/// What came since the last [`RunSignals::caught`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Caught {
    /// Write the next step (`writeNowSignal`).
    pub write_now: bool,
    /// Write the next step and stop (`stopAtWriteNowSignal`).
    pub stop_at_write_now: bool,
}

/// The handlers of one run's signals, installed for the process.
#[derive(Debug)]
pub struct RunSignals {
    pub write_now: Option<i32>,
    pub stop_at_write_now: Option<i32>,
}

impl RunSignals {
    /// Installs the handlers of the given signals (`None`: that one is not handled).
    pub fn install(write_now: Option<i32>, stop_at_write_now: Option<i32>) -> Result<Self, String> {
        for (signal, number) in [
            (write_now, &WRITE_NOW_SIGNAL),
            (stop_at_write_now, &STOP_SIGNAL),
        ] {
            let Some(signal) = signal else {
                continue;
            };
            number.store(signal, Ordering::Relaxed);
            // SAFETY: the action is fully initialised (zeroed, then its handler, an empty
            // mask and SA_RESTART, so that an interrupted write goes on), and the handler
            // only stores to atomics, which is async-signal-safe.
            let installed = unsafe {
                let mut action: libc::sigaction = std::mem::zeroed();
                action.sa_sigaction = on_signal as extern "C" fn(libc::c_int) as usize;
                libc::sigemptyset(&mut action.sa_mask);
                action.sa_flags = libc::SA_RESTART;
                libc::sigaction(signal, &action, std::ptr::null_mut())
            };
            if installed != 0 {
                return Err(format!(
                    "cannot handle signal {signal}: {}",
                    std::io::Error::last_os_error()
                ));
            }
        }
        Ok(RunSignals {
            write_now,
            stop_at_write_now,
        })
    }

    /// The signals that came since the last look.
    pub fn caught(&self) -> Caught {
        Caught {
            write_now: WRITE_NOW_CAUGHT.swap(false, Ordering::Relaxed),
            stop_at_write_now: STOP_CAUGHT.swap(false, Ordering::Relaxed),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_caught_signal_is_reported_once() {
        let signals = RunSignals::install(Some(libc::SIGUSR2), Some(libc::SIGURG)).unwrap();
        assert_eq!(signals.caught(), Caught::default());
        // SAFETY: raise delivers the signal to this thread, whose handler is installed.
        unsafe { libc::raise(libc::SIGUSR2) };
        let write = Caught {
            write_now: true,
            stop_at_write_now: false,
        };
        assert_eq!(signals.caught(), write);
        assert_eq!(signals.caught(), Caught::default());
        // SAFETY: as above.
        unsafe { libc::raise(libc::SIGURG) };
        assert!(signals.caught().stop_at_write_now);
    }
}
