//! The run log on stdout in OpenFOAM's manner: a banner, one `Time = …` block per step with
//! the solver's own lines, `ExecutionTime = … s  ClockTime = … s`, and `End`.
//!
//! A progress bar with the estimated remaining time is drawn on stderr, and only when stdout is
//! a terminal: a person is watching, and the bar is erased before each log line so the two
//! never mix. In a pipe, a file or CI the log is plain lines only.

use super::time_name::format_general;
use crate::grid::Grid;
use std::io::{IsTerminal, Stdout, Write};
use std::path::PathBuf;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// What the banner states about the run.
#[derive(Clone, Debug)]
pub struct Banner {
    /// The command line, as OpenFOAM's `Exec :` line shows it.
    pub exec: String,
    pub case: PathBuf,
    /// Coupling model, e.g. `direct` or `dragLaw`.
    pub model: String,
    pub threads: usize,
    pub grid: Grid,
    /// Further `key : value` lines (particles, pressure solver, …).
    pub extra: Vec<(String, String)>,
}

/// Minimum time between two redraws of the progress bar.
const PROGRESS_INTERVAL: Duration = Duration::from_millis(200);
const BAR_WIDTH: usize = 30;

/// The log writer. `W` is stdout in a run and a buffer in tests.
pub struct Log<W: Write> {
    out: W,
    show_progress: bool,
    bar_visible: bool,
    started: Instant,
    cpu_at_start: f64,
    last_bar: Option<Instant>,
}

impl Log<Stdout> {
    /// The log on stdout, with a progress bar when stdout is a terminal.
    pub fn stdout() -> Self {
        let show = std::io::stdout().is_terminal();
        Log::new(std::io::stdout(), show)
    }
}

impl<W: Write> Log<W> {
    pub fn new(out: W, show_progress: bool) -> Self {
        Log {
            out,
            show_progress,
            bar_visible: false,
            started: Instant::now(),
            cpu_at_start: cpu_time_seconds(),
            last_bar: None,
        }
    }

    /// The run's header.
    pub fn banner(&mut self, banner: &Banner) -> std::io::Result<()> {
        let rule =
            "/*---------------------------------------------------------------------------*\\";
        let [nx, ny, nz] = banner.grid.n;
        let [hx, hy, hz] = banner.grid.h;
        let mut text = format!(
            "{rule}\n  fsim {}  |  particles in a fluid at the particle scale\n\
             \\*---------------------------------------------------------------------------*/\n\
             Exec   : {}\nDate   : {}\nPID    : {}\nCase   : {}\nModel  : {}\nThreads: {}\n\
             Grid   : {nx} x {ny} x {nz} = {} cells, h = ({} {} {}) m\n",
            env!("CARGO_PKG_VERSION"),
            banner.exec,
            utc_now(),
            std::process::id(),
            banner.case.display(),
            banner.model,
            banner.threads,
            banner.grid.cell_count(),
            format_general(hx, 6),
            format_general(hy, 6),
            format_general(hz, 6),
        );
        for (key, value) in &banner.extra {
            text.push_str(&format!("{key:<7}: {value}\n"));
        }
        text.push_str(
            "\\*---------------------------------------------------------------------------*/\n\n",
        );
        self.write_text(&text)
    }

    /// Opens a step's block: `Time = <time name>` and a blank line.
    pub fn time(&mut self, time_name: &str) -> std::io::Result<()> {
        self.write_text(&format!("Time = {time_name}\n\n"))
    }

    /// One line of the caller's, e.g. `Courant Number mean: 0.1 max: 0.4` or `deltaT = 1e-05`.
    pub fn line(&mut self, text: &str) -> std::io::Result<()> {
        self.write_text(&format!("{text}\n"))
    }

    /// Closes a step's block. ExecutionTime is the CPU time of the process (all threads) since
    /// the log was created, ClockTime the wall time in whole seconds, as in OpenFOAM.
    pub fn execution_time(&mut self) -> std::io::Result<()> {
        let cpu = cpu_time_seconds() - self.cpu_at_start;
        let wall = self.started.elapsed().as_secs_f64().round();
        self.write_text(&format!(
            "ExecutionTime = {} s  ClockTime = {} s\n\n",
            format_general(cpu, 6),
            wall
        ))
    }

    /// The last lines of a run that finished normally: the process's peak resident memory
    /// (when the system tells it) and `End`.
    pub fn end(&mut self) -> std::io::Result<()> {
        if let Some(bytes) = peak_resident_bytes() {
            self.write_text(&format!("Peak memory = {:.1} MB\n\n", bytes as f64 / 1e6))?;
        }
        self.write_text("End\n\n")?;
        self.clear_bar();
        Ok(())
    }

    /// Redraws the progress bar for simulated time `time` in `[start, end]` (at most five
    /// times a second; nothing when stdout is not a terminal).
    pub fn progress(&mut self, time: f64, start: f64, end: f64) {
        if !self.show_progress {
            return;
        }
        if self
            .last_bar
            .is_some_and(|t| t.elapsed() < PROGRESS_INTERVAL)
        {
            return;
        }
        self.last_bar = Some(Instant::now());
        let line = progress_line(time, start, end, self.started.elapsed().as_secs_f64());
        let mut err = std::io::stderr().lock();
        let _ = write!(err, "\r\x1b[2K{line}");
        let _ = err.flush();
        self.bar_visible = true;
    }

    /// The writer, for tests.
    pub fn into_inner(self) -> W {
        self.out
    }

    fn write_text(&mut self, text: &str) -> std::io::Result<()> {
        self.clear_bar();
        self.out.write_all(text.as_bytes())?;
        self.out.flush()
    }

    fn clear_bar(&mut self) {
        if self.bar_visible {
            let _ = write!(std::io::stderr().lock(), "\r\x1b[2K");
            self.bar_visible = false;
            // Redraw on the next call without waiting for the interval.
            self.last_bar = None;
        }
    }
}

/// `[#######.........]  42.0%  t = 0.042  remaining 1m 05s`. The remaining time assumes the
/// rest of the run proceeds at the average rate so far.
fn progress_line(time: f64, start: f64, end: f64, elapsed: f64) -> String {
    let span = end - start;
    let fraction = if span > 0.0 {
        ((time - start) / span).clamp(0.0, 1.0)
    } else {
        1.0
    };
    let filled = (fraction * BAR_WIDTH as f64).round() as usize;
    let remaining = if fraction > 0.0 {
        format_duration(elapsed * (1.0 - fraction) / fraction)
    } else {
        "?".to_string()
    };
    format!(
        "[{}{}] {:5.1}%  t = {}  remaining {}",
        "#".repeat(filled),
        ".".repeat(BAR_WIDTH - filled),
        100.0 * fraction,
        format_general(time, 6),
        remaining
    )
}

fn format_duration(seconds: f64) -> String {
    let s = seconds.round() as u64;
    match s {
        0..=59 => format!("{s}s"),
        60..=3599 => format!("{}m {:02}s", s / 60, s % 60),
        _ => format!("{}h {:02}m", s / 3600, (s % 3600) / 60),
    }
}

/// CPU time of this process, all threads, user + system, in seconds: `getrusage`'s, to the
/// microsecond (the ticks of `/proc/self/stat` are 10 ms, too coarse to time a few steps).
/// Where it fails the wall time since the first call stands in for it.
pub fn cpu_time_seconds() -> f64 {
    // SAFETY: getrusage only writes the struct it is handed, which is zeroed and owned here.
    let usage = unsafe {
        let mut usage: libc::rusage = std::mem::zeroed();
        (libc::getrusage(libc::RUSAGE_SELF, &mut usage) == 0).then_some(usage)
    };
    let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    match usage {
        Some(u) => seconds(u.ru_utime) + seconds(u.ru_stime),
        None => {
            static FIRST: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
            FIRST.get_or_init(Instant::now).elapsed().as_secs_f64()
        }
    }
}

/// Peak resident set size of this process (`VmHWM` of `/proc/self/status`), in bytes.
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// The current UTC time as `YYYY-MM-DD hh:mm:ss UTC` (civil date from days since the epoch:
/// H. Hinnant's `civil_from_days` algorithm).
fn utc_now() -> String {
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02}:{:02} UTC",
        rem / 3600,
        (rem % 3600) / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_has_banner_time_blocks_and_end() {
        let mut log = Log::new(Vec::new(), false);
        log.banner(&Banner {
            exec: "fsimFoam -case cavity".into(),
            case: PathBuf::from("cavity"),
            model: "direct".into(),
            threads: 2,
            grid: Grid::new([64, 64, 1], [1.0 / 64.0; 3], [0.0; 3]),
            extra: vec![("Solver".into(), "DCT".into())],
        })
        .unwrap();
        log.time("0.005").unwrap();
        log.line("Courant Number mean: 0.1 max: 0.5").unwrap();
        log.line("deltaT = 0.005").unwrap();
        log.execution_time().unwrap();
        log.progress(0.5, 0.0, 1.0);
        log.end().unwrap();
        let text = String::from_utf8(log.into_inner()).unwrap();
        assert!(text.contains("Case   : cavity\n"), "{text}");
        assert!(text.contains("Model  : direct\nThreads: 2\n"), "{text}");
        assert!(
            text.contains("Grid   : 64 x 64 x 1 = 4096 cells, h = (0.015625"),
            "{text}"
        );
        assert!(text.contains("Solver : DCT\n"), "{text}");
        assert!(text.contains(
            "Time = 0.005\n\nCourant Number mean: 0.1 max: 0.5\ndeltaT = 0.005\nExecutionTime = "
        ));
        assert!(text.contains(" s  ClockTime = 0 s\n\n"), "{text}");
        assert!(text.ends_with("End\n\n"));
        assert!(
            !text.contains('\r'),
            "no progress bar in a non-terminal log"
        );
    }

    #[test]
    fn progress_line_estimates_remaining_time() {
        let line = progress_line(0.25, 0.0, 1.0, 30.0);
        assert!(
            line.starts_with(&format!("[{}{}]", "#".repeat(8), ".".repeat(22))),
            "{line}"
        );
        assert!(line.contains(" 25.0%"), "{line}");
        assert!(line.ends_with("remaining 1m 30s"), "{line}");
        assert!(progress_line(0.0, 0.0, 1.0, 0.0).ends_with("remaining ?"));
        assert_eq!(format_duration(7325.0), "2h 02m");
    }

    #[test]
    fn cpu_time_grows_with_work() {
        // Spin until the process has used 50 ms of CPU; on a loaded machine that takes longer
        // than 50 ms of wall time, hence the generous wall-clock limit.
        let before = cpu_time_seconds();
        let start = Instant::now();
        let mut x = 0.0f64;
        while cpu_time_seconds() - before < 0.05 && start.elapsed() < Duration::from_secs(20) {
            for _ in 0..10_000 {
                x = (x + 1.0).sqrt();
            }
        }
        assert!(x > 0.0);
        let spent = cpu_time_seconds() - before;
        assert!((0.05..1.0).contains(&spent), "cpu time {spent}");
    }

    /// The CPU clock ticks finely enough to time a few short steps (`/proc`'s ticked by
    /// 10 ms).
    #[test]
    fn cpu_time_ticks_by_less_than_a_millisecond() {
        let start = Instant::now();
        let before = cpu_time_seconds();
        let mut after = before;
        while after == before && start.elapsed() < Duration::from_secs(20) {
            after = cpu_time_seconds();
        }
        assert!(
            after > before && after - before < 1e-3,
            "{before} -> {after}"
        );
    }

    #[test]
    fn utc_date_has_the_expected_shape() {
        let now = utc_now();
        assert_eq!(now.len(), 23, "{now}");
        assert!(now.starts_with("20") && now.ends_with(" UTC"));
    }
}
