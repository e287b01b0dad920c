//! The unit sphere split into quadrangles, with the trapezoidal rule on each (paper eq. 6).

/// Quadrature on the unit sphere: a cubed sphere of `6 m²` quadrangles (each face of a cube
/// split into `m × m` by equal angles, then projected radially), integrated by the
/// trapezoidal rule on every quadrangle: `∫_Q f dS ≈ |Q| (f₁ + f₂ + f₃ + f₄) / 4` with `|Q|`
/// the exact spherical area (paper eq. 6; second order in the quadrangle size).
///
/// Corners shared by neighbouring quadrangles of one cube face are merged, so the rule is a
/// list of points with weights (`Σ w = 4π` to round-off). The equal-angle split keeps the
/// quadrangles within a factor 1.3 of each other in size, where a latitude–longitude split
/// crowds the poles.
#[derive(Clone, Debug, PartialEq)]
pub struct SphereQuadrature {
    /// Unit vectors (outward normals) of the nodes.
    pub points: Vec<[f64; 3]>,
    /// Weights, summing to `4π`.
    pub weights: Vec<f64>,
    /// Quadrangles per cube-face edge.
    pub per_edge: usize,
}

impl SphereQuadrature {
    /// `6 m²` quadrangles, `m = per_edge ≥ 1`.
    pub fn cubed(per_edge: usize) -> Self {
        let m = per_edge.max(1);
        let nodes = (m + 1) * (m + 1);
        let mut points = Vec::with_capacity(6 * nodes);
        let mut weights = Vec::with_capacity(6 * nodes);
        let angle = |i: usize| (i as f64 / m as f64 - 0.5) * std::f64::consts::FRAC_PI_2;
        for face in 0..6 {
            let axis = face / 2;
            let sign = if face % 2 == 0 { 1.0 } else { -1.0 };
            let base = points.len();
            for b in 0..=m {
                for a in 0..=m {
                    let (ta, tb) = (angle(a).tan(), angle(b).tan());
                    let mut p = [0.0; 3];
                    p[axis] = sign;
                    p[(axis + 1) % 3] = ta;
                    p[(axis + 2) % 3] = tb;
                    let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                    points.push([p[0] / norm, p[1] / norm, p[2] / norm]);
                    weights.push(0.0);
                }
            }
            for b in 0..m {
                for a in 0..m {
                    let corner = [
                        base + a + (m + 1) * b,
                        base + a + 1 + (m + 1) * b,
                        base + a + 1 + (m + 1) * (b + 1),
                        base + a + (m + 1) * (b + 1),
                    ];
                    let q = corner.map(|i| points[i]);
                    let area = triangle_area(q[0], q[1], q[2]) + triangle_area(q[0], q[2], q[3]);
                    for &i in &corner {
                        weights[i] += 0.25 * area;
                    }
                }
            }
        }
        merge_shared_nodes(&mut points, &mut weights, m);
        // Lexicographic in (z, y, x): consecutive nodes on a sphere read neighbouring grid
        // samples, which the caches then still hold.
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&i, &j| {
            let (a, b) = (points[i], points[j]);
            (a[2], a[1], a[0]).partial_cmp(&(b[2], b[1], b[0])).unwrap()
        });
        SphereQuadrature {
            points: order.iter().map(|&i| points[i]).collect(),
            weights: order.iter().map(|&i| weights[i]).collect(),
            per_edge: m,
        }
    }

    /// The rule whose quadrangles have edges of about `spacing` on a sphere of `radius`
    /// (a cube-face edge spans a quarter great circle, `π R / 2`).
    pub fn with_spacing(radius: f64, spacing: f64) -> Self {
        let m = (std::f64::consts::FRAC_PI_2 * radius / spacing).ceil() as usize;
        Self::cubed(m.max(2))
    }

    /// The rules of [`Self::with_spacing`] for every radius up to `radius`, by edge count.
    pub fn family(radius: f64, spacing: f64) -> SphereQuadratureFamily {
        let largest = Self::with_spacing(radius, spacing).per_edge;
        SphereQuadratureFamily {
            spacing,
            rules: (0..=largest).map(|m| Self::cubed(m.max(2))).collect(),
        }
    }

    /// Number of quadrangles, `6 m²`.
    pub fn quadrangles(&self) -> usize {
        6 * self.per_edge * self.per_edge
    }
}

/// [`SphereQuadrature::with_spacing`] for radii up to a largest one, built once (the shell
/// integral's radii change with each sphere's surface offset).
#[derive(Clone, Debug, PartialEq)]
pub struct SphereQuadratureFamily {
    spacing: f64,
    /// Indexed by quadrangles per cube-face edge.
    rules: Vec<SphereQuadrature>,
}

impl SphereQuadratureFamily {
    /// The rule with edges of about the family's spacing on a sphere of `radius` (the
    /// largest rule beyond the family's radius).
    pub fn at(&self, radius: f64) -> &SphereQuadrature {
        let m = (std::f64::consts::FRAC_PI_2 * radius / self.spacing).ceil() as usize;
        &self.rules[m.clamp(2, self.rules.len() - 1)]
    }
}

/// Merges the nodes on the cube's edges, which two (three at the corners) faces hold,
/// into one with the summed weight: the sampling cost of a rule is its node count.
/// `points` hold the faces' `(m + 1)²` nodes each, in face order.
fn merge_shared_nodes(points: &mut Vec<[f64; 3]>, weights: &mut Vec<f64>, m: usize) {
    let side = m + 1;
    let on_edge = |i: usize| {
        let (a, b) = (i % side, (i / side) % side);
        a == 0 || a == m || b == 0 || b == m
    };
    let close = |p: [f64; 3], q: [f64; 3]| (0..3).all(|d| (p[d] - q[d]).abs() < 1e-12);
    let mut keep = vec![true; points.len()];
    for i in (0..points.len()).filter(|&i| on_edge(i)) {
        if !keep[i] {
            continue;
        }
        for j in (i + 1..points.len()).filter(|&j| on_edge(j)) {
            if keep[j] && close(points[i], points[j]) {
                weights[i] += weights[j];
                keep[j] = false;
            }
        }
    }
    let mut k = 0;
    for i in 0..points.len() {
        if keep[i] {
            points[k] = points[i];
            weights[k] = weights[i];
            k += 1;
        }
    }
    points.truncate(k);
    weights.truncate(k);
}

/// Area of the spherical triangle of unit vectors `a, b, c` (Van Oosterom & Strackee 1983:
/// `tan(E/2) = |a·(b×c)| / (1 + a·b + b·c + c·a)`).
fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let cross = [
        b[1] * c[2] - b[2] * c[1],
        b[2] * c[0] - b[0] * c[2],
        b[0] * c[1] - b[1] * c[0],
    ];
    let triple = dot(a, cross).abs();
    2.0 * triple.atan2(1.0 + dot(a, b) + dot(b, c) + dot(c, a))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn integrate(q: &SphereQuadrature, f: impl Fn([f64; 3]) -> f64) -> f64 {
        q.points
            .iter()
            .zip(&q.weights)
            .map(|(&p, &w)| w * f(p))
            .sum()
    }

    #[test]
    fn weights_sum_to_the_sphere_area_and_second_moments_converge_at_second_order() {
        let mut errors = Vec::new();
        for m in [4, 8, 16] {
            let q = SphereQuadrature::cubed(m);
            assert_eq!(q.quadrangles(), 6 * m * m);
            // Euler: V − E + F = 2 with F = 6m², E = 12m² (each node shared once).
            assert_eq!(q.points.len(), 6 * m * m + 2);
            assert!((integrate(&q, |_| 1.0) - 4.0 * PI).abs() < 1e-12);
            // Odd moments vanish by symmetry; second moments are exact (cube symmetry).
            assert!(integrate(&q, |p| p[0]).abs() < 1e-12);
            assert!((integrate(&q, |p| p[2] * p[2]) - 4.0 * PI / 3.0).abs() < 1e-12);
            // ∫ exp(a·n) dS = 4π sinh|a| / |a|
            let a = [0.6, -0.3, 0.2f64];
            let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            let exact = 4.0 * PI * norm.sinh() / norm;
            errors.push(
                (integrate(&q, |p| (a[0] * p[0] + a[1] * p[1] + a[2] * p[2]).exp()) - exact).abs(),
            );
            // ∫ x⁴ dS = 4π/5
            errors.push((integrate(&q, |p| p[0].powi(4)) - 4.0 * PI / 5.0).abs());
        }
        // Each halving of the quadrangles divides the error by at least 3.5 (order ≥ 1.8).
        for k in 0..2 {
            for moment in 0..2 {
                let (coarse, fine) = (errors[2 * k + moment], errors[2 * k + 2 + moment]);
                assert!(coarse / fine > 3.5, "{errors:?}");
            }
        }
        assert_eq!(SphereQuadrature::with_spacing(1.0, 0.1).per_edge, 16);
        let family = SphereQuadrature::family(1.0, 0.1);
        for radius in [0.05, 0.3, 0.77, 1.0] {
            assert_eq!(
                family.at(radius),
                &SphereQuadrature::with_spacing(radius, 0.1)
            );
        }
    }
}
