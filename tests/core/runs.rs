//! The integrator, the paper's reference runs, damping, retargeting, moving
//! the obstacle and bad input.

use super::*;
use redundant_ik::nalgebra::DVector;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

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
    method: Method,
    min_distance: f64,
    collides: bool,
}

#[test]
fn numerical_runs_match_the_reference_rows_of_the_spec() {
    let rows = [
        Reference {
            task: Scene::task1(),
            method: Method::NO_AVOIDANCE,
            min_distance: 0.0019,
            collides: true,
        },
        Reference {
            task: Scene::task1(),
            method: Method::NUMERICAL,
            min_distance: 0.2345,
            collides: false,
        },
        Reference {
            task: Scene::task2(),
            method: Method::NO_AVOIDANCE,
            min_distance: 0.0016,
            collides: true,
        },
        Reference {
            task: Scene::task2(),
            method: Method::NUMERICAL,
            min_distance: 0.2193,
            collides: false,
        },
    ];
    for r in rows {
        let t = Planner::run(r.task, r.method, None).unwrap();
        let s = &t.summary;
        assert_eq!(t.steps.len(), 101);
        let d = s.min_distance.unwrap();
        assert!(
            (d - r.min_distance).abs() < 1e-3,
            "{}: min distance {d}",
            r.method
        );
        assert_eq!(s.collided, r.collides, "{}", r.method);
        assert!(
            s.final_error < 1e-6,
            "{}: final error {}",
            r.method,
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
    for method in methods::ALL.iter().copied().filter(|m| !m.uses_networks()) {
        let t = Planner::run(s.clone(), method, None).unwrap();
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
    let v_before = p
        .null_space(p.theta().as_slice())
        .map(DVector::from_vec)
        .unwrap();
    p.set_obstacles(vec![Obstacle::new(1.2, 1.3, 0.05)])
        .unwrap();
    let v_after = p
        .null_space(p.theta().as_slice())
        .map(DVector::from_vec)
        .unwrap();
    assert!((v_before - v_after).amax() > 1e-3);
    let d = p.sample().distance.unwrap();
    let expected = obstacle::clearance(&Arm::paper().joints(p.theta()), &Vector2::new(1.2, 1.3));
    assert_eq!(d, expected);
}

#[test]
fn network_methods_without_networks_fail_clearly() {
    for method in methods::ALL.iter().copied().filter(|m| m.uses_networks()) {
        let err = Planner::new(Scene::task1(), method, None).unwrap_err();
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
        Err(UnknownName { kind: "method", .. })
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
