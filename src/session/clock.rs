//! The clock: real time turned into RK4 steps at the chosen speed, a run
//! that ends where its line ends (the scene's final time `tf`: the clock
//! stops there and the arm holds still), and the step-by-step controls.

use super::Session;
use crate::error::{finite, Result};

/// Most steps one animation frame may take (keeps a slow device responsive).
pub const MAX_STEPS_PER_FRAME: usize = 40;

impl Session {
    pub(super) fn run_to_end(&mut self) {
        self.running = true;
    }

    /// Whether the run has ended: its line ends at the scene's final time
    /// `tf`, and there the clock stops and the arm holds still.
    pub fn ended(&self) -> bool {
        let p = self.planner();
        p.time() >= p.scene().tf - 1e-9
    }

    /// Starts or pauses the clock. Starting a run that has ended replays it
    /// from `t = 0`: no clock runs on with nothing to do.
    pub fn set_running(&mut self, running: bool) {
        if running && !self.running {
            self.backlog = 0.0;
            if self.ended() {
                self.reset();
            }
        }
        self.running = running;
    }

    /// Whether the clock runs.
    pub fn running(&self) -> bool {
        self.running
    }

    /// One RK4 step; pauses the clock. Nothing at the end of the run.
    pub fn step(&mut self) -> Result<()> {
        self.running = false;
        self.backlog = 0.0;
        let r = self.advance(self.steps_left().min(1));
        self.remember_poses();
        r
    }

    /// Steps until `t >= time` or the end of the run, whichever comes
    /// first.
    pub fn run_until(&mut self, time: f64) -> Result<()> {
        finite("time", time)?;
        let dt = self.planner().scene().dt;
        let n = ((time - self.planner().time()) / dt - 1e-9)
            .ceil()
            .clamp(0.0, self.steps_left() as f64) as usize;
        let r = self.advance(n);
        self.remember_poses();
        self.check_stop();
        r
    }

    /// Advances the clock by `elapsed_ms` of real time, scaled by the speed
    /// (nothing happens while paused; at most [`MAX_STEPS_PER_FRAME`]
    /// steps). If a step fails the clock pauses and the state is the last
    /// good one.
    pub fn tick(&mut self, elapsed_ms: f64) -> Result<()> {
        if !(self.running && elapsed_ms.is_finite() && elapsed_ms > 0.0) {
            return Ok(());
        }
        let dt = self.planner().scene().dt;
        self.backlog += elapsed_ms.min(250.0) / 1000.0 * self.speed / dt;
        let n = (self.backlog.floor() as usize)
            .min(MAX_STEPS_PER_FRAME)
            .min(self.steps_left());
        self.backlog = (self.backlog - n as f64).clamp(0.0, 1.0);
        let r = self.advance(n);
        self.check_stop();
        r
    }

    /// Steps from now to the end of the run.
    fn steps_left(&self) -> usize {
        let p = self.planner();
        ((p.scene().tf - p.time()) / p.scene().dt - 1e-9)
            .ceil()
            .max(0.0) as usize
    }

    fn check_stop(&mut self) {
        if self.ended() {
            self.running = false;
            self.backlog = 0.0;
        }
    }

    /// The poses before the next step, for smooth drawing.
    pub(super) fn remember_poses(&mut self) {
        self.prev_theta.clear();
        self.prev_theta
            .extend_from_slice(self.twin.main().theta().as_slice());
        self.ghost_prev.clear();
        if let Some(g) = self.twin.ghost() {
            self.ghost_prev.extend_from_slice(g.theta().as_slice());
        }
    }

    /// Takes `n` steps, timing the planner's.
    fn advance(&mut self, n: usize) -> Result<()> {
        if n == 0 {
            return Ok(());
        }
        let mut solver = 0.0;
        let mut taken = 0;
        for _ in 0..n {
            self.remember_poses();
            let t0 = (self.clock)();
            let stepped = self.twin.step();
            solver += (self.clock)() - t0;
            if let Err(e) = stepped {
                self.running = false;
                self.backlog = 0.0;
                self.error = Some(e.to_string());
                self.frame_steps = taken;
                return Err(e);
            }
            taken += 1;
            self.record();
        }
        self.error = None;
        self.frame_steps = taken;
        self.solver_ms = solver;
        self.solver_ms_per_step = solver / taken as f64;
        Ok(())
    }

    /// Appends the planner's current sample to the histories.
    pub(super) fn record(&mut self) {
        self.histories.record(self.twin.main().sample());
    }

    /// End-effector trail.
    pub fn trail(&self) -> &std::collections::VecDeque<[f64; 2]> {
        &self.histories.trail
    }

    /// Every [`super::STROBE_EVERY`]th pose's joints since the line was planned.
    pub fn strobe(&self) -> &std::collections::VecDeque<Vec<[f64; 2]>> {
        &self.histories.strobe
    }

    /// The time series of the plots.
    pub fn history(&self) -> &std::collections::VecDeque<super::Point> {
        &self.histories.points
    }

    /// The joints to draw for the planner (or the ghost): between the last
    /// two steps while the clock runs, so motion looks smooth at any speed.
    pub fn display_joints(&self, ghost: bool) -> Option<Vec<[f64; 2]>> {
        let (planner, prev) = if ghost {
            (self.twin.ghost()?, &self.ghost_prev)
        } else {
            (self.twin.main(), &self.prev_theta)
        };
        let a = if self.running {
            self.backlog.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let now = planner.theta();
        let theta: Vec<f64> = now
            .iter()
            .zip(prev.iter().chain(std::iter::repeat(&0.0)))
            .map(|(n, p)| p + a * (n - p))
            .collect();
        let arm = &planner.scene().arm;
        Some(
            arm.joints(&nalgebra::DVector::from_vec(theta))
                .iter()
                .map(|p| [p[0], p[1]])
                .collect(),
        )
    }
}
