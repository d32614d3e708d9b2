//! The playground's arms and obstacles, and the shipped network sets.

use super::*;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

// ---- the playground: arms and several obstacles ---------------------------

#[test]
fn a_new_arm_restarts_from_its_own_start_pose_and_the_numerical_methods_run_at_once() {
    let mut s = Session::new(1).unwrap();
    s.set_arm(four_links()).unwrap();
    let st = s.state();
    assert_eq!(st.arm.links().len(), 4);
    assert_eq!(st.theta.len(), 4);
    assert_eq!(st.t, 0.0);
    assert!(
        st.joints.iter().all(|p| p[1] > 0.0),
        "start pose above the ground"
    );
    for method in methods::ALL.iter().copied().filter(|m| !m.uses_networks()) {
        s.set_method(method).unwrap();
        s.run_task();
        s.run_until(10.0).unwrap();
        assert!(s.state().final_error < 5e-3, "{method} reaches the target");
    }
}

#[test]
fn networks_for_another_arm_are_set_aside_and_the_network_cases_fall_back() {
    let mut s = Session::new(1).unwrap();
    s.set_networks(Arc::new(Networks::embedded().unwrap()))
        .unwrap();
    s.set_method(Method::CASE3).unwrap();
    s.set_arm(four_links()).unwrap();
    assert!(s.networks().is_none());
    assert_eq!(s.state().method, "numerical");
    assert!(matches!(
        s.set_networks(Arc::new(Networks::embedded().unwrap())),
        Err(Error::NetworksForAnotherArm { .. })
    ));
    // Back to the paper's arm: its task, and the networks install again.
    s.set_arm(Arm::paper()).unwrap();
    s.set_networks(Arc::new(Networks::embedded().unwrap()))
        .unwrap();
    s.set_method(Method::CASE3).unwrap();
}

#[test]
fn a_bad_arm_is_refused_and_the_old_one_stays() {
    let mut s = Session::new(1).unwrap();
    assert!(Arm::new(0.5, vec![0.6]).is_err());
    assert!(Arm::new(f64::NAN, vec![0.6, 0.6]).is_err());
    assert!(Arm::new(0.5, vec![0.6, -0.1]).is_err());
    assert_eq!(s.state().arm, &Arm::paper());
    s.set_arm(four_links()).unwrap();
    assert_eq!(s.state().arm, &four_links());
}

#[test]
fn obstacles_can_be_added_moved_and_removed_up_to_eight() {
    let mut s = Session::new(1).unwrap();
    assert_eq!(s.obstacles().len(), 1);
    assert!(matches!(
        s.add_obstacle(Obstacle::new(0.0, 0.2, 0.05)),
        Err(Error::ObstacleOnPost { .. })
    ));
    for k in 1..MAX_OBSTACLES {
        let i = s
            .add_obstacle(Obstacle::new(-0.6 + 0.1 * k as f64, 1.6, 0.04))
            .unwrap();
        assert_eq!(i, k);
    }
    assert!(matches!(
        s.add_obstacle(Obstacle::new(0.9, 0.9, 0.05)),
        Err(Error::OutOfRange { .. })
    ));
    assert_eq!(s.obstacles().len(), MAX_OBSTACLES);
    s.move_obstacle(3, [1.0, 1.7]).unwrap();
    assert_eq!(s.obstacles()[3].centre, [1.0, 1.7]);
    assert_eq!(s.obstacles()[3].radius, 0.04, "moving keeps the radius");
    s.remove_obstacle(0).unwrap();
    assert_eq!(s.obstacles().len(), MAX_OBSTACLES - 1);
    assert_eq!(s.obstacles()[2].centre, [1.0, 1.7], "the others shift down");
    assert!(s.remove_obstacle(99).is_err());
    assert!(s.add_obstacle(Obstacle::new(0.5, 0.5, -1.0)).is_err());
    assert!(s.add_obstacle(Obstacle::new(f64::NAN, 0.5, 0.05)).is_err());
    assert_eq!(
        s.obstacles().len(),
        MAX_OBSTACLES - 1,
        "refusals change nothing"
    );
}

#[test]
fn the_readout_follows_the_nearest_obstacle() {
    let mut s = Session::new(1).unwrap();
    // The canonical obstacle at (0.5, 0.5), and one right on the start arm's last link.
    let joints = s.state().joints.to_vec();
    let (a, b) = (joints[2], joints[3]);
    let on = [(a[0] + b[0]) / 2.0 + 0.06, (a[1] + b[1]) / 2.0];
    s.add_obstacle(Obstacle::new(on[0], on[1], 0.02)).unwrap();
    s.reset();
    let st = s.state();
    assert_eq!(st.nearest, Some(1));
    assert!(st.distance.unwrap() < 0.07);
    s.remove_obstacle(1).unwrap();
    s.reset();
    assert_eq!(s.state().nearest, Some(0));
}

#[test]
fn dragging_moves_the_obstacle_grabbed() {
    let mut s = Session::new(1).unwrap();
    s.add_obstacle(Obstacle::new(-0.5, 1.5, 0.05)).unwrap();
    s.drag_start(Some(Handle::Obstacle(1)));
    assert_eq!(s.state().dragging, Some("obstacle"));
    assert_eq!(s.state().dragging_obstacle, Some(1));
    s.drag_to([-0.6, 1.4]).unwrap();
    assert_eq!(s.obstacles()[1].centre, [-0.6, 1.4]);
    assert_eq!(s.obstacles()[0].centre, [0.5, 0.5]);
    s.drag_end([-0.6, 1.4]).unwrap();
}

#[test]
fn a_shipped_network_set_is_installed_by_name_and_the_method_settings_survive_a_task() {
    use redundant_ik::networks::NetworkSet;
    let mut s = Session::new(1).unwrap();
    s.set_method(Method::CASE3).unwrap();
    assert_eq!(
        s.network_set(),
        Some(NetworkSet::Paper),
        "the paper's set by default"
    );
    s.use_network_set(NetworkSet::Reach).unwrap();
    assert_eq!(s.state().network_set, Some("reach"));
    let range = s.state().trained_range.unwrap().clone();
    assert!(range.phi.names.iter().any(|n| n == "sin theta2"));
    s.set_param(&methods::REFINE, 2.0).unwrap();
    s.set_param(&methods::SIGN_SMOOTHING, 0.05).unwrap();
    s.load_task(2).unwrap();
    let st = s.state();
    assert_eq!(
        (st.params.get("refine"), st.params.get("sign_smoothing")),
        (Some(&2.0), Some(&0.05))
    );
    assert_eq!(st.network_set, Some("reach"), "a task keeps the networks");
    // Networks the user installs are no shipped set.
    s.set_networks(Arc::new(Networks::embedded().unwrap()))
        .unwrap();
    assert_eq!(s.network_set(), None);
    // A shipped set is refused for another arm; the networks in use stay.
    let mut four = Session::new(1).unwrap();
    four.set_arm(Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap())
        .unwrap();
    assert!(matches!(
        four.use_network_set(NetworkSet::Reach),
        Err(Error::NetworksUnavailable(_))
    ));
    assert_eq!(four.network_set(), None);
}

/// A target beyond the arm's reach is said so with the damping on or off
/// (issue 27: with it on, the page gave no "out of reach" note).
#[test]
fn a_target_out_of_reach_is_said_so_with_damping_on_or_off() {
    for damping in [false, true] {
        let mut s = Session::new(1).unwrap();
        s.set_damping(damping).unwrap();
        assert!(!s.state().out_of_reach, "the paper's target is in reach");
        // The arm reaches 2.05 m from the top of its 0.5 m post.
        s.set_target([0.0, 3.0], None).unwrap();
        let st = s.state();
        assert!(st.out_of_reach, "damping {damping}");
        assert!(st.damping, "the damping is on (switched on, or on already)");
        s.set_target([0.6, 0.2], None).unwrap();
        assert!(!s.state().out_of_reach);
    }
}

/// A dragged target or obstacle lands on the millimetre, so the page's
/// link quotes short decimals that reproduce the scene (issue 27:
/// `target=-0.7999998728434248`).
#[test]
fn a_drag_lands_on_the_millimetre() {
    let mut s = Session::new(1).unwrap();
    s.drag_start(Some(Handle::Target));
    s.drag_end([-0.7999998728434248, 1.30000004]).unwrap();
    assert_eq!(s.state().target, [-0.8, 1.3]);
    s.drag_start(Some(Handle::Obstacle(0)));
    s.drag_to([0.91234, 0.40049]).unwrap();
    s.drag_end([0.91234, 0.40049]).unwrap();
    assert_eq!(s.state().obstacles[0].centre, [0.912, 0.4]);
}

/// The keys select the target, each obstacle and each elbow in turn, and
/// move what they select (issue 27: Shift+arrows moved only the first
/// obstacle).
#[test]
fn the_keys_select_and_move_every_handle() {
    let mut s = Session::new(1).unwrap();
    s.add_obstacle(Obstacle::new(1.2, 1.4, 0.05)).unwrap();
    assert_eq!(s.selected(), Handle::Target);
    let order: Vec<Handle> = (0..5).map(|_| s.select_next(true)).collect();
    assert_eq!(
        order,
        [
            Handle::Obstacle(0),
            Handle::Obstacle(1),
            Handle::Joint(1),
            Handle::Joint(2),
            Handle::Target
        ]
    );
    assert_eq!(s.select_next(false), Handle::Joint(2), "and back");
    s.select(Handle::Obstacle(1));
    s.nudge_selected(-1.0, 0.0, true).unwrap();
    assert_eq!(s.state().obstacles[1].centre, [1.195, 1.4], "5 mm");
    s.nudge_selected(0.0, 1.0, false).unwrap();
    assert!(
        (s.state().obstacles[1].centre[1] - 1.45).abs() < 1e-12,
        "5 cm"
    );
    // An elbow moves the arm along its self-motion, the hand held.
    s.select(Handle::Joint(1));
    let (hand, elbow) = (s.state().ee, s.state().joints[1]);
    s.nudge_selected(1.0, 0.0, false).unwrap();
    let st = s.state();
    assert!(
        (st.ee[0] - hand[0]).hypot(st.ee[1] - hand[1]) < 1e-6,
        "the hand holds"
    );
    assert!(
        (st.joints[1][0] - elbow[0]).hypot(st.joints[1][1] - elbow[1]) > 0.01,
        "the elbow moves"
    );
    // A selection whose obstacle is gone falls back to the target.
    s.select(Handle::Obstacle(1));
    s.remove_obstacle(1).unwrap();
    assert_eq!(s.selected(), Handle::Target);
}
