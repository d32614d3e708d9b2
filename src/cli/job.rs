//! What `simulate` runs for an arm in space, from the options or a run
//! file: its robot, scene, method, networks, task and source.

use std::sync::Arc;

use redundant_ik::networks::space::SpaceNetworks;
use redundant_ik::scene::SpaceScene;
use redundant_ik::urdf::RobotSource;
use redundant_ik::Method;

use super::robot::Robot;
use super::task::PoseSpec;

/// What a command runs on an arm in space: the robot, the scene, the
/// method and the networks of a learned method, from `--arm A` (or
/// `--urdf FILE`) and the scene options, or from a spatial run file
/// (`--from`: its scene, its method unless `--method` is given, the
/// networks it names in its arithmetic).
pub struct Job {
    /// The arm.
    pub robot: Robot,
    /// The scene.
    pub scene: SpaceScene,
    /// The method.
    pub method: Method,
    /// The networks, for a learned method.
    pub nets: Option<Arc<SpaceNetworks>>,
    /// The hand's pose task, where the options or the run file ask for
    /// it (`scene` then holds its position's part).
    pub pose: Option<PoseSpec>,
    /// Where the robot came from, as a run file records it.
    pub source: Option<RobotSource>,
}
