//! What `model auto` reads from a case to predict each candidate's error and cost.

use crate::case::cloud_properties::Cloud;
use crate::case::{Case, InternalField, VelocityBc};
use crate::error::FsimError;

/// The case as the error and cost models see it.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The block's side lengths, m.
    pub lengths: [f64; 3],
    pub particles: usize,
    pub d_min: f64,
    pub d_max: f64,
    /// The particles' volume over the volume they occupy: the domain's period along periodic
    /// axes, their bounding box grown by a radius on each side along the others (a bed's
    /// solid fraction, not the column's).
    pub phi: f64,
    /// The particle Reynolds number `U d / ν` of the largest particle, `U` the driven flow's
    /// velocity when there is one, else the settling velocity.
    pub reynolds: f64,
    /// Every particle held in place (`fixedParticles yes` in `direct` or `dragLawCoeffs`).
    pub fixed: bool,
    pub nu: f64,
    pub rho_fluid: f64,
    /// The heaviest particle's density, kg/m³.
    pub rho_particle: f64,
    /// The velocity that sets the Courant bound, m/s: the largest of `meanVelocityForce`'s
    /// `Ubar`, a fixed or inlet boundary velocity, and the settling velocity of the largest
    /// particle (Stokes', or Newton's with C_d = 0.44 when smaller).
    pub velocity: f64,
    /// The simulated time, s.
    pub duration: f64,
    /// Every initial field is uniform (the grid may then change).
    pub uniform_fields: bool,
}

impl Scene {
    /// The scene of `case` with its `cloud` (read for either model).
    pub fn from_case(case: &Case, cloud: &Cloud) -> Result<Scene, FsimError> {
        let p = &cloud.particles;
        let n = p.len();
        if n == 0 {
            return Err(FsimError::input(
                "constant/couplingProperties: model auto needs particles; the cloud has none",
            ));
        }
        let grid = &case.mesh.grid;
        let lengths = grid.length();
        let (mut d_min, mut d_max, mut solid, mut rho_p) = (f64::INFINITY, 0.0f64, 0.0, 0.0f64);
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for i in 0..n {
            let d = p.diameter[i];
            d_min = d_min.min(d);
            d_max = d_max.max(d);
            solid += std::f64::consts::PI / 6.0 * d * d * d;
            rho_p = rho_p.max(p.density[i]);
            for a in 0..3 {
                lo[a] = lo[a].min(p.position[i][a] - 0.5 * d);
                hi[a] = hi[a].max(p.position[i][a] + 0.5 * d);
            }
        }
        let mut occupied = 1.0;
        for a in 0..3 {
            let (start, end) = (grid.origin[a], grid.origin[a] + lengths[a]);
            occupied *= if cloud.domain.is_periodic(a) {
                lengths[a]
            } else {
                (hi[a].min(end) - lo[a].max(start)).max(d_max.min(lengths[a]))
            };
        }
        let nu = case.transport.nu;
        let rho_f = case.transport.rho;
        let fixed = case.coupling.direct.fixed_particles
            || cloud.drag_law.as_ref().is_some_and(|o| o.fixed_particles);
        let g = norm(case.gravity);
        let stokes = if fixed {
            0.0
        } else {
            let reduced = (rho_p / rho_f - 1.0).abs() * g;
            let newton = (4.0 * reduced * d_max / (3.0 * 0.44)).sqrt();
            (reduced * d_max * d_max / (18.0 * nu)).min(newton)
        };
        let mut flow: f64 = 0.0;
        for f in &case.mean_velocity_forces {
            flow = flow.max(norm(f.ubar));
        }
        for bc in &case.fields.u_bc {
            let v = match bc {
                VelocityBc::FixedValue(v) | VelocityBc::InletOutlet { inlet_value: v } => *v,
                VelocityBc::InterstitialInletVelocity { inlet_velocity, .. } => *inlet_velocity,
                _ => [0.0; 3],
            };
            flow = flow.max(norm(v));
        }
        let velocity = flow.max(stokes);
        let relative = if flow > 0.0 { flow } else { stokes };
        let uniform_fields = matches!(case.fields.u, InternalField::Uniform(_))
            && matches!(case.fields.p, InternalField::Uniform(_));
        Ok(Scene {
            lengths,
            particles: n,
            d_min,
            d_max,
            phi: (solid / occupied).min(0.74),
            reynolds: relative * d_max / nu,
            fixed,
            nu,
            rho_fluid: rho_f,
            rho_particle: rho_p,
            velocity,
            duration: case.control.end_time - case.control.start_time,
            uniform_fields,
        })
    }
}

fn norm(v: [f64; 3]) -> f64 {
    crate::Vec3::from(v).norm()
}
