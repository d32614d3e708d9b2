//! `redundant-ik figure`: the paper's stroboscopic figures (Figs. 2-11) as
//! SVG, a run's time series (`--plots`, the page's plots) or every method
//! over time (`--compare`), for a planar arm; for an arm in space the run's
//! two orthographic views, its plots and the comparison. The drawing is the library's
//! ([`redundant_ik::figure`]), the same the page saves.

use std::path::{Path, PathBuf};

use std::sync::Arc;

use clap::Args;
use redundant_ik::figure;
use redundant_ik::networks::space::SpaceNetworks;
use redundant_ik::planner::{methods, Method, Networks, Planned, SceneOf, Surrogate};
use redundant_ik::scene::PoseScene;
use redundant_ik::space::{Chain, PoseChain};
use redundant_ik::{Planner, Scene, Trajectory};

use super::simulate::{MethodArg, SceneArgs};
use super::space::Job;

/// Options of `redundant-ik figure`.
#[derive(Args, Debug)]
pub struct FigureArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub method: MethodArg,
    /// Output SVG file, or with --all a directory.
    #[arg(long)]
    pub out: PathBuf,
    /// Write the whole set: both tasks in every available method, plus the
    /// comparison figure of each task.
    #[arg(long, conflicts_with = "from")]
    pub all: bool,
    /// Instead of the arm: clearance and tracking error over time for every
    /// method on one figure.
    #[arg(long, conflicts_with_all = ["all", "plots"])]
    pub compare: bool,
    /// Instead of the arm: the run's distance to the obstacle, tracking
    /// error and joint angles over time (the page's plots).
    #[arg(long, conflicts_with = "all")]
    pub plots: bool,
    /// Draw the manipulability ellipse {J theta_dot : |theta_dot| <= 1} (for an arm in space, the ellipsoid's three principal ellipses) at
    /// the final pose (at 1/4 scale, as the page's legend switch does).
    #[arg(long, conflicts_with_all = ["compare", "plots"])]
    pub ellipse: bool,
    /// Draw the arm every this many steps (the page's stroboscopic trace).
    #[arg(long, default_value_t = redundant_ik::session::STROBE_EVERY)]
    pub every: usize,
}

fn write(path: &Path, svg: &str) -> Result<(), String> {
    std::fs::write(path, svg).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// Runs `redundant-ik figure`.
pub fn run(args: &FigureArgs) -> Result<(), String> {
    if args.every == 0 {
        return Err("--every must be at least 1".into());
    }
    let e = |x: redundant_ik::Error| x.to_string();
    let task = args.scene.task()?;
    if args.compare {
        let scene = args.scene.scene()?;
        let runs = run_all_methods(&args.scene, &scene)?;
        return write(
            &args.out,
            &figure::compare_svg(task, &scene, &runs).map_err(e)?,
        );
    }
    if !args.all {
        let (run, traj) = args.scene.run(args.scene.method(&args.method)?)?;
        let scene = run.scene;
        let svg = if args.plots {
            figure::series_svg(task, &scene, &traj)
        } else {
            figure::arm_svg_with(task, &scene, &traj, args.every, args.ellipse)
        };
        return write(&args.out, &svg.map_err(e)?);
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create directory {}: {e}", args.out.display()))?;
    for task in [1, 2] {
        let mut sa = args.scene.clone();
        sa.task = super::task::TaskArg::Paper(task);
        let scene = sa.scene()?;
        let runs = run_all_methods(&sa, &scene)?;
        for traj in &runs {
            let path = args.out.join(format!("task{task}_{}.svg", traj.method));
            write(
                &path,
                &figure::arm_svg_with(task, &scene, traj, args.every, args.ellipse).map_err(e)?,
            )?;
        }
        let path = args.out.join(format!("task{task}_compare.svg"));
        write(&path, &figure::compare_svg(task, &scene, &runs).map_err(e)?)?;
    }
    Ok(())
}

/// `figure` for an arm in space: its run's two views (`--ellipse`: the
/// ellipsoid at the end), its plots (`--plots`), or every method's runs
/// (`--compare`, `--all`); of the hand's position, or of its pose where
/// the job is of the pose (its orientation's error in the title and the
/// plots).
pub fn space(args: &FigureArgs, job: Job) -> Result<(), String> {
    if args.every == 0 {
        return Err("--every must be at least 1".into());
    }
    let e = |x: redundant_ik::Error| x.to_string();
    let label = job.robot.label.as_str();
    if let Some(spec) = &job.pose {
        let scene =
            PoseScene::from_space(job.scene.clone(), spec.orientation, spec.weight).map_err(e)?;
        // Cases 1 and 3 need a Phi, which no network has for the pose.
        let runs_here = |m: Method| !m.entry().info.networks.phi;
        return figures::<PoseChain, 6>(args, &job, &scene, runs_here, |one| match one {
            Drawn::Run(traj) if args.plots => figure::pose_series_svg(label, &scene, traj),
            Drawn::Run(traj) => figure::pose_svg(label, &scene, traj, args.every, args.ellipse),
            Drawn::Compare(runs) => figure::pose_compare_svg(label, &scene, runs),
        });
    }
    let scene = job.scene.clone();
    figures::<Chain, 3>(
        args,
        &job,
        &scene,
        |_| true,
        |one| match one {
            Drawn::Run(traj) if args.plots => figure::space_series_svg(label, &scene, traj),
            Drawn::Run(traj) => {
                figure::space_svg_with(label, &scene, traj, args.every, args.ellipse)
            }
            Drawn::Compare(runs) => figure::space_compare_svg(label, &scene, runs),
        },
    )
}

/// What a figure of an arm in space draws: one run, or every method's.
enum Drawn<'a, T> {
    Run(&'a T),
    Compare(&'a [T]),
}

/// Runs `scene` (of an arm in space, with `M` task coordinates) as `args`
/// ask and writes what `draw` makes of it: the job's method, or every
/// method that runs in space and `runs_here` (`--compare`; `--all` writes
/// each run's figure and the comparison into a directory).
fn figures<A, const M: usize>(
    args: &FigureArgs,
    job: &Job,
    scene: &A::Scene,
    runs_here: impl Fn(Method) -> bool,
    draw: impl Fn(Drawn<'_, Trajectory<M, A::Point>>) -> redundant_ik::Result<String>,
) -> Result<(), String>
where
    A: Planned<M>,
    A::Scene: SceneOf<A, M> + redundant_ik::model::Scene<A> + Clone,
    SpaceNetworks: Surrogate<A, M>,
{
    let e = |x: redundant_ik::Error| x.to_string();
    let run = |method: Method, nets: Option<Arc<SpaceNetworks>>| {
        Planner::run(scene.clone(), method, nets.map(|n| n as Networks<A, M>))
    };
    if !(args.compare || args.all) {
        let traj = run(job.method, job.nets.clone()).map_err(e)?;
        return write(&args.out, &draw(Drawn::Run(&traj)).map_err(e)?);
    }
    let mut runs = Vec::new();
    for &method in methods::ALL
        .iter()
        .filter(|m| m.in_space() && runs_here(**m))
    {
        let nets = match &job.nets {
            Some(n) if method.uses_networks() => Some(n.clone()),
            _ => match super::space::networks_for(
                &args.scene.networks,
                &job.robot,
                &job.scene.arm,
                &[method],
            ) {
                Ok(n) => n,
                Err(e) => {
                    eprintln!("skipping {method}: {e}");
                    continue;
                }
            },
        };
        runs.push(run(method, nets).map_err(|e| format!("{method}: {e}"))?);
    }
    let compare = draw(Drawn::Compare(&runs)).map_err(e)?;
    if args.compare {
        return write(&args.out, &compare);
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create directory {}: {e}", args.out.display()))?;
    let arm = &job.robot.key;
    for traj in &runs {
        let path = args.out.join(format!("{arm}_{}.svg", traj.method));
        write(&path, &draw(Drawn::Run(traj)).map_err(e)?)?;
    }
    write(&args.out.join(format!("{arm}_compare.svg")), &compare)
}

/// Runs `scene` with every method whose networks are available (the others
/// are skipped with a note on stderr).
fn run_all_methods(sa: &SceneArgs, scene: &Scene) -> Result<Vec<Trajectory>, String> {
    let mut runs = Vec::new();
    for &method in methods::ALL {
        let nets = match sa
            .spec(method)
            .and_then(|run| run.surrogate_for(method).map_err(|e| e.to_string()))
        {
            Ok(n) => n,
            Err(e) => {
                eprintln!("skipping {method}: {e}");
                continue;
            }
        };
        runs.push(Planner::run(scene.clone(), method, nets).map_err(|e| e.to_string())?);
    }
    Ok(runs)
}
