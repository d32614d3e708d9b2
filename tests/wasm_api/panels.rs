//! Weights and their arithmetic, feedback, the benchmark, the comparison,
//! names and colours, keys.

use super::*;
use wasm_bindgen_test::wasm_bindgen_test;

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
fn the_networks_arithmetic_is_part_of_the_run_and_a_bad_name_changes_nothing() {
    let mut d = demo(1);
    d.set_method("case3").unwrap();
    assert_eq!(state(&d)["precision"], "f64");
    assert!(json_of(d.run().unwrap()).get("precision").is_none());
    d.run_until(10.0).unwrap();
    let f64_error = state(&d)["final_error"].as_f64().unwrap();
    let revision = state(&d)["revision"]["run"].clone();
    d.set_precision("f32").unwrap();
    assert_eq!(state(&d)["precision"], "f32");
    assert_ne!(state(&d)["revision"]["run"], revision, "another run");
    assert_eq!(json_of(d.run().unwrap())["precision"], "f32");
    d.load_task(1).unwrap();
    d.run_until(10.0).unwrap();
    let f32_error = state(&d)["final_error"].as_f64().unwrap();
    assert_ne!(f32_error, f64_error);
    assert!(
        (f32_error - f64_error).abs() < 1e-5,
        "{f32_error} vs {f64_error}"
    );
    let err = d.set_precision("f16").err().unwrap();
    assert!(message(err).contains("f64"), "names the choices");
    assert_eq!(state(&d)["precision"], "f32", "unchanged");
    // The names a menu offers, the default first.
    let names = json_of(redundant_ik::web::precisions().unwrap());
    assert_eq!(names[0][0], "f64");
    assert_eq!(names[1][0], "f32");
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
    for precision in [None, Some("f64"), Some("f32")] {
        let p = || precision.map(String::from);
        for method in ["numerical", "case3"] {
            let ns = bench_step(method, 1.0, p()).unwrap();
            assert!(ns.is_finite() && ns > 0.0, "{method}: {ns}");
            let ns = bench_theta_dot(method, 1.0, p()).unwrap();
            assert!(ns.is_finite() && ns > 0.0, "{method}: {ns}");
        }
        let f = json_of(bench_forward(1.0, p()).unwrap());
        assert!(f["phi"].as_f64().is_some_and(|x| x > 0.0), "{f}");
        assert!(f["v"].as_f64().is_some_and(|x| x > 0.0), "{f}");
    }
    assert!(message(bench_step("case9", 1.0, None).err().unwrap()).contains("unknown method"));
    for bad in [0.0, f64::NAN, 1e9] {
        assert!(message(bench_theta_dot("numerical", bad, None).err().unwrap()).contains("batch"));
    }
    let err = bench_forward(1.0, Some("f16".into())).err().unwrap();
    assert!(
        message(err).contains("precision"),
        "an unknown precision is refused by name"
    );
}

#[wasm_bindgen_test]
fn compare_methods_runs_the_current_scene_in_all_five_methods_off_screen() {
    let mut d = demo(1);
    d.set_damping(false).unwrap();
    d.set_obstacle(0.55, 0.45).unwrap();
    let before = state(&d);
    let js = d.compare_methods().unwrap();
    let text: String = js_sys::JSON::stringify(&js).unwrap().into();
    let rows: Value = serde_json::from_str(&text).unwrap();
    let rows = rows.as_array().unwrap();
    let methods: Vec<&str> = rows.iter().map(|r| r["method"].as_str().unwrap()).collect();
    let registry: Vec<&str> = redundant_ik::planner::methods::ALL
        .iter()
        .map(|m| m.name())
        .collect();
    assert_eq!(methods, registry);
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
    // The joint weighting's choices, [name, label], in menu order.
    assert_eq!(l["joint_weightings"][0][0], "none");
    assert_eq!(l["joint_weightings"][1][0], "wln");
    // Which methods the weighting reaches, from their files.
    for (e, method) in m.as_array().unwrap().iter().zip(methods::ALL) {
        assert_eq!(e["weighting"], method.info().weighting, "{method}");
    }
    let p = json_of(palette().unwrap());
    assert_eq!(p["arm"], "#1d4e89");
    // The drawing in perspective's legend: its own entries in the same
    // form (the pose task's frames and the self pairs among them), the two
    // ellipsoids switched by the page, the plane's colours.
    let space = json_of(legend(Some(true)).unwrap());
    let keys: Vec<&str> = space
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["key"].as_str().unwrap())
        .collect();
    assert_eq!(
        keys,
        [
            "arm",
            "sphere",
            "target",
            "path",
            "trail",
            "reference",
            "shadow",
            "frame",
            "self",
            "ghost",
            "ellipse",
            "force"
        ]
    );
    let toggles: Vec<&str> = space
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["toggle"] == true)
        .map(|e| e["key"].as_str().unwrap())
        .collect();
    assert_eq!(toggles, ["ellipse", "force"]);
    let l = json_of(legend(None).unwrap());
    let by_key = |list: &serde_json::Value, key: &str| {
        list.as_array()
            .unwrap()
            .iter()
            .find(|e| e["key"] == key)
            .unwrap()["swatch"]
            .clone()
    };
    assert_eq!(by_key(&space, "ghost"), by_key(&l, "ghost"));
    let arm = &l[0];
    assert_eq!(arm["key"], "arm");
    assert_eq!(
        arm["swatch"], "rgba(29, 78, 137, 1)",
        "the palette's arm colour"
    );
    assert!(l[1]["label"].as_str().unwrap().contains("every 5th pose"));
}

#[wasm_bindgen_test]
fn keys_select_an_item_and_the_arrows_move_it() {
    let mut d = demo(1);
    let before = state(&d);
    assert!(d.key("ArrowRight", false).unwrap());
    let after = state(&d);
    assert!((pair(&after["target"])[0] - pair(&before["target"])[0] - 0.05).abs() < 1e-12);
    // n selects the obstacle; Shift+arrow moves it 5 mm.
    assert!(d.key("n", false).unwrap());
    assert_eq!(state(&d)["selected"], "obstacle");
    assert!(d.key("ArrowDown", true).unwrap());
    assert!((pair(&state(&d)["obstacle"])[1] - 0.495).abs() < 1e-12);
    assert!(!d.key("q", false).unwrap(), "other keys are not used");
    // Onto the post: refused, and the obstacle stays.
    d.set_obstacle(0.09, 0.3).unwrap();
    assert!(d.key("ArrowLeft", false).is_err());
    assert_eq!(pair(&state(&d)["obstacle"]), [0.09, 0.3]);
    // a adds one, selected; Delete removes it.
    assert!(d.key("a", false).unwrap());
    assert_eq!(state(&d)["obstacles"].as_array().unwrap().len(), 2);
    assert_eq!(state(&d)["selected_index"], 1);
    assert!(d.key("Delete", false).unwrap());
    assert_eq!(state(&d)["obstacles"].as_array().unwrap().len(), 1);
    assert_eq!(state(&d)["selected"], "target");
}

#[wasm_bindgen_test]
fn the_joint_weighting_and_the_floor_are_set_by_name_and_refused_otherwise() {
    let mut d = demo(1);
    assert_eq!(state(&d)["weighting"], "none");
    assert_eq!(state(&d)["floor"], false);
    let e = message(d.set_weighting("qp").unwrap_err());
    assert!(e.contains("joint weighting") && e.contains("qp"), "{e}");
    assert_eq!(state(&d)["weighting"], "none", "nothing changed");
    d.set_weighting("wln").unwrap();
    d.set_floor(true);
    let s = state(&d);
    assert_eq!(s["weighting"], "wln");
    assert_eq!(s["floor"], true);
    assert_eq!(s["singular_values"].as_array().unwrap().len(), 2);
    assert_eq!(s["past_limits"].as_array().unwrap().len(), 0);
    assert_eq!(s["limit_steps"], 0);
}
