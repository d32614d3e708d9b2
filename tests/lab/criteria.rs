//! The secondary criteria: Chan and Dubey's joint-range criterion `H` (the
//! weights of `wln`) and Yoshikawa's manipulability (`manipulability`),
//! each gradient against central differences on random arms of 2-6 links;
//! what `jointrange`'s `v` is.

use super::{limits_around, random_arm, random_theta};
use redundant_ik::nalgebra::{DVector, Vector2};
use redundant_ik::nn::Rng;
use redundant_ik::planner::methods::{JOINT_RANGE, JOINT_RANGE_GAIN, MANIPULABILITY};
use redundant_ik::{Method, Planner, Pose, Scene};
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

#[test]
fn the_range_criterion_is_one_per_joint_at_the_middles_and_grows_toward_either_limit() {
    let limits: redundant_ik::arm::JointLimits = "-1:3,-2:2".parse().unwrap();
    assert_eq!(limits.range_criterion(&[1.0, 0.0]), 2.0);
    let mut g = [9.0; 2];
    limits.range_gradient_into(&[1.0, 0.0], &mut g);
    assert_eq!(g, [0.0, 0.0]);
    let h = |t: f64| limits.range_criterion(&[t, 0.0]);
    assert!(h(2.0) > h(1.5) && h(2.9) > h(2.0) && h(-0.9) > h(0.0));
    // Past a limit it stays finite, and the gradient points back in.
    limits.range_gradient_into(&[3.2, -2.5], &mut g);
    assert!(g.iter().all(|x| x.is_finite()));
    assert!(g[0] > 0.0 && g[1] < 0.0, "{g:?}");
}

#[test]
fn the_range_criterions_gradient_matches_central_differences_on_random_limits() {
    let mut rng = Rng::new(11);
    let mut compared = 0;
    for _ in 0..400 {
        let n = 2 + rng.below(5);
        let theta = random_theta(&mut rng, n);
        let limits = limits_around(&mut rng, &theta, 0.05);
        let mut g = vec![0.0; n];
        limits.range_gradient_into(&theta, &mut g);
        let h = 1e-6;
        for i in 0..n {
            let mut up = theta.clone();
            up[i] += h;
            let mut down = theta.clone();
            down[i] -= h;
            let fd = (limits.range_criterion(&up) - limits.range_criterion(&down)) / (2.0 * h);
            assert!(
                (fd - g[i]).abs() <= 1e-5 * (1.0 + g[i].abs()),
                "joint {i}: {} vs {fd}",
                g[i]
            );
            compared += 1;
        }
    }
    assert!(compared > 1000, "{compared}");
}

#[test]
fn the_manipulability_gradient_matches_central_differences_on_random_arms() {
    let mut rng = Rng::new(12);
    let mut compared = 0;
    for _ in 0..400 {
        let arm = random_arm(&mut rng);
        let n = arm.dof();
        let theta = random_theta(&mut rng, n);
        let pose = Pose::new(&arm, &theta).unwrap();
        // Away from singular poses, where w is not differentiable.
        if pose.manipulability() < 1e-2 {
            continue;
        }
        let mut g = vec![0.0; n];
        pose.manipulability_gradient_into(1e-6, &mut g);
        let w = |t: &[f64]| Pose::new(&arm, t).unwrap().manipulability();
        let h = 1e-6;
        for i in 0..n {
            let mut up = theta.clone();
            up[i] += h;
            let mut down = theta.clone();
            down[i] -= h;
            let fd = (w(&up) - w(&down)) / (2.0 * h);
            assert!(
                (fd - g[i]).abs() <= 1e-6 * (1.0 + g[i].abs()),
                "{n} links, joint {i}: {} vs {fd}",
                g[i]
            );
            compared += 1;
        }
    }
    assert!(compared > 1000, "{compared}");
    // Joint 1 turns the whole arm: w does not depend on it.
    let pose = Pose::new(&Scene::task1().arm, &[0.3, 1.0, -0.5]).unwrap();
    let mut g = [1.0; 3];
    pose.manipulability_gradient_into(1e-6, &mut g);
    assert!(g[0].abs() < 1e-14, "{g:?}");
}

#[test]
fn manipulability_climbs_w_in_the_null_space_while_the_hand_holds_still() {
    let scene = Scene::task1();
    let p = Planner::new(scene.clone(), MANIPULABILITY, None).unwrap();
    let theta = DVector::from_vec(scene.theta0.clone());
    let rates = p
        .theta_dot(
            theta.as_slice(),
            [(Vector2::zeros())[0], (Vector2::zeros())[1]],
        )
        .map(DVector::from_vec)
        .unwrap();
    let pose = Pose::new(&scene.arm, theta.as_slice()).unwrap();
    let mut g = [0.0; 3];
    pose.manipulability_gradient_into(1e-6, &mut g);
    // w grows along the rates, and J theta_dot = 0.
    let dw: f64 = g.iter().zip(rates.iter()).map(|(a, b)| a * b).sum();
    assert!(dw > 0.0, "{dw}");
    let jac = pose.jacobian();
    for r in 0..2 {
        let x: f64 = (0..3).map(|i| jac[2 * i + r] * rates[i]).sum();
        assert!(x.abs() < 1e-14, "{x}");
    }
}

#[test]
fn jointrange_pulls_each_joint_toward_the_middle_of_its_range_and_nothing_without_limits() {
    let mut scene = Scene::task1();
    // Without limits: the rates of eq. (5) with v = 0.
    let free = Planner::new(scene.clone(), JOINT_RANGE, None).unwrap();
    let theta = DVector::from_vec(vec![0.4, 1.9, -1.2]);
    let xdot = Vector2::new(-0.1, 0.05);
    let scene_free = free
        .theta_dot(theta.as_slice(), [xdot[0], xdot[1]])
        .map(DVector::from_vec)
        .unwrap();
    let mut bare = scene.clone();
    bare.obstacles.clear();
    let bare = Planner::new(bare, Method::NO_AVOIDANCE, None).unwrap();
    assert_eq!(
        scene_free,
        bare.theta_dot(theta.as_slice(), [xdot[0], xdot[1]])
            .map(DVector::from_vec)
            .unwrap()
    );
    // With limits: v_i = -k (theta_i - mid_i) / (n range_i^2).
    scene.arm = scene
        .arm
        .clone()
        .with_limits(Some("-1:1,-0.5:2.5,-2:2".parse().unwrap()), None)
        .unwrap();
    scene.set_param(&JOINT_RANGE_GAIN, 6.0).unwrap();
    let p = Planner::new(scene.clone(), JOINT_RANGE, None).unwrap();
    let v = p
        .null_space(theta.as_slice())
        .map(DVector::from_vec)
        .unwrap();
    let mids = [0.0, 1.0, 0.0];
    let ranges = [2.0, 3.0, 4.0];
    for i in 0..3 {
        let want = -6.0 * (theta[i] - mids[i]) / (3.0 * ranges[i] * ranges[i]);
        assert!((v[i] - want).abs() < 1e-15, "joint {i}: {} vs {want}", v[i]);
    }
}
