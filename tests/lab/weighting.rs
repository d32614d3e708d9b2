//! Weighted least norm, the paper's `W` of eq. (7): the weighted route is
//! eqs. (6)-(7) with the null-space vector in `W`'s metric, `W = I` is the
//! paper's route to the last bit, no limits change no method's rates, far
//! limits change them by no more than the weights' departure from 1, and a
//! joint past its limit is an outcome.

use std::sync::Arc;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use super::{limits_around, random_arm, random_theta, PAPER_LIMITS};
use redundant_ik::ik::{self, Weights};
use redundant_ik::nalgebra::{DMatrix, DVector, Vector2};
use redundant_ik::networks::Networks;
use redundant_ik::nn::Rng;
use redundant_ik::planner::{methods, Surrogate};
use redundant_ik::scene::JointWeighting;
use redundant_ik::{Method, Obstacle, Planner, Pose, Scene};

fn networks() -> Arc<dyn Surrogate> {
    Arc::new(Networks::embedded().unwrap())
}

fn xdot(rng: &mut Rng) -> [f64; 2] {
    [rng.range(-0.3, 0.3), rng.range(-0.3, 0.3)]
}

#[test]
fn with_w_equal_to_i_the_weighted_route_is_eq_18_to_the_last_bit() {
    let mut rng = Rng::new(21);
    for _ in 0..300 {
        let arm = random_arm(&mut rng);
        let n = arm.dof();
        let pose = Pose::new(&arm, &random_theta(&mut rng, n)).unwrap();
        let v: Vec<f64> = (0..n).map(|_| rng.range(-1.0, 1.0)).collect();
        let (x, delta) = (xdot(&mut rng), rng.range(0.0, 0.01));
        let mut a = vec![0.0; n];
        let mut b = vec![0.0; n];
        let plain = ik::theta_dot_symmetric_into(pose.jacobian(), x, &v, delta, &mut a);
        let ones = vec![1.0; n];
        let weighted = ik::theta_dot_weighted_into(pose.jacobian(), &ones, x, &v, delta, &mut b);
        assert_eq!(plain.is_ok(), weighted.is_ok());
        assert_eq!(a, b);
    }
}

#[test]
fn the_weighted_route_is_eqs_6_and_7_with_v_in_the_metric_of_w() {
    let mut rng = Rng::new(22);
    let mut compared = 0;
    for _ in 0..300 {
        let arm = random_arm(&mut rng);
        let n = arm.dof();
        let pose = Pose::new(&arm, &random_theta(&mut rng, n)).unwrap();
        let w: Vec<f64> = (0..n).map(|_| 1.0 + rng.range(0.0, 20.0)).collect();
        let winv: Vec<f64> = w.iter().map(|x| 1.0 / x).collect();
        let v: Vec<f64> = (0..n).map(|_| rng.range(-1.0, 1.0)).collect();
        let (x, delta) = (xdot(&mut rng), rng.range(1e-4, 0.05));
        let mut rates = vec![0.0; n];
        ik::theta_dot_weighted_into(pose.jacobian(), &winv, x, &v, delta, &mut rates).unwrap();
        // theta_dot = J+ Xdot + (I - J+ J) W^-1 v, J+ of eqs. (6) and (7).
        let j = DMatrix::from_column_slice(2, n, pose.jacobian());
        let wm = DMatrix::from_diagonal(&DVector::from_vec(w.clone()));
        let z = DMatrix::identity(2, 2);
        let weights = Weights { w: &wm, z: &z };
        let wv = DVector::from_iterator(n, v.iter().zip(&winv).map(|(a, b)| a * b));
        let xd = DVector::from_vec(x.to_vec());
        for pinv in [
            ik::pseudoinverse_eq6(&j, weights, delta).unwrap(),
            ik::pseudoinverse_eq7(&j, weights, delta).unwrap(),
        ] {
            let want = ik::theta_dot_eq5(&j, &pinv, &xd, &wv);
            let scale = 1.0 + want.amax();
            for (a, b) in rates.iter().zip(want.iter()) {
                assert!((a - b).abs() < 1e-9 * scale, "{a} vs {b}");
            }
            compared += 1;
        }
    }
    assert_eq!(compared, 600);
}

#[test]
fn the_learned_phi_weighted_is_the_weighted_damped_pseudoinverse_when_it_is_exact() {
    let mut rng = Rng::new(23);
    for _ in 0..300 {
        let arm = random_arm(&mut rng);
        let n = arm.dof();
        let pose = Pose::new(&arm, &random_theta(&mut rng, n)).unwrap();
        if pose.sigma_min() < 0.05 {
            continue;
        }
        let winv: Vec<f64> = (0..n).map(|_| 1.0 / (1.0 + rng.range(0.0, 20.0))).collect();
        let delta = rng.range(0.0, 0.05);
        let mut phi = vec![0.0; 2 * n];
        ik::phi_into(pose.jacobian(), 0.0, &mut phi).unwrap();
        ik::weight_phi(&mut phi, pose.jacobian(), &winv, delta).unwrap();
        let mut exact = vec![0.0; 2 * n];
        ik::phi_weighted_into(pose.jacobian(), &winv, delta, &mut exact).unwrap();
        let scale = exact.iter().fold(1.0f64, |a, x| a.max(x.abs()));
        for (a, b) in phi.iter().zip(&exact) {
            assert!((a - b).abs() < 1e-9 * scale, "{a} vs {b}");
        }
    }
}

/// The paper's tasks with a second obstacle, and random poses near them.
fn poses(rng: &mut Rng, scene: &Scene, count: usize) -> Vec<DVector<f64>> {
    (0..count)
        .map(|_| DVector::from_iterator(3, scene.theta0.iter().map(|t| t + rng.range(-0.6, 0.6))))
        .collect()
}

#[test]
fn without_limits_no_methods_rates_change_with_wln() {
    let nets = networks();
    let mut rng = Rng::new(24);
    for task in [1, 2] {
        let mut scene = Scene::task(task).unwrap();
        scene.obstacles.push(Obstacle::new(1.0, 1.3, 0.05));
        let mut wln = scene.clone();
        wln.weighting = JointWeighting::Wln;
        for &m in methods::ALL {
            let a = Planner::new(scene.clone(), m, Some(nets.clone())).unwrap();
            let b = Planner::new(wln.clone(), m, Some(nets.clone())).unwrap();
            for theta in poses(&mut rng, &scene, 40) {
                let x = Vector2::new(-0.09, -0.08);
                assert_eq!(
                    a.theta_dot(theta.as_slice(), [x[0], x[1]]).ok(),
                    b.theta_dot(theta.as_slice(), [x[0], x[1]]).ok(),
                    "{m}"
                );
            }
        }
    }
}

/// The methods built on eq. (5), which the weighting reaches.
fn weighted_methods() -> Vec<Method> {
    let names = [
        "none",
        "numerical",
        "case1",
        "case2",
        "case3",
        "distance",
        "manipulability",
        "jointrange",
    ];
    names.iter().map(|n| n.parse().unwrap()).collect()
}

#[test]
fn far_limits_change_the_rates_by_no_more_than_the_weights_departure_from_one() {
    let nets = networks();
    let mut rng = Rng::new(25);
    let mut compared = 0;
    for far in [20.0, 40.0, 80.0] {
        let mut scene = Scene::task1();
        let limits = limits_around(&mut rng, &scene.theta0, far);
        scene.arm = scene
            .arm
            .clone()
            .with_limits(Some(limits.clone()), None)
            .unwrap();
        let mut wln = scene.clone();
        wln.weighting = JointWeighting::Wln;
        for m in weighted_methods() {
            let a = Planner::new(scene.clone(), m, Some(nets.clone())).unwrap();
            let b = Planner::new(wln.clone(), m, Some(nets.clone())).unwrap();
            for theta in poses(&mut rng, &scene, 20) {
                let x = Vector2::new(-0.09, -0.08);
                let rates = |p: &Planner| {
                    p.theta_dot(theta.as_slice(), [x[0], x[1]])
                        .map(DVector::from_vec)
                };
                let (Ok(ra), Ok(rb)) = (rates(&a), rates(&b)) else {
                    continue;
                };
                let mut g = vec![0.0; 3];
                limits.range_gradient_into(theta.as_slice(), &mut g);
                // The largest departure of a weight from 1.
                let eps = g.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                let change = (&ra - &rb).amax();
                assert!(
                    change <= eps * (1.0 + ra.amax()) * 10.0,
                    "{m}, limits {far} rad away: {change} against {eps}"
                );
                compared += 1;
            }
        }
    }
    assert!(compared > 400, "{compared}");
}

#[test]
fn with_the_papers_limits_wln_keeps_every_method_of_eq_5_within_them_on_both_tasks() {
    let nets = networks();
    for task in [1, 2] {
        let mut scene = Scene::task(task).unwrap();
        scene.arm = scene
            .arm
            .clone()
            .with_limits(Some(PAPER_LIMITS.parse().unwrap()), None)
            .unwrap();
        scene.weighting = JointWeighting::Wln;
        for m in weighted_methods() {
            let run = Planner::run(scene.clone(), m, Some(nets.clone())).unwrap();
            assert_eq!(run.summary.limit_steps, 0, "Task {task}, {m}");
            assert!(run.summary.reached, "Task {task}, {m}");
        }
    }
}

#[test]
fn a_joint_past_its_limit_is_recorded_counted_and_no_success() {
    // Task 1's unweighted numerical route turns joint 2 to 1.80 rad.
    let mut scene = Scene::task1();
    scene.arm = scene
        .arm
        .clone()
        .with_limits(Some("-2:2,-2:1.7,-2:2".parse().unwrap()), None)
        .unwrap();
    let run = Planner::run(scene.clone(), Method::NUMERICAL, None).unwrap();
    let past: Vec<_> = run
        .steps
        .iter()
        .filter(|s| !s.past_limits.is_empty())
        .collect();
    assert!(!past.is_empty());
    assert!(past
        .iter()
        .all(|s| s.past_limits == [2] && s.theta[1] > 1.7));
    assert_eq!(run.summary.limit_steps, past.len());
    assert!(run.summary.reached && !run.summary.collided && !run.summary.success);
    // The JSON says which joints, and only where one is past.
    let json = serde_json::to_value(&run).unwrap();
    assert_eq!(json["steps"][0].get("past_limits"), None);
    let k = run
        .steps
        .iter()
        .position(|s| !s.past_limits.is_empty())
        .unwrap();
    assert_eq!(json["steps"][k]["past_limits"], serde_json::json!([2]));
    assert_eq!(json["summary"]["limit_steps"], past.len());
    // Weighted, the route keeps joint 2 within 1.7.
    scene.weighting = JointWeighting::Wln;
    let run = Planner::run(scene, Method::NUMERICAL, None).unwrap();
    assert_eq!(run.summary.limit_steps, 0);
    assert!(run.summary.success);
}
