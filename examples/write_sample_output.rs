//! Writes a small sample run with analytic fields, for the Python VTK checks
//! (`tools/tests/test_vtk_output.py`) and for looking at fsim's output in ParaView.
//!
//! `cargo run --release --example write_sample_output -- CASE_DIR`
//!
//! Grid: 16 × 12 × 8 cells, h = (0.0625, 0.05, 0.1) m, origin (−0.5, 0.2, 1); L = n·h.
//! At time t, for each cell centre (x, y, z):
//!   U = (sin(2π (x − x₀)/Lx) · (1 + t),  cos(2π (y − y₀)/Ly),  z · t),   p = x · y + t.
//! Particles i = 0 … 4 (none at t = 1e-05, to exercise an empty set):
//!   position (−0.4 + 0.15 i, 0.5, 1.25 + t), id 100 + i, d = 1e-3 (1 + i),
//!   U = (i, t, −1), omega = (0, 0, i t), F_hydro = (1e-6 i, 0, 0), F_contact = (0, −1e-7, t).
//! Written times: 0, 1e-05, 0.1, 0.25, 1 (precision 6).

use fsim::grid::Grid;
use fsim::output::{
    write_fluid, Banner, CaseOutput, CellData, Log, Monitor, OutputError, ParticleFields,
    RestartHeader, SafeDir, PARTICLE_FILE_NAME, RESTART_FILE_NAME,
};
use fsim::Vec3;
use std::f64::consts::PI;
use std::path::PathBuf;

const TIMES: [f64; 5] = [0.0, 1e-5, 0.1, 0.25, 1.0];

fn main() -> Result<(), OutputError> {
    let case_dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .expect("usage: write_sample_output CASE_DIR"),
    );
    std::fs::create_dir_all(&case_dir)
        .map_err(|e| OutputError::io(&case_dir, "cannot create case directory", e))?;
    let grid = Grid::new([16, 12, 8], [0.0625, 0.05, 0.1], [-0.5, 0.2, 1.0]);
    let mut output = CaseOutput::open(&case_dir, 6, 0, 0.0)?;
    let mut log = Log::stdout();
    let log_err = |e| OutputError::io(std::path::Path::new("<stdout>"), "cannot write log", e);
    log.banner(&Banner {
        exec: std::env::args().collect::<Vec<_>>().join(" "),
        case: case_dir.clone(),
        model: "sample (analytic fields, no solver)".into(),
        threads: 1,
        grid: grid.clone(),
        extra: vec![("Writes".into(), format!("{TIMES:?}"))],
    })
    .map_err(log_err)?;
    let mut monitor = Monitor::create(&case_dir, "sample", "0", &["Time", "meanP"])?;
    for (step, &t) in TIMES.iter().enumerate() {
        let (u, p) = fluid(&grid, t);
        log.time(&output.time_name(t)).map_err(log_err)?;
        let dir = output.begin(t)?;
        write_fluid(
            dir.dir(),
            &grid,
            &format!("fsim sample t = {t}"),
            &[CellData::Vector("U", &u), CellData::Scalar("p", &p)],
        )?;
        let count = if t == 1e-5 { 0 } else { 5 };
        write_particles(dir.dir(), t, count)?;
        RestartHeader::new(t, step as u64, 1e-5).write(
            dir.dir(),
            RESTART_FILE_NAME,
            &[("p", &p)],
        )?;
        let path = output.commit(dir)?;
        monitor.row(&[t, p.iter().sum::<f64>() / p.len() as f64])?;
        log.line(&format!("wrote {}", path.display()))
            .map_err(log_err)?;
        log.execution_time().map_err(log_err)?;
        log.progress(t, TIMES[0], TIMES[TIMES.len() - 1]);
        // Slow enough, when run in a terminal, to watch the progress bar.
        if std::env::var_os("FSIM_SAMPLE_SLOW").is_some() {
            std::thread::sleep(std::time::Duration::from_millis(700));
        }
    }
    log.line(&format!(
        "collection {}",
        output.collection_path().display()
    ))
    .map_err(log_err)?;
    log.end().map_err(log_err)?;
    Ok(())
}

fn fluid(grid: &Grid, t: f64) -> (Vec<[f64; 3]>, Vec<f64>) {
    let length = grid.length();
    let mut u = vec![[0.0; 3]; grid.cell_count()];
    let mut p = vec![0.0; grid.cell_count()];
    for k in 0..grid.n[2] {
        for j in 0..grid.n[1] {
            for i in 0..grid.n[0] {
                let [x, y, z] = grid.cell_centre(i, j, k);
                let c = grid.cell_index(i, j, k);
                u[c] = [
                    (2.0 * PI * (x - grid.origin[0]) / length[0]).sin() * (1.0 + t),
                    (2.0 * PI * (y - grid.origin[1]) / length[1]).cos(),
                    z * t,
                ];
                p[c] = x * y + t;
            }
        }
    }
    (u, p)
}

fn write_particles(dir: &SafeDir, t: f64, count: usize) -> Result<(), OutputError> {
    let idx = |i: usize| i as f64;
    let positions: Vec<_> = (0..count)
        .map(|i| Vec3::new(-0.4 + 0.15 * idx(i), 0.5, 1.25 + t))
        .collect();
    let id: Vec<i64> = (0..count as i64).map(|i| 100 + i).collect();
    let d: Vec<_> = (0..count).map(|i| 1e-3 * (1.0 + idx(i))).collect();
    let velocity: Vec<_> = (0..count).map(|i| Vec3::new(idx(i), t, -1.0)).collect();
    let omega: Vec<_> = (0..count)
        .map(|i| Vec3::new(0.0, 0.0, idx(i) * t))
        .collect();
    let hydro: Vec<_> = (0..count)
        .map(|i| Vec3::new(1e-6 * idx(i), 0.0, 0.0))
        .collect();
    let contact: Vec<_> = (0..count).map(|_| Vec3::new(0.0, -1e-7, t)).collect();
    ParticleFields {
        positions: &positions,
        id: &id,
        d: &d,
        velocity: &velocity,
        omega: &omega,
        hydrodynamic_force: &hydro,
        contact_force: &contact,
    }
    .write(dir, PARTICLE_FILE_NAME)
}
