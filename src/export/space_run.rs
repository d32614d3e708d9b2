//! The run files of an arm in space written before the one run file
//! ([`super::RUN_FORMAT`]), read: `redundant-ik-space-run/1`, one flat
//! object that named its preset and held a part of each sample (what it
//! does not hold is computed again from each sample's angles). The
//! spatial runs printed before files could be replayed (`"redundant-ik
//! run in space"`, which lacked the limits, the weighting and the other
//! methods' parameters) are refused with a reason.

use serde::Deserialize;

use super::run::{
    refusal, Recorded, SpaceRunFile, PLANAR_RUN_FORMAT_1, RUN_FORMAT, SPACE_FAMILY,
    SPACE_RUN_FORMAT_1, SPACE_UNVERSIONED,
};
use crate::arm::{JointLimits, RateLimits};
use crate::error::{Error, Result};
use crate::ik::DampingSchedule;
use crate::model::Model;
use crate::networks::space::SpaceNetworkSet;
use crate::nn::Precision;
use crate::planner::params::by_name;
use crate::planner::REACH_TOLERANCE;
use crate::planner::{observe_pose, Method, Planned, Planner, Sample, Summary};
use crate::run::NetworkChoice;
use crate::scene::{JointWeighting, ParamMap, Params, SpacePath, SpaceScene};
use crate::space::{Chain, Sphere, Vec3};

/// A version 1 file: one flat object.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Fields {
    /// Read by the probe before this ([`older`]).
    #[allow(dead_code)]
    format: serde::de::IgnoredAny,
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
    #[serde(default)]
    networks: Option<SpaceNetworkSet>,
    #[serde(default)]
    precision: Precision,
    samples: Vec<WireSample>,
    summary: WireSummary,
}

/// A sample as a version 1 file holds it.
#[derive(Debug, Clone, PartialEq, Deserialize)]
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

/// The summary as a version 1 file holds it.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
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
        min_self_clearance: None,
        self_collision_steps: 0,
        final_error: w.final_error,
        max_tracking_error: w.max_error,
        final_orientation_error: None,
        max_orientation_error: None,
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

impl Recorded<3> for Chain {
    type Set = SpaceNetworkSet;
    fn older(format: Option<&str>, text: &str) -> Option<Result<SpaceRunFile>> {
        older(format, text)
    }
    fn chain_of(scene: &SpaceScene) -> Option<&Chain> {
        Some(&scene.arm)
    }
}

/// The run file of a spatial file of version 1 (`None`: `format` is no
/// older spatial one); refused with a reason for the unversioned output
/// and for other versions.
fn older(format: Option<&str>, text: &str) -> Option<Result<SpaceRunFile>> {
    match format? {
        SPACE_RUN_FORMAT_1 => Some(read(text)),
        PLANAR_RUN_FORMAT_1 => Some(Err(refusal(
            text,
            "a run of a planar arm: this reads runs of arms in space".into(),
        ))),
        SPACE_UNVERSIONED => Some(Err(refusal(
            text,
            "written before runs in space could be replayed (it lacks the limits, the weighting and the parameters): run it again to replay it".into(),
        ))),
        other if other.starts_with(SPACE_FAMILY) => Some(Err(refusal(
            text,
            format!(
                "format '{}' is not supported (expected '{}' or '{SPACE_RUN_FORMAT_1}')",
                crate::error::clip(other),
                RUN_FORMAT
            ),
        ))),
        _ => None,
    }
}

/// A version 1 file: its preset's chain with the file's limits, its
/// scene, its samples and summary completed from the angles.
fn read(text: &str) -> Result<SpaceRunFile> {
    let f: Fields = serde_json::from_str(text).map_err(|e| {
        refusal(
            text,
            format!("not the JSON of simulate --arm ... --json: {e}"),
        )
    })?;
    let mut values = Vec::with_capacity(f.params.0.len());
    for (name, v) in &f.params.0 {
        values.push((by_name(name)?, *v));
    }
    let mut params = Params::default();
    params.set_all(&values)?;
    let mut scene = SpaceScene::by_key(&f.arm)?;
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
        return Err(refusal(text, "a run has its start sample at least".into()));
    }
    if let Some(s) = f.samples.iter().find(|s| s.theta.len() != n) {
        return Err(Error::DimensionMismatch {
            what: format!("the angles of the sample at t = {}", s.t),
            expected: n,
            found: s.theta.len(),
        });
    }
    let steps = samples_of(&scene, f.samples)?;
    let summary = summary_of(f.method, &scene, f.summary, &steps);
    Ok(SpaceRunFile {
        format: SPACE_RUN_FORMAT_1.into(),
        task: None,
        method: f.method,
        scene,
        networks: f.networks.map(NetworkChoice::Set),
        precision: f.precision,
        steps,
        summary,
        robot: None,
    })
}
