//! `--task`: the paper's task of a planar arm (1 or 2), or the task of an
//! arm in space, its hand's position or its full pose; and what the pose
//! task of a command asks for (`--target X,Y,Z,ROLL,PITCH,YAW`,
//! `--orientation-weight`).

use redundant_ik::scene::ORIENTATION_WEIGHT;
use redundant_ik::space::rotation::{log, rpy_matrix};

use super::Numbers;

/// What `--task` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TaskArg {
    /// One of the paper's tasks (section VI), for a planar arm.
    Paper(u32),
    /// The hand's position, for an arm in space.
    Position,
    /// The hand's full pose, for an arm in space.
    Pose,
}

impl TaskArg {
    /// The paper's task, for a command of a planar arm; refused for the
    /// tasks of an arm in space.
    pub fn paper(self) -> Result<u32, String> {
        match self {
            TaskArg::Paper(t) => Ok(t),
            TaskArg::Position | TaskArg::Pose => Err(format!(
                "--task {}: a task of an arm in space (--arm panda, --arm iiwa14 or --urdf FILE); a planar arm's tasks are the paper's 1 and 2",
                self.name()
            )),
        }
    }

    /// Its name on the command line.
    pub fn name(self) -> String {
        match self {
            TaskArg::Paper(t) => t.to_string(),
            TaskArg::Position => "position".into(),
            TaskArg::Pose => "pose".into(),
        }
    }
}

/// `--task`'s value: a number (the paper's task), `position` or `pose`.
pub fn parse_task(s: &str) -> Result<TaskArg, String> {
    match s.trim() {
        "position" => Ok(TaskArg::Position),
        "pose" => Ok(TaskArg::Pose),
        t => t.parse().map(TaskArg::Paper).map_err(|_| {
            format!("expected 1 or 2 (a planar arm's paper task), position or pose (an arm in space), not '{t}'")
        }),
    }
}

/// What the hand's pose task of a command asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoseSpec {
    /// The target's orientation as a rotation vector (rad); `None`: the
    /// start's, kept.
    pub orientation: Option<[f64; 3]>,
    /// `z` of the paper's `Z` (m^2/rad^2).
    pub weight: f64,
}

/// The pose task the options ask for, if they do: `--task pose`, or a
/// `--target` of six numbers; `None` for the hand's position. Refused
/// where the options contradict each other.
pub fn pose_spec(
    task: TaskArg,
    target: Option<&Numbers>,
    orientation_weight: Option<f64>,
) -> Result<Option<PoseSpec>, String> {
    let six = match target {
        Some(Numbers(v)) if v.len() == 6 => Some([v[3], v[4], v[5]]),
        _ => None,
    };
    let pose = task == TaskArg::Pose || six.is_some();
    if !pose {
        if orientation_weight.is_some() {
            return Err("--orientation-weight weighs the orientation of the hand's pose task: give --task pose or --target X,Y,Z,ROLL,PITCH,YAW".into());
        }
        return Ok(None);
    }
    if task == TaskArg::Position {
        return Err("--task position takes a target X,Y,Z; X,Y,Z,ROLL,PITCH,YAW is the hand's pose (--task pose)".into());
    }
    let orientation = match six {
        Some(rpy) => {
            if let Some(bad) = rpy.iter().find(|x| !x.is_finite()) {
                return Err(format!(
                    "--target: roll, pitch and yaw must be finite, got {bad}"
                ));
            }
            Some(log(&rpy_matrix(rpy)))
        }
        None => None,
    };
    let weight = orientation_weight.unwrap_or(ORIENTATION_WEIGHT.default);
    ORIENTATION_WEIGHT
        .check(weight)
        .map_err(|e| format!("--orientation-weight: {e}"))?;
    Ok(Some(PoseSpec {
        orientation,
        weight,
    }))
}
