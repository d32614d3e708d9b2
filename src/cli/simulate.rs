//! `redundant-ik simulate`: one planning run, as a readable summary or JSON.

use std::path::PathBuf;

use clap::Args;
use redundant_ik::export::{self, RunFile};
use redundant_ik::run::Run;
use redundant_ik::{DampingSchedule, Method, Planner, Scene, Trajectory};

use std::fmt::Write as _;

use redundant_ik::arm::{JointLimits, RateLimits};
use redundant_ik::geometry::Placement;
use redundant_ik::planner::methods::{DELTA, LAMBDA};
use redundant_ik::scene::{JointWeighting, PAPER_RADIUS};

use super::params::{Given, ParamArgs};
use super::path_arg::{parse_path, PathArg};
use super::NetworkArgs;
use super::{
    emit, method_help, parse_arm, parse_list, parse_method, parse_numbers, ArmChoice, Numbers,
};

/// Parses `--joint-limits` (the core's syntax, `LO:HI,...`).
fn parse_joint_limits(s: &str) -> Result<JointLimits, String> {
    s.parse().map_err(|e: redundant_ik::Error| e.to_string())
}

/// Parses `--rate-limits` (the core's syntax, `R,...`).
fn parse_rate_limits(s: &str) -> Result<RateLimits, String> {
    s.parse().map_err(|e: redundant_ik::Error| e.to_string())
}

/// Parses `--joint-weighting` (`none` or `wln`).
fn parse_weighting(s: &str) -> Result<JointWeighting, String> {
    s.parse().map_err(|e: redundant_ik::Error| e.to_string())
}

/// Scene options shared by `simulate`, `figure` and `atlas`.
#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// Which arguments the command line gave (first, so that it sees them
    /// all before the other fields take theirs).
    #[command(flatten)]
    pub given: Given,
    /// A run file (the JSON of `simulate --json`, or of the page's
    /// "Download run"): its scene, task and, unless --method is given, its
    /// method. No other scene option goes with it.
    #[arg(long)]
    pub from: Option<PathBuf>,
    /// The task: for a planar arm the paper's task (1 or 2) that provides
    /// the defaults; for an arm in space position (the hand's position,
    /// the default) or pose (the hand's full pose, its start orientation
    /// kept unless --target gives one: X,Y,Z,ROLL,PITCH,YAW).
    #[arg(long, default_value = "1", value_parser = super::task::parse_task)]
    pub task: super::task::TaskArg,
    /// The pose task's Z = diag(1, 1, 1, z, z, z) of eqs. (6)-(7): z in
    /// m²/rad², a radian of orientation error weighing as sqrt(z) metres
    /// of position error where the solve is damped [default: 1, Z = I]
    #[arg(long, allow_hyphen_values = true)]
    pub orientation_weight: Option<f64>,
    /// Check the arm in space's capsules against each other: every pair
    /// but adjacent links, pairs an SRDF disables (--srdf, with --urdf)
    /// and pairs touching at the zero pose or the start pose; distance,
    /// priority and qp keep them apart, and a run where two meet is a
    /// self-collision.
    #[arg(long)]
    pub self_collision: bool,
    /// The arm, POST:L1,L2,... in metres, or a preset's name: paper (the
    /// default, 0.5:0.6,0.85,0.6), four, five or iiwa-planar (a KUKA iiwa14 in its plane, with its limits and its own task); in space, panda (Franka Panda) or iiwa14 (KUKA LBR iiwa 14), each with its limits and its own task (docs/space.md).
    #[arg(long, value_parser = parse_arm, allow_hyphen_values = true)]
    pub arm: Option<ArmChoice>,
    /// Position limits of the arm's joints, LO:HI,LO:HI,... in radians,
    /// one pair per link (e.g. -2.0944:2.0944,-2.0944:2.0944,-2.0944:2.0944);
    /// the start pose must lie within them. Default: unlimited (or the
    /// preset's).
    #[arg(long, value_parser = parse_joint_limits, allow_hyphen_values = true)]
    pub joint_limits: Option<JointLimits>,
    /// Rate limits of the arm's joints, R,R,... in rad/s, one per link.
    /// Default: unlimited (or the preset's).
    #[arg(long, value_parser = parse_rate_limits, allow_hyphen_values = true)]
    pub rate_limits: Option<RateLimits>,
    /// How the methods of eq. (5) (none, numerical, Cases 1-3, distance,
    /// manipulability, jointrange) use the joint limits: none (W = I, the
    /// paper's) or wln (weighted least norm, W from the limits).
    #[arg(long, value_parser = parse_weighting, default_value = "none")]
    pub joint_weighting: JointWeighting,
    /// Obstacle centre X,Y in metres, with its own radius X,Y,R (repeat for
    /// several obstacles); for an arm in space a sphere X,Y,Z or X,Y,Z,R.
    #[arg(long, value_parser = parse_numbers, allow_hyphen_values = true)]
    pub obstacle: Vec<Numbers>,
    /// Radius of the obstacles given without one, in metres.
    #[arg(long, allow_hyphen_values = true)]
    pub radius: Option<f64>,
    /// Make the floor (y = 0) and the post obstacles for distance, priority
    /// and qp, and a link below the floor or across the post a collision.
    #[arg(long)]
    pub floor: bool,
    /// Switch on the damping schedule near singular poses.
    #[arg(long)]
    pub damping: bool,
    /// Runge-Kutta step (s).
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Final time (s), a whole number of steps.
    #[arg(long, allow_hyphen_values = true)]
    pub tf: Option<f64>,
    /// End of the straight line X,Y in metres (X,Y,Z for an arm in space;
    /// X,Y,Z,ROLL,PITCH,YAW for its hand's pose, URDF's fixed-axis
    /// roll-pitch-yaw in radians, which makes the task the pose).
    #[arg(long, value_parser = parse_numbers, allow_hyphen_values = true)]
    pub target: Option<Numbers>,
    /// The path the hand follows at constant speed over tf: line (the
    /// straight line to --target, the default), circle:CX,CY[,LAPS] (the
    /// circle about CX,CY through the hand's start, counter-clockwise,
    /// LAPS whole laps, default 1) or points:X,Y;X,Y;... (the polyline from
    /// the hand through the points, ending at the last; at most 64). For
    /// an arm in space circle:CX,CY,CZ,NX,NY,NZ[,LAPS] (in the plane
    /// through C with normal N, counter-clockwise seen from N's tip) or
    /// points:X,Y,Z;X,Y,Z;... (docs/space.md).
    #[arg(long, value_parser = parse_path, allow_hyphen_values = true)]
    pub path: Option<PathArg>,
    /// Initial joint angles in radians, one per link (default: the task's
    /// for the paper's arm, else the page's start pose for the arm).
    #[arg(long, allow_hyphen_values = true)]
    pub theta0: Option<String>,
    /// Closed-loop gain K in Xdot + K (X_ref - X); 0 is the paper's open loop.
    #[arg(long, allow_hyphen_values = true)]
    pub feedback: Option<f64>,
    /// The methods' parameters, one flag each (`--lambda`, `--delta`,
    /// `--influence`, ...), from their declarations.
    #[command(flatten)]
    pub params: ParamArgs,
    #[command(flatten)]
    pub networks: NetworkArgs,
    /// A robot's URDF in place of --arm.
    #[command(flatten)]
    pub robot: super::robot::UrdfArgs,
}

impl SceneArgs {
    /// The scene's flags given on the command line besides `--from`
    /// (every argument of [`SceneArgs`] but `--from` and the networks,
    /// which the run needs from outside the file), as `--flag`.
    pub fn beside_from(&self) -> Vec<String> {
        let networks = <NetworkArgs as clap::Args>::augment_args(clap::Command::new("networks"));
        self.given.flags_of::<SceneArgs>(|id| {
            id == "from" || networks.get_arguments().any(|n| n.get_id() == id)
        })
    }

    /// The paper task: `--task`, or the run file's.
    pub fn task(&self) -> Result<u32, String> {
        let task = self.task.paper()?;
        Ok(self.run_file()?.map_or(task, |r| r.task.unwrap_or(task)))
    }

    /// The method: `--method`, else the run file's, else `numerical`.
    pub fn method(&self, arg: &MethodArg) -> Result<Method, String> {
        Ok(match arg.method {
            Some(m) => m,
            None => self.run_file()?.map_or(Method::NUMERICAL, |r| r.method),
        })
    }

    /// The run these options describe with `method`: the run file's (its
    /// networks and their precision, where it names them; the network
    /// options then cannot change them), else the scene of the options
    /// with the networks they choose.
    pub fn spec(&self, method: Method) -> Result<Run, String> {
        if let Some(file) = self.run_file()? {
            let mut run = file.run();
            run.method = method;
            match (&run.networks, self.networks.given(&self.given)) {
                (Some(_), Some(flag)) => {
                    return Err(format!(
                        "--from names the networks its run used; {flag} cannot change them"
                    ))
                }
                (None, _) => {
                    run.networks = Some(self.networks.choice()?);
                    if self.given.has("precision") {
                        run.precision = self.networks.precision;
                    }
                }
                (Some(_), None) => {}
            }
            return Ok(run);
        }
        Ok(Run {
            task: self.task.paper()?,
            method,
            scene: self.scene()?,
            networks: Some(self.networks.choice()?),
            precision: self.networks.precision,
        })
    }

    /// The scene these options describe, validated.
    pub fn scene(&self) -> Result<Scene, String> {
        if let Some(run) = self.run_file()? {
            return Ok(run.scene);
        }
        let mut s = Scene::task(self.task.paper()?).map_err(|e| e.to_string())?;
        if let Some(ArmChoice::Space(p)) = &self.arm {
            return Err(format!(
                "--arm {} is an arm in space: this command takes planar arms (simulate runs it)",
                p.key
            ));
        }
        if let Some(ArmChoice::Planar(arm)) = &self.arm {
            if !arm.same_geometry(&s.arm) {
                s.theta0 = redundant_ik::session::start_pose(arm);
            }
            s.arm = arm.clone();
            s.use_preset_task();
        }
        if self.joint_limits.is_some() || self.rate_limits.is_some() {
            let arm = s.arm.clone();
            s.arm = arm
                .with_limits(
                    self.joint_limits.clone().or(s.arm.joint_limits().cloned()),
                    self.rate_limits.clone().or(s.arm.rate_limits().cloned()),
                )
                .map_err(|e| e.to_string())?;
        }
        let radius = s.obstacles.first().map_or(PAPER_RADIUS, |o| o.radius);
        self.settings_onto(&mut s, disc, radius)?;
        if let Some(Numbers(v)) = &self.target {
            s.target = match v[..] {
                [x, y] => [x, y],
                _ => {
                    return Err(format!(
                        "--target: a planar arm's target is X,Y, got {} numbers",
                        v.len()
                    ))
                }
            };
        }
        if let Some(v) = &self.path {
            s.path = v.planar()?;
        }
        s.validate().map_err(|e| e.to_string())?;
        Ok(s)
    }

    /// The options every arm's scene takes, on `s`: the obstacles (each
    /// read by `place`, `radius` or `--radius` where it gives none; without
    /// `--obstacle`, the scene's with `--radius`), damping, the joint
    /// weighting, the floor, `dt`, `tf`, the start, the closed-loop gain and
    /// the methods' parameters (set all at once, then checked together:
    /// `d_s < d_i` whatever the order). The arm, its limits, the target and
    /// the path are each kind's.
    pub(super) fn settings_onto<A, P, const M: usize, const D: usize>(
        &self,
        s: &mut redundant_ik::scene::Scene<A, P, M, D>,
        place: fn(&Numbers) -> Result<Placement<D>, String>,
        radius: f64,
    ) -> Result<(), String> {
        let radius = self.radius.unwrap_or(radius);
        if !self.obstacle.is_empty() {
            s.obstacles = self
                .obstacle
                .iter()
                .map(|o| place(o).map(|p| p.ball(radius)))
                .collect::<Result<_, _>>()?;
        } else {
            for o in &mut s.obstacles {
                o.radius = radius;
            }
        }
        if self.damping {
            s.damping = Some(DampingSchedule::default());
        }
        s.weighting = self.joint_weighting;
        s.floor = self.floor;
        if let Some(v) = self.dt {
            s.dt = v;
        }
        if let Some(v) = self.tf {
            s.tf = v;
        }
        if let Some(v) = &self.theta0 {
            s.theta0 = parse_list(v).map_err(|e| format!("--theta0: {e}"))?;
        }
        if let Some(v) = self.feedback {
            s.feedback_gain = v;
        }
        s.params
            .set_all(&self.params.values)
            .map_err(|e| e.to_string())
    }

    /// Runs the scene with `method`: the run and what it did.
    pub fn run(&self, method: Method) -> Result<(Run, Trajectory), String> {
        let run = self.spec(method)?;
        let nets = run.surrogate_for(method).map_err(|e| e.to_string())?;
        let traj = Planner::run(run.scene.clone(), method, nets).map_err(|e| e.to_string())?;
        Ok((run, traj))
    }
}

/// An obstacle for a planar arm: `X,Y` or `X,Y,R`; a sphere's `X,Y,Z,R`
/// is refused with a reason.
fn disc(n: &Numbers) -> Result<Placement<2>, String> {
    match n.0[..] {
        [x, y] => Ok(Placement { centre: [x, y], radius: None }),
        [x, y, r] => Ok(Placement { centre: [x, y], radius: Some(r) }),
        [_, _, _, _] => Err("--obstacle: X,Y,Z,R places a sphere, for an arm in space (--arm panda or iiwa14); a planar arm takes X,Y or X,Y,R".into()),
        _ => Err(format!("--obstacle: a planar arm's obstacle is X,Y or X,Y,R, got {} numbers", n.0.len())),
    }
}

/// The `--method` option of `simulate` and `figure` (default: the run
/// file's method with `--from`, else `numerical`).
#[derive(Args, Debug, Clone)]
pub struct MethodArg {
    #[arg(long = "method", alias = "mode", value_parser = parse_method, help = method_help())]
    pub method: Option<Method>,
}

/// Options of `redundant-ik simulate`.
#[derive(Args, Debug)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub method: MethodArg,
    /// Print one JSON object (every step and the summary) instead of text:
    /// what `--from` reads back.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print the run as CSV instead of text: t, each joint angle, the hand,
    /// the reference point, the tracking error, the smallest
    /// link-to-obstacle clearance and the collision flag, one line per step.
    #[arg(long)]
    pub csv: bool,
}

/// Runs `redundant-ik simulate`.
pub fn run(args: &SimulateArgs) -> Result<(), String> {
    let method = args.scene.method(&args.method)?;
    let task = args.scene.task()?;
    let (run, traj) = args.scene.run(method)?;
    let scene = run.scene.clone();
    let mut out = String::new();
    macro_rules! w {
        ($o:ident, $($arg:tt)*) => {{
            let _ = writeln!($o, $($arg)*);
        }};
    }
    if args.csv {
        return emit(&export::run_csv(&traj.steps));
    }
    if args.json {
        return emit(&format!("{}\n", RunFile::new(run, traj).to_json()));
    }
    let s = &traj.summary;
    let first = &traj.steps[0];
    w!(
        out,
        "Task {} | method {} | lambda {} | delta {}{} | dt {} s | tf {} s{}",
        task,
        traj.method,
        scene.param(&LAMBDA),
        scene.param(&DELTA),
        if scene.damping.is_some() {
            " + schedule"
        } else {
            ""
        },
        scene.dt,
        scene.tf,
        if scene.feedback_gain > 0.0 {
            format!(" | feedback K = {}", scene.feedback_gain)
        } else {
            String::new()
        }
    );
    w!(
        out,
        "start  theta = [{}]  X = ({:.6}, {:.6})",
        fmt_list(&first.theta),
        first.ee[0],
        first.ee[1]
    );
    let last = traj.steps.last().unwrap_or(first);
    // The line's end is the target; another path names itself and its end.
    let end = scene.path_end();
    let goal = if scene.path.is_line() {
        format!("target ({}, {})", end[0], end[1])
    } else {
        format!(
            "path {} ending at ({:.6}, {:.6})",
            scene.path, end[0], end[1]
        )
    };
    w!(
        out,
        "end    theta = [{}]  X = ({:.6}, {:.6})  {goal}",
        fmt_list(&last.theta),
        last.ee[0],
        last.ee[1],
    );
    if let Some(l) = scene.arm.joint_limits() {
        w!(out, "joint limits {l} rad");
    }
    if let Some(why) = traj
        .method
        .without_limits(scene.arm.joint_limits().is_some())
    {
        w!(out, "{why}");
    }
    if let Some(r) = scene.arm.rate_limits() {
        w!(out, "rate limits  {r} rad/s");
    }
    for ob in &scene.obstacles {
        w!(
            out,
            "obstacle at ({}, {}), radius {} m",
            ob.centre[0],
            ob.centre[1],
            ob.radius
        );
    }
    match s.min_distance {
        Some(d) => w!(
            out,
            "smallest link-to-obstacle distance  {d:.4} m  -> {}",
            if s.collided {
                "COLLISION"
            } else {
                "no collision"
            }
        ),
        None => w!(out, "no obstacles"),
    }
    w!(
        out,
        "final end-effector error            {:.3e} m",
        s.final_error
    );
    w!(
        out,
        "largest tracking error              {:.3e} m",
        s.max_tracking_error
    );
    if !s.target_reachable {
        w!(
            out,
            "target is out of the arm's reach: not reached{}",
            if s.auto_damping {
                " (damping schedule switched on automatically)"
            } else {
                ""
            }
        );
    } else if !s.reached {
        w!(out, "target not reached (error above 5 mm)");
    }
    if s.max_delta > 0.0 {
        w!(
            out,
            "largest damping delta used          {:.3e}",
            s.max_delta
        );
    }
    if s.handover_steps > 0 {
        w!(
            out,
            "near a singular pose the exact damped Phi stood in for the network in {} steps",
            s.handover_steps
        );
    }
    if s.out_of_range_steps > 0 {
        w!(
            out,
            "warning: {} steps left the networks' trained range",
            s.out_of_range_steps
        );
    }
    emit(&out)
}

/// Numbers to four places, joined by `, ` (joint angles in a summary).
pub(super) fn fmt_list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.4}"))
        .collect::<Vec<_>>()
        .join(", ")
}
