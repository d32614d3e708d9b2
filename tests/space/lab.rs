//! The criteria beyond the paper in space, as a specification:
//! Yoshikawa's manipulability and its analytic gradient, the
//! `manipulability` and `jointrange` methods, and weighted least norm
//! (Chan and Dubey) on the spatial chains.

use redundant_ik::arm::JointLimits;
use redundant_ik::model::Model;
use redundant_ik::nn::Rng;
use redundant_ik::planner::methods::{
    self, DELTA, JOINT_RANGE_GAIN, LAMBDA, MANIPULABILITY_GAIN, SIGN_SMOOTHING,
};
use redundant_ik::planner::Trajectory;
use redundant_ik::scene::{JointWeighting, SpaceScene};
use redundant_ik::space::manipulability::{manipulability, manipulability_gradient_into};
use redundant_ik::space::{criterion, Chain, SpacePose, Sphere, PRESETS};
use redundant_ik::{Arm, Method, Planner, Pose, Scene};

/// A pose within the chain's limits, from `rng`.
fn random_theta(chain: &Chain, rng: &mut Rng) -> Vec<f64> {
    let limits = chain.joint_limits().unwrap().ranges();
    limits
        .iter()
        .map(|&[lo, hi]| lo + (hi - lo) * rng.uniform())
        .collect()
}

fn run(scene: &SpaceScene, m: Method) -> Trajectory<3> {
    Planner::new(scene.clone(), m, None)
        .and_then(Planner::run_to_end)
        .unwrap()
}

/// The preset's task without its sphere.
fn free(key: &str) -> SpaceScene {
    let mut s = SpaceScene::by_key(key).unwrap();
    s.obstacles.clear();
    s
}

/// The mean of `f` over a run's poses.
fn mean_over(scene: &SpaceScene, run: &Trajectory<3>, f: impl Fn(&SpacePose) -> f64) -> f64 {
    let sum: f64 = run
        .steps
        .iter()
        .map(|s| f(&SpacePose::new(&scene.arm, &s.theta).unwrap()))
        .sum();
    sum / run.steps.len() as f64
}

/// The smallest distance of any joint from a limit over a run, as a
/// fraction of its range.
fn closest_to_a_limit(scene: &SpaceScene, run: &Trajectory<3>) -> f64 {
    let limits = scene.arm.joint_limits().unwrap().ranges();
    run.steps
        .iter()
        .flat_map(|s| {
            s.theta
                .iter()
                .zip(limits)
                .map(|(&t, &[lo, hi])| (t - lo).min(hi - t) / (hi - lo))
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn the_manipulability_gradient_is_the_derivative_of_w() {
    let mut rng = Rng::new(11);
    for p in PRESETS {
        let chain = p.chain();
        let mut checked = 0;
        for _ in 0..40 {
            let theta = random_theta(&chain, &mut rng);
            let pose = SpacePose::new(&chain, &theta).unwrap();
            let w = manipulability(&pose);
            // det(J J^T) is the product of the eigenvalues of J J^T.
            let e = redundant_ik::space::linalg::eigenvalues_sym3(pose.jjt());
            assert!((w * w - e[0] * e[1] * e[2]).abs() < 1e-12, "{}", p.key);
            if w < 1e-3 {
                continue; // too close to a singular pose for differences
            }
            let mut g = vec![0.0; chain.dof()];
            manipulability_gradient_into(&pose, 1e-6, &mut g);
            let h = 1e-6;
            for j in 0..chain.dof() {
                let (mut up, mut down) = (theta.clone(), theta.clone());
                up[j] += h;
                down[j] -= h;
                let at = |t: &[f64]| manipulability(&SpacePose::new(&chain, t).unwrap());
                let numeric = (at(&up) - at(&down)) / (2.0 * h);
                assert!(
                    (g[j] - numeric).abs() < 1e-8,
                    "{} joint {j}: {} against {numeric} at {theta:?}",
                    p.key,
                    g[j]
                );
            }
            checked += 1;
        }
        assert!(checked >= 30, "{}: {checked} poses checked", p.key);
    }
}

#[test]
fn the_manipulability_method_keeps_w_higher_than_none() {
    for p in PRESETS {
        let scene = free(p.key);
        let none = run(&scene, Method::NO_AVOIDANCE);
        let w0 = mean_over(&scene, &none, manipulability);
        let last = |r: &Trajectory<3>| {
            manipulability(&SpacePose::new(&scene.arm, &r.steps.last().unwrap().theta).unwrap())
        };
        // At the default gain 0.5 and at 20: higher w, more with more gain.
        let mut before = w0;
        for (gain, at_least) in [(0.5, 1.0), (20.0, 1.01)] {
            let mut s = scene.clone();
            s.params.set(&MANIPULABILITY_GAIN, gain).unwrap();
            let climb = run(&s, methods::MANIPULABILITY);
            let w1 = mean_over(&scene, &climb, manipulability);
            println!(
                "{} k_m {gain}: mean w none {w0:.5} manipulability {w1:.5}; at the end {:.5} against {:.5}",
                p.key,
                last(&none),
                last(&climb)
            );
            assert!(
                w1 > at_least * w0 && w1 > before,
                "{}: {w1} against {w0}",
                p.key
            );
            assert!(last(&climb) > last(&none), "{}", p.key);
            assert!(climb.summary.max_tracking_error < 1e-6, "{}", p.key);
            before = w1;
        }
        // Without a gain it is none.
        let mut off = scene.clone();
        off.params.set(&MANIPULABILITY_GAIN, 0.0).unwrap();
        let flat = run(&off, methods::MANIPULABILITY);
        assert_eq!(flat.steps.last(), none.steps.last(), "{}", p.key);
    }
}

/// The joint-range method's own criterion: the mean over the joints of
/// `((theta_i - mid_i) / (hi_i - lo_i))^2`.
fn spread(scene: &SpaceScene) -> impl Fn(&SpacePose) -> f64 + '_ {
    move |pose| {
        let limits = scene.arm.joint_limits().unwrap().ranges();
        let sum: f64 = pose
            .theta()
            .iter()
            .zip(limits)
            .map(|(&t, &[lo, hi])| ((t - 0.5 * (lo + hi)) / (hi - lo)).powi(2))
            .sum();
        sum / limits.len() as f64
    }
}

/// Its criterion, not the smallest margin: on the iiwa14's line the joint
/// nearest a limit is the one the task drives, and pulling the others to
/// their middles brings it 1.5% of its range nearer (0.0822 to 0.0814 at
/// `k_r = 10`).
#[test]
fn the_joint_range_method_keeps_the_joints_nearer_the_middles_of_their_ranges() {
    for p in PRESETS {
        let scene = free(p.key);
        let none = run(&scene, Method::NO_AVOIDANCE);
        let q0 = mean_over(&scene, &none, spread(&scene));
        let end = |r: &Trajectory<3>| {
            spread(&scene)(&SpacePose::new(&scene.arm, &r.steps.last().unwrap().theta).unwrap())
        };
        let mut before = q0;
        for gain in [10.0, 50.0] {
            let mut s = scene.clone();
            s.params.set(&JOINT_RANGE_GAIN, gain).unwrap();
            let range = run(&s, methods::JOINT_RANGE);
            let q1 = mean_over(&scene, &range, spread(&scene));
            println!(
                "{} k_r {gain}: mean spread none {q0:.5} jointrange {q1:.5}, at the end {:.5} against {:.5}; \
                 closest to a limit none {:.4} jointrange {:.4}",
                p.key,
                end(&none),
                end(&range),
                closest_to_a_limit(&scene, &none),
                closest_to_a_limit(&scene, &range)
            );
            assert!(q1 < q0 && q1 < before, "{}: {q1} against {q0}", p.key);
            assert!(end(&range) < end(&none), "{}", p.key);
            assert!(range.summary.max_tracking_error < 1e-6, "{}", p.key);
            before = q1;
        }
    }
    // Started near its first joint's lower limit, the Panda's jointrange
    // spends fewer steps past it than none.
    let scene = near_a_limit("panda");
    let (none, range) = (
        run(&scene, Method::NO_AVOIDANCE),
        run(&scene, methods::JOINT_RANGE),
    );
    println!(
        "panda near a limit: limit steps none {} jointrange {}",
        none.summary.limit_steps, range.summary.limit_steps
    );
    assert!(range.summary.limit_steps < none.summary.limit_steps);
}

/// A preset's task without its sphere, started with its first joint 10%
/// of its range from a limit (the Panda's lower, the iiwa14's upper): the
/// line then drives that joint past it.
fn near_a_limit(key: &str) -> SpaceScene {
    let mut s = free(key);
    let [lo, hi] = s.arm.joint_limits().unwrap().ranges()[0];
    s.theta0[0] = match key {
        "panda" => lo + 0.1 * (hi - lo),
        _ => hi - 0.1 * (hi - lo),
    };
    s
}

#[test]
fn weighted_least_norm_keeps_a_joint_started_near_its_limit_within_it() {
    for p in PRESETS {
        let scene = near_a_limit(p.key);
        let mut wln = scene.clone();
        wln.weighting = JointWeighting::Wln;
        for m in [
            Method::NO_AVOIDANCE,
            Method::NUMERICAL,
            methods::MANIPULABILITY,
            methods::JOINT_RANGE,
        ] {
            let (plain, weighted) = (run(&scene, m), run(&wln, m));
            println!(
                "{} {m}: limit steps none {} wln {}; wln off the line by {:.1e} m",
                p.key,
                plain.summary.limit_steps,
                weighted.summary.limit_steps,
                weighted.summary.max_tracking_error
            );
            assert!(plain.summary.limit_steps > 0, "{m}: {:?}", plain.summary);
            assert!(
                weighted.summary.limit_steps < plain.summary.limit_steps,
                "{} {m}: {} against {}",
                p.key,
                weighted.summary.limit_steps,
                plain.summary.limit_steps
            );
            assert!(
                weighted.summary.max_tracking_error < 1e-6,
                "{} {m}: {:?}",
                p.key,
                weighted.summary
            );
        }
    }
}

/// `v` of each of these methods at `pose`, by its formula.
fn v_of(m: Method, scene: &SpaceScene, pose: &SpacePose) -> Vec<f64> {
    let n = pose.dof();
    let mut v = vec![0.0; n];
    match m.name() {
        "none" => {}
        "numerical" => criterion::null_space_vector_into(
            &scene.arm,
            pose,
            scene.obstacles.iter().map(|s| s.centre),
            scene.param(&LAMBDA),
            scene.param(&SIGN_SMOOTHING),
            &mut v,
        ),
        "manipulability" => {
            manipulability_gradient_into(pose, 1e-6, &mut v);
            v.iter_mut()
                .for_each(|x| *x *= scene.param(&MANIPULABILITY_GAIN));
        }
        "jointrange" => {
            let k = scene.param(&JOINT_RANGE_GAIN);
            let limits = scene.arm.joint_limits().unwrap().ranges();
            for ((vi, &t), &[lo, hi]) in v.iter_mut().zip(pose.theta()).zip(limits) {
                *vi = -k * (t - 0.5 * (lo + hi)) / (n as f64 * (hi - lo) * (hi - lo));
            }
        }
        other => unreachable!("{other}"),
    }
    v
}

#[test]
fn without_weighting_the_rates_are_eq18_with_each_methods_v() {
    let mut rng = Rng::new(5);
    let xdot = [0.05, -0.1, 0.08];
    for p in PRESETS {
        let scene = SpaceScene::preset(&p);
        assert!(scene.weighting.is_none());
        let delta = scene.param(&DELTA);
        for m in [
            Method::NO_AVOIDANCE,
            Method::NUMERICAL,
            methods::MANIPULABILITY,
            methods::JOINT_RANGE,
        ] {
            let planner = Planner::new(scene.clone(), m, None).unwrap();
            for _ in 0..10 {
                let theta = random_theta(&scene.arm, &mut rng);
                let pose = SpacePose::new(&scene.arm, &theta).unwrap();
                let mut want = vec![0.0; theta.len()];
                Chain::eq18(&pose, xdot, &v_of(m, &scene, &pose), delta, &mut want).unwrap();
                let got = planner.theta_dot(&theta, xdot).unwrap();
                for (g, w) in got.iter().zip(&want) {
                    assert!(
                        (g - w).abs() < 1e-12,
                        "{} {m}: {got:?} against {want:?}",
                        p.key
                    );
                }
            }
        }
    }
}

#[test]
fn the_weighted_eq18_is_eq18_at_unit_weights_and_keeps_the_hand_velocity() {
    let mut rng = Rng::new(9);
    let chain = PRESETS[1].chain();
    let xdot = [0.1, 0.02, -0.05];
    for _ in 0..10 {
        let theta = random_theta(&chain, &mut rng);
        let pose = SpacePose::new(&chain, &theta).unwrap();
        let v: Vec<f64> = (0..7).map(|_| rng.uniform() - 0.5).collect();
        let (mut plain, mut unit) = (vec![0.0; 7], vec![0.0; 7]);
        Chain::eq18(&pose, xdot, &v, 0.01, &mut plain).unwrap();
        Chain::eq18_weighted(&pose, &[1.0; 7], xdot, &v, 0.01, &mut unit).unwrap();
        for (a, b) in plain.iter().zip(&unit) {
            assert!((a - b).abs() < 1e-15, "{plain:?} against {unit:?}");
        }
        // Undamped, the weighted rates still give the hand its velocity,
        // and a joint of weight 1/w_i moves less than at weight 1 for v = 0.
        let winv = [1.0, 0.5, 1.0, 0.1, 1.0, 1.0, 0.3];
        let mut rates = vec![0.0; 7];
        Chain::eq18_weighted(&pose, &winv, xdot, &v, 0.0, &mut rates).unwrap();
        let jac = pose.jacobian();
        for r in 0..3 {
            let hand: f64 = (0..7).map(|i| jac[3 * i + r] * rates[i]).sum();
            assert!((hand - xdot[r]).abs() < 1e-9, "{hand} against {}", xdot[r]);
        }
    }
}

/// Weighted least norm needs limits: on the Panda's chain without them
/// (started near where its first joint's limit was), `wln` is `none` to
/// the last bit, in every method.
#[test]
fn on_a_chain_without_limits_the_weighting_changes_nothing() {
    let mut scene = near_a_limit("panda");
    scene.obstacles = SpaceScene::by_key("panda").unwrap().obstacles;
    scene.arm = scene.arm.clone().with_limits(None, None).unwrap();
    let mut wln = scene.clone();
    wln.weighting = JointWeighting::Wln;
    for m in methods::ALL
        .iter()
        .copied()
        .filter(|m| m.in_space() && !m.uses_networks())
    {
        let (a, b) = (run(&scene, m), run(&wln, m));
        assert_eq!(a.steps, b.steps, "{m}");
    }
}

/// The planar paper arm with +-2 rad limits, and the same arm as a chain in
/// space whose axes are parallel (every axis the world's `+y`, the planar
/// `(x, y)` the world's `(x, z)`, as in `planner.rs`), with the same limits.
fn planar_twins() -> (Arm, Chain) {
    let limits = || JointLimits::new(vec![[-2.0, 2.0]; 3]).unwrap();
    let arm = Arm::paper().with_limits(Some(limits()), None).unwrap();
    let chain = super::planar_as_chain(&arm)
        .with_limits(Some(limits()), None)
        .unwrap();
    (arm, chain)
}

/// On a chain whose axes are parallel the manipulability is the planar
/// arm's, and weighted least norm weights as in the plane: the rates of
/// every method in space with `wln` are the planar weighted ones.
#[test]
fn a_chain_whose_axes_are_parallel_has_the_planar_manipulability_and_weights() {
    let (arm, chain) = planar_twins();
    let poses = [
        vec![0.3, 1.2, -0.4],
        vec![1.9, -1.85, 1.7],
        vec![-1.95, 1.9, -1.9],
        vec![1.5, 1.95, 0.2],
    ];
    for theta in &poses {
        let (plane, space) = (
            Pose::new(&arm, theta).unwrap(),
            SpacePose::new(&chain, theta).unwrap(),
        );
        assert!((plane.manipulability() - manipulability(&space)).abs() < 1e-14);
        let (mut a, mut b) = (vec![0.0; 3], vec![0.0; 3]);
        plane.manipulability_gradient_into(1e-6, &mut a);
        manipulability_gradient_into(&space, 1e-6, &mut b);
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-13, "{a:?} against {b:?}");
        }
    }
    let mut planar = Scene::task1();
    planar.arm = arm;
    planar.theta0 = vec![0.3, 1.2, -0.4];
    planar.params.set(&DELTA, 0.02).unwrap();
    planar.weighting = JointWeighting::Wln;
    let o = planar.obstacles[0].centre;
    let mut space = SpaceScene::preset(&PRESETS[0]);
    space.arm = chain;
    space.theta0 = planar.theta0.clone();
    space.target = [planar.target[0], 0.0, planar.target[1]];
    space.obstacles = vec![Sphere::new([o[0], 0.0, o[1]], 0.05)];
    space.params = planar.params.clone();
    space.weighting = JointWeighting::Wln;
    let mut unweighted = planar.clone();
    unweighted.weighting = JointWeighting::None;
    for m in methods::ALL
        .iter()
        .copied()
        .filter(|m| m.in_space() && !m.uses_networks())
    {
        let (plane, flat) = (
            Planner::new(planar.clone(), m, None).unwrap(),
            Planner::new(unweighted.clone(), m, None).unwrap(),
        );
        let spatial = Planner::new(space.clone(), m, None).unwrap();
        let mut weighted_somewhere = false;
        for theta in &poses {
            for xdot in [[0.1, -0.2], [-0.3, 0.1]] {
                let rates = |p: &Planner| {
                    nalgebra::DVector::from_vec(p.theta_dot(theta, [xdot[0], xdot[1]]).unwrap())
                };
                let (want, plain) = (rates(&plane), rates(&flat));
                weighted_somewhere |= (&want - &plain).amax() > 1e-6;
                let got = spatial.theta_dot(theta, [xdot[0], 0.0, xdot[1]]).unwrap();
                for (g, w) in got.iter().zip(want.iter()) {
                    assert!((g - w).abs() < 1e-12, "{m}: {got:?} against {want:?}");
                }
            }
        }
        // The weighting reaches the methods of eq. (5) only (MethodInfo::weighting).
        assert_eq!(
            weighted_somewhere,
            m.info().weighting,
            "{m}: weighted at some pose"
        );
    }
}
