//! DEM throughput benchmark: ~30,000 spheres settling under gravity in a walled box with the
//! linear spring-dashpot model with tangential history (LAMMPS `gran/hooke/history` form).
//!
//! The initial state is a random packing (solid fraction 0.30) with small random velocities;
//! an untimed warm-up with a 4× larger step (t_c/12.5, still stable) lets the bed form on the
//! floor (contact-rich), then the same state
//! (restored from a snapshot) and step count are timed on each thread count. The report gives
//! particle-steps per second and bytes per particle.
//!
//! ```text
//! cargo run --release --example dem_settling -- [particles] [steps] [warm-up steps] [--lammps DIR]
//! ```
//! With `--lammps DIR` it also writes `DIR/settling.data` (the same initial state as a LAMMPS
//! data file) and `DIR/params.in` (the same coefficients) for `tools/bench/dem_settling.lmp`.

use fsim::Vec3;
use std::io::Write;
use std::time::Instant;

use fsim::particles::{
    random_packing, Dem, DemConfig, DomainBox, PairModel, ParticleState, SplitMix64, WallModel,
};

const D: f64 = 1e-3;
const RHO: f64 = 2500.0;
const KN: f64 = 200.0;
const E: f64 = 0.5;
const MU: f64 = 0.5;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n_target: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(30_000);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let warmup: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(4000);
    let lammps_dir = args
        .iter()
        .position(|a| a == "--lammps")
        .map(|k| args[k + 1].clone());

    // box 40 d × 40 d × height for φ = 0.35
    let phi = 0.3;
    let side = 40.0 * D;
    let height = n_target as f64 * std::f64::consts::PI * D * D * D / 6.0 / phi / (side * side);
    let hi = [side, side, height];
    let t0 = Instant::now();
    let centres = random_packing([0.0; 3], hi, D, phi, 1).expect("packing");
    let t_pack = t0.elapsed().as_secs_f64();
    let mut rng = SplitMix64::new(2);
    let mut p = ParticleState::with_capacity(centres.len());
    for (k, x) in centres.iter().enumerate() {
        p.push(k as u64 + 1, *x, D, RHO);
        p.velocity[k] = Vec3::new(
            0.2 * (rng.next_f64() - 0.5),
            0.2 * (rng.next_f64() - 0.5),
            0.2 * (rng.next_f64() - 0.5),
        );
    }
    let n = p.len();
    let linear = PairModel::LinearSpringDashpot {
        kn: KN,
        restitution: E,
        kt: 2.0 / 7.0 * KN,
        mu: MU,
        tangential_damping_ratio: 0.5,
        collision_resolution_steps: 50.0,
    };
    let wall = WallModel::LinearSpringDashpot {
        kn: KN,
        restitution: E,
        kt: 2.0 / 7.0 * KN,
        mu: MU,
        tangential_damping_ratio: 0.5,
        collision_resolution_steps: 50.0,
    };
    let mut cfg = DemConfig::new(linear, wall);
    cfg.gravity = Vec3::new(0.0, 0.0, -9.81);
    cfg.skin_fraction = 0.1;
    let domain = DomainBox::walled([0.0; 3], hi);
    let mut warm = Dem::new(cfg.clone(), domain.clone(), p.clone()).expect("valid input");
    let h = warm.collision_time_step();
    println!(
        "DEM settling benchmark: {n} particles, box {:.1} x {:.1} x {:.1} d, packing {t_pack:.2} s, dt = {h:.4e} s, {warmup} warm-up + {steps} timed steps",
        hi[0] / D,
        hi[1] / D,
        hi[2] / D
    );
    let t = Instant::now();
    for _ in 0..warmup {
        warm.step(4.0 * h);
    }
    let snapshot = warm.snapshot();
    println!(
        "warm-up: {:.1} s, t = {:.4} s, {} springs, mean velocity {:?}",
        t.elapsed().as_secs_f64(),
        warm.time(),
        snapshot.history.pairs.len(),
        warm.mean_velocity()
    );
    drop(warm);
    let p = snapshot.particles.clone();

    if let Some(dir) = &lammps_dir {
        write_lammps(dir, &p, hi, h, steps).expect("write LAMMPS input");
        println!("wrote {dir}/settling.data and {dir}/params.in");
    }

    let max_threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(2);
    let mut rates = Vec::new();
    for threads in 1..=max_threads {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let (rate, cpu_rate, dem) = pool.install(|| {
            let mut dem = Dem::restore(cfg.clone(), domain.clone(), &snapshot).unwrap();
            let (t, cpu) = (Instant::now(), process_cpu_seconds());
            for _ in 0..steps {
                dem.step(h);
            }
            let work = (n * steps) as f64;
            (
                work / t.elapsed().as_secs_f64(),
                work / (process_cpu_seconds() - cpu),
                dem,
            )
        });
        let (kt, kr) = dem.kinetic_energy();
        println!(
            "threads {threads}: {rate:.4e} particle-steps/s (wall), {cpu_rate:.4e} per CPU-second, {:.1} bytes/particle, {} list builds, {} listed pairs, {} springs, max overlap/d {:.2e}, KE {:.4e} J",
            dem.memory_bytes() as f64 / n as f64,
            dem.list_rebuilds(),
            dem.pair_count(),
            dem.snapshot().history.pairs.len(),
            dem.max_overlap_ratio(),
            kt + kr
        );
        rates.push(rate);
    }
    if rates.len() == 2 {
        println!("2-thread speed-up: {:.3}", rates[1] / rates[0]);
    }
}

/// User + system CPU time of this process (Linux `/proc/self/stat`, 100 ticks/s): on a shared
/// machine the wall clock of a 1-thread run counts other jobs' time, the CPU time does not.
fn process_cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after_name = stat.rsplit(')').next().unwrap_or("");
    let fields: Vec<&str> = after_name.split_whitespace().collect();
    // fields after the name start at field 3 (state); utime and stime are fields 14 and 15
    let ticks = |k: usize| {
        fields
            .get(k - 3)
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    (ticks(14) + ticks(15)) / 100.0
}

/// The same initial state and coefficients for LAMMPS (`units si`, `atom_style sphere`).
/// LAMMPS' `gran/hooke/history` takes the damping rate γ_n with F = m_eff γ_n v_n; for equal
/// spheres m_eff = m/2, and the restitution e is recovered with
/// γ_n = 2a √(k_n/m_eff) / √(π² + a²), a = −ln e; the wall (m_eff = m) gets its own γ_n.
fn write_lammps(
    dir: &str,
    p: &ParticleState,
    hi: [f64; 3],
    dt: f64,
    steps: usize,
) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut f = std::io::BufWriter::new(std::fs::File::create(format!("{dir}/settling.data"))?);
    writeln!(
        f,
        "fsim DEM settling benchmark\n\n{} atoms\n1 atom types\n",
        p.len()
    )?;
    writeln!(
        f,
        "0 {:.17e} xlo xhi\n0 {:.17e} ylo yhi\n0 {:.17e} zlo zhi\n",
        hi[0], hi[1], hi[2]
    )?;
    writeln!(f, "Atoms # sphere\n")?;
    for i in 0..p.len() {
        let x = p.position[i];
        writeln!(
            f,
            "{} 1 {:.17e} {:.17e} {:.17e} {:.17e} {:.17e}",
            p.id[i], p.diameter[i], p.density[i], x[0], x[1], x[2]
        )?;
    }
    writeln!(f, "\nVelocities\n")?;
    for i in 0..p.len() {
        let v = p.velocity[i];
        let w = p.angular_velocity[i];
        writeln!(
            f,
            "{} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e} {:.17e}",
            p.id[i], v[0], v[1], v[2], w[0], w[1], w[2]
        )?;
    }
    let m = RHO * std::f64::consts::PI * D * D * D / 6.0;
    let a = -E.ln();
    let pi2 = std::f64::consts::PI.powi(2);
    let gamma_pair = 2.0 * a * (KN / (0.5 * m)).sqrt() / (pi2 + a * a).sqrt();
    let gamma_wall = 2.0 * a * (KN / m).sqrt() / (pi2 + a * a).sqrt();
    let mut g = std::fs::File::create(format!("{dir}/params.in"))?;
    writeln!(
        g,
        "variable kn equal {KN:.17e}\nvariable kt equal {:.17e}\nvariable gn equal {gamma_pair:.17e}\nvariable gt equal {:.17e}\n\
         variable gnw equal {gamma_wall:.17e}\nvariable gtw equal {:.17e}\nvariable mu equal {MU}\nvariable dt equal {dt:.17e}\n\
         variable skin equal {:.17e}\nvariable steps equal {steps}\nvariable xhi equal {:.17e}\nvariable yhi equal {:.17e}\nvariable zhi equal {:.17e}",
        2.0 / 7.0 * KN,
        0.5 * gamma_pair,
        0.5 * gamma_wall,
        0.1 * D,
        hi[0],
        hi[1],
        hi[2]
    )?;
    Ok(())
}
