//! A URDF chain as the one chain model, running in the planner: the
//! Panda read from `robots/panda.urdf` runs the preset's task as the
//! preset's modified-DH chain does (to 1e-9 rad, every method without
//! networks); the Jacobians of the shipped robots agree with Pinocchio's;
//! the UR5e, another maker's arm, reaches a target past a sphere; a run
//! of a URDF chain is a run file that reads back; what does not run yet
//! is refused with its reason.

use redundant_ik::export::SpaceRunFile;
use redundant_ik::nn::Precision;
use redundant_ik::planner::{methods, Planner};
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::{Chain, SpacePose, Sphere};
use redundant_ik::urdf::volume;
use redundant_ik::urdf::{Urdf, UrdfChain};
use redundant_ik::Method;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// The chain model of the URDF at `path` (from the crate's folder).
fn chain(path: &str, tip: Option<&str>) -> redundant_ik::Result<Chain> {
    let urdf = Urdf::parse(&std::fs::read_to_string(format!("{ROOT}/{path}")).unwrap())?;
    let uc = UrdfChain::new(&urdf, None, tip)?;
    let (v, _) = volume::volumes(&urdf, &uc, &|_| None, 0.05);
    uc.to_chain(&v, None)
}

#[test]
fn the_pandas_urdf_runs_its_task_as_the_preset_does() {
    let urdf = chain("robots/panda.urdf", None).unwrap();
    let preset = SpaceScene::by_key("panda").unwrap();
    assert_eq!(urdf.joint_limits(), preset.arm.joint_limits());
    assert_eq!(urdf.rate_limits(), preset.arm.rate_limits());
    let mut scene = preset.clone();
    scene.arm = urdf;
    let mut worst: f64 = 0.0;
    for m in [
        Method::NO_AVOIDANCE,
        Method::NUMERICAL,
        methods::DISTANCE,
        methods::PRIORITY,
        methods::QP,
        methods::MANIPULABILITY,
        methods::JOINT_RANGE,
    ] {
        let ours = Planner::new(scene.clone(), m, None)
            .and_then(Planner::run_to_end)
            .unwrap();
        let theirs = Planner::new(preset.clone(), m, None)
            .and_then(Planner::run_to_end)
            .unwrap();
        assert_eq!(ours.steps.len(), theirs.steps.len(), "{m}");
        for (a, b) in ours.steps.iter().zip(&theirs.steps) {
            for (x, y) in a.theta.iter().zip(&b.theta) {
                worst = worst.max((x - y).abs());
            }
        }
        let (a, b) = (&ours.summary, &theirs.summary);
        assert_eq!(
            (a.collision_steps, a.limit_steps),
            (b.collision_steps, b.limit_steps),
            "{m}"
        );
        assert!(
            (a.min_clearance.unwrap() - b.min_clearance.unwrap()).abs() < 1e-9,
            "{m}"
        );
    }
    assert!(worst < 1e-9, "{worst:e} rad");
}

#[test]
fn the_shipped_robots_jacobians_agree_with_pinocchios() {
    let text = std::fs::read_to_string(format!("{ROOT}/tests/data/urdf/pinocchio.json")).unwrap();
    let data: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for f in data["files"].as_array().unwrap() {
        let path = f["file"].as_str().unwrap();
        if !path.starts_with("robots/") {
            continue; // the test arm's prismatic joint does not run yet
        }
        let c = chain(path, None).unwrap();
        for run in f["runs"].as_array().unwrap() {
            let q: Vec<f64> = serde_json::from_value(run["q"].clone()).unwrap();
            let pose = SpacePose::new(&c, &q).unwrap();
            let hand: [f64; 3] = serde_json::from_value(run["tip"]["translation"].clone()).unwrap();
            let jac: Vec<Vec<f64>> = serde_json::from_value(run["jacobian"].clone()).unwrap();
            for (k, row) in jac.iter().take(3).enumerate() {
                worst = worst.max((pose.hand()[k] - hand[k]).abs());
                for (i, x) in row.iter().enumerate() {
                    worst = worst.max((pose.jacobian()[3 * i + k] - x).abs());
                }
            }
        }
        checked += 1;
    }
    assert_eq!(checked, 3);
    assert!(worst < 1e-9, "{worst:e}");
}

#[test]
fn the_ur5e_reaches_a_target_past_a_sphere_and_its_run_file_reads_back() {
    let arm = chain("robots/ur5e.urdf", None).unwrap();
    let theta0 = vec![0.0, -1.2, 1.4, -1.8, -1.5, 0.0];
    let start = SpacePose::new(&arm, &theta0).unwrap().hand();
    let mut scene = SpaceScene::by_key("panda").unwrap();
    scene.arm = arm;
    scene.theta0 = theta0;
    scene.target = [start[0], start[1] + 0.25, start[2]];
    // A sphere the forearm sweeps through without avoidance, clear of the
    // arm at the start (found by trying a few places: most places near
    // this start overlap the wrist already).
    let sphere = Sphere::new([start[0] - 0.1, start[1] + 0.12, start[2] + 0.1], 0.05);
    scene.obstacles = vec![sphere];
    scene.feedback_gain = 1.0;
    scene.validate().unwrap();
    let pose = SpacePose::new(&scene.arm, &scene.theta0).unwrap();
    assert!(redundant_ik::space::clearance(&scene.arm, &pose, &[sphere]) > 0.04);
    let run = |m: Method| {
        Planner::new(scene.clone(), m, None)
            .and_then(Planner::run_to_end)
            .unwrap()
    };
    assert!(
        run(Method::NO_AVOIDANCE).summary.collision_steps > 0,
        "the sphere is in the way"
    );
    for m in [Method::NUMERICAL, methods::QP] {
        let run = run(m);
        let s = &run.summary;
        assert!(s.final_error < 1e-5, "{m}: {s:?}");
        assert_eq!((s.collision_steps, s.limit_steps), (0, 0), "{m}: {s:?}");
        if m == methods::QP {
            // The dampers hold the stop distance, 0.02 m.
            assert!(s.min_clearance.unwrap() > 0.0199, "{s:?}");
        }
        let file = SpaceRunFile::of(None, scene.clone(), run, None, Precision::F64);
        let text = file.to_json();
        assert!(
            text.contains("\"joints\":[{\"rotation\""),
            "the file carries the URDF's chain"
        );
        assert_eq!(SpaceRunFile::from_json(&text).unwrap(), file);
    }
}

#[test]
fn what_does_not_run_yet_is_refused_with_its_reason() {
    let e = chain("tests/data/urdf/slider_arm.urdf", Some("tool"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("prismatic") && e.contains("does not run yet"),
        "{e}"
    );
    // A revolute joint without limits needs them given.
    let text = "<robot name='r'><link name='a'/><link name='b'/><link name='c'/><link name='d'/>\
        <joint name='j1' type='revolute'><parent link='a'/><child link='b'/></joint>\
        <joint name='j2' type='continuous'><parent link='b'/><child link='c'/><origin xyz='0.3 0 0'/></joint>\
        <joint name='j3' type='continuous'><parent link='c'/><child link='d'/><origin xyz='0.3 0 0'/></joint></robot>";
    let urdf = Urdf::parse(text).unwrap();
    let uc = UrdfChain::new(&urdf, None, None).unwrap();
    let e = uc.to_chain(&[], None).unwrap_err().to_string();
    assert!(e.contains("'j1'") && e.contains("--joint-limits"), "{e}");
    let limits = redundant_ik::arm::JointLimits::new(vec![[-1.0, 1.0]; 3]).unwrap();
    let c = uc.to_chain(&[], Some(limits)).unwrap();
    assert_eq!(c.dof(), 3);
    // Its axis is the URDF's default, x: the chain's first joint turns about it.
    let pose = SpacePose::new(&c, &[0.0; 3]).unwrap();
    assert!((pose.axis(0)[0] - 1.0).abs() < 1e-15);
}
