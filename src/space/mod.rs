//! Arms in space: serial chains from modified Denavit-Hartenberg rows or
//! a URDF's joint frames ([`Chain`]), the named robots ([`PRESETS`]: the
//! Franka Panda and the KUKA LBR iiwa 14), one kinematics pass per pose
//! ([`SpacePose`]: the joint frames, the hand and its `3 x n` positional
//! Jacobian), spheres as obstacles and their distances to the links'
//! capsules ([`Sphere`], [`CapsulePair`]), and the paper's criterion
//! generalised to space ([`criterion`]). The task is the hand's position
//! (`m = 3`), or its full pose ([`PoseChain`], `m = 6`: `docs/pose.md`),
//! and the chain's capsules may be kept apart ([`self_pairs`]).
//! `docs/space.md` has the models, their sources and the formulas.

mod chain;
pub mod criterion;
mod hand_pose;
pub mod linalg;
pub mod manipulability;
mod pairs;
pub mod phi;
pub(crate) mod pose;
mod preset;
pub mod rotation;
pub mod self_pairs;
mod sphere;

pub use chain::{Chain, JointFrame, LinkVolume, Row, Segment, IDENTITY, MAX_JOINTS, MIN_JOINTS};
pub use hand_pose::{
    pose_distance, pose_error, pose_geodesic, HandPose, PoseChain, ORIENTATION_WEIGHT,
};
pub use pairs::{Obstruction, SpacePair, SpacePairs};
pub(crate) use pose::{add, cross, dot, norm, scale, sub};
pub use pose::{SpacePose, Vec3};
pub use preset::{Named, SpacePreset, SpaceTask, PRESETS};
pub use sphere::{clearance, closest, CapsulePair, Sphere, SpherePlacement, MAX_SPHERES};
