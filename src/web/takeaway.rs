//! What the page lets a user take away, made in its workers' module
//! (feature `worker`): a run as the JSON of `redundant-ik simulate --json`
//! and as CSV, and its figures; an atlas's cells as CSV and its maps. The
//! formats and the drawing are the library's ([`crate::export`],
//! [`crate::figure`]), so the page and the command line write the same
//! files. The page's own module carries none of it (plotters stays here).

use serde::Serialize;
use wasm_bindgen::prelude::*;

use super::worker::files;
use super::{js_err, to_js};
use crate::atlas::Atlas;
use crate::export::{self, RunFile};
use crate::figure;
use crate::networks;
use crate::planner::{Method, Planner};
use crate::scene::Scene;
use crate::session::STROBE_EVERY;

/// The files of one run.
#[derive(Serialize)]
struct RunFiles {
    /// The JSON of `simulate --json` (what `simulate --from` reads).
    json: String,
    /// One line per step.
    csv: String,
    /// The stroboscopic drawing (`redundant-ik figure`).
    figure: String,
    /// The time series (`redundant-ik figure --plots`).
    plots: String,
}

/// Runs `scene` (the page's `Demo.scene()`, from paper task `task`) with
/// `mode` from `t = 0` to `tf`, as the page does, with the networks of the
/// weights files `phi_json` and `v_json` if both are given and fit the
/// arm, else the built-in ones where they fit; returns `{ json, csv,
/// figure, plots }` (the figures as SVG, the arm drawn every
/// [`STROBE_EVERY`]th step, as on the stage). Throws with the core's
/// message on bad input.
#[wasm_bindgen(js_name = runFiles)]
pub fn run_files(
    scene: JsValue,
    mode: &str,
    task: u32,
    phi_json: Option<String>,
    v_json: Option<String>,
) -> Result<JsValue, JsError> {
    let scene: Scene = serde_wasm_bindgen::from_value(scene)
        .map_err(|e| JsError::new(&format!("not a scene: {e}")))?;
    scene.validate().map_err(js_err)?;
    let method: Method = mode.parse().map_err(js_err)?;
    let installed = files(phi_json, v_json)?;
    let nets = networks::for_method(method, &scene.arm, installed.as_ref()).map_err(js_err)?;
    let run = Planner::run(scene.clone(), method, nets).map_err(js_err)?;
    let figure = figure::arm_svg(task, &scene, &run, STROBE_EVERY).map_err(js_err)?;
    let plots = figure::series_svg(task, &scene, &run).map_err(js_err)?;
    let csv = export::run_csv(&scene, &run.steps);
    let json = RunFile::new(task, scene, run).to_json();
    to_js(&RunFiles {
        json,
        csv,
        figure,
        plots,
    })
}

/// The files of an atlas.
#[derive(Serialize)]
struct AtlasFiles {
    /// The JSON of `redundant-ik atlas --json`.
    json: String,
    /// One line per cell (`redundant-ik atlas --csv`).
    csv: String,
    /// The maps (`redundant-ik atlas --out`), of the modes asked for.
    figure: String,
}

/// An atlas (the object a job finished with) computed on `scene`:
/// `{ json, csv, figure }`, the figure of the modes named in `modes` (all
/// of the atlas's when empty). Throws on an atlas that does not read back.
#[wasm_bindgen(js_name = atlasFiles)]
pub fn atlas_files(atlas: JsValue, scene: JsValue, modes: Vec<String>) -> Result<JsValue, JsError> {
    let atlas: Atlas = serde_wasm_bindgen::from_value(atlas)
        .map_err(|e| JsError::new(&format!("not an atlas: {e}")))?;
    let scene: Scene = serde_wasm_bindgen::from_value(scene)
        .map_err(|e| JsError::new(&format!("not a scene: {e}")))?;
    let json = serde_json::to_string(&atlas).map_err(|e| JsError::new(&e.to_string()))?;
    let csv = export::atlas_csv(&atlas);
    let shown = if modes.is_empty() {
        atlas
    } else {
        only(atlas, &modes)?
    };
    let figure = figure::atlas_svg(&shown, &scene).map_err(js_err)?;
    to_js(&AtlasFiles { json, csv, figure })
}

/// The atlas restricted to `modes` (in the atlas's order).
fn only(mut atlas: Atlas, modes: &[String]) -> Result<Atlas, JsError> {
    let keep: Vec<usize> = atlas
        .modes
        .iter()
        .enumerate()
        .filter(|(_, m)| modes.iter().any(|n| n == m.name()))
        .map(|(k, _)| k)
        .collect();
    if keep.is_empty() {
        return Err(JsError::new(&format!(
            "the atlas has none of the modes {}",
            modes.join(", ")
        )));
    }
    atlas.modes = keep.iter().map(|&k| atlas.modes[k]).collect();
    atlas.summary = keep.iter().map(|&k| atlas.summary[k].clone()).collect();
    for c in &mut atlas.cells {
        c.outcomes = keep.iter().map(|&k| c.outcomes[k].clone()).collect();
    }
    Ok(atlas)
}
