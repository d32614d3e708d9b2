//! The hand's full pose as the session's task (the page's "Hand: pose"):
//! the scene of the hand's position with an orientation for the target
//! and the paper's `Z` weight, run as a [`PoseScene`] (the command line's
//! `--task pose`). The session keeps its position scene, which the
//! pointer, the keys and the fields edit as before, and the target's
//! orientation beside it; a run of the pose is shown by its positions
//! (what the view, the trail and the plots draw), its samples of six
//! coordinates kept for the run file.

use std::sync::Arc;

use super::SpaceSession;
use crate::error::{Error, Result};
use crate::networks::space::SpaceNetworks;
use crate::planner::methods::Method;
use crate::planner::{Networks, Planned, Planner, Sample, Summary, Trajectory};
use crate::scene::{PoseScene, SpacePath, SpaceScene, ORIENTATION_WEIGHT};
use crate::space::rotation::{self, Mat3};
use crate::space::{PoseChain, Vec3};

/// The target's orientation where the task is the hand's pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orientation {
    /// The target's orientation as a rotation vector (rad, world axes).
    pub rotation: Vec3,
    /// `Z`'s orientation weight `z` (m^2/rad^2; [`ORIENTATION_WEIGHT`]).
    pub weight: f64,
}

/// A run as the session keeps it: the samples it shows (positions), the
/// pose task's samples of six coordinates (empty for the position task),
/// the outcome, and why it stopped early.
pub(super) struct Played {
    pub samples: Vec<Sample<3>>,
    pub pose_steps: Vec<Sample<6, Vec3>>,
    pub summary: Summary,
    pub failure: Option<String>,
}

/// `scene` run in `method` from `t = 0` to `tf`, as its pose task where
/// `orientation` is given: the samples up to the first step that failed,
/// the outcome so far, and why it failed.
pub(super) fn run(
    scene: &SpaceScene,
    orientation: Option<Orientation>,
    method: Method,
    networks: Option<Arc<SpaceNetworks>>,
) -> Played {
    let Some(o) = orientation else {
        let nets = networks.map(|n| n as Networks<_, 3>);
        let (samples, summary, failure) = steps(Planner::new(scene.clone(), method, nets), method);
        return Played {
            samples,
            pose_steps: Vec::new(),
            summary,
            failure,
        };
    };
    let planner = PoseScene::from_space(scene.clone(), Some(o.rotation), o.weight).and_then(|s| {
        let nets = networks.map(|n| n as Networks<PoseChain, 6>);
        Planner::new(s, method, nets)
    });
    let (pose_steps, summary, failure) = steps(planner, method);
    Played {
        samples: pose_steps.iter().map(Sample::position).collect(),
        pose_steps,
        summary,
        failure,
    }
}

/// Whether `method` runs the hand's pose: it has a rule for it and needs
/// no `Phi` network (Cases 1 and 3 do, and none is trained for the pose:
/// its pseudoinverse is `n x 6`, the networks' `n x 3`).
pub(super) fn runs_pose(method: Method) -> bool {
    <PoseChain as Planned<6>>::rule(method.entry()).is_some() && !method.info().networks.phi
}

/// Refuses a method without a rule for the hand's pose, with the reason.
pub(super) fn check_pose_method(method: Method) -> Result<()> {
    if runs_pose(method) {
        return Ok(());
    }
    Err(Error::Syntax {
        what: "method",
        text: method.name().into(),
        expected: "a method that runs the hand's pose: Cases 1 and 3 need a Phi network, and none is trained for the pose (its pseudoinverse is n x 6, the networks' n x 3); choose another, or the hand's position".into(),
    })
}

/// Every sample of `planner` to `tf` or its first failed step.
fn steps<A: Planned<M>, const M: usize>(
    planner: Result<Planner<A, M>>,
    method: Method,
) -> (Vec<Sample<M, A::Point>>, Summary, Option<String>) {
    let mut p = match planner {
        Ok(p) => p,
        Err(e) => return (Vec::new(), Summary::nothing(method), Some(e.to_string())),
    };
    let mut samples = vec![p.sample().clone()];
    while !p.done() {
        match p.step() {
            Ok(s) => samples.push(s.clone()),
            Err(e) => return (samples, p.summary(), Some(e.to_string())),
        }
    }
    (samples, p.summary(), None)
}

impl SpaceSession {
    /// The target's orientation and `Z`'s weight where the task is the
    /// hand's pose; `None` for its position.
    pub fn orientation(&self) -> Option<Orientation> {
        self.orientation
    }

    /// The scene of the pose task (the position scene with the target's
    /// orientation), where the task is the pose.
    pub fn pose_scene(&self) -> Option<PoseScene> {
        let o = self.orientation?;
        PoseScene::from_space(self.scene.clone(), Some(o.rotation), o.weight).ok()
    }

    /// Makes the task the hand's full pose (`true`: the target's
    /// orientation the hand's at the start, `Z = I`) or its position.
    /// Refused, changing nothing, for a chain of fewer than six joints or
    /// a method that does not run the pose (Cases 1 and 3: no `Phi` is
    /// trained for it).
    pub fn set_pose_task(&mut self, on: bool) -> Result<()> {
        if on == self.orientation.is_some() {
            return Ok(());
        }
        let orientation = if on {
            let scene =
                PoseScene::from_space(self.scene.clone(), None, crate::space::ORIENTATION_WEIGHT)?;
            let t = scene.target;
            Some(Orientation {
                rotation: [t[3], t[4], t[5]],
                weight: scene.arm.orientation_weight(),
            })
        } else {
            None
        };
        self.take(self.scene.clone(), orientation, self.method)
    }

    /// The target's orientation by its roll, pitch and yaw (rad; URDF's
    /// fixed axes, `R = Rz(yaw) Ry(pitch) Rx(roll)`, the command line's
    /// `--target X,Y,Z,ROLL,PITCH,YAW`). Refused, changing nothing, where
    /// the task is the hand's position, an angle is not finite, or the
    /// path is not the line (a circle or a polyline keeps the start
    /// orientation).
    pub fn set_target_rpy(&mut self, rpy: Vec3) -> Result<()> {
        for (&a, what) in rpy.iter().zip(["roll", "pitch", "yaw"]) {
            crate::error::coordinate(&format!("target {what}"), a)?;
        }
        self.set_target_rotation(&rotation::rpy_matrix(rpy))
    }

    /// The target's orientation as a rotation matrix (by rows): what the
    /// page's rotation gizmo sets. Refused as [`SpaceSession::set_target_rpy`].
    pub fn set_target_rotation(&mut self, r: &Mat3) -> Result<()> {
        let mut o = self.pose_task()?;
        if self.scene.path != SpacePath::Line {
            return Err(Error::Syntax {
                what: "path",
                text: self.scene.path.to_string(),
                expected: "the straight line for an orientation of the target's own: a circle or a polyline of the pose task keeps the hand's start orientation".into(),
            });
        }
        // A rotation: finite, `R R^T = I` and `det R = 1` (to 1e-6: a
        // matrix written to six digits passes, a scaling or a mirror not).
        let rrt = rotation::mul_transpose(r, r);
        let off = (0..3)
            .flat_map(|i| (0..3).map(move |j| (i, j)))
            .map(|(i, j)| (rrt[i][j] - f64::from(u8::from(i == j))).abs())
            .fold(0.0, f64::max);
        let det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
            - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
            + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
        if !(off <= 1e-6 && (det - 1.0).abs() <= 1e-6) {
            return Err(Error::Syntax {
                what: "target orientation",
                text: format!("{r:?}"),
                expected: "a rotation matrix: finite, orthonormal rows, determinant 1".into(),
            });
        }
        o.rotation = rotation::log(r);
        self.take(self.scene.clone(), Some(o), self.method)
    }

    /// Turns the target's orientation by `angle` (rad) about world axis
    /// `axis` (0: x, 1: y, 2: z): the rotation keys.
    pub fn turn_target(&mut self, axis: usize, angle: f64) -> Result<()> {
        let o = self.pose_task()?;
        crate::error::coordinate("turn", angle)?;
        let mut unit = [0.0; 3];
        *unit.get_mut(axis).ok_or_else(|| Error::Syntax {
            what: "axis",
            text: axis.to_string(),
            expected: "0, 1 or 2 (x, y or z)".into(),
        })? = 1.0;
        let r = rotation::mul(&rotation::about(unit, angle), &rotation::exp(o.rotation));
        self.set_target_rotation(&r)
    }

    /// `Z`'s orientation weight `z` of the pose task; refused, changing
    /// nothing, outside [`ORIENTATION_WEIGHT`]'s bounds or for the
    /// position task.
    pub fn set_orientation_weight(&mut self, weight: f64) -> Result<()> {
        let mut o = self.pose_task()?;
        ORIENTATION_WEIGHT.check(weight)?;
        o.weight = weight;
        self.take(self.scene.clone(), Some(o), self.method)
    }

    /// The pose task's whole run (six coordinates a sample: what its run
    /// file keeps); `None` for the position task.
    pub fn pose_trajectory(&self) -> Option<Trajectory<6, Vec3>> {
        self.orientation.map(|_| Trajectory {
            method: self.method,
            steps: self.pose_steps.clone(),
            summary: self.summary.clone(),
        })
    }

    /// The target's orientation as a rotation matrix (by rows), for the
    /// pose task.
    pub fn target_rotation(&self) -> Option<Mat3> {
        self.orientation.map(|o| rotation::exp(o.rotation))
    }

    /// The hand's rotation (by rows) at the pose shown: the last joint's
    /// axes turned by the flange's rotation.
    pub fn hand_rotation(&self) -> Mat3 {
        let n = self.pose.dof();
        let last = self.pose.frame(n - 1);
        let frame: Mat3 = std::array::from_fn(|r| std::array::from_fn(|c| last[c][r]));
        rotation::mul(&frame, &self.scene.arm.flange_rotation())
    }

    /// The pose task's orientation, or why there is none.
    fn pose_task(&self) -> Result<Orientation> {
        self.orientation.ok_or_else(|| Error::Syntax {
            what: "task",
            text: "position".into(),
            expected:
                "the hand's pose task for an orientation of the target (Hand: pose; --task pose)"
                    .into(),
        })
    }

    /// Takes `scene`, `orientation` and `method` when they run together
    /// (the scene validates; where the task is the pose, the pose scene
    /// validates and the method runs it), then recomputes the
    /// run. Where the pose task's path is not the line, the target's
    /// orientation follows the hand's start (a circle or a polyline keeps
    /// it).
    pub(super) fn take(
        &mut self,
        scene: SpaceScene,
        mut orientation: Option<Orientation>,
        method: Method,
    ) -> Result<()> {
        scene.validate()?;
        if let Some(o) = orientation.as_mut() {
            check_pose_method(method)?;
            // A circle or a polyline keeps the start's orientation; the
            // line takes the target's. Built once: checked and read back.
            let given = (scene.path == SpacePath::Line).then_some(o.rotation);
            let pose = PoseScene::from_space(scene.clone(), given, o.weight)?;
            o.rotation = [pose.target[3], pose.target[4], pose.target[5]];
        }
        self.scene = scene;
        self.orientation = orientation;
        self.method = method;
        self.recompute();
        Ok(())
    }
}
