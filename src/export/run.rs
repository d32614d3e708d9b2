//! A run as a file: the scene, the method, every sample and the summary.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::planner::{Method, Sample, Summary, Trajectory};
use crate::scene::Scene;

/// Largest run file read (bytes): a run of the longest scene (10 000
/// steps of a 6-link arm) is about 6 MB.
pub const MAX_RUN_FILE_BYTES: usize = 16 << 20;

/// One run: `{ task, mode, scene, steps, summary }`, the JSON of
/// `redundant-ik simulate --json` and of the page's "Download run".
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunFile {
    /// The paper task the scene came from (its start pose and target may
    /// have been changed since: the scene says what was run).
    pub task: u32,
    /// The method.
    pub mode: Method,
    /// Everything that defines the run.
    pub scene: Scene,
    /// One sample per RK4 step, the start first.
    pub steps: Vec<Sample>,
    /// The outcome.
    pub summary: Summary,
}

impl RunFile {
    /// The file of a run of `scene` (from paper task `task`).
    pub fn new(task: u32, scene: Scene, run: Trajectory) -> Self {
        Self {
            task,
            mode: run.method,
            scene,
            steps: run.steps,
            summary: run.summary,
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
        let run: Self = serde_json::from_str(text)
            .map_err(|e| refuse(format!("not the JSON of simulate --json: {e}")))?;
        run.scene.validate()?;
        Ok(run)
    }
}
