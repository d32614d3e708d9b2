//! The core, as a specification: kinematics, the pseudoinverse identities,
//! the obstacle vector, the integrator and the paper's reference runs.
//!
//! One file serves both targets: `cargo test` runs it natively and
//! `wasm-pack test --headless --chrome` runs the same tests in a browser.

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::f64::consts::PI;

use redundant_ik::ik::{self, DampingSchedule, Weights};
use redundant_ik::kinematics;
use redundant_ik::nalgebra::{DMatrix, DVector, Vector2};
use redundant_ik::obstacle::{self, Obstacle};
use redundant_ik::planner::methods::{self, DELTA, LAMBDA};
use redundant_ik::scene::Param;
use redundant_ik::{Arm, Error, Method, Planner, Pose, Scene};

/// Small deterministic generator so that the same "random" poses are checked
/// on every target (no OS entropy in the browser).
struct Lcg(u64);
impl Lcg {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
    fn theta(&mut self, n: usize) -> DVector<f64> {
        DVector::from_fn(n, |_, _| self.uniform(-PI, PI))
    }
    fn spd(&mut self, n: usize) -> DMatrix<f64> {
        let a = DMatrix::from_fn(n, n, |_, _| self.uniform(-1.0, 1.0));
        &a * a.transpose() + DMatrix::identity(n, n) * 0.5
    }
}

fn theta(v: &[f64]) -> DVector<f64> {
    DVector::from_column_slice(v)
}

fn jacobian_dyn(arm: &Arm, th: &DVector<f64>) -> DMatrix<f64> {
    let j = arm.jacobian(th);
    DMatrix::from_fn(2, arm.dof(), |r, c| j[(r, c)])
}

#[test]
fn forward_kinematics_reproduces_the_papers_start_points() {
    let arm = Arm::paper();
    let x1 = arm.forward(&theta(&[PI / 12.0, PI / 2.0, -PI / 6.0]));
    assert!(
        (x1 - Vector2::new(1.555884, 1.014851)).norm() < 1e-6,
        "{x1}"
    );
    let x2 = arm.forward(&Scene::task2().theta0_vector());
    assert!(
        (x2 - Vector2::new(1.495943, 0.559559)).norm() < 1e-6,
        "{x2}"
    );
    // The theta0 printed for Task 2 does not give the printed start
    // (docs/conventions.md).
    let printed = arm.forward(&theta(&[PI / 12.0, PI / 2.0, PI / 6.0]));
    assert!((printed - Vector2::new(1.400592, 0.435295)).norm() < 1e-6);
}

#[test]
fn joints_start_at_the_post_top_and_end_at_the_end_effector() {
    let arm = Arm::paper();
    let th = Scene::task1().theta0_vector();
    let p = arm.joints(&th);
    assert_eq!(p.len(), 4);
    assert_eq!(p[0], Vector2::new(0.0, 0.5));
    assert!((p[3] - arm.forward(&th)).norm() < 1e-15);
    for (k, l) in arm.links().iter().enumerate() {
        assert!(((p[k + 1] - p[k]).norm() - l).abs() < 1e-12);
    }
}

#[test]
fn analytic_jacobian_matches_central_differences() {
    let mut rng = Lcg(1);
    for arm in [
        Arm::paper(),
        Arm::new(0.3, vec![0.4, 0.7, 0.2, 0.5]).unwrap(),
    ] {
        for _ in 0..20 {
            let th = rng.theta(arm.dof());
            let j = arm.jacobian(&th);
            let h = 1e-6;
            for i in 0..arm.dof() {
                let mut tp = th.clone();
                let mut tm = th.clone();
                tp[i] += h;
                tm[i] -= h;
                let fd = (arm.forward(&tp) - arm.forward(&tm)) / (2.0 * h);
                assert!(
                    (fd - j.column(i)).norm() < 1e-8,
                    "column {i}: {fd} vs {}",
                    j.column(i)
                );
            }
        }
    }
}

#[test]
fn eq6_equals_eq7_for_random_spd_weights() {
    let mut rng = Lcg(2);
    let arm = Arm::paper();
    for _ in 0..20 {
        let j = jacobian_dyn(&arm, &rng.theta(3));
        let (w, z) = (rng.spd(3), rng.spd(2));
        let delta = rng.uniform(1e-3, 1.0);
        let a = ik::pseudoinverse_eq6(&j, Weights { w: &w, z: &z }, delta).unwrap();
        let b = ik::pseudoinverse_eq7(&j, Weights { w: &w, z: &z }, delta).unwrap();
        assert!((&a - &b).amax() < 1e-9 * a.amax().max(1.0), "{a} vs {b}");
    }
}

#[test]
fn undamped_pseudoinverse_is_a_right_inverse() {
    let mut rng = Lcg(3);
    let arm = Arm::paper();
    for _ in 0..20 {
        let j = jacobian_dyn(&arm, &rng.theta(3));
        let pinv = ik::pseudoinverse_eq6(
            &j,
            Weights {
                w: &rng.spd(3),
                z: &rng.spd(2),
            },
            0.0,
        )
        .unwrap();
        let jj = &j * &pinv;
        assert!((jj - DMatrix::identity(2, 2)).amax() < 1e-9);
    }
}

#[test]
fn null_space_term_moves_no_end_effector() {
    let mut rng = Lcg(4);
    let arm = Arm::paper();
    for _ in 0..20 {
        let j = jacobian_dyn(&arm, &rng.theta(3));
        let pinv = ik::pseudoinverse_eq6(
            &j,
            Weights {
                w: &rng.spd(3),
                z: &rng.spd(2),
            },
            0.0,
        )
        .unwrap();
        let v = DVector::from_fn(3, |_, _| rng.uniform(-5.0, 5.0));
        let projected = (DMatrix::identity(3, 3) - &pinv * &j) * &v;
        assert!((&j * projected).amax() < 1e-9);
    }
}

#[test]
fn symmetric_route_and_network_route_equal_eq5() {
    // Eqs. (17)-(18) and eq. (21) with the exact Phi are eq. (5) with W = Z = I.
    let mut rng = Lcg(5);
    let arm = Arm::paper();
    let (w, z) = (DMatrix::identity(3, 3), DMatrix::identity(2, 2));
    for delta in [0.0, 0.01, 0.3] {
        for _ in 0..10 {
            let th = rng.theta(3);
            let j = arm.jacobian(&th);
            let xdot = Vector2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
            let v = DVector::from_fn(3, |_, _| rng.uniform(-1.0, 1.0));
            let pinv =
                ik::pseudoinverse_eq6(&jacobian_dyn(&arm, &th), Weights { w: &w, z: &z }, delta)
                    .unwrap();
            let xd = DVector::from_column_slice(xdot.as_slice());
            let eq5 = ik::theta_dot_eq5(&jacobian_dyn(&arm, &th), &pinv, &xd, &v);
            let eq18 = ik::theta_dot_symmetric(&j, &xdot, &v, delta).unwrap();
            let eq21 = ik::theta_dot_network(&ik::phi(&j, delta).unwrap(), &j, &xdot, &v);
            assert!((&eq5 - &eq18).amax() < 1e-9, "{eq5} vs {eq18}");
            assert!((&eq5 - &eq21).amax() < 1e-9, "{eq5} vs {eq21}");
        }
    }
}

#[test]
fn determinant_gradient_matches_finite_differences_and_is_lower_triangular() {
    let mut rng = Lcg(6);
    let arm = Arm::paper();
    for _ in 0..30 {
        let th = rng.theta(3);
        let o = Vector2::new(rng.uniform(-1.0, 2.0), rng.uniform(-0.5, 2.0));
        let g = obstacle::determinant_gradient(&arm, &th, &o);
        let h = 1e-6;
        for i in 0..3 {
            let mut tp = th.clone();
            let mut tm = th.clone();
            tp[i] += h;
            tm[i] -= h;
            let dp = obstacle::triangle_determinants(&arm.joints(&tp), &o);
            let dm = obstacle::triangle_determinants(&arm.joints(&tm), &o);
            for k in 0..3 {
                let fd = (dp[k] - dm[k]) / (2.0 * h);
                assert!(
                    (fd - g[(k, i)]).abs() < 1e-7,
                    "dD_{k}/dtheta_{i}: {fd} vs {}",
                    g[(k, i)]
                );
                if i > k {
                    assert_eq!(g[(k, i)], 0.0, "D_{k} must not depend on theta_{i}");
                }
            }
        }
    }
}

#[test]
fn triangle_determinant_is_twice_the_signed_area() {
    let joints = [Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)];
    // O above the link: det[(0, 1), (1, 0)] = -1, area of the triangle 1/2.
    let d = obstacle::triangle_determinants(&joints, &Vector2::new(0.0, 1.0));
    assert_eq!(d, vec![-1.0]);
}

#[test]
fn obstacle_vector_is_the_area_gradient_scaled_by_lambda_over_four() {
    let arm = Arm::paper();
    let th = Scene::task1().theta0_vector();
    let ob = Obstacle::new(0.5, 0.5, 0.05);
    let g = obstacle::area_gradient(&arm, &th, &ob.point());
    let v4 = obstacle::null_space_vector(&arm, &th, &[ob], 4.0);
    let v2 = obstacle::null_space_vector(&arm, &th, &[ob], 2.0);
    assert!((&v4 - &g).amax() < 1e-15);
    assert!((&v2 * 2.0 - &v4).amax() < 1e-15);
    // Ascent direction: a small step along g increases the total area sum V_k.
    let area = |t: &DVector<f64>| -> f64 {
        obstacle::triangle_determinants(&arm.joints(t), &ob.point())
            .iter()
            .map(|d| d.abs())
            .sum()
    };
    assert!(area(&(&th + 1e-4 * &g)) > area(&th));
    // Two obstacles sum.
    let ob2 = Obstacle::new(1.0, 1.5, 0.05);
    let both = obstacle::null_space_vector(&arm, &th, &[ob, ob2], 4.0);
    let sum = &g + obstacle::area_gradient(&arm, &th, &ob2.point());
    assert!((both - sum).amax() < 1e-14);
}

#[test]
fn clearance_is_the_distance_to_the_nearest_moving_link() {
    let joints = [
        Vector2::new(0.0, 0.5),
        Vector2::new(1.0, 0.5),
        Vector2::new(1.0, 1.5),
    ];
    let d = obstacle::clearance(&joints, &Vector2::new(0.5, 0.8));
    assert!((d - 0.3).abs() < 1e-15);
    let d = obstacle::clearance(&joints, &Vector2::new(2.0, 2.5));
    assert!((d - 2f64.sqrt()).abs() < 1e-15);
}

fn final_theta(dt: f64) -> DVector<f64> {
    let mut s = Scene::task1();
    s.dt = dt;
    let mut p = Planner::new(s, Method::NO_AVOIDANCE, None).unwrap();
    while p.time() < 10.0 - 1e-9 {
        p.step().unwrap();
    }
    p.theta().clone()
}

#[test]
fn rk4_error_falls_about_sixteen_times_when_dt_halves() {
    let reference = final_theta(0.4 / 64.0);
    let e1 = (final_theta(0.4) - &reference).norm();
    let e2 = (final_theta(0.2) - &reference).norm();
    let ratio = e1 / e2;
    assert!(
        (12.0..=20.0).contains(&ratio),
        "errors {e1:e} {e2:e}, ratio {ratio}"
    );
    assert!(
        e2 > 1e-12,
        "errors must be above round-off for the ratio to mean anything"
    );
}

struct Reference {
    task: Scene,
    mode: Method,
    min_distance: f64,
    collides: bool,
}

#[test]
fn numerical_runs_match_the_reference_rows_of_the_spec() {
    let rows = [
        Reference {
            task: Scene::task1(),
            mode: Method::NO_AVOIDANCE,
            min_distance: 0.0019,
            collides: true,
        },
        Reference {
            task: Scene::task1(),
            mode: Method::NUMERICAL,
            min_distance: 0.2345,
            collides: false,
        },
        Reference {
            task: Scene::task2(),
            mode: Method::NO_AVOIDANCE,
            min_distance: 0.0016,
            collides: true,
        },
        Reference {
            task: Scene::task2(),
            mode: Method::NUMERICAL,
            min_distance: 0.2193,
            collides: false,
        },
    ];
    for r in rows {
        let t = Planner::run(r.task, r.mode, None).unwrap();
        let s = &t.summary;
        assert_eq!(t.steps.len(), 101);
        let d = s.min_distance.unwrap();
        assert!(
            (d - r.min_distance).abs() < 1e-3,
            "{}: min distance {d}",
            r.mode
        );
        assert_eq!(s.collided, r.collides, "{}", r.mode);
        assert!(
            s.final_error < 1e-6,
            "{}: final error {}",
            r.mode,
            s.final_error
        );
        assert!(s.reached && s.target_reachable && !s.auto_damping);
        let last = t.steps.last().unwrap();
        assert!((last.t - 10.0).abs() < 1e-12);
    }
}

#[test]
fn damping_keeps_joint_rates_finite_at_a_fully_stretched_pose() {
    let arm = Arm::paper();
    let stretched = theta(&[0.3, 0.0, 0.0]);
    let j = arm.jacobian(&stretched);
    // Pull outwards along the arm: impossible, exactly at the singularity.
    let out = Vector2::new(0.3f64.sin(), 0.3f64.cos());
    let v = DVector::zeros(3);
    assert!(matches!(
        ik::theta_dot_symmetric(&j, &out, &v, 0.0),
        Err(Error::Singular(_))
    ));
    let schedule = DampingSchedule::default();
    let delta = schedule.delta(&j);
    assert!((delta - schedule.delta_max).abs() < 1e-12);
    let rates = ik::theta_dot_symmetric(&j, &(0.5 * out), &v, delta).unwrap();
    assert!(rates.iter().all(|r| r.is_finite()));
    // |Phi| <= 1 / (2 sqrt(delta)).
    assert!(rates.norm() <= 0.5 / (2.0 * delta.sqrt()) + 1e-12);
    // Far from singularities the schedule adds nothing: the paper's runs are unchanged.
    assert_eq!(
        schedule.delta(&arm.jacobian(&Scene::task1().theta0_vector())),
        0.0
    );
}

#[test]
fn an_out_of_reach_target_completes_with_finite_numbers_and_is_not_reached() {
    let mut s = Scene::task1();
    s.target = [3.0, 2.0];
    for mode in methods::ALL.iter().copied().filter(|m| !m.uses_networks()) {
        let t = Planner::run(s.clone(), mode, None).unwrap();
        assert!(t
            .steps
            .iter()
            .all(|st| st.theta.iter().all(|x| x.is_finite())));
        let sum = &t.summary;
        assert!(!sum.target_reachable && !sum.reached && sum.auto_damping);
        assert!(sum.final_error.is_finite() && sum.final_error > 0.5);
    }
}

#[test]
fn a_failed_step_reports_an_error_and_leaves_the_state_unchanged() {
    let mut s = Scene::task1();
    s.theta0 = vec![0.0, 0.0, 0.0]; // straight up: J J^T is singular
    s.target = [0.5, 1.5];
    let mut p = Planner::new(s, Method::NO_AVOIDANCE, None).unwrap();
    let before = p.sample().clone();
    assert!(matches!(p.step(), Err(Error::Singular(_))));
    assert_eq!(p.sample(), &before);
    p.set_damping(Some(DampingSchedule::default())).unwrap();
    assert!(p.step().is_ok());
}

#[test]
fn retargeting_plans_a_new_line_from_the_current_end_effector() {
    let mut p = Planner::new(Scene::task1(), Method::NUMERICAL, None).unwrap();
    for _ in 0..30 {
        p.step().unwrap();
    }
    let here = p.sample().ee;
    p.set_target([1.0, 1.2], 2.05).unwrap();
    let line = p.line();
    assert_eq!(line.start, here);
    assert!((line.t0 - 3.0).abs() < 1e-12);
    assert!(
        (line.duration - 2.1).abs() < 1e-12,
        "rounded up to whole steps"
    );
    for _ in 0..21 {
        p.step().unwrap();
    }
    let s = p.summary();
    assert!(s.final_error < 1e-6, "{}", s.final_error);
    // After the line ends the end effector holds still.
    for _ in 0..10 {
        p.step().unwrap();
    }
    assert!(p.summary().final_error < 1e-6);
}

#[test]
fn moving_the_obstacle_takes_effect_at_the_next_step() {
    let mut p = Planner::new(Scene::task1(), Method::NUMERICAL, None).unwrap();
    let v_before = p.null_space(p.theta()).unwrap();
    p.set_obstacles(vec![Obstacle::new(1.2, 1.3, 0.05)])
        .unwrap();
    let v_after = p.null_space(p.theta()).unwrap();
    assert!((v_before - v_after).amax() > 1e-3);
    let d = p.sample().distance.unwrap();
    let expected = obstacle::clearance(&Arm::paper().joints(p.theta()), &Vector2::new(1.2, 1.3));
    assert_eq!(d, expected);
}

#[test]
fn network_modes_without_networks_fail_clearly() {
    for mode in methods::ALL.iter().copied().filter(|m| m.uses_networks()) {
        let err = Planner::new(Scene::task1(), mode, None).unwrap_err();
        assert!(matches!(err, Error::NetworksUnavailable(_)));
        assert!(err.to_string().contains("networks not available"));
    }
    let mut p = Planner::new(Scene::task1(), Method::NUMERICAL, None).unwrap();
    assert!(p.set_method(Method::CASE3).is_err());
    assert_eq!(p.method(), Method::NUMERICAL);
}

/// A way to spoil a scene, and the words its error message must contain.
/// A change that spoils a scene, and the error it must give.
type BadInput = (Box<dyn Fn(&mut Scene)>, fn(&Error) -> bool);

#[test]
fn bad_input_is_rejected_with_an_error_naming_the_problem() {
    use Error::*;
    let named = |e: &Error, name: &str| e.to_string().contains(name);
    let cases: Vec<BadInput> = vec![
        (
            Box::new(|s| s.theta0[1] = f64::NAN),
            |e| matches!(e, NonFinite { what } if what == "theta_2"),
        ),
        (Box::new(|s| s.theta0 = vec![0.1, 0.2]), |e| {
            matches!(
                e,
                DimensionMismatch {
                    expected: 3,
                    found: 2,
                    ..
                }
            )
        }),
        (
            Box::new(|s| s.target[0] = f64::INFINITY),
            |e| matches!(e, NonFinite { what } if what == "target x"),
        ),
        (
            Box::new(|s| s.obstacles[0].centre[1] = f64::NAN),
            |e| matches!(e, NonFinite { what } if what == "obstacle y"),
        ),
        (
            Box::new(|s| s.obstacles[0].radius = 0.0),
            |e| matches!(e, NotPositive { what, .. } if what == "obstacle radius"),
        ),
        (Box::new(|s| s.obstacles[0].centre = [0.02, 0.3]), |e| {
            matches!(e, ObstacleOnPost { .. })
        }),
        (
            Box::new(|s| s.dt = 0.0),
            |e| matches!(e, NotPositive { what, value } if what == "time step dt" && *value == 0.0),
        ),
        (Box::new(|s| s.dt = -0.1), |e| {
            matches!(e, NotPositive { .. })
        }),
        (Box::new(|s| s.tf = 10.05), |e| {
            matches!(e, NotWholeSteps { .. })
        }),
        (Box::new(|s| s.tf = 1e8), |e| {
            matches!(e, TooManySteps { .. })
        }),
        // Finite angles and lengths whose sums overflow (found by fuzzing).
        (
            Box::new(|s| s.theta0 = vec![1e308, 1e308, 0.0]),
            |e| matches!(e, TooLarge { what, unit: "rad", .. } if what == "theta_1"),
        ),
        (
            Box::new(|s| s.feedback_gain = -1.0),
            |e| matches!(e, Negative { what, .. } if what == "feedback gain"),
        ),
        // Numbers so large that squared distances overflow.
        (
            Box::new(|s| s.target = [1e300, 0.0]),
            |e| matches!(e, TooLarge { what, .. } if what == "target x"),
        ),
        (
            Box::new(|s| s.obstacles[0].centre = [0.5, -1e200]),
            |e| matches!(e, TooLarge { what, .. } if what == "obstacle y"),
        ),
        // RK4 integrates the closed-loop error e' = -K e stably only for K dt < 2.785.
        (
            Box::new(|s| s.feedback_gain = 30.0),
            |e| matches!(e, UnstableGain { gain, max_gain, .. } if *gain == 30.0 && (*max_gain - 25.0).abs() < 1e-9),
        ),
    ];
    for (mutate, expected) in cases {
        let mut s = Scene::task1();
        mutate(&mut s);
        let err = Planner::new(s, Method::NUMERICAL, None).unwrap_err();
        assert!(expected(&err), "unexpected error: {err:?}");
        // Every message is a sentence a user can act on.
        assert!(err.to_string().len() > 20, "{err}");
    }
    // The parameters are checked where they are set, a refused value
    // changing nothing.
    type Case = (&'static Param, f64, fn(&Error) -> bool);
    let params: Vec<Case> = vec![
        (
            &LAMBDA,
            f64::NAN,
            |e| matches!(e, NonFinite { what } if what == "lambda"),
        ),
        (
            &LAMBDA,
            -1.0,
            |e| matches!(e, Negative { what, .. } if what == "lambda"),
        ),
        // Gains so large that the first step overflows.
        (
            &LAMBDA,
            1e308,
            |e| matches!(e, OutOfRange { what, max, .. } if what == "lambda" && *max == 1000.0),
        ),
        (
            &DELTA,
            1e308,
            |e| matches!(e, OutOfRange { what, .. } if what.contains("delta")),
        ),
        (
            &DELTA,
            -1.0,
            |e| matches!(e, Negative { what, .. } if what.contains("delta")),
        ),
    ];
    for (param, value, expected) in params {
        let mut s = Scene::task1();
        let err = s.set_param(param, value).unwrap_err();
        assert!(
            expected(&err),
            "{param} = {value}: unexpected error: {err:?}"
        );
        assert!(err.to_string().len() > 20, "{err}");
        assert_eq!(s, Scene::task1(), "a refused value changes nothing");
    }
    // The messages name the problem.
    let mut s = Scene::task1();
    s.feedback_gain = 30.0;
    let err = Planner::new(s, Method::NUMERICAL, None).unwrap_err();
    assert!(named(&err, "makes the RK4 step unstable"), "{err}");
    assert!(matches!(
        Arm::new(0.5, vec![0.6, -0.85, 0.6]),
        Err(NotPositive { what, .. }) if what == "link length L2"
    ));
    assert!(matches!(
        Arm::new(0.5, vec![0.6, 0.0, 0.6]),
        Err(NotPositive { .. })
    ));
    assert!(matches!(
        Arm::new(f64::NAN, vec![0.6, 0.6]),
        Err(NonFinite { .. })
    ));
    assert!(matches!(
        Arm::new(-0.5, vec![0.6, 0.6]),
        Err(Negative { .. })
    ));
    assert!(Arm::new(0.5, vec![0.1; 32]).is_ok());
    for n in [0, 1, 33, 100] {
        assert!(matches!(
            Arm::new(0.5, vec![0.1; n]),
            Err(LinkCount { found, min: 2, max: 32 }) if found == n
        ));
    }
    assert!(matches!(
        "case4".parse::<Method>(),
        Err(UnknownName { kind: "mode", .. })
    ));
    assert!(matches!(Scene::task(3), Err(UnknownTask { task: 3 })));
    let mut p = Planner::new(Scene::task1(), Method::NUMERICAL, None).unwrap();
    assert!(p.set_target([f64::NAN, 0.0], 1.0).is_err());
    assert!(p.set_target([0.5, 0.5], 0.0).is_err());
    assert!(p
        .set_obstacles(vec![Obstacle::new(0.0, 0.25, 0.05)])
        .is_err());
    assert!(p.set_lambda(f64::INFINITY).is_err());
    assert_eq!(
        p.scene().obstacles[0].centre,
        [0.5, 0.5],
        "rejected input changes nothing"
    );
}

#[test]
fn an_obstacle_exactly_on_a_joint_is_handled() {
    // D_k = 0 for the links meeting at that joint: eq. (15) gives 0, not NaN.
    let arm = Arm::paper();
    let th = Scene::task1().theta0_vector();
    let p = arm.joints(&th);
    let o = Vector2::new(p[2][0], p[2][1]);
    let v = obstacle::null_space_vector(&arm, &th, &[Obstacle::new(o[0], o[1], 0.05)], 4.0);
    // O lies on links 2 and 3 (D_2 = D_3 = 0 exactly), so only link 1 pushes:
    // v = (sign(D_1) dD_1/dtheta_1, 0, 0) with lambda = 4.
    let d = obstacle::triangle_determinants(&arm.joints(&th), &o);
    assert_eq!((d[1], d[2]), (0.0, 0.0));
    let dd = obstacle::determinant_gradient(&arm, &th, &o);
    assert_eq!(v[1], 0.0);
    assert_eq!(v[2], 0.0);
    assert!((v[0] - d[0].signum() * dd[(0, 0)]).abs() < 1e-12, "{v}");
    assert!(v[0] != 0.0);
    let mut s = Scene::task1();
    s.obstacles = vec![Obstacle::new(p[2][0], p[2][1], 0.05)];
    let t = Planner::run(s, Method::NUMERICAL, None).unwrap();
    assert!(
        t.summary.collided,
        "starting inside the obstacle is a collision"
    );
}

/// A random arm of `n` links on a post, with lengths in [0.3, 0.9].
fn random_arm(rng: &mut Lcg, n: usize) -> Arm {
    Arm::new(0.5, (0..n).map(|_| rng.uniform(0.3, 0.9)).collect()).unwrap()
}

#[test]
fn the_area_gradient_is_the_gradient_of_the_summed_triangle_areas_for_any_arm() {
    // g_i = sum_k sign(D_k) dD_k/dtheta_i (eq. 15), computed in O(n) by
    // suffix sums; checked against the n x n matrix of dD_k/dtheta_i and
    // against central differences of V = sum_k |D_k|.
    let mut rng = Lcg(11);
    for n in 2..=6 {
        let arm = random_arm(&mut rng, n);
        for _ in 0..20 {
            let th = rng.theta(n);
            let o = Vector2::new(rng.uniform(-1.5, 1.5), rng.uniform(-0.5, 2.5));
            let g = obstacle::area_gradient(&arm, &th, &o);
            let d = obstacle::triangle_determinants(&arm.joints(&th), &o);
            let dd = obstacle::determinant_gradient(&arm, &th, &o);
            let sign = |x: f64| {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            };
            for i in 0..n {
                let from_matrix: f64 = (0..n).map(|k| sign(d[k]) * dd[(k, i)]).sum();
                assert!((g[i] - from_matrix).abs() < 1e-12, "n = {n}, i = {i}");
            }
            if d.iter().all(|x| x.abs() > 1e-3) {
                let area = |t: &DVector<f64>| -> f64 {
                    obstacle::triangle_determinants(&arm.joints(t), &o)
                        .iter()
                        .map(|x| x.abs())
                        .sum()
                };
                let h = 1e-6;
                for i in 0..n {
                    let (mut tp, mut tm) = (th.clone(), th.clone());
                    tp[i] += h;
                    tm[i] -= h;
                    let fd = (area(&tp) - area(&tm)) / (2.0 * h);
                    assert!((fd - g[i]).abs() < 1e-6, "n = {n}: {fd} vs {}", g[i]);
                }
            }
        }
    }
}

#[test]
fn a_pose_holds_the_kinematics_of_its_angles() {
    let mut rng = Lcg(12);
    for n in 2..=6 {
        let arm = random_arm(&mut rng, n);
        let th = rng.theta(n);
        let pose = Pose::new(&arm, th.as_slice()).unwrap();
        let joints = arm.joints(&th);
        for (p, q) in pose.joints().iter().zip(&joints) {
            assert_eq!(p, &[q[0], q[1]]);
        }
        let j = arm.jacobian(&th);
        assert_eq!(pose.jacobian(), j.as_slice());
        let phi = arm.absolute_angles(&th);
        for (i, a) in phi.iter().enumerate() {
            assert!((pose.sin()[i] - a.sin()).abs() < 3e-16);
            assert!((pose.cos()[i] - a.cos()).abs() < 3e-16);
        }
        assert!((pose.sigma_min() - ik::smallest_singular_value(&j)).abs() < 1e-15);
        assert!((pose.manipulability() - ik::manipulability(&j)).abs() < 1e-15);
        let o = Vector2::new(0.4, 0.7);
        assert_eq!(pose.clearance([0.4, 0.7]), obstacle::clearance(&joints, &o));
    }
}

#[test]
fn a_pose_refuses_angles_that_do_not_fit_and_stays_as_it_was() {
    let arm = Arm::paper();
    let mut pose = Pose::new(&arm, &[0.1, 0.2, 0.3]).unwrap();
    let before = pose.clone();
    assert!(matches!(
        pose.update(&arm, &[0.1, 0.2]),
        Err(Error::DimensionMismatch { .. })
    ));
    let four = Arm::new(0.5, vec![0.5; 4]).unwrap();
    assert!(pose.update(&four, &[0.1, 0.2, 0.3, 0.4]).is_err());
    assert_eq!(pose, before);
    assert!(matches!(
        Pose::new(&arm, &[0.1, f64::NAN, 0.3]),
        Err(Error::NonFinite { .. })
    ));
}

#[test]
fn sin_cos_is_within_two_ulp_of_the_c_library() {
    // fdlibm's reduction and kernels; libm beyond 8e5 rad.
    let mut worst = 0.0f64;
    for i in 0..=200_000 {
        for scale in [4.0, 100.0, 1e5, 1e6] {
            let x = (i as f64 / 100_000.0 - 1.0) * scale;
            let (s, c) = kinematics::sin_cos(x);
            let (s0, c0) = x.sin_cos();
            worst = worst.max((s - s0).abs()).max((c - c0).abs());
            // Two ulp of a value of magnitude at most 1.
            assert!(
                (s - s0).abs() <= 2.3e-16 && (c - c0).abs() <= 2.3e-16,
                "x = {x}"
            );
        }
    }
    assert!(worst > 0.0, "not the library's own function");
    let (s, c) = kinematics::sin_cos(f64::NAN);
    assert!(s.is_nan() && c.is_nan());
    let (s, c) = kinematics::sin_cos(f64::INFINITY);
    assert!(s.is_nan() && c.is_nan());
    assert_eq!(kinematics::sin_cos(0.0), (0.0, 1.0));
}

#[test]
fn a_learned_phi_takes_a_constant_delta_exactly_when_it_is_exact() {
    // Phi_delta = Phi_0 (I + delta Phi_0^T Phi_0)^-1 = J^T (J J^T + delta I)^-1.
    let mut rng = Lcg(13);
    for n in 2..=5 {
        let arm = random_arm(&mut rng, n);
        let j = arm.jacobian(&rng.theta(n));
        if ik::smallest_singular_value(&j) < 0.05 {
            continue;
        }
        for delta in [0.0, 1e-4, 0.01, 0.3] {
            let exact = ik::phi(&j, delta).unwrap();
            let mut damped: Vec<f64> = {
                let p0 = ik::phi(&j, 0.0).unwrap();
                (0..n).flat_map(|i| [p0[(i, 0)], p0[(i, 1)]]).collect()
            };
            ik::damp_phi(&mut damped, delta).unwrap();
            for i in 0..n {
                for c in 0..2 {
                    let e = exact[(i, c)];
                    assert!((damped[2 * i + c] - e).abs() < 1e-12 * (1.0 + e.abs()));
                }
            }
        }
    }
    assert!(ik::damp_phi(&mut [1.0, 2.0], -0.1).is_err());
    assert!(ik::damp_phi(&mut [1.0, 2.0], f64::NAN).is_err());
}

#[test]
fn the_allocation_free_routines_equal_the_matrix_forms_and_refuse_wrong_sizes() {
    let arm = Arm::paper();
    let th = Scene::task1().theta0_vector();
    let j = arm.jacobian(&th);
    let v = DVector::from_vec(vec![0.2, -0.1, 0.3]);
    let xdot = Vector2::new(-0.1, -0.08);
    let m = ik::theta_dot_symmetric(&j, &xdot, &v, 0.01).unwrap();
    let mut out = [0.0; 3];
    ik::theta_dot_symmetric_into(j.as_slice(), [-0.1, -0.08], v.as_slice(), 0.01, &mut out)
        .unwrap();
    assert_eq!(out, [m[0], m[1], m[2]]);
    let mut phi = [0.0; 6];
    ik::phi_into(j.as_slice(), 0.0, &mut phi).unwrap();
    let p = ik::phi(&j, 0.0).unwrap();
    let net = ik::theta_dot_network(&p, &j, &xdot, &v);
    ik::theta_dot_network_into(&phi, j.as_slice(), [-0.1, -0.08], v.as_slice(), &mut out).unwrap();
    assert!((net - DVector::from_row_slice(&out)).amax() < 1e-15);
    // Wrong sizes are errors, not panics.
    assert!(
        ik::theta_dot_symmetric_into(j.as_slice(), [0.0; 2], &[0.0; 2], 0.0, &mut out).is_err()
    );
    assert!(
        ik::theta_dot_symmetric_into(&j.as_slice()[..5], [0.0; 2], &[0.0; 3], 0.0, &mut out)
            .is_err()
    );
    assert!(ik::phi_into(j.as_slice(), 0.0, &mut phi[..5]).is_err());
    assert!(
        ik::theta_dot_network_into(&phi[..4], j.as_slice(), [0.0; 2], &[0.0; 3], &mut out).is_err()
    );
}

#[test]
fn the_planner_rates_through_its_workspace_equal_the_convenience_form() {
    for mode in methods::ALL.iter().copied().filter(|m| !m.uses_networks()) {
        let mut p = Planner::new(Scene::task2(), mode, None).unwrap();
        let th = DVector::from_vec(vec![0.4, 1.2, 0.3]);
        let a = p.theta_dot(&th, &Vector2::new(-0.05, 0.02)).unwrap();
        let mut b = [0.0; 3];
        p.theta_dot_into(th.as_slice(), [-0.05, 0.02], &mut b)
            .unwrap();
        assert_eq!(a.as_slice(), &b);
        assert!(p.theta_dot_into(&[0.1, 0.2], [0.0; 2], &mut b).is_err());
    }
}

#[test]
fn reset_returns_to_the_state_of_a_fresh_planner() {
    let mut s = Scene::task1();
    s.damping = Some(DampingSchedule::default());
    let fresh = Planner::new(s.clone(), Method::NUMERICAL, None).unwrap();
    let mut p = Planner::new(s, Method::NUMERICAL, None).unwrap();
    for _ in 0..37 {
        p.step().unwrap();
    }
    p.reset();
    assert_eq!(p.sample(), fresh.sample());
    assert_eq!(p.summary(), fresh.summary());
    assert_eq!(p.line(), fresh.line());
    for _ in 0..100 {
        p.step().unwrap();
    }
    let run = Planner::run(Scene::task1(), Method::NUMERICAL, None).unwrap();
    assert!((p.summary().final_error - run.summary.final_error).abs() < 1e-12);
}
