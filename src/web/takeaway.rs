//! What the page lets a user take away, made in its workers' module
//! (feature `worker`): a run as the JSON of `redundant-ik simulate --json`
//! and as CSV, and its figures; an atlas's cells as CSV and its maps. The
//! formats and the drawing are the library's ([`crate::export`],
//! [`crate::figure`]), so the page and the command line write the same
//! files. The page's own module carries none of it (plotters stays here).

use serde::Serialize;
use wasm_bindgen::prelude::*;

use super::js_err;
use super::worker::{from_js, read_run, to_js};
use crate::atlas::{Atlas, Cell};
use crate::export::{self, RunFile};
use crate::figure;
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

/// Runs `run` (the page's `Demo.run()`: its task, scene, method and
/// networks) from `t = 0` to `tf`, as the page does; returns `{ json, csv,
/// figure, plots }` (the figures as SVG, the arm drawn every
/// [`STROBE_EVERY`]th step, as on the stage; the JSON names the networks,
/// so `simulate --from` replays it with them). Throws with the core's
/// message on bad input.
#[wasm_bindgen(js_name = runFiles)]
pub fn run_files(run: JsValue) -> Result<JsValue, JsError> {
    let run = read_run(run)?;
    let (task, scene, method) = (run.task, run.scene.clone(), run.method);
    let nets = run.surrogate_for(method).map_err(js_err)?;
    let traj = Planner::run(scene.clone(), method, nets).map_err(js_err)?;
    let figure = figure::arm_svg(task, &scene, &traj, STROBE_EVERY).map_err(js_err)?;
    let plots = figure::series_svg(task, &scene, &traj).map_err(js_err)?;
    let csv = export::run_csv(&traj.steps);
    let json = RunFile::new(run, traj).to_json();
    to_js(&RunFiles {
        json,
        csv,
        figure,
        plots,
    })
}

/// The files of an atlas (the planar atlas's, and a slice atlas's in
/// space: [`super::space_takeaway`]).
#[derive(Serialize)]
pub(super) struct AtlasFiles {
    /// The JSON of `redundant-ik atlas --json`.
    pub(super) json: String,
    /// One line per cell (`redundant-ik atlas --csv`).
    pub(super) csv: String,
    /// The maps (`redundant-ik atlas --out`), of the methods asked for.
    pub(super) figure: String,
}

/// An atlas (the object a job finished with) computed on `scene`:
/// `{ json, csv, figure }`, the figure of the methods named in `methods` (all
/// of the atlas's when empty). Throws on an atlas that does not read back.
#[wasm_bindgen(js_name = atlasFiles)]
pub fn atlas_files(
    atlas: JsValue,
    scene: JsValue,
    methods: Vec<String>,
) -> Result<JsValue, JsError> {
    // An atlas's cells may hold NaN (a distance where nothing ran): read
    // as absent, as the atlas's JSON file writes it.
    let atlas: Atlas = from_js(&atlas, "not an atlas", false)?;
    let scene: Scene = from_js(&scene, "not a scene", true)?;
    let json = serde_json::to_string(&atlas).map_err(|e| JsError::new(&e.to_string()))?;
    let csv = export::atlas_csv(&atlas);
    let shown = if methods.is_empty() {
        atlas
    } else {
        only(atlas, &methods)?
    };
    let figure = figure::atlas_svg(&shown, &scene).map_err(js_err)?;
    to_js(&AtlasFiles { json, csv, figure })
}

/// The atlas restricted to `methods` (in the atlas's order).
fn only(mut atlas: Atlas, methods: &[String]) -> Result<Atlas, JsError> {
    let keep = restrict(&mut atlas.methods, &mut atlas.cells, methods)?;
    atlas.summary = keep.iter().map(|&k| atlas.summary[k].clone()).collect();
    Ok(atlas)
}

/// An atlas's `methods` and its `cells`' outcomes restricted to the
/// methods named in `names` (in the atlas's order), for either atlas;
/// returns the indices kept, or why none is.
pub(super) fn restrict<const D: usize>(
    methods: &mut Vec<Method>,
    cells: &mut [Cell<D>],
    names: &[String],
) -> Result<Vec<usize>, JsError> {
    let keep: Vec<usize> = methods
        .iter()
        .enumerate()
        .filter(|(_, m)| names.iter().any(|n| n == m.name()))
        .map(|(k, _)| k)
        .collect();
    if keep.is_empty() {
        return Err(JsError::new(&format!(
            "the atlas has none of the methods {}",
            names.join(", ")
        )));
    }
    *methods = keep.iter().map(|&k| methods[k]).collect();
    for c in cells {
        c.outcomes = keep.iter().map(|&k| c.outcomes[k].clone()).collect();
    }
    Ok(keep)
}
