//! The browser API (src/wasm.rs) in a real browser:
//! `wasm-pack test --headless --chrome`. Native `cargo test` skips this file.
#![cfg(target_family = "wasm")]

use redundant_ik::web::{networks_error, Demo};
use serde_json::Value;
use wasm_bindgen::prelude::*;
use wasm_bindgen_test::*;
use web_sys::HtmlCanvasElement;

wasm_bindgen_test_configure!(run_in_browser);

#[wasm_bindgen(inline_js = "
export function make_canvas(w, h) {
  const c = document.createElement('canvas');
  c.style.width = w + 'px';
  c.style.height = h + 'px';
  c.style.display = 'block';
  document.body.appendChild(c);
  return c;
}")]
extern "C" {
    fn make_canvas(w: u32, h: u32) -> HtmlCanvasElement;
}

fn demo(task: u32) -> Demo {
    let mut d = Demo::new(make_canvas(640, 520), Some(make_canvas(640, 300)), task).unwrap();
    d.resize(640.0, 520.0, 1.0).unwrap();
    d
}

fn state(d: &Demo) -> Value {
    json_of(d.state().unwrap())
}

/// A JavaScript value as JSON.
fn json_of(js: JsValue) -> Value {
    let text: String = js_sys::JSON::stringify(&js).unwrap().into();
    serde_json::from_str(&text).unwrap()
}

fn message(e: JsError) -> String {
    let v: JsValue = e.into();
    let err: js_sys::Error = v.unchecked_into();
    err.message().into()
}

fn pair(v: &Value) -> [f64; 2] {
    [v[0].as_f64().unwrap(), v[1].as_f64().unwrap()]
}

#[wasm_bindgen_test]
fn a_new_demo_is_task_1_at_rest_in_numerical_mode() {
    let d = demo(1);
    let s = state(&d);
    assert_eq!(s["t"], 0.0);
    assert_eq!(s["mode"], "numerical");
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
fn modes_parse_and_bad_names_throw() {
    let mut d = demo(2);
    let err = d.set_method("case4").err().unwrap();
    assert!(message(err).contains("unknown mode 'case4'"));
    assert_eq!(state(&d)["mode"], "numerical");
    for m in redundant_ik::planner::methods::ALL {
        let mode = m.name();
        match (d.set_method(mode), networks_error(None)) {
            (Ok(()), _) => {
                assert_eq!(state(&d)["mode"], mode);
                d.step().unwrap();
                let ghost = !state(&d)["ghost"].is_null();
                assert_eq!(ghost, m.uses_networks(), "ghost arm only with networks");
            }
            (Err(e), Some(_)) => assert!(message(e).contains("networks not available")),
            (Err(e), None) => panic!("mode {mode}: {}", message(e)),
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
fn user_weights_load_or_say_what_is_wrong() {
    use redundant_ik::networks::{PHI_EQUIVARIANT_JSON, V_PLAIN_JSON};
    let mut d = demo(1);
    let err = d.load_networks("{}", V_PLAIN_JSON).err().unwrap();
    assert!(message(err).contains("bad network weights"));
    let err = d
        .load_networks(V_PLAIN_JSON, PHI_EQUIVARIANT_JSON)
        .err()
        .unwrap();
    assert!(message(err).contains("bad network weights"));
    d.load_networks(PHI_EQUIVARIANT_JSON, V_PLAIN_JSON).unwrap();
    d.set_method("case3").unwrap();
    d.load_task(1).unwrap();
    d.run_until(10.0).unwrap();
    let s = state(&d);
    assert_eq!(s["collided"], false);
    assert!(!s["trained_range"].is_null());
    assert!(s["final_error"].as_f64().unwrap() < 5e-3);
}

#[wasm_bindgen_test]
fn closed_loop_feedback_shrinks_the_networks_drift_and_survives_a_task_load() {
    let final_error = |d: &Demo| state(d)["final_error"].as_f64().unwrap();
    let mut d = demo(1);
    d.set_damping(false).unwrap();
    d.set_method("case3").unwrap();
    d.load_task(1).unwrap();
    d.run_until(10.0).unwrap();
    let open = final_error(&d);
    assert_eq!(
        state(&d)["feedback"],
        0.0,
        "the paper's open loop by default"
    );

    d.set_feedback(1.0).unwrap();
    d.load_task(1).unwrap();
    assert_eq!(state(&d)["feedback"], 1.0, "a task load keeps the gain");
    d.run_until(10.0).unwrap();
    let closed = final_error(&d);
    assert_eq!(state(&d)["collided"], false);
    assert!(
        closed < 1e-4 && closed < open / 5.0,
        "open loop {open:.2e} m, closed loop {closed:.2e} m"
    );

    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        let err = d.set_feedback(bad).err().unwrap();
        assert!(message(err).contains("feedback gain"));
    }
    assert_eq!(state(&d)["feedback"], 1.0, "a refused gain changes nothing");
}

#[wasm_bindgen_test]
fn the_in_browser_benchmark_returns_costs_or_refuses_bad_input() {
    use redundant_ik::web::{bench_forward, bench_step, bench_theta_dot};
    for mode in ["numerical", "case3"] {
        let ns = bench_step(mode, 1.0).unwrap();
        assert!(ns.is_finite() && ns > 0.0, "{mode}: {ns}");
        let ns = bench_theta_dot(mode, 1.0).unwrap();
        assert!(ns.is_finite() && ns > 0.0, "{mode}: {ns}");
    }
    let f = json_of(bench_forward(1.0).unwrap());
    assert!(f["phi"].as_f64().is_some_and(|x| x > 0.0), "{f}");
    assert!(f["v"].as_f64().is_some_and(|x| x > 0.0), "{f}");
    assert!(message(bench_step("case9", 1.0).err().unwrap()).contains("unknown mode"));
    for bad in [0.0, f64::NAN, 1e9] {
        assert!(message(bench_theta_dot("numerical", bad).err().unwrap()).contains("batch"));
    }
}

#[wasm_bindgen_test]
fn compare_modes_runs_the_current_scene_in_all_five_modes_off_screen() {
    let mut d = demo(1);
    d.set_damping(false).unwrap();
    d.set_obstacle(0.55, 0.45).unwrap();
    let before = state(&d);
    let js = d.compare_modes().unwrap();
    let text: String = js_sys::JSON::stringify(&js).unwrap().into();
    let rows: Value = serde_json::from_str(&text).unwrap();
    let rows = rows.as_array().unwrap();
    let modes: Vec<&str> = rows.iter().map(|r| r["mode"].as_str().unwrap()).collect();
    let registry: Vec<&str> = redundant_ik::planner::methods::ALL
        .iter()
        .map(|m| m.name())
        .collect();
    assert_eq!(modes, registry);
    let collided = |i: usize| rows[i]["summary"]["collided"].as_bool().unwrap();
    for (i, m) in redundant_ik::planner::methods::ALL.iter().enumerate() {
        // Without avoidance the arm hits the moved obstacle; every method
        // that avoids keeps clear of it and reaches the target.
        assert_eq!(collided(i), !m.avoids(), "{m}");
        if m.avoids() {
            assert!(rows[i]["summary"]["final_error"].as_f64().unwrap() < 5e-3);
        }
    }
    assert!(rows.iter().all(|r| r["error"].is_null()));
    assert_eq!(state(&d), before, "the simulation on screen is untouched");
}

#[wasm_bindgen_test]
fn the_state_says_when_the_exact_phi_stood_in_for_the_network() {
    let mut d = demo(1);
    d.set_method("case1").unwrap();
    let s = state(&d);
    assert_eq!(s["handover_steps"], 0);
    assert_eq!(s["phi_handover"], false);
    // Out of reach: the arm stretches, the damping schedule hands Phi over.
    d.set_target(2.5, 0.8, Some(10.0)).unwrap();
    d.run_until(10.0).unwrap();
    let s = state(&d);
    assert!(s["handover_steps"].as_u64().unwrap() > 10, "{s}");
}

#[wasm_bindgen_test]
fn names_colours_and_the_legend_come_from_the_module() {
    use redundant_ik::planner::methods;
    use redundant_ik::web::{legend, limits, methods as listed, palette};
    let m = json_of(listed().unwrap());
    let names: Vec<&str> = m
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["name"].as_str().unwrap())
        .collect();
    let registry: Vec<&str> = methods::ALL.iter().map(|m| m.name()).collect();
    assert_eq!(names, registry);
    assert_eq!(m[3]["label"], "Case 2");
    assert_eq!(m[3]["networks"]["v"], true);
    assert_eq!(m[3]["paper_figures"][1], 10);
    assert!(m[3]["description"]
        .as_str()
        .unwrap()
        .contains("v by a network"));
    let l = json_of(limits().unwrap());
    assert_eq!(l["max_links"], redundant_ik::session::MAX_LINKS);
    assert_eq!(l["max_obstacles"], redundant_ik::session::MAX_OBSTACLES);
    assert_eq!(l["arm_presets"][1]["links"].as_array().unwrap().len(), 4);
    let p = json_of(palette().unwrap());
    assert_eq!(p["arm"], "#1d4e89");
    let l = json_of(legend().unwrap());
    let arm = &l[0];
    assert_eq!(arm["key"], "arm");
    assert_eq!(
        arm["swatch"], "rgba(29, 78, 137, 1)",
        "the palette's arm colour"
    );
    assert!(l[1]["label"].as_str().unwrap().contains("every 5th pose"));
}

#[wasm_bindgen_test]
fn arrow_keys_move_the_target_and_with_shift_the_obstacle() {
    let mut d = demo(1);
    let before = state(&d);
    assert!(d.key("ArrowRight", false).unwrap());
    let after = state(&d);
    assert!((pair(&after["target"])[0] - pair(&before["target"])[0] - 0.05).abs() < 1e-12);
    assert!(d.key("ArrowDown", true).unwrap());
    assert!((pair(&state(&d)["obstacle"])[1] - 0.45).abs() < 1e-12);
    assert!(!d.key("a", false).unwrap(), "other keys are not used");
    // Onto the post: refused, and the obstacle stays.
    d.set_obstacle(0.09, 0.3).unwrap();
    assert!(d.key("ArrowLeft", true).is_err());
    assert_eq!(pair(&state(&d)["obstacle"]), [0.09, 0.3]);
}

/// A JavaScript object from JSON text.
fn js_of(json: &str) -> JsValue {
    js_sys::JSON::parse(json).unwrap()
}

#[wasm_bindgen_test]
fn an_atlas_job_maps_the_pages_scene_a_chunk_at_a_time() {
    use redundant_ik::web::AtlasJob;
    let d = demo(1);
    let options = js_of(
        r#"{"modes": ["none", "numerical"], "n": 4, "region": [0.2, 0.8, 0.2, 0.8], "task": 1}"#,
    );
    let mut job = AtlasJob::new(d.scene().unwrap(), options, None, None).unwrap();
    assert_eq!((job.total(), job.done(), job.row()), (16, 0, 4));
    assert!(message(job.finish().err().unwrap()).contains("atlas cells computed"));
    assert_eq!(job.advance(4), 4);
    assert_eq!(job.advance(100), 16);
    let a = json_of(job.finish().unwrap());
    assert_eq!(a["task"], 1);
    assert_eq!(a["grid"]["n"], 4);
    assert_eq!(a["cells"].as_array().unwrap().len(), 16);
    assert_eq!(a["modes"], serde_json::json!(["none", "numerical"]));
    // The page's scene is the task with its damping switch on: the same
    // atlas as the core computes for that scene.
    let mut scene = redundant_ik::Scene::task(1).unwrap();
    scene.damping = Some(redundant_ik::DampingSchedule::default());
    let spec = redundant_ik::atlas::Spec {
        scene,
        grid: redundant_ik::atlas::Grid::new([0.2, 0.8, 0.2, 0.8], 4).unwrap(),
        modes: vec![
            redundant_ik::Method::NO_AVOIDANCE,
            redundant_ik::Method::NUMERICAL,
        ],
        task: Some(1),
    };
    let core = redundant_ik::atlas::Atlas::run(spec, None).unwrap();
    use serde::Serialize;
    let core = core
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .unwrap();
    assert_eq!(a, json_of(core));
}

#[wasm_bindgen_test]
fn bad_atlas_options_throw_with_the_reason() {
    use redundant_ik::web::AtlasJob;
    let d = demo(1);
    let job = |options: &str| {
        AtlasJob::new(d.scene().unwrap(), js_of(options), None, None)
            .err()
            .map(message)
            .unwrap_or_default()
    };
    assert!(job(r#"{"n": 1}"#).contains("grid points per side"));
    assert!(job(r#"{"n": 3.5}"#).contains("whole number"));
    assert!(job(r#"{"n": 1e300}"#).contains("grid points per side"));
    assert!(job(r#"{"modes": ["numerical", "fast"]}"#).contains("unknown mode 'fast'"));
    assert!(job(r#"{"modes": []}"#).contains("number of modes"));
    assert!(job(r#"{"region": [0, 1, 0]}"#).contains("four numbers"));
    assert!(job(r#"{"region": [1, 0, 0, 1]}"#).contains("empty"));
    assert!(job(r#"{"n": "many"}"#).contains("atlas options"));
    assert!(job(r#"{"colour": "red"}"#).contains("unknown field"));
    let not_a_scene = AtlasJob::new(js_of(r#"{"arm": 3}"#), JsValue::UNDEFINED, None, None);
    assert!(message(not_a_scene.err().unwrap()).contains("not a scene"));
    let corrupt = AtlasJob::new(
        d.scene().unwrap(),
        js_of(r#"{"modes": ["case3"], "n": 3}"#),
        Some("{".into()),
        Some("{".into()),
    );
    assert!(message(corrupt.err().unwrap()).contains("bad network weights"));
    // A scene that fails validation is refused by the core.
    let mut scene: Value = json_of(d.scene().unwrap());
    scene["lambda"] = serde_json::json!(-1.0);
    let bad = AtlasJob::new(js_of(&scene.to_string()), JsValue::UNDEFINED, None, None);
    assert!(message(bad.err().unwrap()).contains("lambda"));
}

#[wasm_bindgen_test]
fn an_atlas_layer_is_checked_then_drawn_and_finds_the_cell_under_the_pointer() {
    use redundant_ik::web::atlas_classes;
    let classes = json_of(atlas_classes().unwrap());
    let names: Vec<&str> = classes
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "success",
            "collision",
            "missed",
            "failed",
            "path_blocked",
            "start_overlap"
        ]
    );
    assert!(classes[0]["swatch"].as_str().unwrap().starts_with("rgba("));
    let mut d = demo(1);
    assert_eq!(d.atlas_cell_at(100.0, 100.0), None, "no layer, no cell");
    let region = vec![0.0, 1.0, 0.0, 1.0];
    let refused = |e: JsError| message(e);
    assert!(refused(
        d.set_atlas_layer(vec![0.0, 1.0], 3, vec![0; 9])
            .unwrap_err()
    )
    .contains("four numbers"));
    assert!(refused(
        d.set_atlas_layer(region.clone(), 3, vec![0; 8])
            .unwrap_err()
    )
    .contains("has 8 entries"));
    assert!(refused(
        d.set_atlas_layer(region.clone(), 3, vec![6; 9])
            .unwrap_err()
    )
    .contains("class index"));
    assert!(
        refused(d.set_atlas_layer(region.clone(), 1, vec![0]).unwrap_err()).contains("grid points")
    );
    assert!(refused(
        d.set_atlas_layer(vec![0.0, f64::NAN, 0.0, 1.0], 3, vec![0; 9])
            .unwrap_err()
    )
    .contains("finite"));
    d.set_atlas_layer(region, 3, (0..9).map(|k| k % 6).collect())
        .unwrap();
    d.draw();
    // The cell under the canvas point of a cell centre is that cell.
    for (k, p) in [(0usize, [0.0, 0.0]), (4, [0.5, 0.5]), (5, [1.0, 0.5])] {
        let xy = d.world_to_canvas(p[0], p[1]).unwrap();
        assert_eq!(d.atlas_cell_at(xy[0], xy[1]), Some(k), "{p:?}");
    }
    let far = d.world_to_canvas(2.0, 1.8).unwrap();
    assert_eq!(d.atlas_cell_at(far[0], far[1]), None);
    assert_eq!(d.atlas_cell_at(f64::NAN, 1.0), None);
    d.clear_atlas_layer();
    let xy = d.world_to_canvas(0.5, 0.5).unwrap();
    assert_eq!(d.atlas_cell_at(xy[0], xy[1]), None);
}

#[wasm_bindgen_test]
fn the_legend_lists_what_the_stage_drew() {
    use redundant_ik::web::legend;
    let keys: Vec<String> = json_of(legend().unwrap())
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["key"].as_str().unwrap().to_string())
        .collect();
    let drawn = |d: &Demo| -> Vec<String> {
        keys.iter()
            .enumerate()
            .filter(|(i, _)| d.drawn() & (1 << i) != 0)
            .map(|(_, k)| k.clone())
            .collect()
    };
    let mut d = demo(1);
    d.draw();
    assert_eq!(
        drawn(&d),
        ["arm", "path", "reference", "target", "obstacle"]
    );
    d.set_method("case3").unwrap();
    d.run_until(10.0).unwrap();
    d.draw();
    let now = drawn(&d);
    for k in ["strobe", "trail", "ghost", "region"] {
        assert!(now.iter().any(|x| x == k), "{k} in {now:?}");
    }
    assert!(!now.iter().any(|x| x == "dampers" || x == "floor"));
}
