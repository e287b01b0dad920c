//! DPMFoam's Goldschmidt tutorial (Debian's `openfoam-examples`, read in place when installed,
//! never copied): its cloud loads into the DEM engine's types with the coefficients of its
//! `constant/kinematicCloudProperties`, checked here by hand against that file.

use fsim::Vec3;
use std::path::Path;

use fsim::case::{Case, Cloud};
use fsim::particles::{Dem, FaceCondition, PairModel, TangentialRule, WallModel};

const GOLDSCHMIDT: &str =
    "/usr/share/doc/openfoam-examples/examples/lagrangian/DPMFoam/Goldschmidt";

#[test]
fn goldschmidt_cloud_maps_onto_the_engine() {
    let dir = Path::new(GOLDSCHMIDT);
    if !dir.is_dir() {
        println!(
            "note: {GOLDSCHMIDT} is absent; install Debian's openfoam-examples to run this test"
        );
        return;
    }
    let case = Case::load(dir).unwrap_or_else(|e| panic!("{}", e.report()));
    let cloud = Cloud::from_case(&case)
        .unwrap_or_else(|e| panic!("{}", e.report()))
        .expect("an active cloud");
    // kinematicCloudPositions.gz: 24,750 lines of (x y z) between '(' and ')'
    let p = &cloud.particles;
    assert_eq!(p.len(), 24_750);
    assert_eq!(p.position[0], Vec3::new(-0.0060, -0.0735, 0.0015));
    assert_eq!(p.position[24_749], Vec3::new(0.0060, 0.0735, 0.2955));
    let (line, col) = cloud.origins[0].line_col();
    assert_eq!((line, col), (18, 1));
    // constantProperties { rho0 2526; }, fixedValueDistribution { value 0.0025; }, U0 (0 0 0)
    assert!(p.diameter.iter().all(|&d| d == 0.0025));
    assert!(p.density.iter().all(|&r| r == 2526.0));
    assert!(p.velocity.iter().all(|&v| v == Vec3::repeat(0.0)));
    assert_eq!(p.id[24_749], 24_749);
    // pairSpringSliderDashpotCoeffs { alpha 0.02; b 1.5; mu 0.10; collisionResolutionSteps 12; }
    // with the particle's youngsModulus 1e8, poissonsRatio 0.35; DPMFoam's tangential reset
    assert_eq!(
        cloud.config.pair_model,
        PairModel::SpringSliderDashpot {
            youngs_modulus: 1e8,
            poissons_ratio: 0.35,
            alpha: 0.02,
            b: 1.5,
            mu: 0.10,
            collision_resolution_steps: 12.0,
            tangential: TangentialRule::DpmFoamReset,
        }
    );
    // wallSpringSliderDashpotCoeffs { youngsModulus 1e8; poissonsRatio 0.23; alpha 0.01; b 1.5;
    // mu 0.09; collisionResolutionSteps 12; }
    assert_eq!(
        cloud.config.wall_model,
        WallModel::SpringSliderDashpot {
            youngs_modulus: 1e8,
            poissons_ratio: 0.23,
            particle_youngs_modulus: 1e8,
            particle_poissons_ratio: 0.35,
            alpha: 0.01,
            b: 1.5,
            mu: 0.09,
            collision_resolution_steps: 12.0,
            tangential: TangentialRule::DpmFoamReset,
        }
    );
    // particleForces { ErgunWenYuDrag {…} gravity; }: gravity from constant/g, buoyancy in air
    assert_eq!(cloud.forces, ["ErgunWenYuDrag", "gravity"]);
    assert_eq!(cloud.config.gravity, Vec3::new(0.0, 0.0, -9.81));
    assert_eq!(cloud.config.fluid_density, 1.2);
    // walls (top, bottom, walls) are soft walls of the wall model; frontAndBack (symmetry)
    // rebounds with its localInteraction coefficients e 0.97, mu 0.09
    let rebound = FaceCondition::Rebound { e: 0.97, mu: 0.09 };
    assert_eq!(
        cloud.domain.faces,
        [
            rebound,
            rebound,
            FaceCondition::Wall,
            FaceCondition::Wall,
            FaceCondition::Wall,
            FaceCondition::Wall
        ]
    );
    assert_eq!(cloud.domain.lo, Vec3::new(-0.0075, -0.075, 0.0));
    assert!((cloud.domain.hi[2] - 0.45).abs() < 1e-15);
    // OpenFOAM settings fsim does not use are listed, each once
    assert!(cloud
        .warnings
        .iter()
        .any(|w| w.contains("ignored keyword 'constantProperties.parcelTypeId'")));
    // the drag-law settings (model dragLaw: no couplingProperties) are read, not listed
    assert!(cloud.drag_law.is_some());
    assert!(!cloud
        .warnings
        .iter()
        .any(|w| w.contains("interpolationSchemes") || w.contains("alphaMax")));
    // the particles are a valid engine input: no overlaps, all inside (3 mm spacing, d 2.5 mm)
    let dem = Dem::new(
        cloud.config.clone(),
        cloud.domain.clone(),
        cloud.particles.clone(),
    )
    .unwrap_or_else(|e| panic!("{}", cloud.locate(&e)));
    assert_eq!(dem.max_overlap_ratio(), 0.0);
}
