//! The slice atlas of an arm in space in the workers' module
//! (`SpaceAtlasJob`): read from a spatial run file's text, advanced a
//! chunk at a time, finished as the JSON text the native `atlas --arm A
//! --json` writes for the same scene.

use super::*;
use redundant_ik::atlas::space::{default_region, slice, Plane};
use redundant_ik::atlas::Grid;
use redundant_ik::export::SpaceRunFile;
use redundant_ik::planner::Planner;
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::SpacePreset;
use redundant_ik::web::SpaceAtlasJob;
use redundant_ik::Method;
use wasm_bindgen_test::wasm_bindgen_test;

/// The run file `simulate --arm panda --json` writes.
pub(crate) fn panda_run() -> (SpaceScene, String) {
    let p = SpacePreset::by_key("panda").unwrap();
    let scene = SpaceScene::preset(p);
    let traj = Planner::new(scene.clone(), Method::NUMERICAL, None)
        .and_then(Planner::run_to_end)
        .unwrap();
    let file = SpaceRunFile::of(None, scene.clone(), traj, None, Default::default());
    (scene, file.to_json())
}

#[wasm_bindgen_test]
fn a_space_atlas_job_is_the_native_slice_a_row_at_a_time() {
    let (scene, run) = panda_run();
    let options = js_sys::JSON::parse(r#"{"methods": ["none", "qp"], "n": 4}"#).unwrap();
    let mut job = SpaceAtlasJob::new(&run, options).unwrap();
    assert_eq!((job.total(), job.done(), job.row()), (16, 0, 4));
    assert!(message(job.finish().err().unwrap()).contains("cells computed"));
    assert_eq!(job.advance(4), 4);
    assert_eq!(job.advance(100), 16);
    let plane = Plane::through_line(&scene);
    let grid = Grid::new(default_region(&scene, plane), 4).unwrap();
    let mut native = slice(
        &scene,
        plane,
        grid,
        &[Method::NO_AVOIDANCE, redundant_ik::planner::methods::QP],
        None,
    )
    .unwrap();
    native.arm = Some("panda");
    assert_eq!(
        job.finish().unwrap(),
        serde_json::to_string(&native).unwrap()
    );
    // The options as JSON text, with a plane and a region of their own.
    let text =
        r#"{"methods": ["numerical"], "n": 3, "plane": "xz:0.0", "region": [0.2, 0.6, 0.2, 0.6]}"#;
    let mut job = SpaceAtlasJob::new(&run, JsValue::from_str(text)).unwrap();
    job.advance(9);
    let a: serde_json::Value = serde_json::from_str(&job.finish().unwrap()).unwrap();
    assert_eq!(a["plane"], serde_json::json!({ "Xz": 0.0 }));
    assert_eq!(a["grid"]["region"], serde_json::json!([0.2, 0.6, 0.2, 0.6]));
}

#[wasm_bindgen_test]
fn a_space_atlas_job_refuses_what_it_cannot_run_with_a_reason() {
    let (_, run) = panda_run();
    let refusal = |options: &str| {
        let o = js_sys::JSON::parse(options).unwrap();
        message(SpaceAtlasJob::new(&run, o).err().unwrap())
    };
    assert!(refusal(r#"{"methods": ["case3"]}"#).contains("options.networks"));
    assert!(refusal(r#"{"method": ["qp"]}"#).contains("unknown field"));
    assert!(refusal(r#"{"n": 2.5}"#).contains("whole number"));
    assert!(refusal(r#"{"plane": "yz:5.0"}"#).contains("slice"));
    assert!(
        refusal(r#"{"networks": {"phi": "{}", "v": "{}"}, "methods": ["case1"]}"#)
            .contains("Phi file")
    );
    let bad = SpaceAtlasJob::new("{\"format\": \"redundant-ik-run/1\"}", JsValue::UNDEFINED);
    assert!(message(bad.err().unwrap()).contains("a planar arm"));
    let bad = SpaceAtlasJob::new("{\"format\": \"redundant-ik-run/9\"}", JsValue::UNDEFINED);
    assert!(message(bad.err().unwrap()).contains("redundant-ik-run/2"));
}

#[wasm_bindgen_test]
fn a_pose_run_file_maps_the_pose_task_as_the_native_pose_slice_does() {
    use redundant_ik::atlas::space::pose_slice;
    use redundant_ik::export::PoseRunFile;
    use redundant_ik::scene::PoseScene;
    let p = SpacePreset::by_key("panda").unwrap();
    let scene = PoseScene::preset(p).unwrap();
    let traj = Planner::new(scene.clone(), redundant_ik::planner::methods::QP, None)
        .and_then(Planner::run_to_end)
        .unwrap();
    let run = PoseRunFile::of(None, scene.clone(), traj, None, Default::default()).to_json();
    // Without a list of methods: every one that runs the pose without networks.
    let mut job = SpaceAtlasJob::new(&run, js_sys::JSON::parse(r#"{"n": 3}"#).unwrap()).unwrap();
    job.advance(9);
    let a: serde_json::Value = serde_json::from_str(&job.finish().unwrap()).unwrap();
    let names: Vec<&str> = a["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap())
        .collect();
    assert!(
        names.contains(&"qp") && names.contains(&"numerical"),
        "{names:?}"
    );
    assert!(!names.iter().any(|m| m.starts_with("case")), "{names:?}");
    // A list of its own: the native pose slice, cell for cell.
    let options = js_sys::JSON::parse(r#"{"methods": ["none", "qp"], "n": 3}"#).unwrap();
    let mut job = SpaceAtlasJob::new(&run, options).unwrap();
    job.advance(9);
    let (position, _, _) = scene.position_scene();
    let plane = Plane::through_line(&position);
    let grid = Grid::new(default_region(&position, plane), 3).unwrap();
    let methods = [Method::NO_AVOIDANCE, redundant_ik::planner::methods::QP];
    let mut native = pose_slice(&scene, plane, grid, &methods, None).unwrap();
    native.arm = Some("panda");
    assert_eq!(
        job.finish().unwrap(),
        serde_json::to_string(&native).unwrap()
    );
    // With the Panda's networks: Case 2 maps (v serves the pose), Case 1
    // is refused (it needs a Phi for the pose, which no network has).
    let networks = serde_json::json!({
        "phi": include_str!("../../weights/phi-panda-reach.json"),
        "v": include_str!("../../weights/v-panda-reach.json"),
    });
    let with = |method: &str| {
        let o = serde_json::json!({ "methods": [method], "n": 2, "networks": networks });
        SpaceAtlasJob::new(&run, js_sys::JSON::parse(&o.to_string()).unwrap())
    };
    assert!(with("case2").is_ok());
    let e = message(with("case1").err().unwrap());
    assert!(e.contains("Phi"), "{e}");
}

/// A slice atlas's files from the workers' module: the JSON as the job
/// finished it, the native CSV and maps of the method asked for; a broken
/// atlas and a method it lacks are refused with the reason.
#[wasm_bindgen_test]
fn a_slice_atlas_gives_its_files_as_the_command_line_writes_them() {
    use redundant_ik::web::slice_atlas_files;
    let (scene, run) = panda_run();
    let options = js_sys::JSON::parse(r#"{"methods": ["none", "qp"], "n": 3}"#).unwrap();
    let mut job = SpaceAtlasJob::new(&run, options).unwrap();
    job.advance(9);
    let json = job.finish().unwrap();
    let files = slice_atlas_files(&json, &run, vec!["qp".into()]).unwrap();
    let get = |k: &str| {
        js_sys::Reflect::get(&files, &k.into())
            .unwrap()
            .as_string()
            .unwrap()
    };
    assert_eq!(get("json"), json);
    let atlas: redundant_ik::atlas::space::SliceAtlas = serde_json::from_str(&json).unwrap();
    assert_eq!(get("csv"), redundant_ik::export::slice_atlas_csv(&atlas));
    let mut qp = atlas.clone();
    qp.methods.remove(0);
    for c in &mut qp.cells {
        c.outcomes.remove(0);
    }
    let label = "Franka Panda (7 joints, in space)";
    assert_eq!(
        get("figure"),
        redundant_ik::figure::slice_svg(&qp, &scene, label, false).unwrap()
    );
    assert!(
        message(slice_atlas_files("{}", &run, vec![]).err().unwrap()).contains("not a slice atlas")
    );
    assert!(message(
        slice_atlas_files(&json, &run, vec!["case3".into()])
            .err()
            .unwrap()
    )
    .contains("none of the methods case3"));
}
