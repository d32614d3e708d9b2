//! What the page lets a user take away of a run in space, made in the
//! workers' module: its figure as SVG, the two orthographic views that
//! `redundant-ik figure --from FILE` draws (the library's
//! [`crate::figure::space_svg`], so the page and the command line draw the
//! same file), and its plots as SVG, what `figure --from FILE --plots`
//! draws ([`crate::figure::space_series_svg`]). The page's module makes the run file itself
//! (`SpaceDemo.runFile`); this reads it back, as `simulate --from` does.

use wasm_bindgen::prelude::*;

use super::js_err;
use crate::export::SpaceRunFile;
use crate::figure;
use crate::planner::Trajectory;
use crate::session::STROBE_EVERY;
use crate::space::SpacePreset;

/// The figure of the run in `run_json` (a run file of an arm in space,
/// `SpaceDemo.runFile()`) as SVG, the chain drawn every
/// [`STROBE_EVERY`]th step. Throws with the core's message on a file that
/// does not read.
#[wasm_bindgen(js_name = spaceFigure)]
pub fn space_figure(run_json: &str) -> Result<String, JsError> {
    let (label, file, traj) = read(run_json)?;
    figure::space_svg(label, &file.scene, &traj, STROBE_EVERY).map_err(js_err)
}

/// The plots of the run in `run_json` (the clearance, the tracking error
/// and the joint angles over time) as SVG. Throws with the core's message
/// on a file that does not read.
#[wasm_bindgen(js_name = spacePlots)]
pub fn space_plots(run_json: &str) -> Result<String, JsError> {
    let (label, file, traj) = read(run_json)?;
    figure::space_series_svg(label, &file.scene, &traj).map_err(js_err)
}

/// A run file's arm (what a figure calls it: its preset's label), the
/// file and its run.
fn read(run_json: &str) -> Result<(&'static str, SpaceRunFile, Trajectory<3>), JsError> {
    let mut file = SpaceRunFile::from_json(run_json).map_err(js_err)?;
    let label = SpacePreset::of(&file.scene.arm).map_or("Arm in space", |p| p.label);
    let traj = Trajectory {
        method: file.method,
        steps: std::mem::take(&mut file.steps),
        summary: file.summary.clone(),
    };
    Ok((label, file, traj))
}
