//! The hand's full pose as the task (`m = 6`): the geometric Jacobian
//! against finite differences, the paper's `Z` (eqs. 6-7), every method
//! on the Panda's pose task, and the numerical route reaching the target
//! pose.

use redundant_ik::model::Model;
use redundant_ik::planner::methods::ALL as ALL_METHODS;
use redundant_ik::planner::{Method, Planner};
use redundant_ik::scene::{PoseScene, SpaceScene};
use redundant_ik::space::rotation::{self, exp, log, mul_transpose};
use redundant_ik::space::{PoseChain, SpacePreset, PRESETS};

fn panda() -> PoseScene {
    PoseScene::preset(SpacePreset::by_key("panda").unwrap()).unwrap()
}

/// A few poses of each preset, spread over their ranges.
fn poses(arm: &PoseChain) -> Vec<Vec<f64>> {
    let n = arm.chain.dof();
    (0..5)
        .map(|k| {
            (0..n)
                .map(|i| 0.9 * ((1.7 * i as f64 + 2.3 * k as f64).sin()))
                .collect()
        })
        .collect()
}

#[test]
fn the_jacobian_is_the_hands_velocity_and_angular_velocity() {
    for p in PRESETS.iter() {
        let scene = PoseScene::preset(p).unwrap();
        let arm = &scene.arm;
        let mut pose = arm.pose();
        let mut moved = arm.pose();
        let h = 1e-6;
        for theta in poses(arm) {
            arm.update(&mut pose, &theta).unwrap();
            let r0 = exp([pose.hand()[3], pose.hand()[4], pose.hand()[5]]);
            for i in 0..theta.len() {
                let mut t = theta.clone();
                t[i] += h;
                arm.update(&mut moved, &t).unwrap();
                let x = moved.hand();
                // The angular velocity: the rotation vector of R(theta +
                // h e_i) R(theta)^T over h.
                let w = log(&mul_transpose(&exp([x[3], x[4], x[5]]), &r0));
                let fd: Vec<f64> = (0..3)
                    .map(|k| (x[k] - pose.hand()[k]) / h)
                    .chain(w.iter().map(|w| w / h))
                    .collect();
                let col = &pose.jacobian()[6 * i..6 * i + 6];
                for (a, b) in fd.iter().zip(col) {
                    assert!(
                        (a - b).abs() < 1e-5,
                        "{} joint {i}: {fd:?} vs {col:?}",
                        p.key
                    );
                }
            }
        }
    }
}

/// `Z = I` makes eq. (6) the plain damped form `J^T (J J^T + delta I)^-1`;
/// another `Z` damps the orientation rows by `delta / z` and leaves an
/// undamped solve as it was.
#[test]
fn z_weights_the_orientation_rows_only_through_the_damping() {
    let scene = panda();
    let chain = scene.arm.chain.clone();
    let theta = &scene.theta0;
    let xdot = [0.05, -0.02, 0.01, 0.1, 0.2, -0.1];
    let v = vec![0.0; 7];
    let rates = |z: f64, delta: f64| {
        let arm = PoseChain::new(chain.clone(), z).unwrap();
        let mut pose = arm.pose();
        arm.update(&mut pose, theta).unwrap();
        let mut out = vec![0.0; 7];
        PoseChain::eq18(&pose, xdot, &v, delta, &mut out).unwrap();
        (out, pose)
    };
    // Z = I against the written-out J^T (J J^T + delta I)^-1 Xdot.
    let (identity, pose) = rates(1.0, 0.01);
    let j = nalgebra::DMatrix::from_column_slice(6, 7, pose.jacobian());
    let a = &j * j.transpose() + nalgebra::DMatrix::identity(6, 6) * 0.01;
    let plain = j.transpose()
        * a.lu()
            .solve(&nalgebra::DVector::from_row_slice(&xdot))
            .unwrap();
    for (x, y) in identity.iter().zip(plain.iter()) {
        assert!((x - y).abs() < 1e-12, "{identity:?} vs {plain:?}");
    }
    // Undamped, Z does not matter; damped, it does.
    let (a0, _) = rates(1.0, 0.0);
    let (b0, _) = rates(100.0, 0.0);
    for (x, y) in a0.iter().zip(&b0) {
        assert!((x - y).abs() < 1e-12);
    }
    let (heavy, _) = rates(100.0, 0.01);
    assert!(heavy
        .iter()
        .zip(&identity)
        .any(|(x, y)| (x - y).abs() > 1e-6));
}

/// The numerical route with feedback reaches the target pose, turned
/// 0.4 rad from the start, within 1e-6 m and 1e-6 rad.
#[test]
fn the_numerical_route_reaches_the_target_pose() {
    let mut scene = panda();
    let r = [scene.target[3], scene.target[4], scene.target[5]];
    let turned = log(&rotation::mul(
        &rotation::about([0.0, 0.6, 0.8], 0.4),
        &exp(r),
    ));
    scene.target[3..].copy_from_slice(&turned);
    scene.obstacles.clear();
    scene.feedback_gain = 10.0;
    let run = Planner::run(scene, Method::NUMERICAL, None).unwrap();
    let s = &run.summary;
    assert!(s.final_error < 1e-6, "{s:?}");
    assert!(s.final_orientation_error.unwrap() < 1e-6, "{s:?}");
    assert!(s.reached);
}

/// Every method but the learned ones runs the pose task and ends on the
/// target; Cases 1-3 are refused for want of networks, and say so.
#[test]
fn every_method_runs_the_pose_task() {
    for &m in ALL_METHODS {
        let mut scene = panda();
        scene.feedback_gain = 10.0;
        let run = Planner::run(scene, m, None);
        if m.uses_networks() {
            let e = run.unwrap_err().to_string();
            assert!(e.contains("networks"), "{m}: {e}");
            continue;
        }
        let run = run.unwrap_or_else(|e| panic!("{m}: {e}"));
        let s = &run.summary;
        assert!(s.final_error < 1e-3, "{m}: {s:?}");
        assert!(s.final_orientation_error.unwrap() < 1e-3, "{m}: {s:?}");
    }
}

/// The position scene and the pose scene of a preset share everything
/// but the target's orientation, which the pose task keeps.
#[test]
fn the_pose_scene_keeps_the_start_orientation_by_default() {
    let space = SpaceScene::by_key("iiwa14").unwrap();
    let pose = PoseScene::from_space(space.clone(), None, 1.0).unwrap();
    assert_eq!(pose.target[..3], space.target);
    assert_eq!(pose.target[3..], pose.start()[3..]);
    assert!(PoseScene::from_space(space.clone(), Some([f64::NAN, 0.0, 0.0]), 1.0).is_err());
    assert!(PoseScene::from_space(space.clone(), None, 0.0).is_err());
    // A circle keeps the start orientation; a turned target needs the line.
    let mut circle = space;
    circle.path = "circle:0.5,0,0.6,0,0,1".parse().unwrap();
    let kept = PoseScene::from_space(circle.clone(), None, 1.0).unwrap();
    assert_eq!(kept.target[3..], kept.start()[3..]);
    let e = PoseScene::from_space(circle, Some([0.1, 0.0, 0.0]), 1.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("straight line") && e.contains("start orientation"),
        "{e}"
    );
}

/// The circle and the polyline of the hand's position, the start
/// orientation held: the numerical route with feedback follows each within
/// 1e-5 rad and, along the circles, 1e-5 m at every sample (RK4's error
/// on a curve, where a line's is rounding), and ends where the path does (back at
/// the start for the circle's whole lap, at the last point for the
/// polyline).
#[test]
fn a_circle_and_a_polyline_keep_the_start_orientation() {
    // A polyline's corner turns the velocity within a step: the hand cuts
    // it by about a millimetre, as in the position task.
    for (path, tolerance) in [
        ("circle:0.4,0,0.55,0,0,1", 1e-5),
        ("circle:0.45,0.05,0.5,0.3,-0.2,1,2", 1e-5),
        ("points:0.45,0.1,0.55;0.4,0.15,0.45;0.5,0.05,0.5", 2e-3),
    ] {
        let mut space = SpaceScene::by_key("panda").unwrap();
        space.obstacles.clear();
        space.path = path.parse().unwrap();
        space.feedback_gain = 10.0;
        let scene = PoseScene::from_space(space, None, 1.0).unwrap();
        let start = scene.start();
        let run = Planner::run(scene.clone(), Method::NUMERICAL, None).unwrap();
        for x in &run.steps {
            assert_eq!(x.reference[3..], start[3..], "{path}");
            assert!(
                x.tracking_error < tolerance,
                "{path} at {}: {}",
                x.t,
                x.tracking_error
            );
            assert!(x.orientation_error.unwrap() < 1e-5, "{path} at {}", x.t);
        }
        let last = run.steps.last().unwrap();
        let end = match &scene.path {
            redundant_ik::scene::SpacePath::Points(p) => *p.last().unwrap(),
            _ => [start[0], start[1], start[2]],
        };
        for (r, e) in last.reference.iter().zip(end) {
            assert!((r - e).abs() < 1e-12, "{path}");
        }
        assert!(run.summary.final_error < 1e-5, "{path}: {:?}", run.summary);
    }
}

/// Case 2 runs the pose task: its `Phi` is exact (the pose's eq. 18) and
/// its `v` the Panda's network, which learned the criterion's gradient of
/// the links and the sphere, whatever the task. Cases 1 and 3 need a
/// `Phi` for the pose (`n x 6`), which none is: refused by name.
#[test]
fn case_2_runs_the_pose_task_with_the_v_network_and_cases_1_and_3_are_refused() {
    use redundant_ik::networks::space::SpaceNetworkSet;
    use redundant_ik::planner::methods::{CASE1, CASE2, CASE3};
    use redundant_ik::planner::{Networks, Surrogate};
    use redundant_ik::space::{Chain, SpacePose};
    let nets = SpaceNetworkSet::PandaReach.load().unwrap();
    let mut scene = panda();
    scene.feedback_gain = 10.0;
    let as_pose = || Some(nets.clone() as Networks<PoseChain, 6>);
    let run = Planner::run(scene.clone(), CASE2, as_pose()).unwrap();
    assert!(run.summary.final_error < 1e-6, "{:?}", run.summary);
    assert!(run.summary.final_orientation_error.unwrap() < 1e-6);
    for m in [CASE1, CASE3] {
        let e = Planner::new(scene.clone(), m, as_pose())
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("needs a Phi network") && e.contains("n x 6"),
            "{m}: {e}"
        );
    }
    // The pose's v is the chain's, pose by pose.
    let theta = [0.2, -0.4, 0.1, -2.0, 0.3, 1.8, 0.5];
    let mut pose = scene.arm.pose();
    scene.arm.update(&mut pose, &theta).unwrap();
    let point = SpacePose::new(&scene.arm.chain, &theta).unwrap();
    let (mut a, mut b) = ([0.0; 7], [0.0; 7]);
    let o = [0.3, 0.2, 0.6];
    Surrogate::<PoseChain, 6>::area_gradient(&*nets, &pose, o, &mut a).unwrap();
    Surrogate::<Chain, 3>::area_gradient(&*nets, &point, o, &mut b).unwrap();
    assert_eq!(a, b);
}
