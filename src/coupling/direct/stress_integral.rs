//! Hydrodynamic force and torque on a sphere from the stress tensor (paper eq. 4–6).

use super::field_sampler::{FieldSampler, Interpolation};
use super::rigid_sphere::RigidSphere;
use super::sphere_quadrature::{SphereQuadrature, SphereQuadratureFamily};
use super::tuning::{QUADRATURE_EDGE_CELLS, SURFACE_OFFSET_CELLS};
use crate::Mat3;
use crate::Vec3;

/// Force and torque on one particle, SI (N, N·m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HydrodynamicLoad {
    pub force: Vec3,
    pub torque: Vec3,
}

/// Momentum (per unit density) of the fluid in the shell between a sphere and its
/// integration surface: `∫ u dV` (m⁴/s) and `∫ (x − x_p) × u dV` (m⁵/s).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShellMomentum {
    pub linear: Vec3,
    pub angular: Vec3,
}

/// Where and how the stress is integrated.
///
/// The integration surface is the sphere of radius `R = r + surface_offset · h` concentric
/// with the particle (`h` the largest cell size). By momentum balance on the fluid shell
/// `r < |x − x_p| < R`, in a frame moving with the particle,
///
/// ```text
/// F = ρ ∮_R [ −p n + ν (∇u + ∇uᵀ) n − u ((u − v_p)·n) ] dS  +  ρ b V_R  −  ρ d/dt ∫_shell u dV
/// ```
///
/// with `p` the (periodic) kinematic pressure the solver holds and `b` the uniform body force
/// on the fluid (the mean pressure gradient of a driven periodic box, `−∇⟨p⟩/ρ`): its linear
/// pressure `−ρ b·x` acts on everything inside `R` as `ρ b V_R`. At `R = r` this is paper
/// eq. 4 (`f_h = I_S + f_h0`), the flux term vanishes (rigid motion) and so does the shell;
/// off the surface the grid resolves the flow far better than on the staircase of forced
/// faces (docs/direct_model.md, "The stress integral"). The shell term is the caller's:
/// [`shell_momentum`] at two times. Torque: the same with `(x − x_p) ×` (a uniform `b`
/// gives none).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StressIntegral {
    /// Distance from the particle surface to the integration surface, in cells (≥ 0).
    pub surface_offset: f64,
    /// Interpolation of velocity and pressure to the quadrature nodes.
    pub interpolation: Interpolation,
}

impl Default for StressIntegral {
    /// The measured best (docs/direct_model.md): three cells out, tricubic.
    fn default() -> Self {
        StressIntegral {
            surface_offset: SURFACE_OFFSET_CELLS,
            interpolation: Interpolation::Cubic,
        }
    }
}

impl StressIntegral {
    /// Radius of the integration surface for a sphere of `radius` on cells of size `h`.
    pub fn surface_radius(&self, radius: f64, h: f64) -> f64 {
        radius + self.surface_offset * h
    }

    /// The shell integral's rules ([`shell_momentum`]) for a sphere of `radius` on cells of
    /// size `h`: edges of about `h` at every radius inside the surface.
    pub fn shell_rules(&self, radius: f64, h: f64) -> SphereQuadratureFamily {
        SphereQuadrature::family(self.surface_radius(radius, h), h)
    }

    /// The quadrature rule for a sphere of `radius` on cells of size `h`: quadrangles of
    /// edge about `h` (as accurate as `h/2` three cells out, at a quarter of the cost:
    /// docs/direct_model.md).
    pub fn quadrature(&self, radius: f64, h: f64) -> SphereQuadrature {
        SphereQuadrature::with_spacing(self.surface_radius(radius, h), QUADRATURE_EDGE_CELLS * h)
    }
}

/// Force and torque on `sphere` from the fluid `fields` (paper eq. 4–6, with the surface
/// and terms of [`StressIntegral`], the shell's rate of change excluded): `rho` the fluid
/// density (kg/m³), `body_force` the uniform body force on the fluid (m/s²), `quadrature`
/// from [`StressIntegral::quadrature`].
pub fn stress_integral_force(
    fields: &impl FieldSampler,
    sphere: &RigidSphere,
    rho: f64,
    body_force: [f64; 3],
    integral: &StressIntegral,
    quadrature: &SphereQuadrature,
) -> HydrodynamicLoad {
    let h = fields.cell_size();
    let radius = integral.surface_radius(sphere.radius, h);
    let nu = fields.nu();
    let (centre, v_sphere) = (sphere.centre, sphere.velocity);
    let mut force = Vec3::zeros();
    let mut torque = Vec3::zeros();
    for (&n, &w) in quadrature.points.iter().zip(&quadrature.weights) {
        let n = Vec3::from(n);
        let arm = radius * n;
        let x = centre + arm;
        let (u, g, p) = fields.velocity_gradient_and_pressure(x, integral.interpolation);
        let u = Vec3::from(u);
        // ∇u with rows i and columns j: ∂u_i/∂x_j
        let grad = Mat3::from_fn(|i, j| g[i][j]);
        // σ/ρ = −p I + ν(∇u + ∇uᵀ) (paper eq. 5), minus the momentum flux through a surface
        // that is not the sphere's own: traction t = σ·n − u ((u − v_p)·n)
        let stress = Mat3::from_diagonal_element(-p) + nu * (grad + grad.transpose());
        let traction = stress * n - u * (u - v_sphere).dot(&n);
        let weight = w * radius * radius;
        force += weight * traction;
        torque += weight * arm.cross(&traction);
    }
    let enclosed = 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
    HydrodynamicLoad {
        force: Vec3::from_fn(|i, _| rho * (force[i] + body_force[i] * enclosed)),
        torque: Vec3::from_fn(|i, _| rho * torque[i]),
    }
}

/// Momentum per unit density of the fluid between `sphere` and its integration surface,
/// by 2-point Gauss–Legendre in radius times, at each radius, the rule of `rules` with
/// quadrangle edges of about `h` there (as the surface's; zero when the surface is the
/// sphere itself). Trilinear whatever the surface's interpolation: the shell term is a small
/// correction (its rate of change), and this keeps it at an eighth of the cost.
pub fn shell_momentum(
    fields: &impl FieldSampler,
    sphere: &RigidSphere,
    integral: &StressIntegral,
    rules: &SphereQuadratureFamily,
) -> ShellMomentum {
    let h = fields.cell_size();
    let (r0, r1) = (sphere.radius, integral.surface_radius(sphere.radius, h));
    let mut out = ShellMomentum::default();
    if r1 <= r0 {
        return out;
    }
    let half = 0.5 * (r1 - r0);
    let mid = 0.5 * (r1 + r0);
    let node = 1.0 / 3.0f64.sqrt();
    let gauss = [(-node, 1.0), (node, 1.0)];
    for (xi, wr) in gauss {
        let rad = mid + half * xi;
        let radial_weight = wr * half * rad * rad;
        let quadrature = rules.at(rad);
        for (&n, &w) in quadrature.points.iter().zip(&quadrature.weights) {
            let arm = Vec3::new(rad * n[0], rad * n[1], rad * n[2]);
            let x = Vec3::from_fn(|d, _| sphere.centre[d] + arm[d]);
            let u = fields.velocity_at(x, Interpolation::Linear);
            let moment = arm.cross(&u);
            for i in 0..3 {
                out.linear[i] += radial_weight * w * u[i];
                out.angular[i] += radial_weight * w * moment[i];
            }
        }
    }
    out
}
