//! A box case written by a test and run as `fsimFoam` runs it: the case files in a scratch
//! folder, loaded by [`Case::load`] and built by [`Simulation::new`], then stepped by
//! [`Simulation::step`]. For set-ups a tutorial does not hold (the settling spheres of
//! `settler.rs`, the sphere between walls of `slit.rs`).
#![allow(dead_code)]

use fsim::case::Case;
use fsim::fluid::TimeScheme;
use fsim::simulation::{Simulation, StepSizing};
use std::fs;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A box of `cells` cells of size `h`, periodic but where `walls` says (per axis: the low and
/// high faces are no-slip walls moving at `wall_velocity`), spheres of one diameter.
pub struct BoxCase {
    pub cells: [usize; 3],
    pub h: f64,
    pub walls: [bool; 3],
    pub wall_velocity: [f64; 3],
    /// `(rho_f, nu)`: kg/m³, m²/s.
    pub fluid: (f64, f64),
    pub gravity: [f64; 3],
    pub scheme: TimeScheme,
    pub initial_velocity: [f64; 3],
    /// `meanVelocityForce`'s `Ubar` (constant/fvOptions), when the flow is driven.
    pub mean_velocity: Option<[f64; 3]>,
    /// The body of `constant/couplingProperties`.
    pub coupling: String,
    /// Sphere centres, their diameter and density.
    pub spheres: Vec<[f64; 3]>,
    pub diameter: f64,
    pub rho_p: f64,
    /// Normal stiffness of the soft contacts, N/m.
    pub kn: f64,
}

static CASES: AtomicUsize = AtomicUsize::new(0);

impl BoxCase {
    /// The simulation of this case, built as `fsimFoam` builds it; steps are set by the
    /// caller ([`step`]), the run's own end and writes are far off.
    pub fn simulation(&self) -> Simulation {
        let dir = std::env::temp_dir().join(format!(
            "fsim-box-case-{}-{}",
            std::process::id(),
            CASES.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = fs::remove_dir_all(&dir);
        self.write(&dir);
        // The caller sets the steps: the run's own end (10¹⁸ steps of 1 ns) is planned past
        // fsimFoam's default limits on purpose, which this test process lifts.
        fsim::case::control_dict::set_plan_limits(fsim::case::control_dict::PlanLimits {
            steps: f64::INFINITY,
            writes: f64::INFINITY,
        });
        let case = Case::load(&dir).unwrap_or_else(|e| panic!("the test's case: {e}"));
        let sim = Simulation::new(&case, None).unwrap_or_else(|e| panic!("{e}"));
        // The simulation holds everything it read; it writes nothing unless asked.
        let _ = fs::remove_dir_all(&dir);
        sim
    }

    fn write(&self, dir: &Path) {
        let file = |rel: &str, class: &str, body: String| {
            let path = dir.join(rel);
            fs::create_dir_all(path.parent().unwrap()).unwrap();
            let object = Path::new(rel).file_name().unwrap().to_string_lossy();
            let header = format!(
                "FoamFile {{ version 2.0; format ascii; class {class}; object {object}; }}\n"
            );
            fs::write(path, header + &body).unwrap();
        };
        file(
            "system/controlDict",
            "dictionary",
            "application fsimFoam; startFrom startTime; startTime 0; stopAt endTime; \
             endTime 1e9; deltaT 1e-9; writeControl timeStep; writeInterval 1000000000;\n"
                .to_string(),
        );
        file(
            "system/fvSolution",
            "dictionary",
            format!("fsim {{ timeScheme {}; }}\n", self.scheme.name()),
        );
        let l: [f64; 3] = std::array::from_fn(|a| self.cells[a] as f64 * self.h);
        // faces by axis: (low, high) as blockMesh names their vertices
        let faces = [
            ("(0 4 7 3)", "(1 2 6 5)"),
            ("(0 1 5 4)", "(3 7 6 2)"),
            ("(0 3 2 1)", "(4 5 6 7)"),
        ];
        let names = [("left", "right"), ("bottom", "top"), ("back", "front")];
        let mut boundary = String::new();
        for a in 0..3 {
            let ((lo, hi), (f_lo, f_hi)) = (names[a], faces[a]);
            if self.walls[a] {
                boundary += &format!("{lo} {{ type wall; faces ({f_lo}); }}\n");
                boundary += &format!("{hi} {{ type wall; faces ({f_hi}); }}\n");
            } else {
                boundary +=
                    &format!("{lo} {{ type cyclic; neighbourPatch {hi}; faces ({f_lo}); }}\n");
                boundary +=
                    &format!("{hi} {{ type cyclic; neighbourPatch {lo}; faces ({f_hi}); }}\n");
            }
        }
        file(
            "system/blockMeshDict",
            "dictionary",
            format!(
                "scale 1;\nvertices ((0 0 0) ({x:e} 0 0) ({x:e} {y:e} 0) (0 {y:e} 0) (0 0 {z:e}) \
                 ({x:e} 0 {z:e}) ({x:e} {y:e} {z:e}) (0 {y:e} {z:e}));\nblocks (hex (0 1 2 3 4 5 \
                 6 7) ({} {} {}) simpleGrading (1 1 1));\nboundary (\n{boundary});\n",
                self.cells[0],
                self.cells[1],
                self.cells[2],
                x = l[0],
                y = l[1],
                z = l[2],
            ),
        );
        let (rho_f, nu) = self.fluid;
        file(
            "constant/transportProperties",
            "dictionary",
            format!("continuousPhase fluid; rho.fluid {rho_f:e}; nu {nu:e};\n"),
        );
        let v = |x: [f64; 3]| format!("({:e} {:e} {:e})", x[0], x[1], x[2]);
        file(
            "constant/g",
            "uniformDimensionedVectorField",
            format!("dimensions [0 1 -2 0 0 0 0]; value {};\n", v(self.gravity)),
        );
        // Each patch's condition: cyclic, or `wall` on the walls' axes.
        let boundary_field = |wall: &str| {
            let mut text = String::new();
            for (&walled, (lo, hi)) in self.walls.iter().zip(names) {
                let body = if walled { wall } else { "type cyclic;" };
                text += &format!("{lo} {{ {body} }} {hi} {{ {body} }}\n");
            }
            text
        };
        let wall_u = format!("type fixedValue; value uniform {};", v(self.wall_velocity));
        file(
            "0/U.fluid",
            "volVectorField",
            format!(
                "dimensions [0 1 -1 0 0 0 0]; internalField uniform {};\nboundaryField {{\n{}}}\n",
                v(self.initial_velocity),
                boundary_field(&wall_u)
            ),
        );
        file(
            "0/p",
            "volScalarField",
            format!(
                "dimensions [0 2 -2 0 0 0 0]; internalField uniform 0;\nboundaryField {{\n{}}}\n",
                boundary_field("type zeroGradient;")
            ),
        );
        if let Some(ubar) = self.mean_velocity {
            file(
                "constant/fvOptions",
                "dictionary",
                format!(
                    "drive {{ type meanVelocityForce; selectionMode all; fields (U.fluid); \
                     Ubar {}; }}\n",
                    v(ubar)
                ),
            );
        }
        file(
            "constant/couplingProperties",
            "dictionary",
            self.coupling.clone(),
        );
        let positions: String = self.spheres.iter().map(|x| v(*x) + "\n").collect();
        file(
            "constant/kinematicCloudPositions",
            "vectorField",
            format!("(\n{positions})\n"),
        );
        let (d, rho_p, kn) = (self.diameter, self.rho_p, self.kn);
        let contact = format!("kn {kn:e}; e 0.5; mu 0.3; collisionResolutionSteps 20;");
        let wall_model = if self.walls.contains(&true) {
            "patchInteractionModel standardWallInteraction; standardWallInteractionCoeffs { \
             type rebound; e 0.5; mu 0.3; }"
        } else {
            "patchInteractionModel none;"
        };
        file(
            "constant/kinematicCloudProperties",
            "dictionary",
            format!(
                "solution {{ active true; coupled true; transient yes; }}\n\
                 constantProperties {{ rho0 {rho_p:e}; }}\n\
                 subModels {{\n\
                   particleForces {{ gravity; }}\n\
                   injectionModels {{ spheres {{ type manualInjection; massTotal 0; \
                     parcelBasisType fixed; nParticle 1; SOI 0; positionsFile \
                     \"kinematicCloudPositions\"; U0 (0 0 0); sizeDistribution {{ type \
                     fixedValue; fixedValueDistribution {{ value {d:e}; }} }} }} }}\n\
                   dispersionModel none;\n\
                   {wall_model}\n\
                   collisionModel pairCollision;\n\
                   pairCollisionCoeffs {{ maxInteractionDistance {d:e}; \
                     pairModel pairLinearSpringDashpot; pairLinearSpringDashpotCoeffs {{ \
                     {contact} }} wallModel wallLinearSpringDashpot; \
                     wallLinearSpringDashpotCoeffs {{ {contact} }} }}\n\
                 }}\n"
            ),
        );
    }
}

/// One step of `dt` as `fsimFoam` takes it.
pub fn step(sim: &mut Simulation, dt: f64) {
    sim.sizing = StepSizing::Fixed(dt);
    sim.step().unwrap_or_else(|e| panic!("{e}"));
}
