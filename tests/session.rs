//! The interactive session the page runs, as a specification, natively and
//! in the browser: the clock, the ghost twin, dragging, the histories and the
//! state the page reads.

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::sync::Arc;

use redundant_ik::networks::Networks;
use redundant_ik::planner::methods;
use redundant_ik::session::{
    Handle, Session, MAX_OBSTACLES, MAX_STEPS_PER_FRAME, NUDGE, STROBE_EVERY,
};
use redundant_ik::{Arm, Error, Method, Obstacle};

fn with_networks(task: u32) -> Session {
    let mut s = Session::new(task).unwrap();
    s.set_networks(Arc::new(Networks::embedded().unwrap()))
        .unwrap();
    s
}

#[test]
fn a_new_session_is_the_papers_task_at_rest_in_numerical_mode_with_damping() {
    let s = Session::new(2).unwrap();
    let st = s.state();
    assert_eq!(
        (st.task, st.mode, st.t, st.running),
        (2, "numerical", 0.0, false)
    );
    assert!(st.damping);
    assert!(st.ghost.is_none());
    assert_eq!(s.trail().len(), 1, "the start is recorded");
    assert!(matches!(
        Session::new(3),
        Err(Error::UnknownTask { task: 3 })
    ));
}

#[test]
fn running_a_task_stops_at_its_final_time_and_avoidance_works() {
    for (mode, collides) in [(Method::NO_AVOIDANCE, true), (Method::NUMERICAL, false)] {
        let mut s = Session::new(1).unwrap();
        s.set_damping(false).unwrap();
        s.set_method(mode).unwrap();
        s.run_task();
        assert!(s.running());
        for _ in 0..10_000 {
            if !s.running() {
                break;
            }
            s.tick(50.0).unwrap();
        }
        let st = s.state();
        assert!(!st.running, "stopped at tf");
        assert!((st.t - 10.0).abs() < 1e-9);
        assert_eq!(st.collided, collides, "{mode}");
    }
}

#[test]
fn the_clock_turns_real_time_into_steps_at_the_chosen_speed() {
    let mut s = Session::new(1).unwrap();
    s.set_running(true);
    s.set_speed(1.0).unwrap();
    // 0.25 s of real time at 1x is 2.5 steps of 0.1 s: two now, the rest kept.
    s.tick(250.0).unwrap();
    assert_eq!(s.state().steps, 2);
    s.tick(50.0).unwrap();
    assert_eq!(s.state().steps, 3);
    // A long stall (a background tab) is capped, then at most 40 steps a frame.
    s.set_speed(50.0).unwrap();
    s.tick(10_000.0).unwrap();
    assert_eq!(s.state().frame_steps, MAX_STEPS_PER_FRAME);
    for bad in [0.0, 51.0, f64::NAN] {
        assert!(s.set_speed(bad).is_err());
    }
    // Paused: nothing moves.
    s.set_running(false);
    let t = s.state().t;
    s.tick(1000.0).unwrap();
    assert_eq!(s.state().t, t);
}

#[test]
fn the_network_cases_need_networks_and_bring_a_numerical_ghost() {
    // An arm the built-in networks were not trained for: refused.
    let mut s = Session::new(1).unwrap();
    s.set_arm(four_links()).unwrap();
    assert!(matches!(
        s.set_method(Method::CASE3),
        Err(Error::NetworksUnavailable(_))
    ));
    assert_eq!(
        s.state().mode,
        "numerical",
        "a refused change changes nothing"
    );
    // The paper's arm takes the built-in networks when none are installed.
    let mut s = Session::new(1).unwrap();
    s.set_method(Method::CASE3).unwrap();
    assert!(s.installed().is_some());
    let mut s = with_networks(1);
    s.set_method(Method::CASE3).unwrap();
    assert!(s.ghost().is_some());
    assert_eq!(s.ghost().unwrap().method(), Method::NUMERICAL);
    // Every change reaches the ghost too.
    s.set_lambda(6.0).unwrap();
    s.set_feedback(1.0).unwrap();
    s.set_obstacle([0.7, 0.8]).unwrap();
    let g = s.ghost().unwrap().scene();
    assert_eq!((g.param(&methods::LAMBDA), g.feedback_gain), (6.0, 1.0));
    assert_eq!(g.obstacles[0].centre, [0.7, 0.8]);
    s.run_until(3.0).unwrap();
    assert_eq!(s.ghost().unwrap().time(), s.planner().time());
    assert!(s.state().ghost.is_some());
    s.set_method(Method::NUMERICAL).unwrap();
    assert!(s.ghost().is_none());
}

#[test]
fn dropping_the_target_plans_a_line_from_the_hand_and_starts_the_clock() {
    let mut s = Session::new(1).unwrap();
    s.run_until(2.0).unwrap();
    let hand = s.state().ee;
    s.drag_start(Some(Handle::Target));
    s.drag_to([0.9, 0.4]).unwrap();
    assert_eq!(
        s.target_marker(),
        [0.9, 0.4],
        "the marker follows the pointer"
    );
    assert_ne!(s.state().target, [0.9, 0.4], "the line waits for the drop");
    s.drag_end([1.0, 0.5]).unwrap();
    let st = s.state();
    assert_eq!(st.target, [1.0, 0.5]);
    assert_eq!(st.line.start, hand);
    assert!(st.running);
    assert!(st.dragging.is_none());
    // A cancelled drag leaves the target where it was.
    s.drag_start(Some(Handle::Target));
    s.drag_to([0.2, 0.2]).unwrap();
    s.drag_cancel();
    assert_eq!(s.target_marker(), [1.0, 0.5]);
}

#[test]
fn the_obstacle_follows_the_pointer_but_never_onto_the_post() {
    let mut s = Session::new(1).unwrap();
    s.drag_start(Some(Handle::Obstacle(0)));
    s.drag_to([0.8, 0.9]).unwrap();
    assert_eq!(s.state().obstacle, Some([0.8, 0.9]));
    assert!(matches!(
        s.drag_to([0.0, 0.3]),
        Err(Error::ObstacleOnPost { .. })
    ));
    assert_eq!(
        s.state().obstacle,
        Some([0.8, 0.9]),
        "stays at its last legal place"
    );
    assert!(s.drag_to([f64::NAN, 0.3]).is_err());
    s.drag_end([0.85, 0.9]).unwrap();
    assert_eq!(s.state().obstacle, Some([0.85, 0.9]));
}

#[test]
fn arrow_keys_nudge_the_target_and_the_obstacle() {
    let mut s = Session::new(1).unwrap();
    let target = s.state().target;
    s.nudge(Handle::Target, 1.0, 0.0).unwrap();
    let st = s.state();
    assert!((st.target[0] - (target[0] + NUDGE)).abs() < 1e-12);
    assert!(st.running, "a new line starts the clock");
    let o = s.state().obstacle.unwrap();
    s.nudge(Handle::Obstacle(0), 0.0, -1.0).unwrap();
    let moved = s.state().obstacle.unwrap();
    assert!((moved[1] - (o[1] - NUDGE)).abs() < 1e-12);
}

#[test]
fn the_histories_keep_the_trail_every_fifth_pose_and_the_time_series() {
    let mut s = Session::new(1).unwrap();
    s.run_until(2.0).unwrap();
    assert_eq!(s.trail().len(), 21);
    assert_eq!(s.strobe().len(), 21usize.div_ceil(STROBE_EVERY));
    assert_eq!(s.history().len(), 21);
    assert_eq!(s.history()[20].theta.len(), 3);
    s.reset();
    assert_eq!((s.trail().len(), s.history().len()), (1, 1));
    // Drawing interpolates only while the clock runs.
    assert_eq!(
        s.display_joints(false).unwrap(),
        s.planner().sample().joints
    );
}

#[test]
fn comparing_the_modes_runs_the_scene_off_screen_and_changes_nothing() {
    let mut s = with_networks(2);
    s.set_damping(false).unwrap();
    s.set_obstacle([0.65, 0.55]).unwrap();
    s.run_until(1.0).unwrap();
    let before = format!("{:?}", s.state());
    let rows = s.compare_methods();
    assert_eq!(rows.len(), methods::ALL.len());
    for (row, m) in rows.iter().zip(methods::ALL) {
        assert_eq!((row.mode, row.label), (m.name(), m.label()));
    }
    let run = |m: Method| rows.iter().find(|r| r.mode == m.name()).unwrap();
    let none = run(Method::NO_AVOIDANCE).summary.as_ref().unwrap();
    let numerical = run(Method::NUMERICAL).summary.as_ref().unwrap();
    assert!(none.collided && !numerical.collided);
    assert_eq!(format!("{:?}", s.state()), before);
    // Without networks for the arm, the methods that need them say why.
    let mut s = Session::new(1).unwrap();
    s.set_arm(four_links()).unwrap();
    for (row, m) in s.compare_methods().iter().zip(methods::ALL) {
        assert_eq!(m.uses_networks(), row.summary.is_none(), "{m}");
        if m.uses_networks() {
            assert!(row.error.as_deref().unwrap().contains("networks"));
        }
    }
}

#[test]
fn loading_a_task_keeps_the_mode_damping_and_feedback_and_runs_it() {
    let mut s = with_networks(1);
    s.set_method(Method::CASE1).unwrap();
    s.set_damping(false).unwrap();
    s.set_feedback(1.0).unwrap();
    s.set_lambda(7.0).unwrap();
    s.load_task(2).unwrap();
    let st = s.state();
    assert_eq!((st.task, st.mode), (2, "case1"));
    assert!(!st.damping);
    assert_eq!(st.feedback, 1.0);
    assert_eq!(st.lambda, 4.0, "the paper's scene");
    assert!(st.running);
    assert!(s.ghost().is_some());
}

#[test]
fn the_state_serialises_to_the_object_the_page_reads() {
    let s = with_networks(1);
    let v = serde_json::to_value(s.state()).unwrap();
    for key in [
        "t",
        "task",
        "mode",
        "running",
        "speed",
        "lambda",
        "damping",
        "feedback",
        "theta",
        "joints",
        "ee",
        "target",
        "line",
        "obstacle",
        "radius",
        "distance",
        "collision",
        "collided",
        "tracking_error",
        "in_range",
        "phi_handover",
        "handover_steps",
        "networks",
        "trained_range",
        "steps",
        "solver_ms",
        "dragging",
        "dragging_obstacle",
        "arm",
        "obstacles",
        "nearest",
        "error",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["dragging"], serde_json::Value::Null);
    assert_eq!(v["joints"].as_array().unwrap().len(), 4);
}

// ---- the playground: arms and several obstacles ---------------------------

fn four_links() -> Arm {
    Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap()
}

#[test]
fn a_new_arm_restarts_from_its_own_start_pose_and_the_numerical_modes_run_at_once() {
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
    for mode in methods::ALL.iter().copied().filter(|m| !m.uses_networks()) {
        s.set_method(mode).unwrap();
        s.run_task();
        s.run_until(10.0).unwrap();
        assert!(s.state().final_error < 5e-3, "{mode} reaches the target");
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
    assert_eq!(s.state().mode, "numerical");
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
        (st.params["refine"], st.params["sign_smoothing"]),
        (2.0, 0.05)
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

// ---- a page for a class: runs that end, a scene that stays ---------------

/// Ticks the clock (50 ms frames) until it stops, at most `frames` frames.
fn tick_until_stopped(s: &mut Session, frames: usize) {
    for _ in 0..frames {
        if !s.running() {
            break;
        }
        s.tick(50.0).unwrap();
    }
}

#[test]
fn a_dropped_target_runs_its_line_to_the_end_and_the_hand_holds_still_in_every_method() {
    // The case: Task 1, then the target dropped at (0.3, 1.2).
    for &m in methods::ALL {
        let mut s = with_networks(1);
        s.set_method(m).unwrap();
        s.load_task(1).unwrap();
        tick_until_stopped(&mut s, 10_000);
        assert!(s.state().ended, "{m}: Task 1 ends");
        s.drag_start(Some(Handle::Target));
        s.drag_end([0.3, 1.2]).unwrap();
        let st = s.state();
        assert!(st.running && !st.ended, "{m}: the drop starts a new run");
        let tf = st.tf;
        assert!(
            (tf - st.line.duration).abs() < 1e-9,
            "{m}: it ends with its line"
        );
        tick_until_stopped(&mut s, 10_000);
        let end = s.state();
        assert!(!end.running && end.ended, "{m}: the clock stopped");
        assert!(
            (end.t - tf).abs() < 1e-9,
            "{m}: at t = tf = {tf}, not {}",
            end.t
        );
        let (t, ee) = (end.t, end.ee);
        // 5 s of page time at any speed: nothing moves, no clock runs on.
        s.set_speed(8.0).unwrap();
        for _ in 0..100 {
            s.tick(50.0).unwrap();
        }
        let still = s.state();
        assert_eq!((still.t, still.ee), (t, ee), "{m}: the hand holds still");
        s.step().unwrap();
        assert_eq!(s.state().t, t, "{m}: a step at the end does nothing");
        s.run_until(1e3).unwrap();
        assert_eq!(s.state().t, t, "{m}: nor does running until later");
    }
}

#[test]
fn a_dropped_targets_run_is_a_scene_from_the_pose_at_the_drop() {
    let mut s = with_networks(1);
    s.set_method(Method::CASE3).unwrap();
    s.run_until(4.0).unwrap();
    let pose = s.state().theta.to_vec();
    s.set_target([0.9, 0.3], None).unwrap();
    let st = s.state();
    assert_eq!(
        (st.t, st.running),
        (0.0, false),
        "a new run, paused at its start"
    );
    assert_eq!(
        s.planner().scene().theta0,
        pose,
        "starting from the pose at the drop"
    );
    assert_eq!(s.trail().len(), 1, "the histories describe this run only");
    s.run_task();
    tick_until_stopped(&mut s, 10_000);
    // What the page showed is the scene run from t = 0 off screen, the
    // file the page hands the command line.
    let scene = s.planner().scene().clone();
    let off = s.run_offscreen(scene, Method::CASE3).unwrap();
    let on = s.planner().summary();
    assert_eq!(on, off);
    s.reset();
    assert_eq!(
        s.state().theta,
        pose.as_slice(),
        "reset goes back to the drop"
    );
    assert!(s.set_target([0.9, 0.3], Some(f64::NAN)).is_err());
    assert!(s.set_target([f64::INFINITY, 0.3], None).is_err());
    assert!(
        s.set_target([0.9, 0.3], Some(1e9)).is_err(),
        "too many steps"
    );
    assert_eq!(s.planner().scene().theta0, pose, "refusals change nothing");
}

#[test]
fn play_after_the_end_replays_the_run() {
    let mut s = Session::new(1).unwrap();
    s.run_task();
    tick_until_stopped(&mut s, 10_000);
    let end = s.state().ee;
    s.set_running(true);
    let st = s.state();
    assert_eq!((st.t, st.running), (0.0, true), "from the start");
    tick_until_stopped(&mut s, 10_000);
    assert_eq!(s.state().ee, end, "the same run again");
}

#[test]
fn moving_the_obstacle_of_an_ended_run_replays_it() {
    let mut s = Session::new(1).unwrap();
    s.run_task();
    tick_until_stopped(&mut s, 10_000);
    s.drag_start(Some(Handle::Obstacle(0)));
    s.drag_to([1.0, 0.8]).unwrap();
    assert!(
        s.state().ended && !s.state().running,
        "no replay while it is held"
    );
    s.drag_end([1.0, 0.9]).unwrap();
    let st = s.state();
    assert_eq!((st.t, st.running), (0.0, true), "released: the run replays");
    tick_until_stopped(&mut s, 10_000);
    let scene = s.planner().scene().clone();
    assert_eq!(scene.obstacles[0].centre, [1.0, 0.9]);
    let off = s.run_offscreen(scene, Method::NUMERICAL).unwrap();
    assert_eq!(
        s.planner().summary(),
        off,
        "with the obstacle where it was dropped"
    );
    // So do the keys, a parameter, the method and a new obstacle.
    for change in 0..4 {
        tick_until_stopped(&mut s, 10_000);
        assert!(s.state().ended);
        match change {
            0 => s.nudge(Handle::Obstacle(0), 1.0, 0.0).unwrap(),
            1 => s.set_lambda(6.0).unwrap(),
            2 => s.set_method(Method::NO_AVOIDANCE).unwrap(),
            _ => drop(s.add_obstacle(Obstacle::new(-0.4, 1.4, 0.05)).unwrap()),
        }
        assert_eq!(s.state().t, 0.0, "change {change} replays");
        assert!(s.running(), "change {change} replays");
    }
    // While a run goes on a change takes effect at the next step.
    s.run_until(3.0).unwrap();
    s.set_lambda(4.0).unwrap();
    assert!((s.state().t - 3.0).abs() < 1e-9);
}

#[test]
fn the_task_buttons_keep_the_obstacles_the_user_added() {
    let mut s = Session::new(1).unwrap();
    let added = [[-0.4, 1.4], [1.2, 1.5], [0.2, 1.8]];
    for c in added {
        s.add_obstacle(Obstacle::new(c[0], c[1], 0.05)).unwrap();
    }
    s.move_obstacle(0, [0.9, 0.9]).unwrap();
    for task in [1, 2, 1] {
        s.load_task(task).unwrap();
        let obs = s.obstacles();
        let paper = redundant_ik::Scene::task(task).unwrap().obstacles[0];
        assert_eq!(
            obs.len(),
            4,
            "Task {task}: the paper's obstacle and the three added"
        );
        assert_eq!(
            obs[0], paper,
            "Task {task}: the paper's obstacle back in its place"
        );
        for (o, c) in obs[1..].iter().zip(added) {
            assert_eq!(o.centre, c, "Task {task} keeps the user's obstacles");
        }
    }
    // Without the paper's obstacle, a task brings it back and keeps all three.
    s.remove_obstacle(0).unwrap();
    assert_eq!(s.obstacles().len(), 3);
    s.load_task(2).unwrap();
    assert_eq!(s.obstacles().len(), 4);
    assert_eq!(s.obstacles()[0].centre, [0.6, 0.6]);
    // Reset keeps them too.
    s.reset();
    assert_eq!(s.obstacles().len(), 4);
}

#[test]
fn the_readouts_reset_with_the_run_they_describe() {
    // Pause, reset, drag the obstacle next to the arm: "smallest so far"
    // is the distance now (it read the old run's 0.471 m before).
    let mut s = Session::new(1).unwrap();
    s.run_task();
    s.run_until(5.0).unwrap();
    s.set_running(false);
    s.reset();
    let joints = s.state().joints.to_vec();
    let mid = [
        (joints[2][0] + joints[3][0]) / 2.0,
        (joints[2][1] + joints[3][1]) / 2.0 + 0.09,
    ];
    s.drag_start(Some(Handle::Obstacle(0)));
    s.drag_to(mid).unwrap();
    s.drag_end(mid).unwrap();
    let st = s.state();
    let d = st.distance.unwrap();
    assert!(d < 0.1, "next to the arm: {d}");
    assert_eq!(
        st.min_distance,
        Some(d),
        "smallest so far is the distance now"
    );
    // Moved away again before the start: the run is its start alone.
    s.move_obstacle(0, [1.2, 1.6]).unwrap();
    let st = s.state();
    assert_eq!(st.min_distance, st.distance);
    // Mid-run, paused: the obstacle moved closer joins the run's smallest.
    s.run_until(2.0).unwrap();
    let far = s.state().min_distance.unwrap();
    let joints = s.state().joints.to_vec();
    let near = [joints[3][0] + 0.08, joints[3][1]];
    s.move_obstacle(0, near).unwrap();
    let st = s.state();
    assert!(st.distance.unwrap() < far);
    assert_eq!(st.min_distance, st.distance);
    assert_eq!(st.t, 2.0_f64.max(st.t), "no step was taken");
}

#[test]
fn a_link_below_the_floor_is_reported() {
    let four = Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap();
    let mut s = Session::new(1).unwrap();
    s.set_arm(four).unwrap();
    s.load_task(1).unwrap();
    tick_until_stopped(&mut s, 10_000);
    let st = s.state();
    // The numerical route takes the 4-link arm's third joint 0.196 m below
    // the floor in Task 1 (`redundant-ik simulate --arm four --task 1`).
    assert!(st.below_floor_steps > 10, "{}", st.below_floor_steps);
    // The flag is the joints' own.
    assert_eq!(st.below_floor, st.joints.iter().skip(1).any(|p| p[1] < 0.0));
    s.reset();
    assert_eq!(s.state().below_floor_steps, 0, "per run");
    // The paper's arm in its own tasks stays above it.
    let mut s = Session::new(2).unwrap();
    s.run_task();
    tick_until_stopped(&mut s, 10_000);
    assert_eq!(s.state().below_floor_steps, 0);
}

#[test]
fn a_run_of_its_own_starts_where_its_address_says() {
    let mut s = Session::new(1).unwrap();
    assert!(!s.state().own_start);
    let pose = vec![0.3, 1.4, -0.2];
    s.set_start(pose.clone(), 3.0).unwrap();
    let st = s.state();
    assert_eq!(
        (st.theta0, st.tf, st.own_start, st.t),
        (pose.as_slice(), 3.0, true, 0.0)
    );
    assert_eq!(st.theta, pose.as_slice());
    assert!(
        s.set_start(vec![0.3, 1.4], 3.0).is_err(),
        "one angle per joint"
    );
    assert!(s.set_start(pose.clone(), 3.05).is_err(), "whole steps");
    assert!(s.set_start(vec![f64::NAN, 1.4, -0.2], 3.0).is_err());
    assert_eq!(s.state().tf, 3.0, "refusals change nothing");
    s.load_task(2).unwrap();
    assert!(!s.state().own_start, "a task starts from its own pose");
}

#[test]
fn the_comparison_says_when_a_hit_is_unavoidable() {
    let mut s = Session::new(1).unwrap();
    assert!(s.compare_methods().iter().all(|r| r.unavoidable.is_none()));
    // On the straight line from the hand to the target.
    let line = s.state().line;
    let mid = [
        (line.start[0] + line.end[0]) / 2.0,
        (line.start[1] + line.end[1]) / 2.0,
    ];
    s.set_obstacle(mid).unwrap();
    let rows = s.compare_methods();
    assert!(rows.iter().all(|r| r.unavoidable == Some("path_blocked")));
    // Every method hits it or stops short of the target (the QP's dampers).
    assert!(rows
        .iter()
        .filter_map(|r| r.summary.as_ref())
        .all(|m| m.collided || !m.reached));
}
