//! Layout measurement behind `ParticleState`: a pair-force loop over the same neighbour list
//! with vectors stored as `Vec<[f64; 3]>` (one 24-byte record per particle) or as three
//! separate `Vec<f64>` per vector quantity. Same arithmetic, same order, same result.
//!
//! ```text
//! cargo run --release --example dem_layout -- [particles] [sweeps]
//! ```

use std::time::Instant;

struct Lists {
    row_start: Vec<u32>,
    partner: Vec<u32>,
}

/// A jittered cubic lattice (spacing 0.99 d, so most neighbours touch), in lattice order,
/// and its half neighbour list with cut-off 1.1 d.
fn setup(n_side: usize) -> (Vec<[f64; 3]>, Vec<[f64; 3]>, Lists) {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let idx = |i: usize, j: usize, k: usize| i + n_side * (j + n_side * k);
    let n = n_side * n_side * n_side;
    let mut x = vec![[0.0; 3]; n];
    let mut v = vec![[0.0; 3]; n];
    for k in 0..n_side {
        for j in 0..n_side {
            for i in 0..n_side {
                let p = idx(i, j, k);
                x[p] = [
                    0.99 * i as f64 + 0.02 * rnd(),
                    0.99 * j as f64 + 0.02 * rnd(),
                    0.99 * k as f64 + 0.02 * rnd(),
                ];
                v[p] = [rnd(), rnd(), rnd()];
            }
        }
    }
    let mut row_start = vec![0u32];
    let mut partner = Vec::new();
    for k in 0..n_side {
        for j in 0..n_side {
            for i in 0..n_side {
                let p = idx(i, j, k);
                for dk in 0..2usize {
                    for dj in 0..3usize {
                        for di in 0..3usize {
                            let (ii, jj, kk) = (i + di, j + dj, k + dk);
                            if ii < 1 || jj < 1 || ii > n_side || jj > n_side || kk >= n_side {
                                continue;
                            }
                            let q = idx(ii - 1, jj - 1, kk);
                            if q <= p {
                                continue;
                            }
                            let d: f64 = (0..3).map(|a| (x[p][a] - x[q][a]).powi(2)).sum();
                            if d < 1.1 * 1.1 {
                                partner.push(q as u32);
                            }
                        }
                    }
                }
                row_start.push(partner.len() as u32);
            }
        }
    }
    (x, v, Lists { row_start, partner })
}

const KN: f64 = 1e3;
const CN: f64 = 0.5;

/// Normal spring-dashpot, scattered to both particles: records of three.
fn sweep_records(x: &[[f64; 3]], v: &[[f64; 3]], l: &Lists, f: &mut [[f64; 3]]) {
    for i in 0..x.len() {
        for k in l.row_start[i] as usize..l.row_start[i + 1] as usize {
            let j = l.partner[k] as usize;
            let d = [x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]];
            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if r2 >= 1.0 {
                continue;
            }
            let r = r2.sqrt();
            let n = [d[0] / r, d[1] / r, d[2] / r];
            let un = (v[i][0] - v[j][0]) * n[0]
                + (v[i][1] - v[j][1]) * n[1]
                + (v[i][2] - v[j][2]) * n[2];
            let fm = KN * (1.0 - r) - CN * un;
            for a in 0..3 {
                f[i][a] += fm * n[a];
                f[j][a] -= fm * n[a];
            }
        }
    }
}

/// The same on separate component arrays.
fn sweep_components(x: [&[f64]; 3], v: [&[f64]; 3], l: &Lists, f: [&mut [f64]; 3]) {
    let [fx, fy, fz] = f;
    for i in 0..x[0].len() {
        for k in l.row_start[i] as usize..l.row_start[i + 1] as usize {
            let j = l.partner[k] as usize;
            let d = [x[0][i] - x[0][j], x[1][i] - x[1][j], x[2][i] - x[2][j]];
            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if r2 >= 1.0 {
                continue;
            }
            let r = r2.sqrt();
            let n = [d[0] / r, d[1] / r, d[2] / r];
            let un = (v[0][i] - v[0][j]) * n[0]
                + (v[1][i] - v[1][j]) * n[1]
                + (v[2][i] - v[2][j]) * n[2];
            let fm = KN * (1.0 - r) - CN * un;
            fx[i] += fm * n[0];
            fx[j] -= fm * n[0];
            fy[i] += fm * n[1];
            fy[j] -= fm * n[1];
            fz[i] += fm * n[2];
            fz[j] -= fm * n[2];
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n_target: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(30_000);
    let sweeps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(300);
    let n_side = (n_target as f64).cbrt().round() as usize;
    let (x, v, lists) = setup(n_side);
    let n = x.len();
    let comp = |a: &[[f64; 3]], c: usize| a.iter().map(|p| p[c]).collect::<Vec<f64>>();
    let (xs, vs) = (
        [comp(&x, 0), comp(&x, 1), comp(&x, 2)],
        [comp(&v, 0), comp(&v, 1), comp(&v, 2)],
    );
    println!(
        "{n} particles, {} listed pairs, {sweeps} sweeps",
        lists.partner.len()
    );
    for round in 0..3 {
        let mut f = vec![[0.0; 3]; n];
        let t = Instant::now();
        for _ in 0..sweeps {
            sweep_records(&x, &v, &lists, &mut f);
        }
        let t_rec = t.elapsed().as_secs_f64();
        let (mut fx, mut fy, mut fz) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let t = Instant::now();
        for _ in 0..sweeps {
            sweep_components(
                [&xs[0], &xs[1], &xs[2]],
                [&vs[0], &vs[1], &vs[2]],
                &lists,
                [&mut fx, &mut fy, &mut fz],
            );
        }
        let t_comp = t.elapsed().as_secs_f64();
        let same = (0..n).all(|i| f[i] == [fx[i], fy[i], fz[i]]);
        let per_pair = |t: f64| t / (sweeps * lists.partner.len()) as f64 * 1e9;
        println!(
            "round {round}: Vec<[f64;3]> {:.2} ns/pair, three Vec<f64> {:.2} ns/pair, ratio {:.3}, identical forces: {same}",
            per_pair(t_rec),
            per_pair(t_comp),
            t_comp / t_rec
        );
    }
}
