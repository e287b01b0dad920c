//! Restarted GMRES (Saad & Schultz 1986) for the small non-symmetric systems of the steady
//! direct-model solver.

/// Outcome of [`gmres`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GmresReport {
    /// Matrix–vector products used.
    pub iterations: usize,
    /// `‖b − A x‖ / ‖b‖` at return.
    pub relative_residual: f64,
}

/// Solves `A x = b` by GMRES(`restart`) from the initial `x`, until the residual falls
/// below `tolerance ‖b‖` or `max_iterations` products. `apply(v, out)` sets `out = A v`.
/// Modified Gram–Schmidt, Givens rotations; the Krylov basis (`restart + 1` vectors) is
/// allocated once per call (see [`GmresWorkspace`] to keep it across calls).
pub fn gmres(
    apply: &mut dyn FnMut(&[f64], &mut [f64]),
    b: &[f64],
    x: &mut [f64],
    restart: usize,
    tolerance: f64,
    max_iterations: usize,
) -> GmresReport {
    GmresWorkspace::new(restart).solve(apply, b, x, tolerance, max_iterations)
}

/// The Krylov basis and Hessenberg matrix of GMRES(`restart`), kept between solves so that
/// a solve in every time step allocates nothing once the sizes have been reached.
#[derive(Debug, Default)]
pub struct GmresWorkspace {
    restart: usize,
    basis: Vec<Vec<f64>>,
    hessenberg: Vec<Vec<f64>>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    g: Vec<f64>,
    y: Vec<f64>,
    work: Vec<f64>,
}

impl GmresWorkspace {
    /// A workspace for GMRES restarted every `restart` products.
    pub fn new(restart: usize) -> Self {
        let m = restart.max(1);
        GmresWorkspace {
            restart: m,
            basis: vec![Vec::new(); m + 1],
            hessenberg: vec![vec![0.0; m]; m + 1],
            cs: vec![0.0; m],
            sn: vec![0.0; m],
            g: vec![0.0; m + 1],
            y: vec![0.0; m],
            work: Vec::new(),
        }
    }

    /// As [`gmres`]. An initial `x` of zeros costs no product.
    pub fn solve(
        &mut self,
        apply: &mut dyn FnMut(&[f64], &mut [f64]),
        b: &[f64],
        x: &mut [f64],
        tolerance: f64,
        max_iterations: usize,
    ) -> GmresReport {
        let n = b.len();
        let m = self.restart;
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
        let b_norm = dot(b, b).sqrt();
        if b_norm == 0.0 {
            x.iter_mut().for_each(|v| *v = 0.0);
            return GmresReport {
                iterations: 0,
                relative_residual: 0.0,
            };
        }
        for v in self.basis.iter_mut() {
            v.resize(n, 0.0);
        }
        self.work.resize(n, 0.0);
        let GmresWorkspace {
            basis,
            hessenberg,
            cs,
            sn,
            g,
            y,
            work,
            ..
        } = self;
        let mut iterations = 0;
        loop {
            if x.iter().all(|&v| v == 0.0) {
                work.iter_mut().for_each(|v| *v = 0.0);
            } else {
                apply(x, work);
            }
            for i in 0..n {
                basis[0][i] = b[i] - work[i];
            }
            let beta = dot(&basis[0], &basis[0]).sqrt();
            if beta <= tolerance * b_norm || iterations >= max_iterations {
                return GmresReport {
                    iterations,
                    relative_residual: beta / b_norm,
                };
            }
            basis[0].iter_mut().for_each(|v| *v /= beta);
            g.iter_mut().for_each(|v| *v = 0.0);
            g[0] = beta;
            let mut k_used = 0;
            for k in 0..m {
                let (head, tail) = basis.split_at_mut(k + 1);
                apply(&head[k], &mut tail[0]);
                iterations += 1;
                for (j, v) in head.iter().enumerate() {
                    let hjk = dot(&tail[0], v);
                    hessenberg[j][k] = hjk;
                    for i in 0..n {
                        tail[0][i] -= hjk * v[i];
                    }
                }
                let norm = dot(&tail[0], &tail[0]).sqrt();
                hessenberg[k + 1][k] = norm;
                if norm > 0.0 {
                    tail[0].iter_mut().for_each(|v| *v /= norm);
                }
                for j in 0..k {
                    let t = cs[j] * hessenberg[j][k] + sn[j] * hessenberg[j + 1][k];
                    hessenberg[j + 1][k] = -sn[j] * hessenberg[j][k] + cs[j] * hessenberg[j + 1][k];
                    hessenberg[j][k] = t;
                }
                let (a, c) = (hessenberg[k][k], hessenberg[k + 1][k]);
                let r = a.hypot(c);
                cs[k] = if r == 0.0 { 1.0 } else { a / r };
                sn[k] = if r == 0.0 { 0.0 } else { c / r };
                hessenberg[k][k] = r;
                hessenberg[k + 1][k] = 0.0;
                g[k + 1] = -sn[k] * g[k];
                g[k] *= cs[k];
                k_used = k + 1;
                if g[k + 1].abs() <= tolerance * b_norm
                    || iterations >= max_iterations
                    || norm == 0.0
                {
                    break;
                }
            }
            // Back substitution for the update y, then x += V y.
            for j in (0..k_used).rev() {
                let s: f64 = (j + 1..k_used).map(|l| hessenberg[j][l] * y[l]).sum();
                y[j] = (g[j] - s) / hessenberg[j][j];
            }
            for (j, yj) in y[..k_used].iter().enumerate() {
                for i in 0..n {
                    x[i] += yj * basis[j][i];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_non_symmetric_system() {
        // Tridiagonal, non-symmetric, diagonally dominant: x = 1 … n.
        let n = 50;
        let matrix = |v: &[f64], out: &mut [f64]| {
            for i in 0..v.len() {
                let left = if i > 0 { v[i - 1] } else { 0.0 };
                let right = if i + 1 < v.len() { v[i + 1] } else { 0.0 };
                out[i] = 4.0 * v[i] - 1.5 * left - 0.5 * right;
            }
        };
        let exact: Vec<f64> = (1..=n).map(|i| i as f64).collect();
        let mut b = vec![0.0; n];
        matrix(&exact, &mut b);
        let mut x = vec![0.0; n];
        let report = gmres(&mut |v, o| matrix(v, o), &b, &mut x, 10, 1e-12, 500);
        assert!(report.relative_residual < 1e-12, "{report:?}");
        for i in 0..n {
            assert!((x[i] - exact[i]).abs() < 1e-9);
        }
    }
}
