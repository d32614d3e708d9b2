//! The `weights` target.

use std::sync::Arc;

use redundant_ik::networks::space::SpaceWeightsFile;
use redundant_ik::networks::{NetKind, WeightsFile};
use redundant_ik::planner::{Method, Planner, Surrogate};
use redundant_ik::{Networks, Scene};

use super::checks::{shipped, step_checked};

/// Weights files from arbitrary bytes, as the page's file picker, its
/// localStorage and the CLI's `--phi`/`--v` read them: parse, validate,
/// pair with the shipped partner, run a planner on the result. A file
/// that loads must save and load back equal, and its networks must never
/// put a non-finite angle into a planner's state.
pub fn weights(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    // The same bytes as a file of an arm in space: what loads saves and
    // loads back equal.
    if let Ok(file) = SpaceWeightsFile::from_json(&text) {
        let json = file.to_json().expect("a loaded file saves");
        let again = SpaceWeightsFile::from_json(&json).expect("a saved file loads");
        assert_eq!(again, file, "save and load changed the spatial file");
    }
    let Ok(file) = <WeightsFile>::from_json(&text) else {
        return;
    };
    // What loads validates, and survives a save.
    file.validate().expect("a loaded file validates");
    let json = file.to_json().expect("a loaded file saves");
    let again = <WeightsFile>::from_json(&json).expect("a saved file loads");
    assert_eq!(again, file, "save and load changed the file");

    let shipped = shipped();
    let pair = match file.net {
        NetKind::Phi => Networks::from_json(&text, &shipped.v_file().to_json().unwrap()),
        NetKind::V => Networks::from_json(&shipped.phi_file().to_json().unwrap(), &text),
    };
    let Ok(nets) = pair else {
        return;
    };
    let nets: Arc<dyn Surrogate> = Arc::new(nets);
    let mut scene = Scene::task1();
    scene.tf = 1.0;
    for method in [Method::CASE1, Method::CASE2, Method::CASE3] {
        let Ok(mut p) = Planner::new(scene.clone(), method, Some(nets.clone())) else {
            continue;
        };
        step_checked(&mut p, 10);
    }
}
