//! The classical fourth-order Runge-Kutta step (section V, step e) and the
//! rate evaluations it makes through the method's rule, for every arm.

use super::methods::Context;
use super::rk4::Stage;
use super::{Planned, Planner, Workspace};
use crate::error::{Error, Result};
use crate::model::Scene as _;

impl<A: Planned<M>, const M: usize> Planner<A, M> {
    /// Damping `delta` in force at `pose`: the scene's constant `delta`
    /// plus the schedule's share.
    pub fn delta_at(&self, pose: &A::Pose) -> f64 {
        self.scene.value(&super::methods::DELTA)
            + self
                .scene
                .damping()
                .map_or(0.0, |d| d.delta_at_sigma(A::sigma_min(pose)))
    }

    fn context(&self) -> Context<'_, A, M> {
        Context {
            scene: &self.scene,
            networks: self.networks.as_deref(),
        }
    }

    /// Null-space vector `v` at `theta` with the current method (zero
    /// without avoidance). A convenience that allocates; the step uses a
    /// workspace. Refused for a method without a null-space vector.
    pub fn null_space(&self, theta: &[f64]) -> Result<Vec<f64>> {
        let arm = self.scene.arm();
        let n = arm.dof();
        let mut pose = arm.pose();
        arm.update(&mut pose, theta)?;
        let mut v = vec![0.0; n];
        let mut rule = self.ws.rule.clone();
        if rule.null_space(&self.context(), &pose, &mut v)? {
            Ok(v)
        } else {
            Err(Error::NoNullSpace {
                method: self.method.name(),
            })
        }
    }

    /// Joint rates `theta_dot(theta)` for task velocity `xdot` with the
    /// current method. A convenience that allocates; see
    /// [`Planner::theta_dot_into`].
    pub fn theta_dot(&self, theta: &[f64], xdot: [f64; M]) -> Result<Vec<f64>> {
        let arm = self.scene.arm();
        let mut pose = arm.pose();
        arm.update(&mut pose, theta)?;
        let mut out = vec![0.0; arm.dof()];
        let mut rule = self.ws.rule.clone();
        rule.theta_dot(&self.context(), &pose, xdot, &mut out)?;
        Ok(out)
    }

    /// [`Planner::theta_dot`] into `out` (`n` entries) through the planner's
    /// workspace: one kinematics pass and no allocation. `theta` must have
    /// `n` entries; it is not checked for finiteness (NaN gives NaN rates).
    pub fn theta_dot_into(&mut self, theta: &[f64], xdot: [f64; M], out: &mut [f64]) -> Result<()> {
        let Self {
            scene,
            networks,
            ws,
            ..
        } = self;
        scene.arm().update(&mut ws.stage, theta)?;
        let cx = Context {
            scene,
            networks: networks.as_deref(),
        };
        ws.rule.theta_dot(&cx, &ws.stage, xdot, out)?;
        Ok(())
    }

    /// The joint rates at `theta` and time `t` for a loop of the user's own
    /// (the Python package's `Controller.step`): the path's task velocity
    /// at `t` ([`Track::velocity_after`](super::Track::velocity_after))
    /// plus, when the feedback gain `K > 0`, `K (X_ref(t) - X(theta))`,
    /// through the method's rule, into `out` (`n` entries). One kinematics
    /// pass and no allocation, as [`Planner::theta_dot_into`].
    pub fn rates_at(&mut self, theta: &[f64], t: f64, out: &mut [f64]) -> Result<()> {
        let Self {
            scene,
            networks,
            ws,
            track,
            ..
        } = self;
        scene.arm().update(&mut ws.stage, theta)?;
        let v = track.velocity_after(t);
        let gain = scene.feedback_gain();
        let xdot = if gain > 0.0 {
            let e = A::task_error(track.reference(t), A::hand(&ws.stage));
            std::array::from_fn(|k| v[k] + gain * e[k])
        } else {
            v
        };
        let cx = Context {
            scene,
            networks: networks.as_deref(),
        };
        ws.rule.theta_dot(&cx, &ws.stage, xdot, out)?;
        Ok(())
    }

    /// One classical RK4 step of size `dt` (section V, step e), then the new
    /// sample, which the planner keeps (see [`Planner::sample`]). On error
    /// the state is left unchanged. Allocation-free.
    pub fn step(&mut self) -> Result<&super::Sample<M, A::Point>> {
        let h = self.scene.dt();
        let t = self.t;
        let t_mid = t + 0.5 * h;
        // A line's Xdot is constant: taken once, at the step's midpoint,
        // for every stage (the paper's runs, to the last bit).
        let line_xdot = self
            .track
            .is_line()
            .then(|| self.track.line_velocity(t_mid));
        let Self {
            scene,
            networks,
            theta,
            track,
            ws,
            ..
        } = self;
        let cx = Context {
            scene,
            networks: networks.as_deref(),
        };
        let theta = theta.as_slice();
        let gain = scene.feedback_gain();
        let arm = scene.arm();
        // The commanded task velocity at a stage of time `tt`: the path's
        // Xdot (a circle's or a polyline's at `tt` itself, the segment after
        // a corner but at the last stage) plus, when K > 0,
        // K (X_ref(tt) - X(theta)).
        let xdot = |tt: f64, last: bool, pose: &A::Pose| -> [f64; M] {
            let v = line_xdot.unwrap_or_else(|| track.velocity(t_mid, tt, !last));
            if gain > 0.0 {
                let e = A::task_error(track.reference(tt), A::hand(pose));
                std::array::from_fn(|k| v[k] + gain * e[k])
            } else {
                v
            }
        };
        let Workspace {
            pose,
            stage,
            rk4,
            rule,
        } = ws;
        // Stage 1 reads the kinematics of the current state, computed when
        // the previous step ended.
        let (next, note) = rk4.step(theta, t, h, |at, out| match at {
            Stage::Start { t } => rule.theta_dot(&cx, pose, xdot(t, false, pose), out),
            Stage::At { theta, t, last } => {
                arm.update(stage, theta)?;
                rule.theta_dot(&cx, stage, xdot(t, last, stage), out)
            }
        })?;
        arm.update(pose, next)?;
        self.theta.copy_from_slice(next);
        self.step_index += 1;
        self.t = self.step_index as f64 * h;
        self.refresh_sample(note);
        self.stats.record(&self.sample);
        self.stats.steps += 1;
        Ok(&self.sample)
    }
}
