//! The figures of a run of the hand's pose (`M = 6`, [`PoseScene`]): the
//! chain's two orthographic views, its plots over time and the comparison
//! of the methods, drawn as an arm in space's run ([`super::space`],
//! [`super::series`]) from the hand's position, with what is the pose's
//! own added: the orientation's error beside the position's in the title
//! and the plots, and `Z` in the caption.

use super::series::pose_plots_svg;
use super::space::space_svg_with;
use super::{space_caption, space_compare_svg};
use crate::error::Result;
use crate::planner::{Sample, Trajectory};
use crate::scene::PoseScene;

/// A run of the hand's pose, as its samples are kept.
pub type PoseRun = Trajectory<6, [f64; 3]>;

/// The run's samples as the hand's position's ([`Sample::position`]).
fn positions(run: &PoseRun) -> Trajectory<3> {
    Trajectory {
        method: run.method,
        summary: run.summary.clone(),
        steps: run.steps.iter().map(Sample::position).collect(),
    }
}

/// The caption of a figure of a run of the hand's pose in `method`: an
/// arm in space's, with `Z`.
fn caption(arm: &str, scene: &PoseScene, method: crate::planner::Method) -> String {
    format!(
        "{} · the hand's pose, Z = diag(1, 1, 1, {})",
        space_caption(arm, &scene.position_scene().0, method),
        scene.arm.orientation_weight()
    )
}

/// The figure of a run of the hand's pose (of `scene`, the arm called
/// `arm`) as SVG: the chain drawn every `every` steps in two views, as
/// [`super::space_svg_with`] draws a run of the hand's position; its title
/// gives the orientation's final error too.
pub fn pose_svg(
    arm: &str,
    scene: &PoseScene,
    run: &PoseRun,
    every: usize,
    ellipsoid: bool,
) -> Result<String> {
    let position = scene.position_scene().0;
    space_svg_with(arm, &position, &positions(run), every, ellipsoid)
}

/// The plots of a run of the hand's pose over time as SVG: the clearance,
/// the tracking error of the position (m) and of the orientation (rad),
/// and the joint angles.
pub fn pose_series_svg(arm: &str, scene: &PoseScene, run: &PoseRun) -> Result<String> {
    let line = caption(arm, scene, run.method);
    pose_plots_svg(arm, &positions(run), scene.arm.chain.dof(), &line)
}

/// Every run of one scene of the hand's pose over time (the clearance and
/// the hand's position error, as [`super::space_compare_svg`] draws them).
pub fn pose_compare_svg(arm: &str, scene: &PoseScene, runs: &[PoseRun]) -> Result<String> {
    let position = scene.position_scene().0;
    let runs: Vec<Trajectory<3>> = runs.iter().map(positions).collect();
    space_compare_svg(arm, &position, &runs)
}
