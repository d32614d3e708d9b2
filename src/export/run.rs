//! A run as a file: the scene, the method, every sample and the summary.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::nn::Precision;
use crate::planner::{Method, Sample, Summary, Trajectory};
use crate::run::{NetworkChoice, Run};
use crate::scene::Scene;

/// Largest run file read (bytes): a run of the longest scene (10 000
/// steps of a 6-link arm) is about 6 MB.
pub const MAX_RUN_FILE_BYTES: usize = 16 << 20;

/// The format and version every planar run file names first (its
/// `format`, as a run in space names [`super::SPACE_RUN_FORMAT`]). Files
/// written before it (0.1's and the unversioned ones of 0.2) have none and
/// read as this version; another version is refused by name.
pub const RUN_FORMAT: &str = "redundant-ik-run/1";
/// Every version of the planar run file starts so.
const RUN_FAMILY: &str = "redundant-ik-run/";

fn run_format() -> String {
    RUN_FORMAT.into()
}

/// One run: `{ format, task, method, scene, networks, precision, steps,
/// summary }`, the JSON of `redundant-ik simulate --json` and of the page's
/// "Download run": the [`Run`] and what it did. Files written before
/// `format` read as [`RUN_FORMAT`], before `networks` as the paper's set,
/// those without `precision` as `f64`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunFile {
    /// [`RUN_FORMAT`].
    #[serde(default = "run_format")]
    pub format: String,
    /// The paper task the scene came from (its start pose and target may
    /// have been changed since: the scene says what was run).
    pub task: u32,
    /// The method (`method` in the JSON, as every output of the tool names
    /// it; `mode`, the older name, is read too).
    #[serde(alias = "mode")]
    pub method: Method,
    /// Everything that defines the motion.
    pub scene: Scene,
    /// The networks the method ran with (absent for a method without).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub networks: Option<NetworkChoice>,
    /// The arithmetic of the networks (absent: `f64`, and for a method
    /// without networks).
    #[serde(default, skip_serializing_if = "Precision::is_f64")]
    pub precision: Precision,
    /// One sample per RK4 step, the start first.
    pub steps: Vec<Sample>,
    /// The outcome.
    pub summary: Summary,
}

impl RunFile {
    /// The file of `run` and what it did: the networks and their precision
    /// are kept for a method that uses them only.
    pub fn new(run: Run, traj: Trajectory) -> Self {
        let learned = traj.method.uses_networks();
        Self {
            format: RUN_FORMAT.into(),
            task: run.task,
            method: traj.method,
            scene: run.scene,
            networks: run.networks.filter(|_| learned),
            precision: if learned {
                run.precision
            } else {
                Precision::F64
            },
            steps: traj.steps,
            summary: traj.summary,
        }
    }

    /// The run it replays.
    pub fn run(&self) -> Run {
        Run {
            task: self.task,
            method: self.method,
            scene: self.scene.clone(),
            networks: self.networks.clone(),
            precision: self.precision,
        }
    }

    /// The JSON text (one line). Serialising these types cannot fail (no
    /// map has keys other than strings).
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// A run file read back; its scene is checked (a file is user input).
    pub fn from_json(text: &str) -> Result<Self> {
        let refuse = |expected: String| Error::Syntax {
            what: "run file",
            text: text.chars().take(48).collect(),
            expected,
        };
        if text.len() > MAX_RUN_FILE_BYTES {
            return Err(refuse(format!(
                "{} bytes, more than the {MAX_RUN_FILE_BYTES} allowed",
                text.len()
            )));
        }
        if super::is_space_run(text) {
            return Err(refuse(
                "a run of an arm in space: simulate --from replays it (this reads planar runs)"
                    .into(),
            ));
        }
        let run: Self = serde_json::from_str(text)
            .map_err(|e| refuse(format!("not the JSON of simulate --json: {e}")))?;
        if run.format != RUN_FORMAT {
            return Err(refuse(if run.format.starts_with(RUN_FAMILY) {
                format!(
                    "a run file of format {} is not supported: this version reads {RUN_FORMAT} (and the unversioned files before it)",
                    run.format
                )
            } else {
                format!("format {RUN_FORMAT}, not {}", run.format)
            }));
        }
        run.scene.validate()?;
        let mut run = run;
        run.summary.success =
            !run.summary.collided && run.summary.limit_steps == 0 && run.summary.reached;
        Ok(run)
    }
}
