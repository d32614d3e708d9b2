//! A URDF chain as the one chain model, running in the planner: the
//! Panda read from `robots/panda.urdf` runs the preset's task as the
//! preset's modified-DH chain does (to 1e-9 rad, every method without
//! networks); the Jacobians of the shipped robots agree with Pinocchio's;
//! the UR5e, another maker's arm, reaches a target past a sphere; a run
//! of a URDF chain is a run file that reads back; a joint without limits
//! is refused with its reason.

use redundant_ik::export::SpaceRunFile;
use redundant_ik::nn::Precision;
use redundant_ik::planner::{methods, Planner};
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::{Chain, PoseChain, SpacePose, Sphere};
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

/// The hand's frame and its whole `6 x n` Jacobian (the pose task's:
/// linear and angular velocity, world-aligned) of every robot Pinocchio
/// read, the test arm's prismatic joint included.
/// Where a drawing puts a link's visuals, the chain model's joint frame
/// times `UrdfChain::link_frames`' frame, is the link's frame as Pinocchio
/// places it: for every moving joint's child link of the four files at
/// Pinocchio's poses, to 1e-9 (the page's 3-D view places its meshes so).
#[test]
fn every_links_frame_placed_on_the_chain_model_is_pinocchios() {
    let text = std::fs::read_to_string(format!("{ROOT}/tests/data/urdf/pinocchio.json")).unwrap();
    let data: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut worst: f64 = 0.0;
    let mut links = 0;
    for f in data["files"].as_array().unwrap() {
        let path = f["file"].as_str().unwrap();
        let tip = (!path.starts_with("robots/")).then(|| f["tip"].as_str().unwrap());
        let urdf =
            Urdf::parse(&std::fs::read_to_string(format!("{ROOT}/{path}")).unwrap()).unwrap();
        let uc = UrdfChain::new(&urdf, None, tip).unwrap();
        let c = chain(path, tip).unwrap();
        let placed = uc.link_frames();
        for run in f["runs"].as_array().unwrap() {
            let q: Vec<f64> = serde_json::from_value(run["q"].clone()).unwrap();
            let pose = SpacePose::new(&c, &q).unwrap();
            let joints = run["joints"].as_array().unwrap();
            for (k, j) in uc.joints.iter().enumerate() {
                // The joint's child link: the one it moves whose frame is the joint's own.
                let child = urdf
                    .joints
                    .iter()
                    .find(|u| u.name == j.name)
                    .unwrap()
                    .child
                    .clone();
                let (_, moved_by, frame) = placed.iter().find(|(n, _, _)| *n == child).unwrap();
                assert_eq!(*moved_by, k + 1, "{path}: {child}");
                let axes = pose.frame(k);
                let origin = pose.joint_origin(k);
                let rotation: [[f64; 3]; 3] =
                    serde_json::from_value(joints[k]["rotation"].clone()).unwrap();
                let translation: [f64; 3] =
                    serde_json::from_value(joints[k]["translation"].clone()).unwrap();
                for (r, theirs) in rotation.iter().enumerate() {
                    // World = joint frame (axes as columns) times the link's frame.
                    let t = origin[r]
                        + (0..3)
                            .map(|m| axes[m][r] * frame.translation[m])
                            .sum::<f64>();
                    worst = worst.max((t - translation[r]).abs());
                    for (col, x_theirs) in theirs.iter().enumerate() {
                        let x = (0..3)
                            .map(|m| axes[m][r] * frame.rotation[m][col])
                            .sum::<f64>();
                        worst = worst.max((x - x_theirs).abs());
                    }
                }
                links += 1;
            }
        }
    }
    assert!(links >= 4 * 10 * 4, "{links} links checked");
    assert!(worst < 1e-9, "{worst:e}");
}

#[test]
fn every_robots_hand_and_jacobian_agree_with_pinocchios() {
    let text = std::fs::read_to_string(format!("{ROOT}/tests/data/urdf/pinocchio.json")).unwrap();
    let data: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for f in data["files"].as_array().unwrap() {
        let path = f["file"].as_str().unwrap();
        let tip = (!path.starts_with("robots/")).then(|| f["tip"].as_str().unwrap());
        let c = chain(path, tip).unwrap();
        let arm = PoseChain::new(c.clone(), 1.0).unwrap();
        let mut pose = arm.pose();
        for run in f["runs"].as_array().unwrap() {
            let q: Vec<f64> = serde_json::from_value(run["q"].clone()).unwrap();
            let space = SpacePose::new(&c, &q).unwrap();
            pose.update(&arm, &q).unwrap();
            let hand: [f64; 3] = serde_json::from_value(run["tip"]["translation"].clone()).unwrap();
            let rotation: [[f64; 3]; 3] =
                serde_json::from_value(run["tip"]["rotation"].clone()).unwrap();
            let jac: Vec<Vec<f64>> = serde_json::from_value(run["jacobian"].clone()).unwrap();
            for (k, row) in rotation.iter().enumerate() {
                worst = worst.max((space.hand()[k] - hand[k]).abs());
                for (ours, theirs) in pose.rotation()[k].iter().zip(row) {
                    worst = worst.max((ours - theirs).abs());
                }
            }
            for (k, row) in jac.iter().enumerate() {
                for (i, x) in row.iter().enumerate() {
                    worst = worst.max((pose.jacobian()[6 * i + k] - x).abs());
                    if k < 3 {
                        worst = worst.max((space.jacobian()[3 * i + k] - x).abs());
                    }
                }
            }
        }
        checked += 1;
    }
    assert_eq!(checked, 4);
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
fn a_joint_without_limits_is_refused_with_its_reason() {
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

/// The test arm slides on its first joint: its Jacobian columns, its
/// manipulability's gradient (position and pose) and a sphere pair's row
/// against finite differences, and every method without networks runs it.
#[test]
fn a_prismatic_joints_columns_and_gradients_are_the_rates_they_claim() {
    use redundant_ik::model::{Clearance, Model};
    let c = chain("tests/data/urdf/slider_arm.urdf", Some("tool")).unwrap();
    let q = [0.2, 0.4, -0.6, 1.1];
    let h = 1e-7;
    let pose = SpacePose::new(&c, &q).unwrap();
    assert!(pose.is_prismatic(0) && !pose.is_prismatic(1));
    let moved = |i: usize| {
        let mut t = q;
        t[i] += h;
        SpacePose::new(&c, &t).unwrap()
    };
    // The hand's columns.
    for i in 0..4 {
        let m = moved(i);
        for k in 0..3 {
            let fd = (m.hand()[k] - pose.hand()[k]) / h;
            assert!((fd - pose.jacobian()[3 * i + k]).abs() < 1e-5, "joint {i}");
        }
    }
    // The manipulability's gradient, for the position and for the pose.
    let mut g = [0.0; 4];
    <Chain as Model<3>>::manipulability_gradient_into(&pose, 1e-9, &mut g);
    let w = <Chain as Model<3>>::manipulability(&pose);
    for (i, gi) in g.iter().enumerate() {
        let fd = (<Chain as Model<3>>::manipulability(&moved(i)) - w) / h;
        assert!(
            (fd - gi).abs() < 1e-5 * (1.0 + fd.abs()),
            "position, joint {i}: {fd} vs {gi}"
        );
    }
    // A pair's row: a sphere beside the forearm.
    let s = Sphere::new([0.3, 0.1, 0.5], 0.05);
    let mut pairs = redundant_ik::space::SpacePairs::with_capacity(16);
    pairs.update(&c, &pose, &[s], f64::INFINITY);
    let mut row = [0.0; 4];
    for p in pairs.as_slice() {
        p.row_into(&pose, &mut row);
        for (i, r) in row.iter().enumerate() {
            let mut again = redundant_ik::space::SpacePairs::with_capacity(16);
            again.update(&c, &moved(i), &[s], f64::INFINITY);
            let d = again
                .as_slice()
                .iter()
                .find(|x| x.segment == p.segment)
                .unwrap();
            let fd = (d.distance - p.distance) / h;
            assert!(
                (fd - r).abs() < 1e-5,
                "segment {} joint {i}: {fd} vs {r}",
                p.segment
            );
        }
    }
    // Every method without networks runs it, the slide in metres.
    let start = pose.hand();
    let mut scene = SpaceScene::by_key("panda").unwrap();
    scene.arm = c;
    scene.theta0 = q.to_vec();
    scene.target = [start[0], start[1], start[2] + 0.1];
    scene.obstacles.clear();
    scene.validate().unwrap();
    for m in methods::ALL.iter().filter(|m| !m.uses_networks()) {
        let run = Planner::run(scene.clone(), *m, None).unwrap();
        assert!(run.summary.final_error < 1e-3, "{m}: {:?}", run.summary);
    }
}
