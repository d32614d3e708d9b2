//! The in-browser benchmark of an arm in space (features `worker` and
//! `space`): the RK4 step of the preset's own task in a method and the
//! forward passes of its networks, the code behind `redundant-ik bench
//! --arm KEY`; or of a robot of the user's, whose scene comes as its run
//! file's text in place of the key. The workers' module carries no
//! weights: the page hands the networks' files as JSON text
//! ([`bench_space_network_files`] names a preset's).

use std::sync::Arc;

use wasm_bindgen::prelude::*;

use super::js_err;
use super::worker::{bench_options, probes, read_space_run, to_js};
use crate::bench::space as sb;
use crate::networks::space::{SpaceNetworkSet, SpaceNetworks};
use crate::planner::{methods, Method};
use crate::scene::SpaceScene;

/// The scene `arm` names, and what messages call it: a preset's key, or a
/// run file's text (of the hand's position or its pose: the position
/// scene is timed).
fn scene_of(arm: &str) -> Result<(SpaceScene, String), JsError> {
    // A key is a word; anything in braces is a run file, refused by its
    // reader where it is not one.
    if arm.trim_start().starts_with('{') {
        return Ok((read_space_run(arm)?.scene, "robot".into()));
    }
    Ok((SpaceScene::by_key(arm).map_err(js_err)?, arm.into()))
}

/// The methods the spatial benchmark times for `arm`, a preset's key or a
/// run file's text (every method that runs in space; the learned ones
/// only where networks are shipped for the arm, or `own_networks` says
/// the page hands networks of its own). Throws for an unknown arm.
#[wasm_bindgen(js_name = benchSpaceMethods)]
pub fn bench_space_methods(arm: &str, own_networks: Option<bool>) -> Result<Vec<String>, JsError> {
    scene_of(arm)?;
    let learned = own_networks == Some(true) || SpaceNetworkSet::for_arm(arm).is_some();
    Ok(methods::ALL
        .iter()
        .filter(|m| learned || !m.uses_networks())
        .map(|m| m.name().to_string())
        .collect())
}

/// The names of the `Phi` and `v` weights files shipped for the preset
/// `arm` (in `weights/` beside the page), or an empty list when none are.
#[wasm_bindgen(js_name = benchSpaceNetworkFiles)]
pub fn bench_space_network_files(arm: &str) -> Vec<String> {
    SpaceNetworkSet::for_arm(arm)
        .map(|s| s.file_names().iter().map(|n| n.to_string()).collect())
        .unwrap_or_default()
}

/// The networks from their files' text, or `None` when either is absent.
fn networks(phi: Option<String>, v: Option<String>) -> Result<Option<Arc<SpaceNetworks>>, JsError> {
    match (phi, v) {
        (Some(phi), Some(v)) => Ok(Some(Arc::new(
            SpaceNetworks::read(&phi, &v).map_err(js_err)?,
        ))),
        _ => Ok(None),
    }
}

/// One RK4 step of `arm`'s task in `method` (a preset's key, or a run
/// file's text), sample included, in nanoseconds; `phi` and `v` are the networks' weights files' text
/// (needed by Cases 1-3, ignored otherwise); `refine` Newton-Schulz steps
/// on the learned `Phi`; `precision` the networks' arithmetic (`f64` when
/// absent, or `f32`).
#[wasm_bindgen(js_name = benchSpaceStep)]
pub fn bench_space_step(
    arm: &str,
    method: &str,
    batch_ms: f64,
    refine: u32,
    phi: Option<String>,
    v: Option<String>,
    precision: Option<String>,
) -> Result<f64, JsError> {
    let method: Method = method.parse().map_err(js_err)?;
    let nets = if method.uses_networks() {
        networks(phi, v)?
    } else {
        None
    };
    let opts = crate::bench::Options {
        refine,
        ..bench_options(batch_ms, precision)?
    };
    let (scene, name) = scene_of(arm)?;
    sb::step_ns_of(scene, &name, method, nets, &opts, &probes()).map_err(js_err)
}

/// Forward passes of `arm`'s networks (a preset's key, or a run file's
/// text; the networks from their files' text) at its start pose in `precision` (`f64` when absent), in nanoseconds:
/// `{ phi, v }`.
#[wasm_bindgen(js_name = benchSpaceForward)]
pub fn bench_space_forward(
    arm: &str,
    batch_ms: f64,
    phi: String,
    v: String,
    precision: Option<String>,
) -> Result<JsValue, JsError> {
    let nets = networks(Some(phi), Some(v))?
        .ok_or_else(|| JsError::new("the networks' files are missing"))?;
    let opts = bench_options(batch_ms, precision)?;
    let f = sb::forward_ns_of(&scene_of(arm)?.0, nets, &opts, &probes()).map_err(js_err)?;
    to_js(&f)
}
