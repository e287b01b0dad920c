//! `fsimFoam` with a particle cloud (`model none`): a contact-rich settling restarts bit for
//! bit, and bad cloud input stops with exit code 2, naming the particle or the keyword with
//! file, line and column, before anything is written.

use crate::support::*;
use fsim::Vec3;
use std::fs;
use std::path::{Path, PathBuf};

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The settling tutorial shortened to 60 ms (the bed is still collapsing: every bead moves
/// and the lower ones are in contact), restarted at 30 ms.
#[test]
fn settling_cloud_restarts_bit_for_bit() {
    let (end, half) = ("0.06", "0.03");
    let scratch = Scratch::new("cloud-restart");
    let whole = copy_tutorial("particleSettling", &scratch.0, "whole");
    let split = copy_tutorial("particleSettling", &scratch.0, "split");
    for case in [&whole, &split] {
        set_entry(&case.join("system/controlDict"), "endTime", end);
        set_entry(&case.join("system/controlDict"), "writeInterval", half);
    }
    let out = fsim(&whole, &["-threads", "2"]);
    assert!(out.status.success(), "{}", stderr(&out));

    let control = split.join("system/controlDict");
    set_entry(&control, "endTime", half);
    let out = fsim(&split, &["-threads", "2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    set_entry(&control, "endTime", end);
    set_entry(&control, "startFrom", "latestTime");
    let out = fsim(&split, &["-threads", "2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(split.join("postProcessing/cloud").join(half).is_dir());

    // contact-rich at the restart: overlaps and many beads in motion
    let monitor = fs::read_to_string(whole.join("postProcessing/cloud/0/cloud.dat")).unwrap();
    let row: Vec<f64> = monitor
        .lines()
        .find(|l| l.starts_with(half))
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(row[7] > 1e-3, "max overlap / d {} at the restart", row[7]);
    assert!(row[2] > 1e-6, "kinetic energy {} at the restart", row[2]);

    for file in ["restart.bin", "particles.vtu", "fluid.vtk"] {
        let a = fs::read(whole.join(end).join(file)).unwrap();
        let b = fs::read(split.join(end).join(file)).unwrap();
        assert!(a == b, "{end}/{file} differs after a restart");
    }
}

/// The tutorial with its injection replaced by `injection` (the text between
/// `injectionModels` and `dispersionModel`), and a positions file.
fn cloud_case(scratch: &Scratch, tag: &str, injection: &str, positions: &str) -> PathBuf {
    let case = copy_tutorial("particleSettling", &scratch.0, tag);
    let props = case.join("constant/kinematicCloudProperties");
    let text = fs::read_to_string(&props).unwrap();
    let (a, b) = (
        text.find("    injectionModels").unwrap(),
        text.find("    dispersionModel").unwrap(),
    );
    let text = format!("{}{injection}\n{}", &text[..a], &text[b..]);
    fs::write(&props, text).unwrap();
    fs::write(case.join("constant/kinematicCloudPositions"), positions).unwrap();
    case
}

const MANUAL: &str = "    injectionModels
    {
        model1
        {
            type            manualInjection;
            parcelBasisType fixed;
            nParticle       1;
            SOI             0;
            positionsFile   \"kinematicCloudPositions\";
            U0              (0 0 0);
            sizeDistribution
            {
                type        fixedValue;
                fixedValueDistribution
                {
                    value   0.002;
                }
            }
        }
    }";

const POSITIONS_HEAD: &str = "FoamFile
{
    version     2.0;
    format      ascii;
    class       vectorField;
    object      kinematicCloudPositions;
}
(
(0.005 0.005 0.005)
(0.010 0.005 0.005)
";

/// Runs the case, expects exit code 2 with nothing written, returns stderr.
fn rejected(case: &Path) -> String {
    let out = fsim(case, &[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(listing(case), ["0", "constant", "system"], "{err}");
    assert_eq!(listing(&case.join("0")), ["U.air", "p"], "{err}");
    err
}

#[test]
fn bad_cloud_input_is_named_and_nothing_is_written() {
    let scratch = Scratch::new("cloud-errors");

    // a manual injection that is fine runs (the control for the cases below)
    let good = cloud_case(
        &scratch,
        "good",
        MANUAL,
        &format!("{POSITIONS_HEAD}(0.015 0.005 0.005) 12 40 2\n)\n"),
    );
    let out = fsim(&good, &["-dry-run"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        String::from_utf8_lossy(&out.stdout).contains("Cloud   : 3 particles"),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );

    // collisionModel none: particles pass through each other, overlaps are allowed
    let case = cloud_case(
        &scratch,
        "noCollision",
        MANUAL,
        &format!("{POSITIONS_HEAD}(0.0119 0.005 0.005)\n)\n"),
    );
    let props = case.join("constant/kinematicCloudProperties");
    let text = fs::read_to_string(&props).unwrap();
    fs::write(
        &props,
        text.replace("collisionModel pairCollision;", "collisionModel none;"),
    )
    .unwrap();
    let out = fsim(&case, &["-dry-run"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        String::from_utf8_lossy(&out.stdout)
            .contains("3 particles; pairModel none, wallModel none"),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );

    // overlapping initial particles: the second line is 1.9 mm from the first
    let case = cloud_case(
        &scratch,
        "overlap",
        MANUAL,
        &format!("{POSITIONS_HEAD}(0.0119 0.005 0.005)\n)\n"),
    );
    let err = rejected(&case);
    assert!(
        err.contains("constant/kinematicCloudPositions:10:1: particles 1 (id 1) and 2 (id 2) overlap by 5.000e-2"),
        "{err}"
    );
    assert!(
        err.contains("the other one is defined at constant/kinematicCloudPositions:11:1"),
        "{err}"
    );

    // a particle outside the box
    let case = cloud_case(
        &scratch,
        "outside",
        MANUAL,
        &format!("{POSITIONS_HEAD}(0.015 0.030 0.005)\n)\n"),
    );
    let err = rejected(&case);
    assert!(
        err.contains("constant/kinematicCloudPositions:11:1: particle 2 (id 2): centre (0.015 0.03 0.005) lies outside the domain"),
        "{err}"
    );

    // a negative diameter
    let case = cloud_case(
        &scratch,
        "diameter",
        &MANUAL.replace("value   0.002;", "value   -0.002;"),
        &format!("{POSITIONS_HEAD})\n"),
    );
    let err = rejected(&case);
    assert!(
        err.contains("constant/kinematicCloudProperties:")
            && err.contains("'value' = -0.002: expected a diameter > 0"),
        "{err}"
    );

    // an unknown injection model
    let case = cloud_case(
        &scratch,
        "injection",
        &MANUAL.replace("manualInjection", "patchInjection"),
        &format!("{POSITIONS_HEAD})\n"),
    );
    let err = rejected(&case);
    assert!(
        err.contains("expected one of manualInjection, randomPacking for 'type', found the word 'patchInjection'"),
        "{err}"
    );

    // an unknown contact model
    let case = copy_tutorial("particleSettling", &scratch.0, "contact");
    let props = case.join("constant/kinematicCloudProperties");
    let text = fs::read_to_string(&props).unwrap();
    fs::write(
        &props,
        text.replace(
            "pairModel pairLinearSpringDashpot;",
            "pairModel hertzMindlin;",
        ),
    )
    .unwrap();
    let err = rejected(&case);
    let line = text
        .lines()
        .position(|l| l.contains("pairModel pairLinearSpringDashpot"))
        .unwrap()
        + 1;
    assert!(
        err.contains(&format!("constant/kinematicCloudProperties:{line}:19: expected one of pairSpringSliderDashpot, pairLinearSpringDashpot for 'pairModel', found the word 'hertzMindlin'")),
        "{err}"
    );

    // a setting that changes the physics and that fsim does not implement: cohesion
    let case = copy_tutorial("particleSettling", &scratch.0, "cohesion");
    let props = case.join("constant/kinematicCloudProperties");
    let text = fs::read_to_string(&props)
        .unwrap()
        .replace(
            "pairModel pairLinearSpringDashpot;",
            "pairModel pairSpringSliderDashpot;",
        )
        .replace(
            "rho0            2500;",
            "rho0 2500; youngsModulus 1e7; poissonsRatio 0.3;",
        )
        .replace(
            "wallModel wallLinearSpringDashpot;",
            "pairSpringSliderDashpotCoeffs { alpha 0.1; b 1.5; mu 0.3; \
             collisionResolutionSteps 12; cohesionEnergyDensity 10; }\n        \
             wallModel wallLinearSpringDashpot;",
        );
    fs::write(&props, &text).unwrap();
    let err = rejected(&case);
    assert!(
        err.contains("cohesionEnergyDensity 10: cohesion is not supported by fsim"),
        "{err}"
    );

    // OpenFOAM's ramp of pair forces after injection, which fsim does not implement
    let case = copy_tutorial("particleSettling", &scratch.0, "ramp");
    let props = case.join("constant/kinematicCloudProperties");
    fs::write(
        &props,
        text.replace("cohesionEnergyDensity 10;", "forceRampTime 0.01;"),
    )
    .unwrap();
    let err = rejected(&case);
    assert!(
        err.contains(
            "forceRampTime 0.01: the ramp of pair forces after injection is not supported"
        ),
        "{err}"
    );

    // a negative start of injection: OpenFOAM would inject nothing
    let case = cloud_case(
        &scratch,
        "negativeSoi",
        &MANUAL.replace("SOI             0;", "SOI             -1e-4;"),
        &format!("{POSITIONS_HEAD})\n"),
    );
    let err = rejected(&case);
    assert!(
        err.contains("SOI -0.0001: a negative start of injection makes OpenFOAM's manualInjection inject nothing"),
        "{err}"
    );

    // a start time holding an OpenFOAM cloud's state, which fsim would not read
    let case = cloud_case(
        &scratch,
        "lagrangian",
        MANUAL,
        &format!("{POSITIONS_HEAD})\n"),
    );
    fs::create_dir_all(case.join("0/lagrangian/kinematicCloud")).unwrap();
    let out = fsim(&case, &[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("0/lagrangian: the start time holds an OpenFOAM cloud's state"),
        "{err}"
    );
    assert_eq!(listing(&case), ["0", "constant", "system"], "{err}");

    // a particle force that fsim does not implement
    let case = copy_tutorial("particleSettling", &scratch.0, "force");
    let props = case.join("constant/kinematicCloudProperties");
    let text = fs::read_to_string(&props)
        .unwrap()
        .replace("        gravity;", "        gravity;\n        SRF;");
    fs::write(&props, text).unwrap();
    let err = rejected(&case);
    assert!(
        err.contains("particle force 'SRF' is not supported by fsim"),
        "{err}"
    );
}

/// A wall whose velocity condition is a uniform `fixedValue` moves in the wall model, as
/// OpenFOAM's `PairCollision` takes the fluid's velocity on the wall face.
#[test]
fn a_fixed_value_wall_moves_in_the_wall_model() {
    let scratch = Scratch::new("moving-wall");
    let case = copy_tutorial("particleSettling", &scratch.0, "belt");
    let u = fs::read_dir(case.join("0"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.file_name().unwrap().to_string_lossy().starts_with('U'))
        .unwrap();
    let text = fs::read_to_string(&u).unwrap().replace(
        "type            noSlip;",
        "type            fixedValue;\n        value           uniform (0.5 0 0);",
    );
    fs::write(&u, text).unwrap();
    let loaded = fsim::case::Case::load(&case).unwrap_or_else(|e| panic!("{}", e.report()));
    let cloud = fsim::case::Cloud::from_case(&loaded)
        .unwrap_or_else(|e| panic!("{}", e.report()))
        .expect("a cloud");
    for f in 0..6 {
        if cloud.domain.faces[f] == fsim::particles::FaceCondition::Wall {
            assert_eq!(
                cloud.domain.wall_velocity[f],
                Vec3::new(0.5, 0.0, 0.0),
                "face {f}"
            );
        }
    }
    assert!(cloud
        .domain
        .faces
        .contains(&fsim::particles::FaceCondition::Wall));
}
