//! The session at rest and running: the clock, the ghost twin, dragging,
//! keys, histories, the comparison and the state.

use super::*;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

#[test]
fn a_new_session_is_the_papers_task_at_rest_in_numerical_method_with_damping() {
    let s = Session::new(2).unwrap();
    let st = s.state();
    assert_eq!(
        (st.task, st.method, st.t, st.running),
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
    for (method, collides) in [(Method::NO_AVOIDANCE, true), (Method::NUMERICAL, false)] {
        let mut s = Session::new(1).unwrap();
        s.set_damping(false).unwrap();
        s.set_method(method).unwrap();
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
        assert_eq!(st.collided, collides, "{method}");
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
        s.state().method,
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
fn comparing_the_methods_runs_the_scene_off_screen_and_changes_nothing() {
    let mut s = with_networks(2);
    s.set_damping(false).unwrap();
    s.set_obstacle([0.65, 0.55]).unwrap();
    s.run_until(1.0).unwrap();
    let before = format!("{:?}", s.state());
    let rows = s.compare_methods();
    assert_eq!(rows.len(), methods::ALL.len());
    for (row, m) in rows.iter().zip(methods::ALL) {
        assert_eq!((row.method, row.label), (m.name(), m.label()));
    }
    let run = |m: Method| rows.iter().find(|r| r.method == m.name()).unwrap();
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
fn loading_a_task_keeps_the_method_damping_and_feedback_and_runs_it() {
    let mut s = with_networks(1);
    s.set_method(Method::CASE1).unwrap();
    s.set_damping(false).unwrap();
    s.set_feedback(1.0).unwrap();
    s.set_lambda(7.0).unwrap();
    s.load_task(2).unwrap();
    let st = s.state();
    assert_eq!((st.task, st.method), (2, "case1"));
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
        "method",
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
