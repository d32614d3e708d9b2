//! A run of an arm in space as a file: what `simulate --arm panda --json`
//! prints and `simulate --from` replays, everything a replay needs (the
//! preset's name, the limits, the start pose, the path, the spheres, the
//! settings and every declared parameter) with every sample and the
//! summary. Versioned by its first field, `format` ([`SPACE_RUN_FORMAT`]):
//! a reader refuses a version it does not know, and the files written
//! before this one (`"redundant-ik run in space"`, which lacked the limits,
//! the weighting and the other methods' parameters) with a reason.

use serde::{Deserialize, Serialize};

use crate::networks::space::SpaceNetworkSet;
use crate::nn::Precision;

use super::MAX_RUN_FILE_BYTES;
use crate::arm::{JointLimits, RateLimits};
use crate::error::{Error, Result};
use crate::ik::DampingSchedule;
use crate::model::Model;
use crate::planner::params::{all, by_name};
use crate::planner::REACH_TOLERANCE;
use crate::planner::{observe_pose, Method, Planned, Planner, Sample, Summary, Trajectory};
use crate::scene::{JointWeighting, ParamMap, Params, SpacePath, SpaceScene};
use crate::space::{Chain, SpacePreset, Sphere, Vec3};

/// The `format` of a spatial run file this version writes and reads.
pub const SPACE_RUN_FORMAT: &str = "redundant-ik-space-run/1";
/// The `format` of the spatial runs printed before files could be
/// replayed (refused with a reason).
const UNVERSIONED: &str = "redundant-ik run in space";
/// The start of every version's `format`.
const FAMILY: &str = "redundant-ik-space-run/";

/// One spatial run and what it did.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceRunFile {
    /// The preset's name (`panda`, `iiwa14`): its chain.
    pub arm: &'static str,
    /// The method.
    pub method: Method,
    /// Everything that defines the motion (the chain is the preset's with
    /// the scene's limits).
    pub scene: SpaceScene,
    /// One sample per RK4 step, the start first (read back from a file,
    /// what the file does not hold is computed again from each sample's
    /// angles: the joints, the distance to the spheres, the damping, the
    /// manipulability).
    pub samples: Vec<Sample<3>>,
    /// The outcome.
    pub summary: Summary,
    /// The shipped network set a learned method ran with (`None`: no
    /// learned method, or the user's own weights files, which a replay
    /// takes again from the command line).
    pub networks: Option<SpaceNetworkSet>,
    /// The arithmetic of a learned method's networks (`f64` for the
    /// others; absent in the file: `f64`).
    pub precision: Precision,
}

/// The JSON form of a [`SpaceRunFile`]: one flat object.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Fields {
    format: String,
    arm: String,
    method: Method,
    theta0: Vec<f64>,
    target: Vec3,
    path: SpacePath,
    spheres: Vec<Sphere>,
    joint_limits: Option<JointLimits>,
    rate_limits: Option<RateLimits>,
    damping: Option<DampingSchedule>,
    dt: f64,
    tf: f64,
    feedback_gain: f64,
    /// Every declared parameter, by name.
    params: ParamMap,
    joint_weighting: JointWeighting,
    floor: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    networks: Option<SpaceNetworkSet>,
    #[serde(default, skip_serializing_if = "Precision::is_f64")]
    precision: Precision,
    samples: Vec<WireSample>,
    summary: WireSummary,
}

/// A sample as this version of the file writes it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct WireSample {
    t: f64,
    theta: Vec<f64>,
    hand: Vec3,
    reference: Vec3,
    tracking_error: f64,
    clearance: Option<f64>,
    /// How many joints are past a limit.
    past_limits: usize,
    relaxed: bool,
    phi_handover: bool,
}

impl From<&Sample<3>> for WireSample {
    fn from(s: &Sample<3>) -> Self {
        Self {
            t: s.t,
            theta: s.theta.clone(),
            hand: s.ee,
            reference: s.reference,
            tracking_error: s.tracking_error,
            clearance: s.clearance,
            past_limits: s.past_limits.len(),
            relaxed: s.relaxed,
            phi_handover: s.phi_handover,
        }
    }
}

/// The summary as this version of the file writes it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct WireSummary {
    steps: usize,
    min_clearance: Option<f64>,
    collision_steps: usize,
    limit_steps: usize,
    relaxed_steps: usize,
    handover_steps: usize,
    max_error: f64,
    final_error: f64,
}

impl From<&Summary> for WireSummary {
    fn from(s: &Summary) -> Self {
        Self {
            steps: s.steps,
            min_clearance: s.min_clearance,
            collision_steps: s.collision_steps,
            limit_steps: s.limit_steps,
            relaxed_steps: s.relaxed_steps,
            handover_steps: s.handover_steps,
            max_error: s.max_tracking_error,
            final_error: s.final_error,
        }
    }
}

/// The samples of a file read back: the file's numbers, and what it does
/// not hold computed from each sample's angles in `scene`; refused where
/// an angle is not finite.
fn samples_of(scene: &SpaceScene, wire: Vec<WireSample>) -> Result<Vec<Sample<3>>> {
    let chain = &scene.arm;
    let mut pose = chain.pose();
    wire.into_iter()
        .map(|w| {
            chain.update(&mut pose, &w.theta)?;
            let mut s = Planner::<Chain, 3>::blank_sample(chain);
            observe_pose::<Chain, 3>(scene, &pose, &mut s);
            s.t = w.t;
            s.ee = w.hand;
            s.reference = w.reference;
            s.tracking_error = w.tracking_error;
            s.clearance = w.clearance;
            s.relaxed = w.relaxed;
            s.phi_handover = w.phi_handover;
            Ok(s)
        })
        .collect()
}

/// The summary of a file read back: the file's numbers, the rest from the
/// samples read back (`samples` has one at least).
fn summary_of(
    method: Method,
    scene: &SpaceScene,
    w: WireSummary,
    samples: &[Sample<3>],
) -> Summary {
    let last = &samples[samples.len() - 1];
    let min = |f: fn(&Sample<3>) -> Option<f64>| samples.iter().filter_map(f).reduce(f64::min);
    let reachable = <Chain as Planned<3>>::track(scene, samples[0].ee, 0.0, scene.tf)
        .ok()
        .zip(crate::space::SpacePose::new(&scene.arm, &scene.theta0).ok())
        .is_none_or(|(track, pose)| track.all_points(|p| scene.arm.reaches(&pose, p)));
    Summary {
        method,
        steps: w.steps,
        t: last.t,
        min_distance: min(|s| s.distance),
        min_clearance: w.min_clearance,
        collided: w.collision_steps > 0,
        collision_steps: w.collision_steps,
        final_error: w.final_error,
        max_tracking_error: w.max_error,
        reached: w.final_error <= REACH_TOLERANCE,
        success: w.collision_steps == 0 && w.limit_steps == 0 && w.final_error <= REACH_TOLERANCE,
        target_reachable: reachable,
        out_of_range_steps: 0,
        max_delta: samples.iter().map(|s| s.delta).fold(0.0, f64::max),
        auto_damping: false,
        handover_steps: w.handover_steps,
        relaxed_steps: w.relaxed_steps,
        limit_steps: w.limit_steps,
    }
}

/// Just the version, to tell a spatial run file from a planar one.
#[derive(Deserialize)]
struct Probe {
    #[serde(default)]
    format: Option<String>,
}

/// The `format` field of `text`, if it is a JSON object that has one; an
/// error where it is not JSON.
fn format_of(text: &str) -> serde_json::Result<Option<String>> {
    Ok(serde_json::from_str::<Probe>(text)?.format)
}

/// Whether `text` claims to be a run of an arm in space (any version, the
/// unversioned output included; a file cut short too, by the `format` its
/// first bytes name): the readers of planar runs send it here.
pub fn is_space_run(text: &str) -> bool {
    match format_of(text) {
        Ok(f) => f.is_some_and(|f| f == UNVERSIONED || f.starts_with(FAMILY)),
        Err(_) => {
            let head = &text.as_bytes()[..text.len().min(256)];
            [FAMILY, UNVERSIONED]
                .iter()
                .any(|f| head.windows(f.len()).any(|w| w == f.as_bytes()))
        }
    }
}

impl SpaceRunFile {
    /// The file of `traj`, the run of `scene` on the preset `arm`.
    pub fn new(arm: &'static SpacePreset, scene: SpaceScene, traj: Trajectory<3>) -> Self {
        Self {
            arm: arm.key,
            method: traj.method,
            scene,
            samples: traj.steps,
            summary: traj.summary,
            networks: None,
            precision: Precision::F64,
        }
    }

    /// The JSON text (one line). Serialising these types cannot fail (no
    /// map has keys other than strings).
    pub fn to_json(&self) -> String {
        let s = &self.scene;
        let fields = Fields {
            format: SPACE_RUN_FORMAT.into(),
            arm: self.arm.into(),
            method: self.method,
            theta0: s.theta0.clone(),
            target: s.target,
            path: s.path.clone(),
            spheres: s.obstacles.clone(),
            joint_limits: s.arm.joint_limits().cloned(),
            rate_limits: s.arm.rate_limits().cloned(),
            damping: s.damping,
            dt: s.dt,
            tf: s.tf,
            feedback_gain: s.feedback_gain,
            params: ParamMap(
                all()
                    .iter()
                    .map(|p| (p.name.to_string(), s.param(p)))
                    .collect(),
            ),
            joint_weighting: s.weighting,
            floor: s.floor,
            networks: self.networks,
            precision: self.precision,
            samples: self.samples.iter().map(WireSample::from).collect(),
            summary: WireSummary::from(&self.summary),
        };
        serde_json::to_string(&fields).unwrap_or_default()
    }

    /// A spatial run file read back: its version, its preset, its scene
    /// (validated, as user input), its method (one that runs in space)
    /// and its samples' sizes are checked.
    pub fn from_json(text: &str) -> Result<Self> {
        let refuse = |expected: String| Error::Syntax {
            what: "run file in space",
            text: text.chars().take(48).collect(),
            expected,
        };
        if text.len() > MAX_RUN_FILE_BYTES {
            return Err(refuse(format!(
                "{} bytes, more than the {MAX_RUN_FILE_BYTES} allowed",
                text.len()
            )));
        }
        let format = format_of(text).map_err(|e| refuse(format!("not JSON: {e}")))?;
        match format.as_deref() {
            Some(SPACE_RUN_FORMAT) => {}
            Some(UNVERSIONED) => {
                return Err(refuse(
                    "written before runs in space could be replayed (it lacks the limits, the weighting and the parameters): run it again to replay it".into(),
                ))
            }
            Some(other) => {
                return Err(refuse(format!(
                    "format '{}' is not supported (expected '{SPACE_RUN_FORMAT}')",
                    crate::error::clip(other)
                )))
            }
            None => {
                return Err(refuse(format!(
                    "not a run in space: expected a JSON object with \"format\": \"{SPACE_RUN_FORMAT}\""
                )))
            }
        }
        let f: Fields = serde_json::from_str(text)
            .map_err(|e| refuse(format!("not the JSON of simulate --arm ... --json: {e}")))?;
        let preset = SpacePreset::by_key(&f.arm).ok_or_else(|| Error::UnknownName {
            kind: "arm in space",
            name: crate::error::clip(&f.arm),
            choices: crate::error::choices(
                &crate::space::PRESETS
                    .iter()
                    .map(|p| p.key)
                    .collect::<Vec<_>>(),
            ),
        })?;
        if !f.method.in_space() {
            return Err(refuse(format!(
                "method {} does not run an arm in space",
                f.method
            )));
        }
        let mut values = Vec::with_capacity(f.params.0.len());
        for (name, v) in &f.params.0 {
            values.push((by_name(name)?, *v));
        }
        let mut params = Params::default();
        params.set_all(&values)?;
        let mut scene = SpaceScene::preset(preset);
        scene.arm = scene.arm.with_limits(f.joint_limits, f.rate_limits)?;
        scene.theta0 = f.theta0;
        scene.target = f.target;
        scene.path = f.path;
        scene.obstacles = f.spheres;
        scene.damping = f.damping;
        scene.dt = f.dt;
        scene.tf = f.tf;
        scene.feedback_gain = f.feedback_gain;
        scene.params = params;
        scene.weighting = f.joint_weighting;
        scene.floor = f.floor;
        scene.validate()?;
        let n = scene.arm.dof();
        if f.samples.is_empty() {
            return Err(refuse("a run has its start sample at least".into()));
        }
        if let Some(s) = f.samples.iter().find(|s| s.theta.len() != n) {
            return Err(Error::DimensionMismatch {
                what: format!("the angles of the sample at t = {}", s.t),
                expected: n,
                found: s.theta.len(),
            });
        }
        let samples = samples_of(&scene, f.samples)?;
        let summary = summary_of(f.method, &scene, f.summary, &samples);
        Ok(Self {
            networks: f.networks,
            precision: f.precision,
            arm: preset.key,
            method: f.method,
            scene,
            samples,
            summary,
        })
    }
}
