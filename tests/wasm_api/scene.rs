//! The `Demo` binding: tasks, methods, refusals, coordinates, dragging and the
//! clock.

use super::*;
use wasm_bindgen_test::wasm_bindgen_test;

#[wasm_bindgen_test]
fn a_new_demo_is_task_1_at_rest_in_numerical_method() {
    let d = demo(1);
    let s = state(&d);
    assert_eq!(s["t"], 0.0);
    assert_eq!(s["method"], "numerical");
    assert_eq!(s["running"], false);
    assert_eq!(s["theta"].as_array().unwrap().len(), 3);
    assert_eq!(pair(&s["obstacle"]), [0.5, 0.5]);
    assert_eq!(s["radius"], 0.05);
    let ee = pair(&s["ee"]);
    assert!((ee[0] - 1.555884).abs() < 1e-6 && (ee[1] - 1.014851).abs() < 1e-6);
}

#[wasm_bindgen_test]
fn unknown_task_is_an_exception_with_the_cores_message() {
    let err = Demo::new(make_canvas(10, 10), None, 3).err().unwrap();
    assert!(message(err).contains("unknown task 3"));
}

#[wasm_bindgen_test]
fn task_1_collides_without_avoidance_and_not_with_it() {
    let mut d = demo(1);
    d.set_method("none").unwrap();
    d.load_task(1).unwrap();
    d.run_until(10.0).unwrap();
    let s = state(&d);
    assert!((s["t"].as_f64().unwrap() - 10.0).abs() < 1e-9);
    assert_eq!(s["collided"], true);
    assert_eq!(s["running"], false, "a task run stops at tf");

    d.set_method("numerical").unwrap();
    d.load_task(1).unwrap();
    assert_eq!(
        state(&d)["collided"],
        false,
        "loading a task clears the flag"
    );
    d.run_until(10.0).unwrap();
    let s = state(&d);
    assert_eq!(s["collided"], false);
    let min = s["min_distance"].as_f64().unwrap();
    assert!((min - 0.2345).abs() < 1e-3, "min distance {min}");
}

#[wasm_bindgen_test]
fn methods_parse_and_bad_names_throw() {
    let mut d = demo(2);
    let err = d.set_method("case4").err().unwrap();
    assert!(message(err).contains("unknown method 'case4'"));
    assert_eq!(state(&d)["method"], "numerical");
    for m in redundant_ik::planner::methods::ALL {
        let method = m.name();
        match (d.set_method(method), networks_error(None)) {
            (Ok(()), _) => {
                assert_eq!(state(&d)["method"], method);
                d.step().unwrap();
                let ghost = !state(&d)["ghost"].is_null();
                assert_eq!(ghost, m.uses_networks(), "ghost arm only with networks");
            }
            (Err(e), Some(_)) => assert!(message(e).contains("networks not available")),
            (Err(e), None) => panic!("method {method}: {}", message(e)),
        }
    }
}

#[wasm_bindgen_test]
fn non_finite_input_from_javascript_is_refused_not_a_panic() {
    let mut d = demo(1);
    assert!(message(d.set_lambda(f64::NAN).err().unwrap()).contains("lambda"));
    assert!(message(d.set_lambda(-1.0).err().unwrap()).contains("negative"));
    assert!(d.set_target(f64::NAN, 0.2, None).is_err());
    assert!(d.set_target(0.5, 0.2, Some(f64::INFINITY)).is_err());
    assert!(d.set_target(0.5, 0.2, Some(0.0)).is_err());
    assert!(d.set_obstacle(f64::INFINITY, 0.5).is_err());
    assert!(d.set_speed(f64::NAN).is_err());
    assert!(d.set_speed(0.0).is_err());
    assert!(d.resize(f64::NAN, 100.0, 1.0).is_err());
    assert!(d.resize(100.0, -1.0, 1.0).is_err());
    assert!(d.world_to_canvas(f64::NAN, 0.0).is_err());
    assert!(d.run_until(f64::NAN).is_err());
    assert_eq!(d.hover(f64::NAN, 1.0, 4.0), None);
    assert_eq!(d.pointer_down(f64::NAN, 1.0, 4.0), None);
    d.frame(f64::NAN).unwrap();
    d.frame(-5.0).unwrap();
    let s = state(&d);
    assert_eq!(s["t"], 0.0);
    assert_eq!(s["lambda"], 4.0);
}

#[wasm_bindgen_test]
fn the_obstacle_cannot_go_onto_the_post() {
    let mut d = demo(1);
    let err = d.set_obstacle(0.02, 0.3).err().unwrap();
    assert!(message(err).contains("base post"));
    assert_eq!(
        pair(&state(&d)["obstacle"]),
        [0.5, 0.5],
        "left where it was"
    );
    d.set_obstacle(0.9, 1.2).unwrap();
    assert_eq!(pair(&state(&d)["obstacle"]), [0.9, 1.2]);
}

#[wasm_bindgen_test]
fn world_and_canvas_coordinates_round_trip() {
    let d = demo(1);
    let p = d.world_to_canvas(0.6, 0.2).unwrap();
    let w = d.canvas_to_world(p[0], p[1]).unwrap();
    assert!((w[0] - 0.6).abs() < 1e-12 && (w[1] - 0.2).abs() < 1e-12);
    // y points up in the world and down on the canvas.
    let q = d.world_to_canvas(0.6, 1.2).unwrap();
    assert!(q[1] < p[1]);
}

#[wasm_bindgen_test]
fn dragging_the_target_plans_a_new_line_from_the_end_effector() {
    let mut d = demo(1);
    d.step().unwrap();
    let before = state(&d);
    let t = d.world_to_canvas(0.6, 0.2).unwrap();
    assert_eq!(d.pointer_down(t[0], t[1], 4.0).as_deref(), Some("target"));
    let goal = d.world_to_canvas(1.0, 0.4).unwrap();
    d.pointer_move(goal[0], goal[1]).unwrap();
    assert_eq!(
        pair(&state(&d)["target"]),
        [0.6, 0.2],
        "the line changes on release"
    );
    d.pointer_up(goal[0], goal[1]).unwrap();
    let s = state(&d);
    let target = pair(&s["target"]);
    assert!((target[0] - 1.0).abs() < 1e-9 && (target[1] - 0.4).abs() < 1e-9);
    assert_eq!(pair(&s["line"]["start"]), pair(&before["ee"]));
    assert_eq!(s["running"], true);
}

#[wasm_bindgen_test]
fn dragging_the_obstacle_moves_it_at_once_and_refuses_the_post() {
    let mut d = demo(1);
    let o = d.world_to_canvas(0.5, 0.5).unwrap();
    assert_eq!(d.pointer_down(o[0], o[1], 4.0).as_deref(), Some("obstacle"));
    let p = d.world_to_canvas(0.8, 1.3).unwrap();
    d.pointer_move(p[0], p[1]).unwrap();
    let at = pair(&state(&d)["obstacle"]);
    assert!((at[0] - 0.8).abs() < 1e-9 && (at[1] - 1.3).abs() < 1e-9);
    let post = d.world_to_canvas(0.0, 0.2).unwrap();
    assert!(d.pointer_move(post[0], post[1]).is_err());
    assert!(d.pointer_up(post[0], post[1]).is_err());
    assert_eq!(pair(&state(&d)["obstacle"]), at);
    assert!(state(&d)["dragging"].is_null());
}

/// Whether a frame handed the page a state (else `undefined`: nothing
/// changed, nothing drawn).
fn frame_changed(d: &mut Demo, elapsed_ms: f64) -> bool {
    !d.frame(elapsed_ms).unwrap().is_undefined()
}

#[wasm_bindgen_test]
fn an_idle_page_draws_nothing_until_something_changes() {
    let canvas = make_canvas(320, 260);
    let mut d = Demo::new(canvas.clone(), None, 1).unwrap();
    d.resize(320.0, 260.0, 1.0).unwrap();
    assert!(frame_changed(&mut d, 16.0), "the first frame draws");
    mark_canvas(&canvas);
    assert!(
        !frame_changed(&mut d, 16.0),
        "paused and untouched: no state"
    );
    assert!(canvas_marked(&canvas), "... and no drawing");
    // Reading changes nothing.
    let _ = (
        d.state().unwrap(),
        d.run().unwrap(),
        d.hover(10.0, 10.0, 4.0),
    );
    let _ = d.world_to_canvas(0.5, 0.5).unwrap();
    assert!(!frame_changed(&mut d, 16.0));
    assert!(canvas_marked(&canvas));
    // A change of the scene draws, and the state says it.
    d.set_lambda(2.0).unwrap();
    let s = json_of(d.frame(16.0).unwrap());
    assert_eq!(s["lambda"], 2.0);
    assert!(!canvas_marked(&canvas), "the change was drawn");
    // So does a change of the view alone (the camera keeps it in a Cell).
    mark_canvas(&canvas);
    assert!(!frame_changed(&mut d, 16.0));
    d.move_view(100.0, 100.0, 100.0, 100.0, 1.5);
    assert!(frame_changed(&mut d, 16.0));
    assert!(!canvas_marked(&canvas));
    mark_canvas(&canvas);
    d.fit_view();
    assert!(frame_changed(&mut d, 16.0));
    assert!(!canvas_marked(&canvas));
    // The clock: every frame while it runs, and the one it stops on.
    d.set_speed(1.0).unwrap();
    d.set_running(true);
    for _ in 0..3 {
        mark_canvas(&canvas);
        assert!(frame_changed(&mut d, 100.0));
        assert!(!canvas_marked(&canvas));
    }
    d.set_running(false);
    assert!(frame_changed(&mut d, 100.0));
    assert!(!frame_changed(&mut d, 100.0));
}

#[wasm_bindgen_test]
fn the_clock_runs_only_while_playing() {
    let mut d = demo(1);
    d.frame(500.0).unwrap();
    assert_eq!(state(&d)["t"], 0.0);
    d.set_speed(1.0).unwrap();
    d.set_running(true);
    for _ in 0..5 {
        d.frame(100.0).unwrap();
    }
    let t = state(&d)["t"].as_f64().unwrap();
    assert!((t - 0.5).abs() < 1e-9, "half a second at 1x: t = {t}");
    // A long pause between frames (a background tab) is not caught up.
    d.frame(5000.0).unwrap();
    let t = state(&d)["t"].as_f64().unwrap();
    assert!(t < 0.85, "at most a quarter second per frame: t = {t}");
    d.reset();
    assert_eq!(state(&d)["t"], 0.0);
    assert!(!d.running());
}

#[wasm_bindgen_test]
fn an_idle_page_in_space_draws_nothing_until_something_changes() {
    use redundant_ik::web::SpaceDemo;
    let canvas = make_canvas(320, 260);
    let mut d = SpaceDemo::new(canvas.clone(), None, "panda", None).unwrap();
    d.resize(320.0, 260.0, 1.0).unwrap();
    let changed = |d: &mut SpaceDemo| !d.frame(16.0).unwrap().is_undefined();
    assert!(changed(&mut d), "the first frame draws");
    mark_canvas(&canvas);
    assert!(!changed(&mut d), "paused and untouched: no state");
    assert!(canvas_marked(&canvas), "... and no drawing");
    let _ = d.state().unwrap();
    assert!(!changed(&mut d));
    d.orbit(12.0, 0.0).unwrap();
    assert!(changed(&mut d), "an orbit draws");
    assert!(!canvas_marked(&canvas));
    assert!(!changed(&mut d));
    d.set_running(true);
    assert!(changed(&mut d));
    assert!(changed(&mut d), "every frame while the clock runs");
}
