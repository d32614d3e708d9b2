//! `simulate` for the hand's pose task of an arm in space (`--task pose`,
//! or `--target X,Y,Z,ROLL,PITCH,YAW`): the pose scene from the position
//! scene of the options, the run, and its summary, run file
//! (`redundant_ik::export::PoseRunFile`) or CSV; and a pose run file
//! given to `--from`.

use std::fmt::Write as _;

use redundant_ik::export::is_pose_run;
use redundant_ik::planner::Trajectory;
use redundant_ik::scene::PoseScene;
use redundant_ik::space::rotation::{exp, matrix_rpy};
use redundant_ik::space::PoseChain;
use redundant_ik::Method;

use super::job::Job;
use super::robot::Robot;
use super::simulate::{SceneArgs, SimulateArgs};
use super::task::PoseSpec;

/// The job of a pose run file given to `--from`, if it is one (no scene
/// option may go with it): its position scene, its method unless `method`
/// is given, its pose, the networks it names (Case 2's), its robot.
pub fn run_file(args: &SceneArgs, method: Option<Method>) -> Result<Option<Job>, String> {
    let Some(file) = args.run_file_of::<PoseChain, 6>(is_pose_run)? else {
        return Ok(None);
    };
    Job::of_file(args, method, file, |scene| {
        let (scene, orientation, weight) = scene.position_scene();
        let pose = PoseSpec {
            orientation: Some(orientation),
            weight,
        };
        (scene, Some(pose))
    })
    .map(Some)
}

/// Runs the pose task of the job (its scene the position scene of the
/// options, its `pose` set) and prints what `args` ask for. Case 2 runs
/// with the networks' `v`; Cases 1 and 3 are refused by the planner (no
/// `Phi` is trained for the pose).
pub fn simulate(args: &SimulateArgs, job: Job) -> Result<(), String> {
    let Job {
        robot,
        scene,
        method,
        nets,
        pose: Some(spec),
        source,
    } = job
    else {
        return Err("simulate: not a pose job".into());
    };
    let scene =
        PoseScene::from_space(scene, spec.orientation, spec.weight).map_err(|e| e.to_string())?;
    super::summary::run_and_write::<PoseChain, 6>(
        args,
        scene,
        method,
        nets,
        source,
        |scene, traj| summary(&robot, scene, traj),
    )
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
    let _ = writeln!(
        out,
        "{} | the hand's pose | method {} | dt {} s | tf {} s | Z = diag(1, 1, 1, {})",
        robot.label,
        traj.method,
        scene.dt,
        scene.tf,
        scene.arm.orientation_weight()
    );
    let goal = if scene.path == redundant_ik::scene::SpacePath::Line {
        format!("target {}", pose_text(scene.target))
    } else {
        format!(
            "path {} ending at {}",
            scene.path,
            pose_text(traj.steps.last().map_or(scene.target, |x| x.reference))
        )
    };
    super::summary::ends(&mut out, &traj.steps, pose_text, &goal);
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
