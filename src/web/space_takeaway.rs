//! What the page lets a user take away of a run in space, made in the
//! workers' module: its figure as SVG, the two orthographic views that
//! `redundant-ik figure --from FILE` draws (the library's
//! [`crate::figure::space_svg`], so the page and the command line draw the
//! same file), and its plots as SVG, what `figure --from FILE --plots`
//! draws ([`crate::figure::space_series_svg`]). The page's module makes the run file itself
//! (`SpaceDemo.runFile`); this reads it back, as `simulate --from` does.
//! And a slice atlas's files: its JSON, its cells as CSV and its maps
//! (`redundant-ik atlas --arm A --json`, `--csv` and `--out`).

use wasm_bindgen::prelude::*;

use super::js_err;
use super::takeaway::{restrict, AtlasFiles};
use super::worker::{read_space_run, to_js};
use crate::atlas::space::SliceAtlas;
use crate::export::{self, is_pose_run, Recorded, RunFile};
use crate::figure;
use crate::model::{Model, Scene as _};
use crate::planner::Trajectory;
use crate::session::STROBE_EVERY;
use crate::space::{Chain, PoseChain};

/// The figure of the run in `run_json` (a run file of an arm in space,
/// `SpaceDemo.runFile()`, of the hand's position or its pose) as SVG, the
/// chain drawn every [`STROBE_EVERY`]th step. Throws with the core's
/// message on a file that does not read.
#[wasm_bindgen(js_name = spaceFigure)]
pub fn space_figure(run_json: &str) -> Result<String, JsError> {
    if is_pose_run(run_json) {
        let (label, file, traj) = read::<PoseChain, 6>(run_json)?;
        return figure::pose_svg(&label, &file.scene, &traj, STROBE_EVERY, false).map_err(js_err);
    }
    let (label, file, traj) = read::<Chain, 3>(run_json)?;
    figure::space_svg(&label, &file.scene, &traj, STROBE_EVERY).map_err(js_err)
}

/// The plots of the run in `run_json` (the clearance, the tracking error
/// and the joint angles over time; of the hand's pose, its orientation's
/// error too) as SVG. Throws with the core's message on a file that does
/// not read.
#[wasm_bindgen(js_name = spacePlots)]
pub fn space_plots(run_json: &str) -> Result<String, JsError> {
    if is_pose_run(run_json) {
        let (label, file, traj) = read::<PoseChain, 6>(run_json)?;
        return figure::pose_series_svg(&label, &file.scene, &traj).map_err(js_err);
    }
    let (label, file, traj) = read::<Chain, 3>(run_json)?;
    figure::space_series_svg(&label, &file.scene, &traj).map_err(js_err)
}

/// A run file's arm (what a figure calls it: its preset's label), the
/// file and its run.
type Read<A, const M: usize> = (String, RunFile<A, M>, Trajectory<M, <A as Model<M>>::Point>);

fn read<A, const M: usize>(run_json: &str) -> Result<Read<A, M>, JsError>
where
    A: Recorded<M> + AsRef<Chain>,
    A::Scene: serde::Serialize + serde::de::DeserializeOwned,
    [f64; M]: serde::Serialize + serde::de::DeserializeOwned,
{
    let mut file = RunFile::<A, M>::from_json(run_json).map_err(js_err)?;
    let label = super::worker::label_of(file.scene.arm().as_ref(), file.robot.as_ref());
    let traj = Trajectory {
        method: file.method,
        steps: std::mem::take(&mut file.steps),
        summary: file.summary.clone(),
    };
    Ok((label, file, traj))
}

/// A slice atlas's files, `{ json, csv, figure }`: `atlas_json` (what the
/// page's slice atlas job finished with, `atlas --arm A --json`) as it is,
/// its cells as CSV, and the maps of the methods named in `methods` (all of
/// the atlas's when empty) drawn on the scene of `run`, the run file the
/// atlas was computed on. Throws with a reason on an atlas or a run file
/// that does not read.
#[wasm_bindgen(js_name = sliceAtlasFiles)]
pub fn slice_atlas_files(
    atlas_json: &str,
    run: &str,
    methods: Vec<String>,
) -> Result<JsValue, JsError> {
    let mut atlas: SliceAtlas = serde_json::from_str(atlas_json)
        .map_err(|e| JsError::new(&format!("not a slice atlas: {e}")))?;
    let run = read_space_run(run)?;
    let (scene, pose, label) = (run.scene, run.pose.is_some(), run.label);
    let csv = export::slice_atlas_csv(&atlas);
    if !methods.is_empty() {
        restrict(&mut atlas.methods, &mut atlas.cells, &methods)?;
    }
    let figure = figure::slice_svg(&atlas, &scene, &label, pose).map_err(js_err)?;
    to_js(&AtlasFiles {
        json: atlas_json.to_string(),
        csv,
        figure,
    })
}
