//! The motion planner of section V, steps (a)-(g): a straight-line task at
//! constant speed, joint rates from eq. (18) or eq. (21), integrated by the
//! classical fourth-order Runge-Kutta method.
//!
//! A [`Planner`] holds the state and can be stepped one RK4 step at a time;
//! target, obstacles, mode and gains may change between steps (the browser
//! demo re-plans a new straight line from the current end effector when the
//! user drags the target). [`Planner::run`] integrates a whole scene.

mod mode;
mod rates;
mod record;

use std::fmt;
use std::sync::Arc;

use nalgebra::{DVector, Matrix2xX, Vector2};

use crate::arm::Arm;
use crate::error::{positive, Error, Result};
use crate::ik::DampingSchedule;
use crate::kinematics::Pose;
use crate::obstacle::Obstacle;
use crate::scene::{self, Scene};

pub use mode::Mode;
pub use rates::Surrogate;
pub use record::{Line, Sample, Summary, Trajectory};

use rates::{Rates, Scratch, Workspace};
use record::Stats;

/// Final end-effector error below which a run counts as having reached its
/// target (5 mm, the acceptance bound for the network cases).
pub const REACH_TOLERANCE: f64 = 5e-3;

/// The motion planner: state plus everything needed to take the next step.
#[derive(Clone)]
pub struct Planner {
    scene: Scene,
    mode: Mode,
    networks: Option<Arc<dyn Surrogate>>,
    theta: DVector<f64>,
    step_index: usize,
    t: f64,
    line: Line,
    stats: Stats,
    auto_damping: bool,
    /// The state as the page and the CLI see it, refreshed in place.
    sample: Sample,
    ws: Workspace,
}

impl fmt::Debug for Planner {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Planner")
            .field("mode", &self.mode)
            .field("t", &self.t)
            .field("theta", &self.theta.as_slice())
            .field("networks", &self.networks.is_some())
            .finish()
    }
}

impl Planner {
    /// A planner at the scene's start. Network modes need `networks`.
    ///
    /// A target outside the workspace is legal: the damping schedule is then
    /// switched on (and the summary says so), so the arm stretches towards it
    /// with bounded joint rates instead of blowing up.
    pub fn new(mut scene: Scene, mode: Mode, networks: Option<Arc<dyn Surrogate>>) -> Result<Self> {
        scene.validate()?;
        check_networks(mode, &networks, &scene.arm)?;
        let auto_damping = needs_auto_damping(&scene);
        if auto_damping {
            scene.damping = Some(DampingSchedule::default());
        }
        let n = scene.arm.dof();
        let theta = scene.theta0_vector();
        let mut ws = Workspace::new(n);
        ws.pose.update(&scene.arm, theta.as_slice())?;
        let start = ws.pose.end_effector();
        let line = Line {
            start,
            end: scene.target,
            t0: 0.0,
            duration: scene.tf,
        };
        let sample = Sample {
            t: 0.0,
            theta: vec![0.0; n],
            joints: vec![[0.0; 2]; n + 1],
            ee: start,
            reference: start,
            tracking_error: 0.0,
            distance: None,
            collision: false,
            delta: 0.0,
            manipulability: 0.0,
            in_range: true,
            phi_handover: false,
        };
        let mut p = Self {
            scene,
            mode,
            networks,
            theta,
            step_index: 0,
            t: 0.0,
            line,
            stats: Stats::new(),
            auto_damping,
            sample,
            ws,
        };
        p.refresh_sample(false);
        p.stats.record(&p.sample);
        Ok(p)
    }

    /// Integrates a whole scene from `t = 0` to `tf` (the paper's runs).
    pub fn run(
        scene: Scene,
        mode: Mode,
        networks: Option<Arc<dyn Surrogate>>,
    ) -> Result<Trajectory> {
        let mut p = Self::new(scene, mode, networks)?;
        let n = p.scene.steps();
        let mut steps = Vec::with_capacity(n + 1);
        steps.push(p.sample.clone());
        for _ in 0..n {
            steps.push(p.step()?.clone());
        }
        Ok(Trajectory {
            mode,
            steps,
            summary: p.summary(),
        })
    }

    /// Integrates the scene from `t = 0` to `tf` keeping only the summary:
    /// no sample is stored, so nothing is allocated after the planner is
    /// built (what an atlas of thousands of runs needs).
    pub fn run_summary(
        scene: Scene,
        mode: Mode,
        networks: Option<Arc<dyn Surrogate>>,
    ) -> Result<Summary> {
        let mut p = Self::new(scene, mode, networks)?;
        for _ in 0..p.scene.steps() {
            p.step()?;
        }
        Ok(p.summary())
    }

    /// Back to the scene's start pose at `t = 0`, with a fresh summary.
    /// Allocation-free.
    pub fn reset(&mut self) {
        self.theta.copy_from_slice(&self.scene.theta0);
        // theta0 was validated (length and finiteness) when the scene entered.
        let _ = self.ws.pose.update(&self.scene.arm, self.theta.as_slice());
        self.step_index = 0;
        self.t = 0.0;
        self.line = Line {
            start: self.ws.pose.end_effector(),
            end: self.scene.target,
            t0: 0.0,
            duration: self.scene.tf,
        };
        self.stats = Stats::new();
        self.refresh_sample(false);
        self.stats.record(&self.sample);
    }

    /// The scene (with any target, obstacle or gain changes applied).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The current mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// Current time (s).
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Current joint angles.
    pub fn theta(&self) -> &DVector<f64> {
        &self.theta
    }

    /// The kinematics of the current state (joints, Jacobian, ...).
    pub fn pose(&self) -> &Pose {
        &self.ws.pose
    }

    /// The line being tracked.
    pub fn line(&self) -> Line {
        self.line
    }

    /// The networks in use, if any.
    pub fn networks(&self) -> Option<&Arc<dyn Surrogate>> {
        self.networks.as_ref()
    }

    /// Switches mode; network modes need networks.
    pub fn set_mode(&mut self, mode: Mode) -> Result<()> {
        check_networks(mode, &self.networks, &self.scene.arm)?;
        self.mode = mode;
        self.resample();
        Ok(())
    }

    /// Installs (or removes) the trained networks. Networks trained for
    /// another arm are refused ([`Error::NetworksForAnotherArm`]).
    pub fn set_networks(&mut self, networks: Option<Arc<dyn Surrogate>>) -> Result<()> {
        check_networks(self.mode, &networks, &self.scene.arm)?;
        self.networks = networks;
        self.resample();
        Ok(())
    }

    /// Re-plans: a new straight line from the current end effector to `target`,
    /// starting now and lasting `duration` seconds (rounded up to whole steps).
    pub fn set_target(&mut self, target: [f64; 2], duration: f64) -> Result<()> {
        crate::error::coordinate("target x", target[0])?;
        crate::error::coordinate("target y", target[1])?;
        positive("line duration", duration)?;
        let steps = (duration / self.scene.dt - 1e-9).ceil().max(1.0);
        self.scene.target = target;
        if needs_auto_damping(&self.scene) {
            self.scene.damping = Some(DampingSchedule::default());
            self.auto_damping = true;
        }
        self.line = Line {
            start: self.ws.pose.end_effector(),
            end: target,
            t0: self.t,
            duration: steps * self.scene.dt,
        };
        self.resample();
        Ok(())
    }

    /// Replaces the obstacles; takes effect at the next step.
    pub fn set_obstacles(&mut self, obstacles: Vec<Obstacle>) -> Result<()> {
        for ob in &obstacles {
            ob.validate(&self.scene.arm)?;
        }
        self.scene.obstacles = obstacles;
        self.resample();
        Ok(())
    }

    /// Moves obstacle `index` to `centre`, keeping its radius; takes effect
    /// at the next step. Allocation-free (what an atlas of thousands of runs
    /// needs). Refused, leaving everything as it was, if the disc would
    /// overlap the base post or `index` names no obstacle.
    pub fn move_obstacle(&mut self, index: usize, centre: [f64; 2]) -> Result<()> {
        let count = self.scene.obstacles.len();
        let Some(ob) = self.scene.obstacles.get(index) else {
            return Err(Error::OutOfRange {
                what: "obstacle index".into(),
                value: index as f64,
                min: 0.0,
                max: count as f64 - 1.0,
            });
        };
        let moved = crate::obstacle::Obstacle {
            centre,
            radius: ob.radius,
        };
        moved.validate(&self.scene.arm)?;
        self.scene.obstacles[index] = moved;
        self.resample();
        Ok(())
    }

    /// Sets `lambda`, the gain of the obstacle vector.
    pub fn set_lambda(&mut self, lambda: f64) -> Result<()> {
        scene::validate_lambda(lambda)?;
        self.scene.lambda = lambda;
        Ok(())
    }

    /// Sets the constant damping `delta` (eqs. 6, 17, 20). In Cases 1 and 3
    /// it damps the network's `Phi` through [`ik::damp_phi`].
    pub fn set_delta(&mut self, delta: f64) -> Result<()> {
        scene::validate_delta(delta)?;
        self.scene.delta = delta;
        self.resample();
        Ok(())
    }

    /// Switches the damping schedule on (`Some`) or off (`None`).
    pub fn set_damping(&mut self, damping: Option<DampingSchedule>) -> Result<()> {
        if let Some(d) = &damping {
            d.validate()?;
        }
        self.scene.damping = damping;
        self.resample();
        Ok(())
    }

    /// Sets the closed-loop gain `K` (0 = open loop, as in the paper).
    pub fn set_feedback_gain(&mut self, gain: f64) -> Result<()> {
        scene::validate_gain(gain, self.scene.dt)?;
        self.scene.feedback_gain = gain;
        Ok(())
    }

    /// Damping `delta` in force at Jacobian `j`: the constant `delta` plus the
    /// schedule's share.
    pub fn delta_at(&self, j: &Matrix2xX<f64>) -> f64 {
        self.scene.delta + self.scene.damping.map_or(0.0, |d| d.delta(j))
    }

    fn rates(&self) -> Rates<'_> {
        Rates {
            scene: &self.scene,
            mode: self.mode,
            networks: self.networks.as_deref(),
        }
    }

    /// Null-space vector `v` at `theta` in the current mode (zero in mode
    /// `none`). A convenience that allocates; the step uses a workspace.
    pub fn null_space(&self, theta: &DVector<f64>) -> Result<DVector<f64>> {
        let n = self.scene.arm.dof();
        let pose = Pose::new(&self.scene.arm, theta.as_slice())?;
        let mut s = Scratch::new(n);
        self.rates().null_space(&pose, &mut s)?;
        Ok(DVector::from_vec(s.v))
    }

    /// Joint rates `theta_dot(theta)` for task velocity `xdot`: eq. (18) in
    /// modes `none`, `numerical` and Case 2, eq. (21) in Cases 1 and 3. A
    /// convenience that allocates; see [`Planner::theta_dot_into`].
    pub fn theta_dot(&self, theta: &DVector<f64>, xdot: &Vector2<f64>) -> Result<DVector<f64>> {
        let n = self.scene.arm.dof();
        let pose = Pose::new(&self.scene.arm, theta.as_slice())?;
        let mut s = Scratch::new(n);
        let mut out = DVector::zeros(n);
        self.rates()
            .theta_dot(&pose, [xdot[0], xdot[1]], &mut s, out.as_mut_slice())?;
        Ok(out)
    }

    /// [`Planner::theta_dot`] into `out` (`n` entries) through the planner's
    /// workspace: one kinematics pass and no allocation. `theta` must have
    /// `n` entries; it is not checked for finiteness (NaN gives NaN rates).
    pub fn theta_dot_into(&mut self, theta: &[f64], xdot: [f64; 2], out: &mut [f64]) -> Result<()> {
        let Self {
            scene,
            mode,
            networks,
            ws,
            ..
        } = self;
        ws.stage.update(&scene.arm, theta)?;
        let rates = Rates {
            scene,
            mode: *mode,
            networks: networks.as_deref(),
        };
        rates.theta_dot(&ws.stage, xdot, &mut ws.scratch, out)?;
        Ok(())
    }

    /// One classical RK4 step of size `dt` (section V, step e), then the new
    /// sample, which the planner keeps (see [`Planner::sample`]). On error
    /// the state is left unchanged. Allocation-free.
    pub fn step(&mut self) -> Result<&Sample> {
        let h = self.scene.dt;
        let t = self.t;
        let line_xdot = self.line.velocity_at(t + 0.5 * h);
        let Self {
            scene,
            mode,
            networks,
            theta,
            line,
            ws,
            ..
        } = self;
        let rates = Rates {
            scene,
            mode: *mode,
            networks: networks.as_deref(),
        };
        let theta = theta.as_slice();
        let gain = scene.feedback_gain;
        // The commanded task velocity at a stage: the line's Xdot plus, when
        // K > 0, K (X_ref(t) - X(theta)).
        let xdot = |tt: f64, pose: &Pose| -> [f64; 2] {
            if gain > 0.0 {
                let r = line.reference(tt);
                let x = pose.end_effector();
                [
                    line_xdot[0] + gain * (r[0] - x[0]),
                    line_xdot[1] + gain * (r[1] - x[1]),
                ]
            } else {
                [line_xdot[0], line_xdot[1]]
            }
        };
        let [k1, k2, k3, k4] = &mut ws.k;
        // Stage 1 reads the kinematics of the current state, computed when
        // the previous step ended.
        let mut handover = rates.theta_dot(&ws.pose, xdot(t, &ws.pose), &mut ws.scratch, k1)?;
        for (stage, (c, tt)) in [(0.5 * h, t + 0.5 * h), (0.5 * h, t + 0.5 * h), (h, t + h)]
            .into_iter()
            .enumerate()
        {
            let (prev, out): (&[f64], &mut [f64]) = match stage {
                0 => (&k1[..], &mut k2[..]),
                1 => (&k2[..], &mut k3[..]),
                _ => (&k3[..], &mut k4[..]),
            };
            for ((s, th), k) in ws.theta_stage.iter_mut().zip(theta).zip(prev) {
                *s = th + c * k;
            }
            ws.stage.update(&scene.arm, &ws.theta_stage)?;
            handover |= rates.theta_dot(&ws.stage, xdot(tt, &ws.stage), &mut ws.scratch, out)?;
        }
        let w = h / 6.0;
        let mut finite = true;
        for (i, next) in ws.next.iter_mut().enumerate() {
            *next = theta[i] + w * (((k1[i] + 2.0 * k2[i]) + 2.0 * k3[i]) + k4[i]);
            // Also false for NaN: a runaway angle is refused like a non-finite one.
            finite &= next.abs() <= crate::arm::MAX_ANGLE;
        }
        if !finite {
            return Err(Error::Diverged { t });
        }
        self.theta.copy_from_slice(&self.ws.next);
        self.ws.pose.update(&self.scene.arm, &self.ws.next)?;
        self.step_index += 1;
        self.t = self.step_index as f64 * h;
        self.refresh_sample(handover);
        self.stats.record(&self.sample);
        self.stats.steps += 1;
        Ok(&self.sample)
    }

    /// The current state: the start, or the result of the last step. Kept up
    /// to date by the planner (no copy, no allocation).
    pub fn sample(&self) -> &Sample {
        &self.sample
    }

    /// Refreshes the sample after a change of setting (same state, same step).
    fn resample(&mut self) {
        self.refresh_sample(self.sample.phi_handover);
    }

    /// Rewrites the sample in place from the current pose.
    fn refresh_sample(&mut self, phi_handover: bool) {
        let pose = &self.ws.pose;
        let s = &mut self.sample;
        let ee = pose.end_effector();
        let reference = self.line.reference(self.t);
        s.t = self.t;
        s.theta.copy_from_slice(pose.theta());
        s.joints.copy_from_slice(pose.joints());
        s.ee = ee;
        s.reference = [reference[0], reference[1]];
        s.tracking_error = distance(ee, [reference[0], reference[1]]);
        s.distance = None;
        s.collision = false;
        for ob in &self.scene.obstacles {
            let d = pose.clearance(ob.centre);
            s.collision |= d < ob.radius;
            s.distance = Some(s.distance.map_or(d, |m| m.min(d)));
        }
        s.delta = self.scene.delta
            + self
                .scene
                .damping
                .map_or(0.0, |d| d.delta_at_sigma(pose.sigma_min()));
        s.manipulability = pose.manipulability();
        s.in_range = in_range(
            self.mode,
            self.networks.as_deref(),
            pose,
            &self.scene.obstacles,
        );
        s.phi_handover = phi_handover;
    }

    /// Whether the networks the current mode uses see inputs inside their
    /// trained range (true for numerical modes).
    pub fn in_range(&self) -> bool {
        self.sample.in_range
    }

    /// Outcome since the last reset.
    pub fn summary(&self) -> Summary {
        let x = self.ws.pose.end_effector();
        let target = self.scene.target;
        let final_error = distance(x, target);
        Summary {
            mode: self.mode,
            steps: self.stats.steps,
            t: self.t,
            min_distance: self.stats.min_distance,
            collided: self.stats.collided,
            final_error,
            max_tracking_error: self.stats.max_tracking_error,
            reached: final_error <= REACH_TOLERANCE,
            target_reachable: self.scene.arm.can_reach(&self.scene.target_vector()),
            out_of_range_steps: self.stats.out_of_range_steps,
            max_delta: self.stats.max_delta,
            auto_damping: self.auto_damping,
            handover_steps: self.stats.handover_steps,
        }
    }
}

/// Euclidean distance between two points.
#[inline]
fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    (dx * dx + dy * dy).sqrt()
}

/// Whether the networks `mode` uses see `pose` (and every obstacle) inside
/// their trained range.
fn in_range(
    mode: Mode,
    networks: Option<&dyn Surrogate>,
    pose: &Pose,
    obstacles: &[Obstacle],
) -> bool {
    let Some(nets) = networks else {
        return true;
    };
    let phi_ok = !mode.learned_phi() || nets.phi_in_range(pose);
    let v_ok = !mode.learned_v() || obstacles.iter().all(|ob| nets.v_in_range(pose, ob.centre));
    phi_ok && v_ok
}

fn needs_auto_damping(scene: &Scene) -> bool {
    scene.damping.is_none() && !scene.arm.can_reach(&scene.target_vector())
}

/// Network modes need networks, and networks must be trained for `arm`.
fn check_networks(mode: Mode, networks: &Option<Arc<dyn Surrogate>>, arm: &Arm) -> Result<()> {
    match networks {
        None if mode.learned_phi() || mode.learned_v() => Err(Error::NetworksUnavailable(format!(
            "mode {mode} needs trained networks and none are loaded"
        ))),
        Some(n) if n.arm() != arm => {
            let spec = |a: &Arm| (a.post(), a.links().to_vec());
            Err(Error::NetworksForAnotherArm {
                trained: spec(n.arm()),
                arm: spec(arm),
            })
        }
        _ => Ok(()),
    }
}
