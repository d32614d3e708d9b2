//! `simulate` for the hand's pose task of an arm in space (`--task pose`,
//! or `--target X,Y,Z,ROLL,PITCH,YAW`): the pose scene from the position
//! scene of the options, the run, and its summary, run file
//! (`redundant_ik::export::PoseRunFile`) or CSV; and a pose run file
//! given to `--from`.

use std::fmt::Write as _;

use redundant_ik::export::{is_pose_run, run_csv, PoseRunFile};
use redundant_ik::nn::Precision;
use redundant_ik::planner::{Planner, Trajectory};
use redundant_ik::scene::{PoseScene, SpaceScene};
use redundant_ik::space::rotation::{exp, matrix_rpy};
use redundant_ik::space::PoseChain;
use redundant_ik::urdf::RobotSource;
use redundant_ik::Method;

use super::emit;
use super::robot::Robot;
use super::simulate::{SceneArgs, SimulateArgs};
use super::task::PoseSpec;

/// A pose run file given to `--from`, if it is one (no scene option may
/// go with it; networks never do: none are trained for the pose task):
/// its position scene, its method and its pose.
#[allow(clippy::type_complexity)]
pub fn run_file(
    args: &SceneArgs,
) -> Result<Option<(SpaceScene, Method, PoseSpec, Option<RobotSource>)>, String> {
    let Some(file) = args.run_file_of::<PoseChain, 6>(is_pose_run)? else {
        return Ok(None);
    };
    super::robot::check_source(file.robot.as_ref(), &file.scene.arm.chain)?;
    let (scene, orientation, weight) = file.scene.position_scene();
    Ok(Some((
        scene,
        file.method,
        PoseSpec {
            orientation: Some(orientation),
            weight,
        },
        file.robot,
    )))
}

/// Runs the pose task of `scene` (the position scene of the options)
/// with `method` and prints what `args` ask for.
pub fn simulate(
    args: &SimulateArgs,
    robot: &Robot,
    scene: SpaceScene,
    spec: PoseSpec,
    method: Method,
    source: Option<RobotSource>,
) -> Result<(), String> {
    if method.uses_networks() {
        return Err(format!(
            "method {method} runs the paper's networks, which are trained for the hand's position: none are trained for its pose (choose a method without networks: {})",
            without_networks()
        ));
    }
    let scene =
        PoseScene::from_space(scene, spec.orientation, spec.weight).map_err(|e| e.to_string())?;
    let traj = Planner::new(scene.clone(), method, None)
        .and_then(Planner::run_to_end)
        .map_err(|e| e.to_string())?;
    if args.json {
        let text = PoseRunFile::of(None, scene, traj, None, Precision::F64)
            .with_robot(source)
            .to_json();
        return emit(&format!("{text}\n"));
    }
    if args.csv {
        return emit(&run_csv(&traj.steps));
    }
    emit(&summary(robot, &scene, &traj))
}

/// The methods that run the pose task, for messages.
fn without_networks() -> String {
    redundant_ik::planner::methods::ALL
        .iter()
        .filter(|m| !m.uses_networks())
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A pose `(p, r)` as its position and URDF's roll-pitch-yaw.
fn pose_text(x: [f64; 6]) -> String {
    let rpy = matrix_rpy(&exp([x[3], x[4], x[5]]));
    format!(
        "({:.4}, {:.4}, {:.4}) rpy ({:.4}, {:.4}, {:.4})",
        x[0], x[1], x[2], rpy[0], rpy[1], rpy[2]
    )
}

fn summary(robot: &Robot, scene: &PoseScene, traj: &Trajectory<6, [f64; 3]>) -> String {
    let s = &traj.summary;
    let mut out = String::new();
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let first = &traj.steps[0];
    let last = traj.steps.last().unwrap_or(first);
    let _ = writeln!(
        out,
        "{} | the hand's pose | method {} | dt {} s | tf {} s | Z = diag(1, 1, 1, {})",
        robot.label,
        traj.method,
        scene.dt,
        scene.tf,
        scene.arm.orientation_weight()
    );
    let _ = writeln!(
        out,
        "start  theta = [{}]  hand {}",
        list(&first.theta),
        pose_text(first.ee)
    );
    let _ = writeln!(
        out,
        "end    theta = [{}]  hand {}  target {}",
        list(&last.theta),
        pose_text(last.ee),
        pose_text(scene.target)
    );
    super::summary::contact(&mut out, s, &scene.arm.chain, &scene.obstacles);
    let _ = writeln!(
        out,
        "final hand error                      {:.3e} m, {:.3e} rad",
        s.final_error,
        s.final_orientation_error.unwrap_or(f64::NAN)
    );
    let _ = writeln!(
        out,
        "largest tracking error                {:.3e} m, {:.3e} rad",
        s.max_tracking_error,
        s.max_orientation_error.unwrap_or(f64::NAN)
    );
    if !s.target_reachable {
        let _ = writeln!(out, "target is out of the arm's reach: not reached");
    }
    super::summary::limits(&mut out, s);
    out
}
