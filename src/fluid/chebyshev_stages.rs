//! Stages of the damped first-order Runge–Kutta–Chebyshev method (`EulerRKC`'s diffusion).
//!
//! For `y' = F(y) = L y + N` (here `L = ν∇²` with the faces a hook constrains, `N` the
//! frozen advection, forces and old pressure gradient), `s` stages
//!
//! ```text
//!   Y₀ = yⁿ,   Y₁ = Y₀ + μ̃₁ Δt F(Y₀),
//!   Y_j = μ_j Y_{j−1} + ν_j Y_{j−2} + μ̃_j Δt F(Y_{j−1}),   j = 2..s,   yⁿ⁺¹ = Y_s,
//!   w₀ = 1 + ε/s²,  w₁ = T_s(w₀)/T_s'(w₀),  b_j = 1/T_j(w₀),
//!   μ̃₁ = b₁ w₁,  μ_j = 2 b_j w₀ / b_{j−1},  ν_j = −b_j / b_{j−2},  μ̃_j = 2 b_j w₁ / b_{j−1}
//! ```
//!
//! (van der Houwen & Sommeijer, ZAMM 60, 479–485, 1980; Verwer, Appl. Numer. Math. 22,
//! 359–379, 1996, eq. 2.4–2.6). The stability polynomial is `P_s(z) = b_s T_s(w₀ + w₁ z)`:
//! `P(0) = P'(0) = 1` (first order), `|P| ≤ b_s < 1` on the real interval
//! `[−β(s), 0]`, `β(s) = (1 + w₀)/w₁` (about `(2 − 4ε/3) s²` for small `ε`; 1.53 s² at the
//! `ε = 0.5` used here). The damping `ε` keeps the polynomial
//! below one in magnitude on the whole interval, so modes slightly off the real axis (the
//! small advection of a viscous flow, a constrained face's non-symmetric row) stay damped.
//! `μ_j + ν_j = 1`, so every stage of a steady state (`F(y) = 0`) is that state: the scheme
//! keeps any steady solution whatever `Δt` and `s`.

/// Damping `ε` of the Chebyshev polynomial. Verwer (1996) uses 0.05 for the first-order
/// method (reach 1.94 s², |P| ≤ 0.95 on the damped part); 0.5 gives up a fifth of the
/// reach (1.53 s²) for |P| ≤ 0.65. A sphere moving through the grid disturbs the stiff modes
/// near it at every step, and they must die out quickly (the settling sphere with each
/// damping: docs/direct_model.md, "`EulerRKC`").
const DAMPING: f64 = 0.5;

/// Share of `β(s)` a step may use: the hook's constrained rows may reach a little beyond the
/// spectrum of the plain Laplacian.
const SAFETY: f64 = 0.9;

/// The coefficients of one stage `j` (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChebyshevStage {
    /// `μ_j`: weight of `Y_{j−1}` (1 for the first stage).
    pub current: f64,
    /// `ν_j`: weight of `Y_{j−2}` (0 for the first stage).
    pub previous: f64,
    /// `μ̃_j`: weight of `Δt F(Y_{j−1})`.
    pub tendency: f64,
    /// Stage time as a fraction of the step (`c_s = 1`).
    pub time: f64,
}

/// The `s`-stage damped Chebyshev method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChebyshevStages {
    pub count: usize,
    w0: f64,
    w1: f64,
}

impl ChebyshevStages {
    /// Most stages a step takes; `EulerRKC`'s step is bounded by their reach.
    pub const MAX_STAGES: usize = 40;

    /// The method with `count ≥ 1` stages.
    pub fn new(count: usize) -> Self {
        let count = count.max(1);
        let w0 = 1.0 + DAMPING / (count * count) as f64;
        let (t, dt) = chebyshev(count, w0);
        ChebyshevStages {
            count,
            w0,
            w1: t / dt,
        }
    }

    /// The fewest stages whose (safety-reduced) reach covers `Δt λ_max`, at most
    /// [`Self::MAX_STAGES`].
    pub fn for_step(dt_lambda_max: f64) -> Self {
        let needed = dt_lambda_max / SAFETY;
        let mut s = 1;
        while s < Self::MAX_STAGES && Self::new(s).real_reach() < needed {
            s += 1;
        }
        Self::new(s)
    }

    /// `SAFETY β(s)`: the largest `Δt λ_max` that `s` stages take.
    pub fn reach(count: usize) -> f64 {
        SAFETY * Self::new(count).real_reach()
    }

    /// `β(s) = (1 + w₀)/w₁`, where `w₀ + w₁ z = −1`.
    fn real_reach(&self) -> f64 {
        (1.0 + self.w0) / self.w1
    }

    /// The stability polynomial `P_s(z) = T_s(w₀ + w₁ z) / T_s(w₀)`.
    pub fn amplification(&self, z: f64) -> f64 {
        chebyshev(self.count, self.w0 + self.w1 * z).0 / chebyshev(self.count, self.w0).0
    }

    /// The stages in order, `j = 1..=s`.
    pub fn stages(&self) -> StageIter {
        StageIter {
            method: *self,
            j: 0,
            t: [1.0, 1.0],
            c: [0.0, 0.0],
        }
    }
}

/// Iterates over the stages of a [`ChebyshevStages`] (no allocation).
pub struct StageIter {
    method: ChebyshevStages,
    j: usize,
    /// `T_{j−1}(w₀)`, `T_{j−2}(w₀)`.
    t: [f64; 2],
    /// `c_{j−1}`, `c_{j−2}`.
    c: [f64; 2],
}

impl Iterator for StageIter {
    type Item = ChebyshevStage;

    fn next(&mut self) -> Option<ChebyshevStage> {
        let ChebyshevStages { count, w0, w1 } = self.method;
        if self.j >= count {
            return None;
        }
        self.j += 1;
        let stage = if self.j == 1 {
            self.t = [w0, 1.0];
            let tendency = w1 / w0;
            ChebyshevStage {
                current: 1.0,
                previous: 0.0,
                tendency,
                time: tendency,
            }
        } else {
            let [t1, t2] = self.t;
            let t = 2.0 * w0 * t1 - t2;
            // b_j / b_{j−1} = T_{j−1}/T_j, b_j / b_{j−2} = T_{j−2}/T_j.
            let current = 2.0 * w0 * t1 / t;
            let previous = -t2 / t;
            let tendency = 2.0 * w1 * t1 / t;
            let time = current * self.c[0] + previous * self.c[1] + tendency;
            self.t = [t, t1];
            ChebyshevStage {
                current,
                previous,
                tendency,
                time,
            }
        };
        self.c = [stage.time, self.c[0]];
        Some(stage)
    }
}

/// `(T_s(x), T_s'(x))` by the three-term recurrences.
fn chebyshev(s: usize, x: f64) -> (f64, f64) {
    let (mut t0, mut t1) = (1.0, x);
    let (mut d0, mut d1) = (0.0, 1.0);
    if s == 0 {
        return (t0, d0);
    }
    for _ in 1..s {
        let t2 = 2.0 * x * t1 - t0;
        let d2 = 2.0 * t1 + 2.0 * x * d1 - d0;
        (t0, t1, d0, d1) = (t1, t2, d1, d2);
    }
    (t1, d1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stages applied to the scalar problem `y' = λ y + n` give the stability
    /// polynomial and the exact treatment of a constant source, `y⁺ = P y + Δt n (P − 1)/z`;
    /// `c_s = 1`; the reach grows as about `1.53 s²`; `|P| ≤ 0.66` on `[−β, −0.3 β]`; first
    /// order.
    #[test]
    fn stages_reproduce_the_stability_polynomial() {
        for s in 1..=ChebyshevStages::MAX_STAGES {
            let m = ChebyshevStages::new(s);
            let beta = m.real_reach();
            assert!(
                beta > 1.5 * (s * s) as f64 && beta <= 2.0 * (s * s) as f64,
                "s = {s}: β = {beta}"
            );
            for &z in &[-0.3 * beta, -0.77 * beta, -beta, -1e-3] {
                let (y0, n, dt) = (1.3, 0.7, 0.25);
                let lambda = z / dt;
                let f = |y: f64| lambda * y + n;
                let (mut prev, mut cur) = (y0, y0);
                let mut last_time = 0.0;
                for st in m.stages() {
                    let next = st.current * cur + st.previous * prev + st.tendency * dt * f(cur);
                    (prev, cur) = (cur, next);
                    last_time = st.time;
                }
                let p = m.amplification(z);
                let exact = p * y0 + dt * n * (p - 1.0) / z;
                assert!(
                    (cur - exact).abs() < 1e-10 * (1.0 + exact.abs()),
                    "s = {s}, z = {z}: {cur} against {exact}"
                );
                assert!(p.abs() < 1.0, "s = {s}, z = {z}: |P| = {}", p.abs());
                if z <= -0.3 * beta && s > 1 {
                    assert!(p.abs() < 0.66, "s = {s}, z = {z}: |P| = {}", p.abs());
                }
                assert!(
                    (last_time - 1.0).abs() < 1e-11,
                    "s = {s}: c_s = {last_time}"
                );
            }
            // First order: P(z) = 1 + z + O(z²).
            let z = 1e-5;
            assert!(
                (m.amplification(-z) - (1.0 - z)).abs() < 10.0 * (s * s * s * s) as f64 * z * z
            );
        }
    }

    #[test]
    fn the_stage_count_covers_the_step() {
        for &z in &[0.5, 2.0, 7.4, 14.9, 100.0, 2000.0] {
            let m = ChebyshevStages::for_step(z);
            assert!(
                ChebyshevStages::reach(m.count) >= z,
                "z = {z}: {} stages",
                m.count
            );
            if m.count > 1 {
                assert!(ChebyshevStages::reach(m.count - 1) < z);
            }
        }
        assert_eq!(ChebyshevStages::for_step(1.5).count, 1);
        assert_eq!(
            ChebyshevStages::for_step(1e9).count,
            ChebyshevStages::MAX_STAGES
        );
    }
}
