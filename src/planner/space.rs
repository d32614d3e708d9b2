//! The RK4 planner for an arm in space: the hand along its path at
//! constant speed (the paper's section V with `m = 3`; the straight line,
//! a circle or a polyline, [`SpaceTrack`]), each rate
//! evaluation through the method's spatial rule, and a sample of what a
//! run records after each step. A planner owns its poses and scratch
//! space: a step allocates nothing.

use crate::space::Chain;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

mod track;

pub use track::SpaceTrack;

use super::methods::{Context, Rule};
use super::methods::{Method, Note};
use super::rk4::{Rk4, Stage};
use super::Surrogate;
use crate::error::{Error, Result};
use crate::scene::SpaceScene;
use crate::space::{clearance, SpacePose, Sphere, Vec3};

/// What a spatial run records after each step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceSample {
    /// Time (s).
    pub t: f64,
    /// Joint angles (rad).
    pub theta: Vec<f64>,
    /// The hand.
    pub hand: Vec3,
    /// Where the path has the hand at `t`.
    pub reference: Vec3,
    /// `|hand - reference|` (m).
    pub tracking_error: f64,
    /// The smallest signed distance between the moving capsules and the
    /// spheres (m; negative: inside), `None` without spheres.
    pub clearance: Option<f64>,
    /// How many joints are past a limit.
    pub past_limits: usize,
    /// The constraints of a program were relaxed in this step.
    pub relaxed: bool,
    /// The exact route stood in for the learned `Phi` in this step (the
    /// damping schedule was active, or the refinement could not converge).
    pub phi_handover: bool,
}

/// A spatial run's outcome.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceSummary {
    /// Steps taken.
    pub steps: usize,
    /// The smallest clearance over the run (m), `None` without spheres.
    pub min_clearance: Option<f64>,
    /// Steps with a capsule inside a sphere.
    pub collision_steps: usize,
    /// Steps with a joint past a limit.
    pub limit_steps: usize,
    /// Steps whose program was relaxed.
    pub relaxed_steps: usize,
    /// Steps where the exact route stood in for the learned `Phi`.
    pub handover_steps: usize,
    /// The largest tracking error (m).
    pub max_error: f64,
    /// The hand's distance from the path's end (the target, for the line)
    /// at the end (m).
    pub final_error: f64,
}

impl SpaceSummary {
    /// The outcome of a run's `samples` (`t = 0` first) whose path ends at
    /// `end` (the final error is NaN without samples).
    pub fn of(samples: &[SpaceSample], end: Vec3) -> Self {
        let Some((first, rest)) = samples.split_first() else {
            return Tally(Self::default()).summary(f64::NAN);
        };
        let mut tally = Tally::new(first);
        for s in rest {
            tally.add(s);
        }
        tally.summary(dist(samples[samples.len() - 1].hand, end))
    }
}

/// A spatial run: every sample from `t = 0`, and its summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpaceTrajectory {
    /// The method.
    pub method: Method,
    /// The samples, `t = 0` first.
    pub samples: Vec<SpaceSample>,
    /// The outcome.
    pub summary: SpaceSummary,
}

/// The RK4 planner of one method on one spatial scene. A copy has its own
/// state and scratch space (an atlas across threads runs one per thread).
#[derive(Clone)]
pub struct SpacePlanner {
    scene: SpaceScene,
    networks: Option<Arc<dyn Surrogate<Chain, 3>>>,
    method: Method,
    rule: Box<dyn Rule<Chain, 3>>,
    theta: Vec<f64>,
    step_index: usize,
    track: SpaceTrack,
    pose: SpacePose,
    stage: SpacePose,
    rk4: Rk4,
    sample: SpaceSample,
    reachable: bool,
    auto_damping: bool,
}

impl SpacePlanner {
    /// A planner of `method` on `scene` at `t = 0`; refused when the scene
    /// (its path included) does not validate or the method has no rule in
    /// space.
    pub fn new(scene: SpaceScene, method: Method) -> Result<Self> {
        Self::with_networks(scene, method, None::<Arc<NoNetworks>>)
    }

    /// A planner of `method` on `scene` with `networks` for the learned
    /// routes (Cases 1-3), refused when they were trained for another arm.
    pub fn with_networks(
        mut scene: SpaceScene,
        method: Method,
        networks: Option<Arc<impl Surrogate<Chain, 3> + 'static>>,
    ) -> Result<Self> {
        let networks = networks.map(|n| n as Arc<dyn Surrogate<Chain, 3>>);
        scene.validate()?;
        if let Some(nets) = &networks {
            nets.check(&scene.chain)?;
        }
        let n = scene.chain.dof();
        let rule = method.space_rule(n)?;
        let pose = SpacePose::new(&scene.chain, &scene.theta0)?;
        let start = pose.hand();
        let track = SpaceTrack::new(&scene.path, start, scene.target, scene.tf)?;
        // A path out of reach: damping switched on unless the scene has its
        // own, as for a planar arm.
        let reachable = track.reachable(pose.joint_origin(0), scene.chain.reach());
        let auto_damping =
            crate::ik::DampingSchedule::switch_on_out_of_reach(&mut scene.damping, reachable);
        let theta = scene.theta0.clone();
        let mut planner = Self {
            networks,
            rule,
            method,
            theta,
            step_index: 0,
            track,
            stage: pose.clone(),
            pose,
            rk4: Rk4::new(n),
            sample: SpaceSample {
                t: 0.0,
                theta: vec![0.0; n],
                hand: start,
                reference: start,
                tracking_error: 0.0,
                clearance: None,
                past_limits: 0,
                relaxed: false,
                phi_handover: false,
            },
            scene,
            reachable,
            auto_damping,
        };
        planner.refresh_sample(Note::default());
        Ok(planner)
    }

    /// The scene.
    pub fn scene(&self) -> &SpaceScene {
        &self.scene
    }

    /// The method.
    pub fn method(&self) -> Method {
        self.method
    }

    /// Whether no point of the path is certainly out of the arm's reach
    /// ([`SpaceTrack::reachable`]).
    pub fn reachable(&self) -> bool {
        self.reachable
    }

    /// Whether the planner switched the damping schedule on because the
    /// path leaves the arm's reach and the scene had none.
    pub fn auto_damping(&self) -> bool {
        self.auto_damping
    }

    /// The sample of the current state.
    pub fn sample(&self) -> &SpaceSample {
        &self.sample
    }

    /// The current pose.
    pub fn pose(&self) -> &SpacePose {
        &self.pose
    }

    /// Time (s).
    pub fn t(&self) -> f64 {
        self.step_index as f64 * self.scene.dt
    }

    /// Whether the run has reached `tf`.
    pub fn done(&self) -> bool {
        self.step_index >= self.scene.steps()
    }

    /// The path being tracked, with its timing.
    pub fn track(&self) -> &SpaceTrack {
        &self.track
    }

    /// Where the path has the hand at `t` (its end after `tf`).
    pub fn reference(&self, t: f64) -> Vec3 {
        self.track.reference(t)
    }

    /// The joint rates at `theta` for hand velocity `xdot` (a convenience
    /// that allocates; the step uses the planner's scratch space).
    pub fn theta_dot(&mut self, theta: &[f64], xdot: Vec3) -> Result<Vec<f64>> {
        let pose = SpacePose::new(&self.scene.chain, theta)?;
        let mut out = vec![0.0; theta.len()];
        let cx = Context::<Chain, 3> {
            scene: &self.scene,
            networks: self.networks.as_deref(),
        };
        self.rule.theta_dot(&cx, &pose, xdot, &mut out)?;
        Ok(out)
    }

    /// One classical RK4 step; on error the state is left unchanged.
    /// Allocation-free.
    pub fn step(&mut self) -> Result<&SpaceSample> {
        let h = self.scene.dt;
        let t = self.t();
        let t_mid = t + 0.5 * h;
        let gain = self.scene.feedback_gain;
        // The commanded hand velocity at a stage of time `tt`: the path's
        // Xdot (a line's constant; a circle's or a polyline's at `tt`
        // itself, the segment after a corner but at the last stage) plus,
        // when K > 0, K (X_ref(tt) - X(theta)).
        let xdot = |track: &SpaceTrack, tt: f64, last: bool, pose: &SpacePose| -> Vec3 {
            let v = track.velocity(t_mid, tt, !last);
            if gain > 0.0 {
                let (r, x) = (track.reference(tt), pose.hand());
                [0, 1, 2].map(|k| v[k] + gain * (r[k] - x[k]))
            } else {
                v
            }
        };
        let Self {
            scene,
            networks,
            track,
            rule,
            theta,
            pose,
            stage,
            rk4,
            ..
        } = self;
        let cx = Context::<Chain, 3> {
            scene,
            networks: networks.as_deref(),
        };
        let (next, note) = rk4.step(theta, t, h, |at, out| match at {
            Stage::Start { t } => rule.theta_dot(&cx, pose, xdot(track, t, false, pose), out),
            Stage::At { theta, t, last } => {
                stage.update(&scene.chain, theta)?;
                rule.theta_dot(&cx, stage, xdot(track, t, last, stage), out)
            }
        })?;
        theta.copy_from_slice(next);
        pose.update(&scene.chain, next)?;
        self.step_index += 1;
        self.refresh_sample(note);
        Ok(&self.sample)
    }

    fn refresh_sample(&mut self, note: Note) {
        let t = self.t();
        let reference = self.reference(t);
        let hand = self.pose.hand();
        let s = &mut self.sample;
        s.t = t;
        s.theta.copy_from_slice(&self.theta);
        s.hand = hand;
        s.reference = reference;
        s.tracking_error = dist(hand, reference);
        s.clearance = (!self.scene.spheres.is_empty())
            .then(|| clearance(&self.scene.chain, &self.pose, &self.scene.spheres));
        s.past_limits = self.scene.chain.joint_limits().map_or(0, |l| {
            l.ranges()
                .iter()
                .zip(&self.theta)
                .filter(|(r, &th)| th < r[0] || th > r[1])
                .count()
        });
        s.relaxed = note.relaxed;
        s.phi_handover = note.handover;
    }

    /// Puts sphere `index` at `sphere` (or adds it, for `index` equal to
    /// the number of spheres); it takes effect at the next step, and the
    /// current sample's clearance is measured again. Allocation-free but
    /// for an added sphere (the scene's list grows). Refused, changing nothing, where the sphere
    /// does not validate (on the base, not finite) or `index` is past the
    /// end.
    pub fn set_sphere(&mut self, index: usize, sphere: Sphere) -> Result<()> {
        let count = self.scene.spheres.len();
        if index > count {
            return Err(Error::OutOfRange {
                what: "sphere index".into(),
                value: index as f64,
                min: 0.0,
                max: count as f64,
            });
        }
        sphere.validate_at(&self.scene.chain, &self.pose)?;
        if index == count {
            if count >= crate::space::MAX_SPHERES {
                return Err(Error::DimensionMismatch {
                    what: "spheres (at most)".into(),
                    expected: crate::space::MAX_SPHERES,
                    found: count + 1,
                });
            }
            self.scene.spheres.push(sphere);
        } else {
            self.scene.spheres[index] = sphere;
        }
        let note = Note {
            relaxed: self.sample.relaxed,
            handover: self.sample.phi_handover,
        };
        self.refresh_sample(note);
        Ok(())
    }

    /// Back to the scene's start pose at `t = 0`: the state a new planner
    /// of the same scene starts in (the path's timing depends on the start
    /// pose only, which has not moved). Allocation-free.
    pub fn reset(&mut self) {
        self.theta.copy_from_slice(&self.scene.theta0);
        // theta0 was validated (length, finiteness) when the scene entered.
        let _ = self.pose.update(&self.scene.chain, &self.scene.theta0);
        self.step_index = 0;
        self.refresh_sample(Note::default());
    }

    /// Runs to `tf` from the current state, recording every sample.
    pub fn run(mut self) -> Result<SpaceTrajectory> {
        let mut samples = Vec::with_capacity(self.scene.steps() + 1);
        let mut tally = Tally::new(&self.sample);
        samples.push(self.sample.clone());
        while !self.done() {
            let s = self.step()?;
            tally.add(s);
            samples.push(s.clone());
        }
        let summary = tally.summary(dist(self.pose.hand(), self.track.end()));
        Ok(SpaceTrajectory {
            method: self.method,
            samples,
            summary,
        })
    }

    /// Runs to `tf` from the current state keeping only the summary (the
    /// summary [`Self::run`] gives, to the last bit): nothing is allocated
    /// (what an atlas of thousands of runs needs). The planner is left at
    /// the end, or where a step failed (the error is returned).
    pub fn run_summary(&mut self) -> Result<SpaceSummary> {
        let mut tally = Tally::new(&self.sample);
        while !self.done() {
            tally.add(self.step()?);
        }
        Ok(tally.summary(dist(self.pose.hand(), self.track.end())))
    }
}

/// A run's summary gathered sample by sample, the start first.
struct Tally(SpaceSummary);

impl Tally {
    fn new(first: &SpaceSample) -> Self {
        let mut t = Tally(SpaceSummary::default());
        t.count(first);
        t
    }

    /// One more step's sample.
    fn add(&mut self, s: &SpaceSample) {
        self.0.steps += 1;
        self.count(s);
    }

    fn count(&mut self, s: &SpaceSample) {
        let t = &mut self.0;
        if let Some(c) = s.clearance {
            t.min_clearance = Some(t.min_clearance.map_or(c, |m| m.min(c)));
            t.collision_steps += usize::from(c < 0.0);
        }
        t.limit_steps += usize::from(s.past_limits > 0);
        t.relaxed_steps += usize::from(s.relaxed);
        t.handover_steps += usize::from(s.phi_handover);
        t.max_error = t.max_error.max(s.tracking_error);
    }

    fn summary(self, final_error: f64) -> SpaceSummary {
        SpaceSummary {
            final_error,
            ..self.0
        }
    }
}

fn dist(a: Vec3, b: Vec3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The type of "no networks" for [`SpacePlanner::new`].
struct NoNetworks;

impl Surrogate<Chain, 3> for NoNetworks {
    fn check(&self, _: &Chain) -> Result<()> {
        Ok(())
    }
    fn phi(&self, _: &SpacePose, _: &mut [f64]) -> Result<()> {
        Err(Error::NetworksUnavailable("no networks".into()))
    }
    fn area_gradient(&self, _: &SpacePose, _: Vec3, _: &mut [f64]) -> Result<()> {
        Err(Error::NetworksUnavailable("no networks".into()))
    }
    fn phi_in_range(&self, _: &SpacePose) -> bool {
        true
    }
    fn v_in_range(&self, _: &SpacePose, _: Vec3) -> bool {
        true
    }
}
