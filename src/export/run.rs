//! A run as a file, for every arm: the scene (the arm in it, whole), the
//! method, its networks, every sample and the summary. One format,
//! versioned by its first field (`format`, [`RUN_FORMAT`]): what
//! `redundant-ik simulate --json` prints for any arm, what the page's
//! "Download run" saves and what `simulate --from`, `figure --from` and
//! `atlas --from` read back. The files of the versions before it still
//! read: the planar `redundant-ik-run/1` and the unversioned planar files
//! (the same layout), and `redundant-ik-space-run/1` ([`super::space_run`]).

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::model::Scene as _;
use crate::networks::NetworkSet;
use crate::nn::Precision;
use crate::planner::{Method, Planned, Sample, Summary, Trajectory};
use crate::run::{NetworkChoice, Run};
use crate::space::{Chain, PoseChain};
use crate::urdf::RobotSource;

/// Largest run file read (bytes): a run of the longest scene (10 000
/// steps of a 6-link arm) is about 6 MB.
pub const MAX_RUN_FILE_BYTES: usize = 16 << 20;

/// The format and version every run file this version writes names first.
pub const RUN_FORMAT: &str = "redundant-ik-run/2";
/// The planar run files of the version before, whose layout is this
/// one's; files written before `format` existed (0.1's and 0.2's) have
/// none and read as it.
pub const PLANAR_RUN_FORMAT_1: &str = "redundant-ik-run/1";
/// Every version of the run file starts so.
const RUN_FAMILY: &str = "redundant-ik-run/";
/// The spatial run files of the version before the one run file (read
/// by `space_run.rs`).
pub const SPACE_RUN_FORMAT_1: &str = "redundant-ik-space-run/1";
/// The spatial runs printed before files could be replayed (refused
/// with a reason).
pub(super) const SPACE_UNVERSIONED: &str = "redundant-ik run in space";
/// The start of every version's `format` of the spatial files before
/// the one run file.
pub(super) const SPACE_FAMILY: &str = "redundant-ik-space-run/";

fn run_format() -> String {
    RUN_FORMAT.into()
}

/// What a run file holds of an arm beyond the planner's model: the kind
/// of its shipped network sets, and how it reads the files of the
/// versions before [`RUN_FORMAT`] (the chain's: `space_run.rs`).
pub trait Recorded<const M: usize>: Planned<M> {
    /// Its shipped network sets ([`NetworkSet`] in the plane,
    /// [`crate::networks::space::SpaceNetworkSet`] in space).
    type Set: Serialize + DeserializeOwned + Copy + PartialEq + std::fmt::Debug;
    /// The run file of an older `format` (`None`: none), if this arm's
    /// files had that version; `None` where they never did.
    fn older(format: Option<&str>, text: &str) -> Option<Result<RunFile<Self, M>>>;
    /// The chain a scene runs, for an arm in space (what a file's
    /// [`RobotSource`] must describe).
    fn chain_of(scene: &Self::Scene) -> Option<&Chain> {
        let _ = scene;
        None
    }
}

impl Recorded<2> for Arm {
    type Set = NetworkSet;
    fn older(format: Option<&str>, text: &str) -> Option<Result<RunFile<Self, 2>>> {
        matches!(format, None | Some(PLANAR_RUN_FORMAT_1)).then(|| parse(text))
    }
}

impl Recorded<6> for PoseChain {
    type Set = crate::networks::space::SpaceNetworkSet;
    /// The pose task came with this version: no older files.
    fn older(_: Option<&str>, _: &str) -> Option<Result<RunFile<Self, 6>>> {
        None
    }
    fn chain_of(scene: &Self::Scene) -> Option<&Chain> {
        Some(&scene.arm.chain)
    }
}

/// One run: `{ format, task, method, scene, networks, precision, steps,
/// summary }`, of an arm `A` whose hand has `M` coordinates (the planar
/// arm's by default). `task` is the paper's task a planar scene came
/// from (absent for an arm in space); `networks` and `precision` are
/// absent for a method without networks (and `precision` when `f64`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(bound(
    serialize = "A::Scene: Serialize, [f64; M]: Serialize",
    deserialize = "A::Scene: Deserialize<'de>, [f64; M]: Deserialize<'de>"
))]
pub struct RunFile<A: Recorded<M> = Arm, const M: usize = 2> {
    /// [`RUN_FORMAT`].
    #[serde(default = "run_format")]
    pub format: String,
    /// The paper task a planar scene came from (its start pose and target
    /// may have been changed since: the scene says what was run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub task: Option<u32>,
    /// The method (`method` in the JSON, as every output of the tool names
    /// it; `mode`, the older name, is read too).
    #[serde(alias = "mode")]
    pub method: Method,
    /// Everything that defines the motion, the arm whole.
    pub scene: A::Scene,
    /// The networks the method ran with (absent for a method without).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub networks: Option<NetworkChoice<A::Set>>,
    /// The arithmetic of the networks (absent: `f64`, and for a method
    /// without networks).
    #[serde(default, skip_serializing_if = "Precision::is_f64")]
    pub precision: Precision,
    /// One sample per RK4 step, the start first.
    pub steps: Vec<Sample<M, A::Point>>,
    /// The outcome.
    pub summary: Summary,
    /// Where an arm in space came from: a shipped robot's name, or the
    /// user's URDF whole (absent for a planar arm and in older files).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robot: Option<RobotSource>,
}

/// The run file of an arm in space.
pub type SpaceRunFile = RunFile<Chain, 3>;

/// The run file of an arm in space whose task is its hand's pose.
pub type PoseRunFile = RunFile<PoseChain, 6>;

/// Which kind of run a file holds: what its arm is and its task.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunKind {
    /// A planar arm's (`M = 2`).
    Planar,
    /// A chain in space's, the hand's position (`M = 3`).
    Space,
    /// A chain in space's, the hand's pose (`M = 6`).
    Pose,
}

impl RunKind {
    /// The kind of run of a hand of `m` coordinates.
    pub fn of_task(m: usize) -> Self {
        match m {
            2 => RunKind::Planar,
            6 => RunKind::Pose,
            _ => RunKind::Space,
        }
    }

    /// What a message calls it.
    pub fn label(self) -> &'static str {
        match self {
            RunKind::Planar => "a planar arm",
            RunKind::Space => "an arm in space (the hand's position)",
            RunKind::Pose => "an arm in space (the hand's pose)",
        }
    }
}

impl RunFile {
    /// The file of `run` and what it did: the networks and their precision
    /// are kept for a method that uses them only.
    pub fn new(run: Run, traj: Trajectory) -> Self {
        RunFile::of(Some(run.task), run.scene, traj, run.networks, run.precision)
    }

    /// The run it replays.
    pub fn run(&self) -> Run {
        Run {
            task: self.task.unwrap_or(1),
            method: self.method,
            scene: self.scene.clone(),
            networks: self.networks.clone(),
            precision: self.precision,
        }
    }
}

impl<A: Recorded<M>, const M: usize> RunFile<A, M>
where
    A::Scene: Serialize + DeserializeOwned,
    [f64; M]: Serialize + DeserializeOwned,
{
    /// The file of `traj`, the run of `scene`: `networks` and `precision`
    /// are kept for a method that uses networks only.
    pub fn of(
        task: Option<u32>,
        scene: A::Scene,
        traj: Trajectory<M, A::Point>,
        networks: Option<NetworkChoice<A::Set>>,
        precision: Precision,
    ) -> Self {
        let learned = traj.method.uses_networks();
        Self {
            format: RUN_FORMAT.into(),
            task,
            method: traj.method,
            scene,
            networks: networks.filter(|_| learned),
            precision: if learned { precision } else { Precision::F64 },
            steps: traj.steps,
            summary: traj.summary,
            robot: None,
        }
    }

    /// The file with `robot` recorded as where its arm came from.
    pub fn with_robot(mut self, robot: Option<RobotSource>) -> Self {
        self.robot = robot;
        self
    }

    /// The JSON text (one line). Serialising these types cannot fail (no
    /// map has keys other than strings).
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// A run file read back, of this version or an older one this arm's
    /// files had; its scene is checked (a file is user input), and so are
    /// its samples' sizes and its method (one that runs this arm).
    pub fn from_json(text: &str) -> Result<Self> {
        if text.len() > MAX_RUN_FILE_BYTES {
            return Err(refusal(
                text,
                format!(
                    "{} bytes, more than the {MAX_RUN_FILE_BYTES} allowed",
                    text.len()
                ),
            ));
        }
        let probe = probe(text).map_err(|e| refusal(text, format!("not JSON: {e}")))?;
        let format = probe.format.as_deref();
        let want = RunKind::of_task(M);
        if let Some(kind) = probe.kind().filter(|&k| k != want) {
            return Err(refusal(
                text,
                format!(
                    "a run of {}: this reads runs of {}",
                    kind.label(),
                    want.label()
                ),
            ));
        }
        let mut run = match format {
            Some(RUN_FORMAT) => parse(text)?,
            other => match A::older(other, text) {
                Some(read) => read?,
                None => return Err(refusal(text, unknown_format(other))),
            },
        };
        run.scene.validate()?;
        // A robot's URDF text is checked against the chain by its reader
        // (the tool's `--from`, `RobotSource::check`), not here: the wasm
        // modules read run files and would carry the URDF reader for it.
        if run.robot.is_some() && A::chain_of(&run.scene).is_none() {
            return Err(refusal(
                text,
                "a run of a planar arm, which names no robot".into(),
            ));
        }
        if !run.method.in_space() && M != 2 {
            return Err(refusal(
                text,
                format!("method {} does not run an arm in space", run.method),
            ));
        }
        let n = run.scene.theta0().len();
        if run.steps.is_empty() {
            return Err(refusal(text, "a run has its start sample at least".into()));
        }
        if let Some(s) = run.steps.iter().find(|s| s.theta.len() != n) {
            return Err(Error::DimensionMismatch {
                what: format!("the angles of the sample at t = {}", s.t),
                expected: n,
                found: s.theta.len(),
            });
        }
        let s = &mut run.summary;
        s.success = !s.collided && s.self_collision_steps == 0 && s.limit_steps == 0 && s.reached;
        run.format = RUN_FORMAT.into();
        Ok(run)
    }
}

/// `text` read as this version's layout.
fn parse<T: DeserializeOwned>(text: &str) -> Result<T> {
    serde_json::from_str(text)
        .map_err(|e| refusal(text, format!("not the JSON of simulate --json: {e}")))
}

/// A run file refused, and why.
pub(super) fn refusal(text: &str, expected: String) -> Error {
    Error::Syntax {
        what: "run file",
        text: text.chars().take(48).collect(),
        expected,
    }
}

/// What a refusal of an unknown `format` says.
fn unknown_format(format: Option<&str>) -> String {
    match format {
        Some(f) if f.starts_with(RUN_FAMILY) => format!(
            "a run file of format {} is not supported: this version reads {RUN_FORMAT} and the versions before it",
            crate::error::clip(f)
        ),
        Some(f) => format!("format {RUN_FORMAT}, not {}", crate::error::clip(f)),
        None => format!("a JSON object with \"format\": \"{RUN_FORMAT}\""),
    }
}

/// What a reader first needs of a run file: its version and which kind
/// of arm it holds (a chain's JSON has `rows`, or `joints` where it was
/// read from URDF).
#[derive(Deserialize)]
struct Probe {
    #[serde(default)]
    format: Option<String>,
    #[serde(default)]
    scene: Option<SceneProbe>,
}

#[derive(Deserialize)]
struct SceneProbe {
    #[serde(default)]
    arm: Option<ArmProbe>,
}

#[derive(Deserialize)]
struct ArmProbe {
    #[serde(default)]
    rows: Option<serde::de::IgnoredAny>,
    #[serde(default)]
    joints: Option<serde::de::IgnoredAny>,
    /// A pose task's arm is `{ chain, orientation_weight }`.
    #[serde(default)]
    chain: Option<serde::de::IgnoredAny>,
}

impl Probe {
    /// Which kind of run the file holds (`None`: it does not say).
    fn kind(&self) -> Option<RunKind> {
        let format = self.format.as_deref().unwrap_or_default();
        if format == SPACE_UNVERSIONED || format.starts_with(SPACE_FAMILY) {
            return Some(RunKind::Space);
        }
        let arm = self.scene.as_ref().and_then(|s| s.arm.as_ref())?;
        Some(if arm.chain.is_some() {
            RunKind::Pose
        } else if arm.rows.is_some() || arm.joints.is_some() {
            RunKind::Space
        } else {
            RunKind::Planar
        })
    }
}

/// Whether `text` is a run of the hand's pose task (a whole JSON file
/// whose arm is a pose task's): the readers send it to
/// [`PoseRunFile::from_json`].
pub fn is_pose_run(text: &str) -> bool {
    probe(text).is_ok_and(|p| p.kind() == Some(RunKind::Pose))
}

fn probe(text: &str) -> serde_json::Result<Probe> {
    serde_json::from_str(text)
}

/// Whether `text` claims to be a run of an arm in space (any version; a
/// file cut short too, by the `format` its first bytes name): the readers
/// send it to [`SpaceRunFile::from_json`], and the rest to
/// [`RunFile::from_json`].
pub fn is_space_run(text: &str) -> bool {
    match probe(text) {
        Ok(p) => matches!(p.kind(), Some(RunKind::Space | RunKind::Pose)),
        // Not JSON, or cut short: by the format its first bytes name.
        Err(_) => {
            let head = &text.as_bytes()[..text.len().min(256)];
            [SPACE_FAMILY, SPACE_UNVERSIONED]
                .iter()
                .any(|f| head.windows(f.len()).any(|w| w == f.as_bytes()))
        }
    }
}
