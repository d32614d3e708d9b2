//! The spatial session's clock (the run computed whole, played at a
//! speed; step, reset, a time asked for) and the comparison of every
//! method on the scene on screen.

use super::{run, SpaceMethodRun, SpaceSession};
use crate::error::{finite, within, Error, Result};
use crate::planner::methods::{Method, ALL};
use crate::planner::{Networks, Planner, Summary};
use crate::scene::SpaceScene;
use crate::session::MAX_STEPS_PER_FRAME;

impl SpaceSession {
    // ---- the clock ------------------------------------------------------

    /// Whether the sample shown is the run's last.
    pub fn ended(&self) -> bool {
        self.index + 1 >= self.samples.len()
    }

    /// Starts or pauses the clock; starting an ended run replays it.
    pub fn set_running(&mut self, running: bool) {
        if running && !self.running {
            self.backlog = 0.0;
            if self.ended() {
                self.show(0);
            }
        }
        self.running = running;
    }

    /// Whether the clock runs.
    pub fn running(&self) -> bool {
        self.running
    }

    /// Playback speed (times real time).
    pub fn set_speed(&mut self, speed: f64) -> Result<()> {
        self.speed = within("speed", speed, 0.05, 64.0)?;
        Ok(())
    }

    /// Back to `t = 0`, paused.
    pub fn reset(&mut self) {
        self.running = false;
        self.backlog = 0.0;
        self.show(0);
    }

    /// One step forward, paused.
    pub fn step(&mut self) {
        self.running = false;
        let last = self.samples.len().saturating_sub(1);
        self.show((self.index + 1).min(last));
    }

    /// Shows the first sample at or after `time` (s), or the last.
    pub fn run_until(&mut self, time: f64) -> Result<()> {
        finite("time", time)?;
        let i = self
            .samples
            .iter()
            .position(|s| s.t >= time - 1e-9)
            .unwrap_or(self.samples.len().saturating_sub(1));
        self.show(i.max(self.index));
        Ok(())
    }

    /// Advances the clock by `elapsed_ms` of real time at the speed (at
    /// most [`MAX_STEPS_PER_FRAME`] samples); the clock stops at the end.
    pub fn tick(&mut self, elapsed_ms: f64) {
        if !(self.running && elapsed_ms.is_finite() && elapsed_ms > 0.0) {
            return;
        }
        self.backlog += elapsed_ms.min(250.0) / 1000.0 * self.speed / self.scene.dt;
        let n = (self.backlog.floor() as usize).min(MAX_STEPS_PER_FRAME);
        self.backlog = (self.backlog - n as f64).clamp(0.0, 1.0);
        let last = self.samples.len().saturating_sub(1);
        self.show((self.index + n).min(last));
        if self.ended() {
            self.running = false;
        }
    }

    // ---- off screen -----------------------------------------------------

    /// Runs `scene` whole in `method` with the session's networks, off
    /// screen (the page's scripted `simulate()`), as its pose task where
    /// the session's task is the hand's pose: its outcome; refused when
    /// the scene does not validate, the method needs networks the session
    /// has not, or a step fails. The scene on the stage does not change.
    pub fn run_offscreen(&self, scene: SpaceScene, method: Method) -> Result<Summary> {
        scene.validate()?;
        if method.uses_networks() && self.networks.is_none() {
            return Err(Error::NetworksUnavailable(format!(
                "{} needs networks for the {}: they have not loaded",
                method.label(),
                self.robot.label
            )));
        }
        if let Some(o) = self.orientation {
            let pose = crate::scene::PoseScene::from_space(scene, Some(o.rotation), o.weight)?;
            let nets = self.networks.clone().map(|n| n as Networks<_, 6>);
            return Planner::run_summary(pose, method, nets);
        }
        let nets = self.networks.clone().map(|n| n as Networks<_, 3>);
        Planner::run_summary(scene, method, nets)
    }

    // ---- the comparison -------------------------------------------------

    /// Every method that can run here (the learned ones where networks are
    /// installed) on this scene, each run whole: its outcome, or why it
    /// failed.
    pub fn compare(&self) -> Vec<SpaceMethodRun> {
        ALL.iter()
            .filter(|m| m.in_space() && (!m.uses_networks() || self.networks.is_some()))
            .filter(|&&m| self.orientation.is_none() || super::pose_task::runs_pose(m))
            .map(|&m| {
                let super::pose_task::Played {
                    summary, failure, ..
                } = run(&self.scene, self.orientation, m, self.networks.clone());
                SpaceMethodRun {
                    method: m,
                    summary,
                    failure,
                }
            })
            .collect()
    }
}
