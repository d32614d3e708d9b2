//! Self-motion of an arm in space, as a specification: the slider's motion
//! along a joint's self-motion and an elbow dragged on the stage move the
//! arm in the null space of its `3 x n` Jacobian, the hand held still; the
//! new pose is the run's start; what is no elbow, no number or past a
//! limit is refused and changes nothing. (The integrator is the plane's,
//! `planner::self_motion`, generic over the hand's dimension.)

use redundant_ik::planner::self_motion::SelfMotion;
use redundant_ik::planner::Method;
use redundant_ik::planner::Planner;
use redundant_ik::scene::SpaceScene;
use redundant_ik::session::space::SpaceSession;
use redundant_ik::space::SpacePose;

fn drift(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[test]
fn the_integrator_moves_a_chain_in_space_along_a_joints_self_motion_and_holds_the_hand() {
    for key in ["panda", "iiwa14"] {
        let scene = SpaceScene::by_key(key).unwrap();
        let chain = &scene.arm;
        let start = SpacePose::new(chain, &scene.theta0).unwrap().hand();
        let mut motion = SelfMotion::new(chain);
        for (joint, amount) in [(0, 0.3), (2, -0.4), (4, 0.25)] {
            let mut theta = scene.theta0.clone();
            motion
                .along(chain, &mut theta, joint, amount, start)
                .unwrap();
            let hand = SpacePose::new(chain, &theta).unwrap().hand();
            assert!(
                drift(hand, start) < 1e-4,
                "{key} joint {}: {}",
                joint + 1,
                drift(hand, start)
            );
            let moved: f64 = theta
                .iter()
                .zip(&scene.theta0)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(
                (moved - amount.abs()).abs() < 0.05 * amount.abs(),
                "{key}: arc {moved}"
            );
            assert_eq!(
                (theta[joint] - scene.theta0[joint]).signum(),
                amount.signum(),
                "{key}: the way asked"
            );
        }
    }
}

#[test]
fn the_slider_makes_the_moved_pose_the_runs_start_with_the_hand_where_it_was() {
    let mut s = SpaceSession::new("panda", Method::NUMERICAL).unwrap();
    s.run_until(2.0).unwrap();
    let hand = s.pose().hand();
    let before = s.pose().theta().to_vec();
    s.self_motion(2, 0.3).unwrap();
    assert_eq!(s.sample().unwrap().t, 0.0, "paused at the new start");
    assert!(!s.running());
    assert!(drift(s.pose().hand(), hand) < 1e-4);
    assert_ne!(s.scene().theta0, before);
    // The run is the planner's own run from that start.
    let own = Planner::new(s.scene().clone(), Method::NUMERICAL, None)
        .unwrap()
        .run_to_end()
        .unwrap();
    assert_eq!(s.samples(), &own.steps[..]);
}

#[test]
fn an_elbow_dragged_on_the_stage_follows_the_pointer_while_the_hand_holds() {
    let mut s = SpaceSession::new("panda", Method::NUMERICAL).unwrap();
    let proj = s.projection(800.0, 600.0);
    let hand = s.pose().hand();
    // The Panda's second joint sits on its first: no elbow there.
    let [x1, y1, _] = proj.project(s.pose().joint_origin(1));
    assert_ne!(s.elbow_at(&proj, x1, y1, 0.0), Some(1));
    let k = 3;
    let [x, y, _] = proj.project(s.pose().joint_origin(k));
    assert_eq!(s.grab_elbow(&proj, x + 2.0, y, 2.0), Some(k));
    assert_eq!(s.state().dragging.as_deref(), Some("elbow 4"));
    // Toward where the elbow can go with the hand held: where a motion
    // along joint 3's self-motion takes it.
    let mut there = s.clone();
    there.self_motion(2, 1.0).unwrap();
    let [gx, gy, _] = proj.project(there.pose().joint_origin(k));
    for _ in 0..20 {
        s.pointer_move(&proj, gx + 2.0, gy).unwrap();
    }
    s.pointer_up();
    let [ex, ey, _] = proj.project(s.pose().joint_origin(k));
    let (before, after) = ((x - gx).hypot(y - gy), (ex - gx).hypot(ey - gy));
    assert!(before > 10.0, "a drag of {before} px");
    assert!(
        after < 0.25 * before,
        "the elbow came to the pointer: {before} px -> {after} px"
    );
    assert!(
        drift(s.pose().hand(), hand) < 1e-3,
        "the hand held: {}",
        drift(s.pose().hand(), hand)
    );
    assert_eq!(s.scene().theta0, s.pose().theta());
}

#[test]
fn no_elbow_no_number_and_a_pose_past_a_limit_are_refused_and_change_nothing() {
    let mut s = SpaceSession::new("panda", Method::NUMERICAL).unwrap();
    let scene = s.scene().clone();
    assert!(
        s.self_motion(7, 0.1).is_err(),
        "the Panda has joints 0 to 6"
    );
    assert!(s.self_motion(0, f64::NAN).is_err());
    assert!(
        s.drag_joint(0, [0.3, 0.0, 0.5]).is_err(),
        "the first joint is no elbow"
    );
    assert!(s.drag_joint(3, [f64::INFINITY, 0.0, 0.5]).is_err());
    // Far along joint 4's self-motion: past its limit (-3.07 to -0.07 rad).
    assert!(s.self_motion(3, -40.0).is_err());
    assert_eq!(*s.scene(), scene);
    let proj = s.projection(800.0, 600.0);
    assert_eq!(s.elbow_at(&proj, 2.0, 2.0, 4.0), None);
    assert_eq!(s.grab_elbow(&proj, f64::NAN, 2.0, 4.0), None);
}

#[test]
fn a_start_pose_is_set_checked_and_kept_in_the_state() {
    let mut s = SpaceSession::new("iiwa14", Method::NUMERICAL).unwrap();
    let mut theta0 = s.scene().theta0.clone();
    theta0[2] += 0.2;
    s.set_start(&theta0).unwrap();
    assert_eq!(s.state().theta0, &theta0[..]);
    assert_eq!(s.pose().theta(), &theta0[..]);
    let scene = s.scene().clone();
    assert!(
        s.set_start(&theta0[..6]).is_err(),
        "six angles for seven joints"
    );
    assert!(s.set_start(&[f64::NAN; 7]).is_err());
    assert!(
        s.set_start(&[0.0, 0.0, 0.0, 9.0, 0.0, 0.0, 0.0]).is_err(),
        "past joint 4's limit"
    );
    assert_eq!(*s.scene(), scene);
}
