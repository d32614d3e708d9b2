//! The in-browser benchmark of an arm in space (features `worker` and
//! `space`): the RK4 step of the preset's own task in a method and the
//! forward passes of its networks, the code behind `redundant-ik bench
//! --arm KEY`. The workers' module carries no weights: the page hands the
//! networks' files as JSON text ([`bench_space_network_files`] names them).

use std::sync::Arc;

use wasm_bindgen::prelude::*;

use super::js_err;
use super::worker::{bench_options, probes, to_js};
use crate::bench::space as sb;
use crate::networks::space::{SpaceNetworkSet, SpaceNetworks};
use crate::planner::{methods, Method};

/// The methods the spatial benchmark times for the preset `arm` (every
/// method that runs in space; the learned ones only where networks are
/// shipped for the arm). Throws for an unknown arm.
#[wasm_bindgen(js_name = benchSpaceMethods)]
pub fn bench_space_methods(arm: &str) -> Result<Vec<String>, JsError> {
    crate::scene::SpaceScene::by_key(arm).map_err(js_err)?;
    let shipped = SpaceNetworkSet::for_arm(arm).is_some();
    Ok(methods::ALL
        .iter()
        .filter(|m| shipped || !m.uses_networks())
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
            SpaceNetworks::from_json(&phi, &v).map_err(js_err)?,
        ))),
        _ => Ok(None),
    }
}

/// One RK4 step of the preset `arm`'s task in `method`, sample included,
/// in nanoseconds; `phi` and `v` are the networks' weights files' text
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
    sb::step_ns_with(arm, method, nets, &opts, &probes()).map_err(js_err)
}

/// Forward passes of the preset `arm`'s networks (from their files' text)
/// at its start pose in `precision` (`f64` when absent), in nanoseconds:
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
    let f = sb::forward_ns(arm, nets, &opts, &probes()).map_err(js_err)?;
    to_js(&f)
}
