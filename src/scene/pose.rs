//! A run of a chain whose task is its hand's full pose (`m = 6`): the
//! scene of a chain in space whose target has six coordinates, the
//! position (m) and the rotation vector of the orientation (rad), and
//! whose arm carries the paper's metric `Z` ([`PoseChain`]). On the
//! straight line the orientation turns along the shortest rotation at a
//! constant rate; a circle or a polyline keeps the start orientation. The
//! spheres, the floor and the settings are the position task's.

use super::space::check_chain_scene;
use super::{Param, Scale, Scene, SpacePath, SpaceScene};
use crate::error::{coordinate, Error, Result};
use crate::space::{PoseChain, SpacePreset, Vec3};

/// A run of the hand's pose: a [`PoseChain`], a six-coordinate target,
/// a path, spheres.
pub type PoseScene = Scene<PoseChain, SpacePath, 6, 3>;

/// How far (rad, per coordinate of the rotation vector) the target's
/// orientation may lie from the start's where a circle or a polyline
/// keeps the start's: a run file's round trip, not a turn.
pub const KEPT: f64 = 1e-9;

/// The paper's `Z` (eqs. 6-7) for the pose task:
/// `Z = diag(1, 1, 1, z, z, z)`, `z` weighting the orientation rows
/// against the position rows (m^2/rad^2). Its default is the paper's
/// `Z = I`. It acts through the damping only (`delta Z^-1` in eq. 6):
/// see `crate::space::HandPose`.
pub static ORIENTATION_WEIGHT: Param = Param {
    name: "orientation_weight",
    flag: "--orientation-weight",
    label: "Orientation weight z (Z)",
    what: "orientation weight z of Z",
    #[cfg(feature = "cli")]
    help: "The pose task's Z = diag(1, 1, 1, z, z, z) of eqs. (6)-(7): a radian of orientation error weighs as sqrt(z) metres of position error where the solve is damped",
    unit: "m²/rad²",
    bounds: (1e-6, 1e6),
    default: crate::space::ORIENTATION_WEIGHT,
    slider: (-3.0, 3.0, 0.5),
    scale: Scale::Log,
    count: false,
    below: None,
    above: None,
};

impl PoseScene {
    /// The pose task of a scene of the hand's position: the same chain,
    /// start, spheres, path and settings; the target's position, and
    /// `orientation` for its orientation (a rotation vector, rad; `None`:
    /// the start's, kept). Refused for a scene that does not validate, a
    /// non-finite orientation, or a weight outside
    /// [`ORIENTATION_WEIGHT`]'s bounds.
    pub fn from_space(scene: SpaceScene, orientation: Option<Vec3>, weight: f64) -> Result<Self> {
        scene.validate()?;
        ORIENTATION_WEIGHT.check(weight)?;
        let arm = PoseChain::new(scene.arm, weight)?;
        let start = arm.start(&scene.theta0)?;
        let r = orientation.unwrap_or([start[3], start[4], start[5]]);
        let [x, y, z] = scene.target;
        let pose = Self {
            arm,
            theta0: scene.theta0,
            target: [x, y, z, r[0], r[1], r[2]],
            path: scene.path,
            obstacles: scene.obstacles,
            damping: scene.damping,
            dt: scene.dt,
            tf: scene.tf,
            feedback_gain: scene.feedback_gain,
            params: scene.params,
            weighting: scene.weighting,
            floor: scene.floor,
        };
        pose.validate()?;
        Ok(pose)
    }

    /// The preset's own task with its start orientation kept.
    pub fn preset(p: &SpacePreset) -> Result<Self> {
        Self::from_space(
            SpaceScene::preset(p),
            None,
            crate::space::ORIENTATION_WEIGHT,
        )
    }

    /// The scene of the hand's position it extends (the target's
    /// position), with the target's orientation (a rotation vector) and
    /// `Z`'s weight: what [`PoseScene::from_space`] takes back.
    pub fn position_scene(&self) -> (SpaceScene, Vec3, f64) {
        let t = self.target;
        let scene = SpaceScene {
            arm: self.arm.chain.clone(),
            theta0: self.theta0.clone(),
            target: [t[0], t[1], t[2]],
            path: self.path.clone(),
            obstacles: self.obstacles.clone(),
            damping: self.damping,
            dt: self.dt,
            tf: self.tf,
            feedback_gain: self.feedback_gain,
            params: self.params.clone(),
            weighting: self.weighting,
            floor: self.floor,
        };
        (scene, [t[3], t[4], t[5]], self.arm.orientation_weight())
    }

    /// The hand's pose at `t = 0` (NaN where `theta0` does not fit).
    pub fn start(&self) -> [f64; 6] {
        self.arm.start(&self.theta0).unwrap_or([f64::NAN; 6])
    }

    /// Checks every field; the first problem found is returned. A circle
    /// or a polyline keeps the start orientation (the target's must be
    /// it, within `KEPT`, 1e-9 rad).
    pub fn validate(&self) -> Result<()> {
        let [x, y, z, ..] = self.target;
        check_chain_scene(
            &self.arm.chain,
            &self.theta0,
            [x, y, z],
            &self.path,
            &self.obstacles,
        )?;
        for (&c, axis) in self.target[3..].iter().zip(["rx", "ry", "rz"]) {
            coordinate(&format!("target orientation {axis}"), c)?;
        }
        ORIENTATION_WEIGHT.check(self.arm.orientation_weight())?;
        let n = self.arm.chain.dof();
        if n < 6 {
            return Err(Error::Syntax {
                what: "task",
                text: "pose".into(),
                expected: format!("a chain of at least 6 joints: the hand's pose has six coordinates, and this chain has {n}"),
            });
        }
        if self.path != SpacePath::Line {
            // A circle or a polyline keeps the start orientation: the
            // target's must be it.
            let start = self.start();
            let turned = (3..6).any(|k| (self.target[k] - start[k]).abs() > KEPT);
            if turned {
                return Err(Error::Syntax {
                    what: "path",
                    text: self.path.to_string(),
                    expected: "the straight line where the target has an orientation of its own: a circle or a polyline of the pose task keeps the hand's start orientation (--task pose, and no orientation in --target)".into(),
                });
            }
            self.path.validate([start[0], start[1], start[2]])?;
        }
        self.validate_settings()
    }
}
