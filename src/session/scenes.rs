//! The scenes a session starts from: a start pose for any arm, the
//! paper's tasks with the page's switches, and what a new task or arm keeps
//! of the methods' settings.

use crate::arm::Arm;
use crate::error::Result;
use crate::ik::DampingSchedule;
use crate::planner::methods::{DELTA, LAMBDA};
use crate::scene::Scene;

/// A start pose for `arm`: a preset's own task's if it has one; else the
/// paper's Task 1 pose for its first three
/// joints (`pi/12, pi/2, -pi/6`), then each further joint bent `-pi/6`,
/// which keeps a 2- to 6-link arm off the ground, bent (not singular) and
/// inside its reach.
pub fn start_pose(arm: &Arm) -> Vec<f64> {
    use std::f64::consts::PI;
    if let Some(task) = crate::arm::Preset::of(arm).and_then(|p| p.task) {
        return task.theta0.to_vec();
    }
    let paper = [PI / 12.0, PI / 2.0, -PI / 6.0];
    (0..arm.dof())
        .map(|i| paper.get(i).copied().unwrap_or(-PI / 6.0))
        .collect()
}

/// The paper's scene `task` with the damping switch and feedback gain given.
pub(super) fn paper_scene(task: u32, damping: bool, feedback: f64) -> Result<Scene> {
    let mut scene = Scene::task(task)?;
    scene.damping = damping.then(DampingSchedule::default);
    scene.feedback_gain = feedback;
    Ok(scene)
}

/// The settings of the methods that a new task or arm keeps from `old`:
/// every parameter but the paper's `lambda` and `delta`, which come with
/// the task.
pub(super) fn keep_method_settings(scene: &mut Scene, old: &Scene) {
    let task = [&LAMBDA, &DELTA].map(|p| (p, scene.param(p)));
    scene.params = old.params.clone();
    // The values came from valid scenes; the order checks cannot fail on
    // them (neither is ordered against another parameter).
    let _ = scene.params.set_all(&task);
    scene.weighting = old.weighting;
    scene.floor = old.floor;
}
