//! Runs that end and replay, a scene that stays, readouts that reset.

use super::*;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

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
    // What the readouts show: the clearance to the disc's edge, the
    // distance to its centre less its radius (issue 27: one distance).
    let c = st.clearance.unwrap();
    assert!((c - (d - st.radius.unwrap())).abs() < 1e-12, "{c} vs {d}");
    assert_eq!(
        st.min_clearance,
        Some(c),
        "smallest so far is the clearance now"
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
