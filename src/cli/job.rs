//! What `simulate` runs for an arm in space, from the options or a run
//! file: its robot, scene, method, networks, task and source.

use std::sync::Arc;

use redundant_ik::export::{Recorded, RunFile};
use redundant_ik::networks::space::{SpaceNetworkSet, SpaceNetworks};
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::Chain;
use redundant_ik::urdf::RobotSource;
use redundant_ik::Method;

use super::robot::Robot;
use super::simulate::SceneArgs;
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

impl Job {
    /// The job of a chain's run file given to `--from` (the hand's
    /// position or its pose): its robot, whose source is checked against
    /// its chain, its method unless `method` is given, the networks it
    /// names (or those the flags give), and its position scene and pose
    /// task as `split` takes them from the file's scene.
    pub fn of_file<A, const M: usize>(
        args: &SceneArgs,
        method: Option<Method>,
        file: RunFile<A, M>,
        split: impl FnOnce(A::Scene) -> (SpaceScene, Option<PoseSpec>),
    ) -> Result<Job, String>
    where
        A: Recorded<M, Set = SpaceNetworkSet> + AsRef<Chain>,
    {
        use redundant_ik::model::Scene as _;
        let chain: &Chain = file.scene.arm().as_ref();
        super::robot::check_source(file.robot.as_ref(), chain)?;
        let robot = Robot::of_chain(chain, RobotSource::name_of(file.robot.as_ref()));
        let method = method.unwrap_or(file.method);
        let nets = super::space_networks::of_run_file(
            &args.networks,
            &args.given,
            file.networks,
            file.precision,
            &robot,
            chain,
            method,
        )?;
        let (scene, pose) = split(file.scene);
        Ok(Job {
            robot,
            scene,
            method,
            nets,
            pose,
            source: file.robot,
        })
    }
}
