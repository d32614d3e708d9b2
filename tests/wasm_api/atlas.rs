//! The atlas job and layer, and the legend of what the stage drew.

use super::*;
use wasm_bindgen_test::wasm_bindgen_test;

/// A JavaScript object from JSON text.
fn js_of(json: &str) -> JsValue {
    js_sys::JSON::parse(json).unwrap()
}

#[wasm_bindgen_test]
fn an_atlas_job_maps_the_pages_scene_a_chunk_at_a_time() {
    use redundant_ik::web::AtlasJob;
    let d = demo(1);
    let options = js_of(
        r#"{"methods": ["none", "numerical"], "n": 4, "region": [0.2, 0.8, 0.2, 0.8], "task": 1}"#,
    );
    let mut job = AtlasJob::new(d.run().unwrap(), options).unwrap();
    assert_eq!((job.total(), job.done(), job.row()), (16, 0, 4));
    assert!(message(job.finish().err().unwrap()).contains("atlas cells computed"));
    assert_eq!(job.advance(4), 4);
    assert_eq!(job.advance(100), 16);
    let a = json_of(job.finish().unwrap());
    assert_eq!(a["task"], 1);
    assert_eq!(a["grid"]["n"], 4);
    assert_eq!(a["cells"].as_array().unwrap().len(), 16);
    assert_eq!(a["methods"], serde_json::json!(["none", "numerical"]));
    // The page's scene is the task with its damping switch on: the same
    // atlas as the core computes for that scene.
    let mut scene = redundant_ik::Scene::task(1).unwrap();
    scene.damping = Some(redundant_ik::DampingSchedule::default());
    let spec = redundant_ik::atlas::Spec {
        scene,
        grid: redundant_ik::atlas::Grid::new([0.2, 0.8, 0.2, 0.8], 4).unwrap(),
        methods: vec![
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
        AtlasJob::new(d.run().unwrap(), js_of(options))
            .err()
            .map(message)
            .unwrap_or_default()
    };
    assert!(job(r#"{"n": 1}"#).contains("grid points per side"));
    assert!(job(r#"{"n": 3.5}"#).contains("whole number"));
    assert!(job(r#"{"n": 1e300}"#).contains("grid points per side"));
    assert!(job(r#"{"methods": ["numerical", "fast"]}"#).contains("unknown method 'fast'"));
    assert!(job(r#"{"methods": []}"#).contains("number of methods"));
    assert!(job(r#"{"region": [0, 1, 0]}"#).contains("four numbers"));
    assert!(job(r#"{"region": [1, 0, 0, 1]}"#).contains("empty"));
    assert!(job(r#"{"n": "many"}"#).contains("atlas options"));
    assert!(job(r#"{"colour": "red"}"#).contains("unknown field"));
    let not_a_run = AtlasJob::new(js_of(r#"{"arm": 3}"#), JsValue::UNDEFINED);
    assert!(message(not_a_run.err().unwrap()).contains("not a run"));
    // A run whose networks are corrupt weights files.
    let mut run: Value = json_of(d.run().unwrap());
    run["networks"] = serde_json::json!({"phi": "{", "v": "{"});
    let corrupt = AtlasJob::new(
        js_of(&run.to_string()),
        js_of(r#"{"methods": ["case3"], "n": 3}"#),
    );
    assert!(message(corrupt.err().unwrap()).contains("bad network weights"));
    // A scene that fails validation is refused by the core.
    let mut run: Value = json_of(d.run().unwrap());
    run["scene"]["params"]["lambda"] = serde_json::json!(-1.0);
    let bad = AtlasJob::new(js_of(&run.to_string()), JsValue::UNDEFINED);
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
            "limit",
            "missed",
            "failed",
            "path_blocked",
            "start_overlap",
            "self_collision"
        ]
    );
    assert!(classes[0]["swatch"].as_str().unwrap().starts_with("rgba("));
    // Only an arm with joint limits has the class limit (the page's legend).
    let only_limited: Vec<bool> = classes
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["limits"].as_bool().unwrap())
        .collect();
    assert_eq!(
        only_limited,
        [false, false, true, false, false, false, false, false]
    );
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
        d.set_atlas_layer(region.clone(), 3, vec![8; 9])
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
    let keys: Vec<String> = json_of(legend(None).unwrap())
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
    // The lab's ellipses: drawn while their legend switch is on.
    assert!(!now.iter().any(|x| x == "ellipse" || x == "force"));
    assert!(d.set_shown("ellipse", true));
    assert!(drawn(&d).iter().any(|x| x == "ellipse"));
    assert!(d.set_shown("force", true));
    assert!(drawn(&d).iter().any(|x| x == "force"));
    assert!(!d.set_shown("arm", false), "not a switch");
    assert!(!d.set_shown("nothing", true));
    assert!(d.set_shown("ellipse", false) && d.set_shown("force", false));
    let off = drawn(&d);
    assert!(!off.iter().any(|x| x == "ellipse" || x == "force"));
    assert!(off.iter().any(|x| x == "arm"), "the arm still drawn");
}
