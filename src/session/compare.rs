//! Runs off screen: the current scene (or a variant of it) from `t = 0`
//! with any method, and the comparison of every method on it. The
//! networks come from [`crate::networks::for_method`], as on screen.

use serde::Serialize;

use super::Session;
use crate::atlas;
use crate::error::Result;
use crate::networks;
use crate::planner::{methods, Method, Planner, Summary};
use crate::scene::Scene;

/// One method's run of the current scene, for the comparison table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodRun {
    /// Method name.
    pub method: &'static str,
    /// Method label ([`Method::label`]).
    pub label: &'static str,
    /// The outcome, if the run went through.
    pub summary: Option<Summary>,
    /// Why it did not.
    pub error: Option<String>,
    /// Whether a hit is unavoidable in this scene, whatever the method: an
    /// obstacle on the arm at `t = 0` (`"start_overlap"`) or on the path
    /// the hand must follow (`"path_blocked"`), as the atlas classes them.
    pub unavoidable: Option<&'static str>,
}

impl Session {
    /// Runs `scene` from `t = 0` to its final time with `method`, off
    /// screen, with the networks the session would use for it; refused
    /// with the scene's own reason where it is not valid.
    pub fn run_offscreen(&self, scene: Scene, method: Method) -> Result<Summary> {
        scene.validate()?;
        let nets = networks::for_method(method, &scene.arm, self.installed(), self.precision())?;
        Planner::run_summary(scene, method, nets)
    }

    /// Runs the current scene from `t = 0` with every method, off screen.
    pub fn compare_methods(&self) -> Vec<MethodRun> {
        let scene = self.planner().scene();
        let unavoidable = scene
            .obstacles
            .iter()
            .filter_map(|o| atlas::unavoidable(scene, o))
            .min()
            .map(|c| c.name());
        methods::ALL
            .iter()
            .map(|&m| {
                let (summary, error) = match self.run_offscreen(scene.clone(), m) {
                    Ok(s) => (Some(s), None),
                    Err(e) => (None, Some(e.to_string())),
                };
                MethodRun {
                    method: m.name(),
                    label: m.label(),
                    summary,
                    error,
                    unavoidable,
                }
            })
            .collect()
    }
}
