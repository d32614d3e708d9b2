//! Self-motion: an elbow pulled toward a point moves the arm in the null
//! space of `J`, the hand holding still (closed loop on the hand); the
//! slider's motion along a joint's self-motion does the same for a
//! keyboard; the page's session drags an elbow this way.

use redundant_ik::planner::self_motion::SelfMotion;
use redundant_ik::session::{Handle, Session};
use redundant_ik::{Arm, Pose, Scene};

fn hand(arm: &Arm, theta: &[f64]) -> [f64; 2] {
    Pose::new(arm, theta).unwrap().end_effector()
}

fn drift(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

#[test]
fn an_elbow_dragged_through_a_one_radian_swing_leaves_the_hand_within_1e_4_m() {
    let scene = Scene::task1();
    let arm = &scene.arm;
    let mut theta = scene.theta0.clone();
    let start = hand(arm, &theta);
    let mut m = SelfMotion::new(arm);
    // Pull the first elbow P(1) round the post, clockwise (joint 1's way),
    // in small moves as a pointer does, until a joint has swung by 1 rad
    // (joint 3: the arm stretches before joint 2 has).
    let mut worst = 0.0f64;
    let mut moves = 0;
    let swing = |t: &[f64]| {
        t.iter()
            .zip(&scene.theta0)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    while swing(&theta) < 1.0 {
        let p = Pose::new(arm, &theta).unwrap().joints()[1];
        let (dx, dy) = (p[0], p[1] - arm.post());
        let to = [p[0] + 0.1 * dy, p[1] - 0.1 * dx];
        m.drag(arm, &mut theta, 1, to, start, 10).unwrap();
        worst = worst.max(drift(hand(arm, &theta), start));
        moves += 1;
        assert!(moves < 500, "the elbow does not follow: {theta:?}");
    }
    eprintln!("hand drift over the swing: {worst:.1e} m in {moves} moves");
    assert!(worst < 1e-4, "the hand drifted {worst} m");
    // Joint 1 turned the way it was pulled.
    assert!(theta[0] > scene.theta0[0] + 0.1, "{theta:?}");
}

#[test]
fn the_sliders_motion_moves_the_joint_the_way_asked_and_holds_the_hand() {
    let scene = Scene::task1();
    let arm = &scene.arm;
    let start = hand(arm, &scene.theta0);
    let mut m = SelfMotion::new(arm);
    for amount in [0.5, -0.5] {
        let mut theta = scene.theta0.clone();
        m.along(arm, &mut theta, 1, amount, start).unwrap();
        let d = drift(hand(arm, &theta), start);
        assert!(d < 1e-6, "{amount}: drift {d}, {theta:?}");
        let moved: f64 = theta
            .iter()
            .zip(&scene.theta0)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt();
        assert!((moved - 0.5).abs() < 0.05, "{moved}");
        // It sets out the way asked: theta_2 grows for amount > 0.
        let mut first = scene.theta0.clone();
        m.along(arm, &mut first, 1, 0.01 * amount.signum(), start)
            .unwrap();
        assert_eq!((first[1] - scene.theta0[1]).signum(), amount.signum());
    }
}

#[test]
fn what_is_no_elbow_or_no_point_is_refused_and_changes_nothing() {
    let scene = Scene::task1();
    let arm = &scene.arm;
    let mut m = SelfMotion::new(arm);
    let mut theta = scene.theta0.clone();
    let hold = hand(arm, &theta);
    for joint in [0, 3, 7] {
        assert!(m.drag(arm, &mut theta, joint, [0.5, 0.5], hold, 5).is_err());
    }
    assert!(m
        .drag(arm, &mut theta, 1, [f64::NAN, 0.5], hold, 5)
        .is_err());
    assert!(m.along(arm, &mut theta, 9, 0.1, hold).is_err());
    assert!(m.along(arm, &mut theta, 1, f64::INFINITY, hold).is_err());
    assert_eq!(theta, scene.theta0);
}

#[test]
fn in_the_session_a_dragged_elbow_becomes_the_runs_start_and_the_hand_stays() {
    let mut s = Session::new(1).unwrap();
    let before = s.planner().sample().ee;
    let elbow = s.planner().pose().joints()[2];
    s.drag_start(Some(Handle::Joint(2)));
    for k in 1..=10 {
        let t = f64::from(k) * 0.02;
        s.drag_to([elbow[0] + t, elbow[1] + t]).unwrap();
    }
    s.drag_end([elbow[0] + 0.2, elbow[1] + 0.2]).unwrap();
    let after = s.planner().sample();
    assert!(drift(after.ee, before) < 1e-6);
    assert_eq!(after.t, 0.0);
    assert_ne!(after.joints[2], elbow);
    assert_eq!(s.planner().scene().theta0, after.theta);
    // An arm with limits refuses a pose past them, changing nothing.
    let mut limited = Session::new(1).unwrap();
    let theta0 = limited.planner().scene().theta0.clone();
    let ranges: Vec<String> = theta0
        .iter()
        .map(|t| format!("{}:{}", t - 0.01, t + 0.01))
        .collect();
    limited
        .set_arm_limits(Some(ranges.join(",").parse().unwrap()), None)
        .unwrap();
    limited.drag_start(Some(Handle::Joint(1)));
    let e = limited.drag_to([1.0, 2.0]).unwrap_err().to_string();
    assert!(e.contains("limits"), "{e}");
    assert_eq!(limited.planner().scene().theta0, theta0);
}
