//! The methods beyond the paper (`docs/methods.md`): the link-obstacle
//! geometry they share, what each reduces to with no obstacle near, the
//! velocity dampers of `qp`, and their parameters' checks.

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use redundant_ik::clearance::{Pair, Pairs};
use redundant_ik::nalgebra::{DVector, Vector2};
use redundant_ik::nn::Rng;
use redundant_ik::planner::methods::{self, DISTANCE, PRIORITY, QP};
use redundant_ik::planner::methods::{
    DAMPER_GAIN, DISTANCE_GAIN, INFLUENCE, RATE_LIMIT, SLACK_WEIGHT, STOP_DISTANCE,
};
use redundant_ik::planner::params;
use redundant_ik::scene::Param;
use redundant_ik::{Arm, Method, Obstacle, Planner, Pose, Scene};

fn random_arm(rng: &mut Rng) -> Arm {
    let n = 2 + rng.below(5);
    Arm::new(
        rng.range(0.0, 0.8),
        (0..n).map(|_| rng.range(0.2, 1.0)).collect(),
    )
    .unwrap()
}

fn random_theta(rng: &mut Rng, n: usize) -> Vec<f64> {
    (0..n).map(|_| rng.range(-2.5, 2.5)).collect()
}

#[test]
fn the_point_jacobian_and_the_clearance_rate_match_finite_differences_on_random_arms() {
    let mut rng = Rng::new(7);
    let mut checked = 0;
    for _ in 0..300 {
        let arm = random_arm(&mut rng);
        let n = arm.dof();
        let theta = random_theta(&mut rng, n);
        let pose = Pose::new(&arm, &theta).unwrap();
        let ob = Obstacle::new(
            rng.range(-1.5, 1.5),
            rng.range(0.0, 2.0),
            rng.range(0.01, 0.2),
        );
        let link = rng.below(n);
        let pair = Pair::at(&pose, link, 0, &ob);
        let mut jp = vec![0.0; 2 * n];
        pair.point_jacobian(&pose, &mut jp);
        let mut row = vec![0.0; n];
        pair.rate_row(&pose, &mut row);
        // The point held fixed on the link: its parameter along the link.
        let joints = pose.joints();
        let (a, b) = (joints[link], joints[link + 1]);
        let len2 = (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2);
        let s = ((pair.point[0] - a[0]) * (b[0] - a[0]) + (pair.point[1] - a[1]) * (b[1] - a[1]))
            / len2;
        let h = 1e-6;
        for i in 0..n {
            let mut tp = theta.clone();
            let mut tm = theta.clone();
            tp[i] += h;
            tm[i] -= h;
            let (pp, pm) = (Pose::new(&arm, &tp).unwrap(), Pose::new(&arm, &tm).unwrap());
            let at = |p: &Pose| {
                let (a, b) = (p.joints()[link], p.joints()[link + 1]);
                [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
            };
            let (xp, xm) = (at(&pp), at(&pm));
            for d in 0..2 {
                let fd = (xp[d] - xm[d]) / (2.0 * h);
                assert!(
                    (fd - jp[2 * i + d]).abs() < 1e-6,
                    "J_p[{d}][{i}]: {fd} vs {}",
                    jp[2 * i + d]
                );
            }
            // dc/dtheta_i = n^T J_p e_i: the clearance itself (closest point
            // free to slide) moves at the same rate to first order.
            let c = |p: &Pose| Pair::at(p, link, 0, &ob).clearance;
            let fd = (c(&pp) - c(&pm)) / (2.0 * h);
            assert!(
                (fd - row[i]).abs() < 1e-5,
                "dc/dtheta_{i}: {fd} vs {}",
                row[i]
            );
        }
        checked += 1;
    }
    assert_eq!(checked, 300);
}

#[test]
fn pairs_are_the_links_within_a_distance_and_the_closest_is_the_nearest() {
    let arm = Arm::paper();
    let pose = Pose::new(&arm, &Scene::task1().theta0).unwrap();
    let obstacles = [Obstacle::new(0.5, 0.5, 0.05), Obstacle::new(1.2, 1.4, 0.1)];
    let mut pairs = Pairs::default();
    pairs.update(&pose, &obstacles, f64::INFINITY);
    assert_eq!(pairs.len(), 2 * arm.dof());
    let closest = pairs.closest().unwrap();
    for ob in &obstacles {
        let d = pose.clearance(ob.centre) - ob.radius;
        assert!(closest.clearance <= d + 1e-12);
    }
    pairs.update(&pose, &obstacles, closest.clearance + 1e-9);
    assert_eq!(
        pairs.len(),
        1,
        "only the closest pair within its own clearance"
    );
    pairs.update(&pose, &[], 1.0);
    assert!(pairs.is_empty());
}

/// Task 1 with its obstacle moved far from the arm's whole motion.
fn far_scene() -> Scene {
    let mut s = Scene::task1();
    s.obstacles = vec![Obstacle::new(-1.6, 0.4, 0.05)];
    s
}

#[test]
fn with_no_obstacle_within_the_influence_distance_each_method_is_the_route_without_avoidance() {
    let scene = far_scene();
    let none = Planner::run(scene.clone(), Method::NO_AVOIDANCE, None).unwrap();
    for method in [DISTANCE, PRIORITY] {
        let run = Planner::run(scene.clone(), method, None).unwrap();
        for (a, b) in run.steps.iter().zip(&none.steps) {
            for (x, y) in a.theta.iter().zip(&b.theta) {
                assert!((x - y).abs() < 1e-12, "{method}: {x} vs {y}");
            }
        }
    }
    // qp: eq. (5) with damped least squares, delta = 1 / w, and the paper's
    // area vector: theta_dot = v + J^T (J J^T + I / w)^-1 (Xdot - J v).
    let p = Planner::new(scene.clone(), QP, None).unwrap();
    let mut damped = scene.clone();
    damped
        .set_param(&methods::DELTA, 1.0 / scene.param(&SLACK_WEIGHT))
        .unwrap();
    let numerical = Planner::new(damped, Method::NUMERICAL, None).unwrap();
    let mut rng = Rng::new(3);
    let mut compared = 0;
    for _ in 0..50 {
        let theta = DVector::from_vec(random_theta(&mut rng, 3));
        let xdot = Vector2::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2));
        let pose = Pose::new(&scene.arm, theta.as_slice()).unwrap();
        let mut pairs = Pairs::default();
        pairs.update(&pose, &scene.obstacles, scene.param(&INFLUENCE));
        if !pairs.is_empty() {
            continue;
        }
        let a = p
            .theta_dot(theta.as_slice(), [xdot[0], xdot[1]])
            .map(DVector::from_vec)
            .unwrap();
        let b = numerical
            .theta_dot(theta.as_slice(), [xdot[0], xdot[1]])
            .map(DVector::from_vec)
            .unwrap();
        // Within the rate limit the box constraints are inactive too.
        if b.amax() < scene.param(&RATE_LIMIT) {
            assert!((&a - &b).amax() < 1e-12, "{a} vs {b}");
            compared += 1;
        }
    }
    // Seed 3 compares 47 of the 50 poses (the other 3 are within the
    // influence distance of the far obstacle or beyond the rate limit); far
    // fewer means the skips grew and the comparison says little.
    assert!(
        compared >= 40,
        "only {compared} of 50 random poses were compared"
    );
}

#[test]
fn the_task_is_tracked_while_no_damper_binds() {
    // delta = 0: the projection is exact, so every method that keeps the
    // task as its first level tracks the line to integration accuracy.
    for method in [DISTANCE, PRIORITY, QP] {
        let run = Planner::run(far_scene(), method, None).unwrap();
        let s = &run.summary;
        assert!(
            s.max_tracking_error < 1e-4,
            "{method}: {}",
            s.max_tracking_error
        );
        assert!(s.reached && !s.collided, "{method}");
    }
}

#[test]
fn every_velocity_damper_holds_at_the_qp_solution() {
    let mut rng = Rng::new(11);
    let mut binding = 0;
    for _ in 0..3000 {
        let mut scene = Scene::task1();
        scene.obstacles = (0..1 + rng.below(3))
            .map(|_| Obstacle::new(rng.range(-0.5, 1.6), rng.range(0.2, 1.8), 0.05))
            .filter(|o| o.validate(&scene.arm).is_ok())
            .collect();
        let theta = DVector::from_vec(random_theta(&mut rng, 3));
        let pose = Pose::new(&scene.arm, theta.as_slice()).unwrap();
        let xdot = Vector2::new(rng.range(-0.3, 0.3), rng.range(-0.3, 0.3));
        let Ok(p) = Planner::new(scene.clone(), QP, None) else {
            continue;
        };
        let rates = p
            .theta_dot(theta.as_slice(), [xdot[0], xdot[1]])
            .map(DVector::from_vec)
            .unwrap();
        let (influence, stop) = (scene.param(&INFLUENCE), scene.param(&STOP_DISTANCE));
        let gain = scene.param(&DAMPER_GAIN);
        let mut pairs = Pairs::default();
        pairs.update(&pose, &scene.obstacles, influence);
        let mut row = vec![0.0; 3];
        let relaxed = pairs.as_slice().iter().any(|q| q.clearance < stop);
        for q in pairs.as_slice() {
            q.rate_row(&pose, &mut row);
            let rate: f64 = row.iter().zip(rates.iter()).map(|(r, t)| r * t).sum();
            let mut bound = -gain * (q.clearance - stop) / (influence - stop);
            if relaxed {
                // Where they may conflict the bounds are capped at 0.
                bound = bound.min(0.0);
            }
            assert!(rate >= bound - 1e-9, "pair {q:?}: {rate} < {bound}");
            binding += usize::from((rate - bound).abs() < 1e-9);
        }
        assert!(rates.amax() <= scene.param(&RATE_LIMIT) + 1e-9, "{rates}");
    }
    assert!(
        binding > 20,
        "only {binding} dampers bound: the test saw little"
    );
}

#[test]
fn beside_the_line_the_qp_keeps_clear_where_the_numerical_route_collides() {
    // Task 1 with the obstacle just beside the line (from the atlas: the
    // numerical route collides there).
    let mut scene = Scene::task1();
    scene.obstacles = vec![Obstacle::new(0.82, 0.51, 0.05)];
    let numerical = Planner::run_summary(scene.clone(), Method::NUMERICAL, None).unwrap();
    assert!(numerical.collided, "the numerical route collides here");
    let qp = Planner::run(scene.clone(), QP, None).unwrap();
    let r = scene.obstacles[0].radius;
    for s in &qp.steps {
        assert!(
            s.distance.unwrap() - r >= 0.0,
            "t = {}: clearance {}",
            s.t,
            s.distance.unwrap() - r
        );
    }
}

#[test]
fn the_new_parameters_are_checked_like_the_others() {
    let mut s = Scene::task1();
    let bad: [(&'static Param, f64, &str); 9] = [
        (&INFLUENCE, f64::NAN, "finite"),
        (&INFLUENCE, -0.1, "between"),
        (&INFLUENCE, 0.01, "below the influence distance"),
        (&STOP_DISTANCE, -0.01, "negative"),
        (&STOP_DISTANCE, 0.5, "below the influence distance"),
        (&DAMPER_GAIN, 0.0, "between"),
        (&SLACK_WEIGHT, 0.5, "between"),
        (&DISTANCE_GAIN, f64::INFINITY, "finite"),
        (&RATE_LIMIT, -1.0, "between"),
    ];
    for (param, value, says) in bad {
        let before = s.clone();
        let err = s.set_param(param, value).unwrap_err();
        assert!(err.to_string().contains(says), "{param} = {value}: {err}");
        assert_eq!(s, before, "a refused value changes nothing");
    }
    // A scene file that carries them is checked as a whole.
    let mut json = serde_json::to_value(&s).unwrap();
    json["params"]["stop_distance"] = 0.4.into();
    assert!(serde_json::from_value::<Scene>(json).is_err());
    // Every parameter a method reads exists, with its bounds.
    for m in methods::ALL {
        for &p in m.params() {
            let (lo, hi) = p.bounds;
            assert!(lo < hi, "{m}: {p}");
            assert!(std::ptr::eq(params::by_name(p.name).unwrap(), p));
        }
    }
}
