//! The arm a training in space draws for: a preset (`train --arm panda`)
//! or a robot read from URDF (`train --urdf FILE`), with the scene its
//! tasks start from and whose first sphere sets the spheres' radius.

use crate::error::{Error, Result};
use crate::scene::SpaceScene;
use crate::space::{Chain, SpacePose, SpacePreset, Sphere};

/// The sphere a robot's own scene gets for training and evaluation when it
/// has none, as a fraction of the chain's reach: 0.05, the Panda's
/// preset's 6 cm against its 1.19 m reach.
pub const SPHERE_PER_REACH: f64 = 0.05;

/// How far (m) that sphere sits clear of the arm's middle joint at the
/// start, ahead of it along the hand's line (the presets' spheres sit 10
/// and 13 cm clear, placed by hand).
pub const SPHERE_CLEARANCE: f64 = 0.05;

/// An arm to train networks for: what the weights file and the messages
/// call it, and the scene of its start pose, its capsules and its sphere.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainArm {
    /// The preset's key, or the robot's name.
    pub name: String,
    /// Its chain, start pose and first sphere (the training draws its
    /// lines' starts within the limits and its spheres over the reach, of
    /// this sphere's radius; `eval` runs this scene).
    pub scene: SpaceScene,
}

impl From<&SpacePreset> for TrainArm {
    fn from(p: &SpacePreset) -> Self {
        Self {
            name: p.key.into(),
            scene: SpaceScene::preset(p),
        }
    }
}

impl TrainArm {
    /// The robot called `name` in `scene`. A scene without a sphere gets
    /// [`probe_sphere`]'s. Refused where the networks cannot serve the
    /// chain: its first joint slides (they are equivariant about the first
    /// joint's turning axis, [`crate::networks::space`]).
    pub fn new(name: &str, mut scene: SpaceScene) -> Result<Self> {
        let chain = &scene.arm;
        let pose = SpacePose::new(chain, &scene.theta0)?;
        if pose.is_prismatic(0) {
            return Err(Error::Training(format!(
                "{name}'s first joint slides: the networks in space are equivariant about the first joint's turning axis, so they cannot be trained for it"
            )));
        }
        if scene.obstacles.is_empty() {
            scene
                .obstacles
                .push(probe_sphere(chain, &pose, scene.target));
        }
        Ok(Self {
            name: name.into(),
            scene,
        })
    }

    /// The chain.
    pub fn chain(&self) -> &Chain {
        &self.scene.arm
    }

    /// The spheres' radius (m): the scene's first sphere's.
    pub fn sphere_radius(&self) -> f64 {
        self.scene
            .obstacles
            .first()
            .map_or(SPHERE_PER_REACH * self.chain().reach(), |s| s.radius)
    }
}

/// A sphere in the presets' manner, in the way of the forearm: of radius
/// [`SPHERE_PER_REACH`] times the reach, [`SPHERE_CLEARANCE`] clear of the
/// capsule at the chain's middle joint at `pose`, ahead of it along the
/// hand's line from `pose` to `target` (straight up where the line is a
/// point).
pub fn probe_sphere(chain: &Chain, pose: &SpacePose, target: [f64; 3]) -> Sphere {
    let r = SPHERE_PER_REACH * chain.reach();
    let middle = pose.joint_origin(chain.dof() / 2);
    let hand = pose.hand();
    let d = [0, 1, 2].map(|k| target[k] - hand[k]);
    let len = d.iter().map(|x| x * x).sum::<f64>().sqrt();
    let dir = if len > 1e-6 {
        d.map(|x| x / len)
    } else {
        [0.0, 0.0, 1.0]
    };
    let gap = SPHERE_CLEARANCE + r + chain.radius();
    Sphere::new([0, 1, 2].map(|k| middle[k] + gap * dir[k]), r)
}
