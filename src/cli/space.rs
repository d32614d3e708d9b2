//! `simulate` for an arm in space (`--arm panda`, `--arm iiwa14`): the
//! scene from the preset's task and the scene options (or a spatial run
//! file's, `--from`), the run through the planner, and its summary,
//! the run file (JSON, `redundant_ik::export::SpaceRunFile`) or CSV.

use std::fmt::Write as _;

use redundant_ik::export::{is_space_run, SpaceRunFile};
use redundant_ik::geometry::Placement;
use redundant_ik::planner::Trajectory;
use redundant_ik::scene::{SpacePath, SpaceScene};
use redundant_ik::space::{Chain, SpacePreset};
use redundant_ik::Method;

pub use super::job::Job;
use super::path_arg::PathArg;
pub use super::robot::Robot;
use super::simulate::{SceneArgs, SimulateArgs};
pub use super::space_networks::networks_for;
use super::task::pose_spec;
use super::Numbers;
use redundant_ik::urdf::RobotSource;

/// The scene of `args` for the preset `p`: its task, with the options
/// given. Options a spatial run does not take yet are refused by name.
pub fn scene(args: &SceneArgs, p: &'static SpacePreset) -> Result<SpaceScene, String> {
    if args.from.is_some() {
        return Err("--from gives the whole scene; --arm cannot change it".into());
    }
    let s = SpaceScene::preset(p);
    let radius = s.obstacles[0].radius;
    apply(args, s, radius)
}

/// The scene options of `args` on `s`; `radius` is a sphere's without one
/// of its own (or `--radius`).
fn apply(args: &SceneArgs, mut s: SpaceScene, radius: f64) -> Result<SpaceScene, String> {
    if args.joint_limits.is_some() || args.rate_limits.is_some() {
        let c = s.arm.clone();
        s.arm = c
            .with_limits(
                args.joint_limits.clone().or(s.arm.joint_limits().cloned()),
                args.rate_limits.clone().or(s.arm.rate_limits().cloned()),
            )
            .map_err(|e| e.to_string())?;
    }
    args.settings_onto(&mut s, sphere, radius)?;
    if let Some(Numbers(v)) = &args.target {
        // Six numbers are a pose: its orientation is the pose task's.
        s.target = match v[..] {
            [x, y, z] | [x, y, z, _, _, _] => [x, y, z],
            _ => {
                return Err(format!(
                    "--target: the hand of an arm in space goes to X,Y,Z (or the pose X,Y,Z,ROLL,PITCH,YAW), got {} numbers",
                    v.len()
                ))
            }
        };
    }
    if let Some(v) = &args.path {
        s.path = space_path(v)?;
    }
    s.validate().map_err(|e| e.to_string())?;
    Ok(s)
}

/// A sphere: `X,Y,Z` or `X,Y,Z,R`; a planar disc's `X,Y` is refused with
/// a reason.
fn sphere(n: &Numbers) -> Result<Placement<3>, String> {
    match n.0[..] {
        [x, y, z] => Ok(Placement { centre: [x, y, z], radius: None }),
        [x, y, z, r] => Ok(Placement { centre: [x, y, z], radius: Some(r) }),
        [_, _] => Err("--obstacle: X,Y places a disc, for a planar arm; an arm in space takes a sphere X,Y,Z or X,Y,Z,R".into()),
        _ => Err(format!(
            "--obstacle: a sphere is X,Y,Z or X,Y,Z,R, got {} numbers",
            n.0.len()
        )),
    }
}

/// The path in space of `--path`, or a refusal that names a planar path
/// as one.
fn space_path(v: &PathArg) -> Result<SpacePath, String> {
    v.space.clone().map_err(|e| match &v.planar {
        Ok(_) => format!(
            "--path {}: a planar path; an arm in space takes line, circle:CX,CY,CZ,NX,NY,NZ[,LAPS] or points:X,Y,Z;X,Y,Z;...",
            v.text
        ),
        Err(_) => e,
    })
}

/// The spatial run file of `--from`, if it names one, read and checked
/// (no scene option may go with it); `None` for a planar run's file.
pub fn run_file(args: &SceneArgs) -> Result<Option<SpaceRunFile>, String> {
    args.run_file_of(is_space_run)
}

/// The spatial job of `args` (`p`: the arm in space `--arm` names, if it
/// names one), or `None` for a planar one.
pub fn job(
    args: &SceneArgs,
    method: Option<Method>,
    p: Option<&'static SpacePreset>,
) -> Result<Option<Job>, String> {
    if let Some(job) = super::pose::run_file(args, method)? {
        return Ok(Some(job));
    }
    if let Some(file) = run_file(args)? {
        return Job::of_file(args, method, file, |scene| (scene, None)).map(Some);
    }
    if args.from.is_none() {
        args.robot.chain.need_urdf(args.robot.urdf.as_deref())?;
    }
    if args.robot.urdf.is_some() {
        return urdf_job(args, method).map(Some);
    }
    let Some(p) = p else {
        return Ok(None);
    };
    let mut scene = scene(args, p)?;
    if args.self_collision {
        scene.arm = super::robot::with_self_collision(scene.arm, &[], &scene.theta0)?;
    }
    let method = method.unwrap_or(Method::NUMERICAL);
    let nets = super::space_networks::networks(&args.networks, p, &[method])?;
    Ok(Some(Job {
        robot: Robot::preset(p),
        scene,
        method,
        nets,
        pose: pose_spec(args.task, args.target.as_ref(), args.orientation_weight)?,
        source: Some(RobotSource::shipped(p.key)),
    }))
}

/// The job of `--urdf FILE`: its chain, a scene of its own (see
/// [`SceneArgs::urdf`]) with the options given; the reader's warnings on
/// stderr.
fn urdf_job(args: &SceneArgs, method: Option<Method>) -> Result<Job, String> {
    let Some(path) = &args.robot.urdf else {
        return Err("--urdf: no file".into());
    };
    let super::robot::UrdfRobot {
        robot,
        scene: s,
        volumes,
        source,
    } = super::robot::urdf_scene(path, &args.robot.chain, args.joint_limits.clone())?;
    let mut scene = apply(args, s, super::robot::DEFAULT_RADIUS)?;
    if args.target.is_none() {
        // The line from where --theta0 (or the middle) puts the hand.
        super::robot::own_line_from_start(&mut scene)?;
    }
    let srdf = &args.robot.chain.srdf;
    if args.self_collision || srdf.is_some() {
        let disabled = match srdf {
            Some(path) => super::robot::srdf_pairs(path, &volumes)?,
            None => Vec::new(),
        };
        scene.arm = super::robot::with_self_collision(scene.arm, &disabled, &scene.theta0)?;
    }
    let method = method.unwrap_or(Method::NUMERICAL);
    let nets = networks_for(&args.networks, &robot, &scene.arm, &[method])?;
    Ok(Job {
        robot,
        scene,
        method,
        nets,
        pose: pose_spec(args.task, args.target.as_ref(), args.orientation_weight)?,
        source: Some(source),
    })
}

/// Runs `simulate` for a spatial job: `--arm A`, or `--from` a spatial
/// run file.
pub fn simulate(args: &SimulateArgs, job: Job) -> Result<(), String> {
    if job.pose.is_some() {
        return super::pose::simulate(args, job);
    }
    output(args, job)
}

/// Runs the job's scene with its method (and the networks of the learned
/// methods) and prints what `args` ask for: the run file (`--json`, what
/// `--from` replays), CSV or a summary.
fn output(args: &SimulateArgs, job: Job) -> Result<(), String> {
    let Job {
        robot,
        scene,
        method,
        nets,
        source,
        ..
    } = job;
    super::summary::run_and_write::<Chain, 3>(args, scene, method, nets, source, |scene, traj| {
        summary(&robot, scene, traj)
    })
}

fn summary(robot: &Robot, scene: &SpaceScene, traj: &Trajectory<3>) -> String {
    let s = &traj.summary;
    let mut out = String::new();
    let point = |v: [f64; 3]| format!("({:.4}, {:.4}, {:.4})", v[0], v[1], v[2]);
    let _ = writeln!(
        out,
        "{} | method {} | dt {} s | tf {} s",
        robot.label, traj.method, scene.dt, scene.tf
    );
    let goal = if scene.path.is_line() {
        format!("target {}", point(scene.target))
    } else {
        format!("path {} ending at {}", scene.path, point(scene.path_end()))
    };
    super::summary::ends(&mut out, &traj.steps, point, &goal);
    super::summary::contact(&mut out, s, &scene.arm, &scene.obstacles);
    let _ = writeln!(
        out,
        "final hand error                      {:.3e} m",
        s.final_error
    );
    let _ = writeln!(
        out,
        "largest tracking error                {:.3e} m",
        s.max_tracking_error
    );
    if let Some(why) = traj
        .method
        .without_limits(scene.arm.joint_limits().is_some())
    {
        let _ = writeln!(out, "{why}");
    }
    if !s.target_reachable {
        let _ = writeln!(
            out,
            "target is out of the arm's reach (farther than {:.3} m from the shoulder): not reached{}",
            scene.arm.reach(),
            if s.auto_damping {
                " (damping schedule switched on automatically)"
            } else {
                ""
            }
        );
    }
    super::summary::limits(&mut out, s);
    out
}
