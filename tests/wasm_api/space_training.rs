//! Training an arm in space's networks in the workers' module
//! (`trainSpaceNetwork`): a shipped arm by its key, or the robot of a run
//! file (what the page sends for a robot the user opened). A run file of a
//! shipped arm's own scene is the same training as its key, byte for byte.

use super::space_atlas::panda_run;
use super::*;
use redundant_ik::export::PoseRunFile;
use redundant_ik::planner::Planner;
use redundant_ik::scene::{PoseScene, SpaceScene};
use redundant_ik::space::SpacePreset;
use redundant_ik::web::train_space_network;
use redundant_ik::Method;
use wasm_bindgen_test::wasm_bindgen_test;

/// Trains with `request` (JSON), counting the epochs reported.
fn train(request: serde_json::Value) -> Result<(String, u32), String> {
    let on_epoch = js_sys::Function::new_with_args(
        "p",
        "globalThis.__epochs = (globalThis.__epochs || 0) + (p.epoch > 0 ? 1 : 0)",
    );
    js_sys::Reflect::set(&js_sys::global(), &"__epochs".into(), &0.into()).unwrap();
    let request = js_sys::JSON::parse(&request.to_string()).unwrap();
    let file = train_space_network(request, &on_epoch).map_err(message)?;
    let epochs = js_sys::Reflect::get(&js_sys::global(), &"__epochs".into()).unwrap();
    Ok((file, epochs.as_f64().unwrap() as u32))
}

#[wasm_bindgen_test]
fn the_robot_of_a_run_file_trains_as_its_preset_key_does() {
    let (_, run) = panda_run();
    let small = |arm: serde_json::Value| {
        let mut r = serde_json::json!({ "net": "phi", "samples": 200, "epochs": 2, "seed": 7 });
        r.as_object_mut()
            .unwrap()
            .extend(arm.as_object().unwrap().clone());
        r
    };
    let (by_key, epochs) = train(small(serde_json::json!({ "arm": "panda" }))).unwrap();
    assert_eq!(epochs, 2, "each epoch reported");
    let (by_run, _) = train(small(serde_json::json!({ "run": run, "name": "my panda" }))).unwrap();
    assert_eq!(by_run, by_key);
    let file: Value = serde_json::from_str(&by_run).unwrap();
    assert_eq!(file["arm"]["rows"].as_array().unwrap().len(), 7);
}

#[wasm_bindgen_test]
fn a_pose_run_file_trains_the_networks_of_its_position_scene() {
    let p = SpacePreset::by_key("panda").unwrap();
    let scene = PoseScene::preset(p).unwrap();
    assert_eq!(scene.position_scene().0, SpaceScene::preset(p));
    let traj = Planner::new(scene.clone(), Method::NUMERICAL, None)
        .and_then(Planner::run_to_end)
        .unwrap();
    let pose = PoseRunFile::of(None, scene, traj, None, Default::default()).to_json();
    let v = serde_json::json!({ "net": "v", "samples": 100, "epochs": 1, "seed": 3 });
    let mut by_pose = v.clone();
    by_pose["run"] = pose.into();
    let mut by_key = v;
    by_key["arm"] = "panda".into();
    assert_eq!(train(by_pose).unwrap().0, train(by_key).unwrap().0);
}

#[wasm_bindgen_test]
fn a_request_names_its_arm_once_and_a_bad_run_is_refused_by_the_reader() {
    let (_, run) = panda_run();
    let both = serde_json::json!({ "arm": "panda", "run": run, "net": "phi" });
    assert!(train(both).unwrap_err().contains("not both"));
    let neither = serde_json::json!({ "net": "phi" });
    assert!(train(neither).unwrap_err().contains("by 'arm'"));
    let broken = serde_json::json!({ "run": "{\"format\": \"redundant-ik-run/3\"", "net": "phi" });
    let e = train(broken).unwrap_err();
    assert!(e.contains("run file") && e.contains("not JSON"), "{e}");
    let long = serde_json::json!({ "run": run, "name": "x".repeat(201), "net": "phi" });
    assert!(train(long).unwrap_err().contains("longer than 200"));
    let unknown = serde_json::json!({ "arm": "ur99", "net": "phi" });
    let e = train(unknown).unwrap_err();
    assert!(
        e.contains("unknown arm in space 'ur99': use panda or iiwa14"),
        "{e}"
    );
}

/// The benchmark of a robot of the user's: its run file's text in place of
/// a preset's key; its learned methods only with networks of its own.
#[wasm_bindgen_test]
fn the_benchmark_times_the_scene_of_a_run_file() {
    use redundant_ik::web::{bench_space_forward, bench_space_methods, bench_space_step};
    let (_, run) = panda_run();
    // A run file names no shipped set: the learned methods need networks handed over.
    let plain = bench_space_methods(&run, None).unwrap();
    assert!(plain.contains(&"qp".to_string()) && !plain.iter().any(|m| m.starts_with("case")));
    assert!(bench_space_methods(&run, Some(true))
        .unwrap()
        .contains(&"case3".to_string()));
    let ns = bench_space_step(&run, "qp", 1.0, 0, None, None, None).unwrap();
    assert!(ns.is_finite() && ns > 0.0, "{ns}");
    let e = message(bench_space_step(&run, "case3", 1.0, 0, None, None, None).unwrap_err());
    assert!(e.contains("needs the networks of the arm 'robot'"), "{e}");
    let phi = include_str!("../../weights/phi-panda-reach.json");
    let v = include_str!("../../weights/v-panda-reach.json");
    let ns = bench_space_step(
        &run,
        "case3",
        1.0,
        0,
        Some(phi.into()),
        Some(v.into()),
        None,
    )
    .unwrap();
    assert!(ns.is_finite() && ns > 0.0, "{ns}");
    let f = json_of(bench_space_forward(&run, 1.0, phi.into(), v.into(), None).unwrap());
    assert!(
        f["phi"].as_f64().unwrap() > 0.0 && f["v"].as_f64().unwrap() > 0.0,
        "{f}"
    );
    // A run file cut short is read as one and refused by the reader; other text is an unknown arm.
    let cut = &run[..run.len() / 2];
    let e = message(bench_space_step(cut, "qp", 1.0, 0, None, None, None).unwrap_err());
    assert!(e.contains("run file"), "{e}");
    let e = message(bench_space_step("ur99", "qp", 1.0, 0, None, None, None).unwrap_err());
    assert!(e.contains("unknown arm in space 'ur99'"), "{e}");
}
