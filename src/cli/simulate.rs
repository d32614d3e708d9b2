//! `redundant-ik simulate`: one planning run, as a readable summary or JSON.

use std::path::PathBuf;

use clap::Args;
use redundant_ik::export::{self, RunFile};
use redundant_ik::{Arm, DampingSchedule, Method, Planner, Scene, Trajectory};

use std::fmt::Write as _;

use redundant_ik::obstacle::Placement;
use redundant_ik::scene::Param;

use super::NetworkArgs;
use super::{emit, method_help, parse_arm, parse_list, parse_method, parse_obstacle, parse_pair};

/// Scene options shared by `simulate`, `figure` and `atlas`.
#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// A run file (the JSON of `simulate --json`, or of the page's
    /// "Download run"): its scene, task and, unless --mode is given, its
    /// method. No other scene option goes with it.
    #[arg(long)]
    pub from: Option<PathBuf>,
    /// Paper task (1 or 2) that provides the defaults.
    #[arg(long, default_value_t = 1)]
    pub task: u32,
    /// The arm, POST:L1,L2,... in metres, or a preset's name: paper (the
    /// default, 0.5:0.6,0.85,0.6), four or five.
    #[arg(long, value_parser = parse_arm, allow_hyphen_values = true)]
    pub arm: Option<Arm>,
    /// Obstacle centre X,Y in metres, with its own radius X,Y,R (repeat for
    /// several obstacles).
    #[arg(long, value_parser = parse_obstacle, allow_hyphen_values = true)]
    pub obstacle: Vec<Placement>,
    /// Radius of the obstacles given without one, in metres.
    #[arg(long, allow_hyphen_values = true)]
    pub radius: Option<f64>,
    /// Gain lambda of the obstacle vector, eq. (14).
    #[arg(long, allow_hyphen_values = true)]
    pub lambda: Option<f64>,
    /// Constant damping factor delta, eqs. (6), (17).
    #[arg(long, allow_hyphen_values = true)]
    pub delta: Option<f64>,
    /// Switch on the damping schedule near singular poses.
    #[arg(long)]
    pub damping: bool,
    /// Runge-Kutta step (s).
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Final time (s), a whole number of steps.
    #[arg(long, allow_hyphen_values = true)]
    pub tf: Option<f64>,
    /// End of the straight line X,Y in metres.
    #[arg(long, value_parser = parse_pair, allow_hyphen_values = true)]
    pub target: Option<[f64; 2]>,
    /// Initial joint angles in radians, one per link (default: the task's
    /// for the paper's arm, else the page's start pose for the arm).
    #[arg(long, allow_hyphen_values = true)]
    pub theta0: Option<String>,
    /// Closed-loop gain K in Xdot + K (X_ref - X); 0 is the paper's open loop.
    #[arg(long, allow_hyphen_values = true)]
    pub feedback: Option<f64>,
    /// Influence distance d_i (m) of distance, priority and qp: link-obstacle
    /// pairs closer than this count (default 0.3).
    #[arg(long, allow_hyphen_values = true)]
    pub influence: Option<f64>,
    /// Stop distance d_s (m) of the velocity dampers (qp) and of the escape
    /// speed (priority); floors the clearance of distance (default 0.02).
    #[arg(long, allow_hyphen_values = true)]
    pub stop_distance: Option<f64>,
    /// Damper gain xi (m/s): the approach speed allowed at d_i (qp;
    /// default 1).
    #[arg(long, allow_hyphen_values = true)]
    pub damper_gain: Option<f64>,
    /// Weight w of the task slack (qp; default 1e6).
    #[arg(long, allow_hyphen_values = true)]
    pub slack_weight: Option<f64>,
    /// Gain lambda_d of the clearance potential (distance; default 1e-3).
    #[arg(long, allow_hyphen_values = true)]
    pub distance_gain: Option<f64>,
    /// Escape speed (m/s) of the point closest to an obstacle at d_s
    /// (priority; default 0.1).
    #[arg(long, allow_hyphen_values = true)]
    pub escape_speed: Option<f64>,
    /// Limit of every joint's rate in rad/s (qp; default 1.5).
    #[arg(long, allow_hyphen_values = true)]
    pub rate_limit: Option<f64>,
    /// Smoothing eps (m^2) of the sign in eq. (15) of the exact obstacle
    /// vector (numerical, Case 1; default 0, the paper's).
    #[arg(long, allow_hyphen_values = true)]
    pub sign_smoothing: Option<f64>,
    /// Newton-Schulz steps refining the learned Phi with the pose's J
    /// (Cases 1 and 3; default 0, the paper's).
    #[arg(long, allow_hyphen_values = true)]
    pub refine: Option<f64>,
    #[command(flatten)]
    pub networks: NetworkArgs,
}

impl SceneArgs {
    /// The run file of `--from`, read and checked, if given.
    pub fn run_file(&self) -> Result<Option<RunFile>, String> {
        let Some(path) = &self.from else {
            return Ok(None);
        };
        let size = std::fs::metadata(path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?
            .len();
        if size > export::MAX_RUN_FILE_BYTES as u64 {
            return Err(format!(
                "{}: {size} bytes, more than the {} a run file may have",
                path.display(),
                export::MAX_RUN_FILE_BYTES
            ));
        }
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let run = RunFile::from_json(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        // The file is the whole scene: an option beside it would be ignored.
        let given = [
            ("--arm", self.arm.is_some()),
            ("--obstacle", !self.obstacle.is_empty()),
            ("--radius", self.radius.is_some()),
            ("--lambda", self.lambda.is_some()),
            ("--delta", self.delta.is_some()),
            ("--damping", self.damping),
            ("--dt", self.dt.is_some()),
            ("--tf", self.tf.is_some()),
            ("--target", self.target.is_some()),
            ("--theta0", self.theta0.is_some()),
            ("--feedback", self.feedback.is_some()),
            ("--influence", self.influence.is_some()),
            ("--stop-distance", self.stop_distance.is_some()),
            ("--damper-gain", self.damper_gain.is_some()),
            ("--slack-weight", self.slack_weight.is_some()),
            ("--distance-gain", self.distance_gain.is_some()),
            ("--escape-speed", self.escape_speed.is_some()),
            ("--rate-limit", self.rate_limit.is_some()),
        ];
        if let Some((flag, _)) = given.iter().find(|(_, set)| *set) {
            return Err(format!(
                "--from gives the whole scene; {flag} cannot change it"
            ));
        }
        Ok(Some(run))
    }

    /// The paper task: `--task`, or the run file's.
    pub fn task(&self) -> Result<u32, String> {
        Ok(self.run_file()?.map_or(self.task, |r| r.task))
    }

    /// The method: `--mode`, else the run file's, else `numerical`.
    pub fn method(&self, arg: &MethodArg) -> Result<Method, String> {
        Ok(match arg.method {
            Some(m) => m,
            None => self.run_file()?.map_or(Method::NUMERICAL, |r| r.mode),
        })
    }

    /// The scene these options describe, validated.
    pub fn scene(&self) -> Result<Scene, String> {
        if let Some(run) = self.run_file()? {
            return Ok(run.scene);
        }
        let mut s = Scene::task(self.task).map_err(|e| e.to_string())?;
        if let Some(arm) = &self.arm {
            if *arm != s.arm {
                s.theta0 = redundant_ik::session::start_pose(arm);
                s.arm = arm.clone();
            }
        }
        let radius = self.radius.unwrap_or(s.obstacles[0].radius);
        if !self.obstacle.is_empty() {
            s.obstacles = self.obstacle.iter().map(|o| o.obstacle(radius)).collect();
        } else {
            for o in &mut s.obstacles {
                o.radius = radius;
            }
        }
        if let Some(v) = self.lambda {
            s.lambda = v;
        }
        if let Some(v) = self.delta {
            s.delta = v;
        }
        if self.damping {
            s.damping = Some(DampingSchedule::default());
        }
        if let Some(v) = self.dt {
            s.dt = v;
        }
        if let Some(v) = self.tf {
            s.tf = v;
        }
        if let Some(v) = self.target {
            s.target = v;
        }
        if let Some(v) = &self.theta0 {
            s.theta0 = parse_list(v).map_err(|e| format!("--theta0: {e}"))?;
        }
        if let Some(v) = self.feedback {
            s.feedback_gain = v;
        }
        // All at once, then checked together (d_s < d_i whatever the order).
        let a = &mut s.avoidance;
        for (field, value) in [
            (&mut a.influence, self.influence),
            (&mut a.stop_distance, self.stop_distance),
            (&mut a.damper_gain, self.damper_gain),
            (&mut a.slack_weight, self.slack_weight),
            (&mut a.distance_gain, self.distance_gain),
            (&mut a.rate_limit, self.rate_limit),
            (&mut a.escape_speed, self.escape_speed),
        ] {
            if let Some(v) = value {
                *field = v;
            }
        }
        for (param, value) in [
            (Param::SignSmoothing, self.sign_smoothing),
            (Param::Refine, self.refine),
        ] {
            if let Some(v) = value {
                param
                    .set(&mut s, v)
                    .map_err(|e| format!("{}: {e}", param.info().flag))?;
            }
        }
        s.validate().map_err(|e| e.to_string())?;
        Ok(s)
    }

    /// Runs the scene with `method`.
    pub fn run(&self, method: Method) -> Result<(Scene, Trajectory), String> {
        let scene = self.scene()?;
        let nets = self.networks.for_method(method)?;
        let traj = Planner::run(scene.clone(), method, nets).map_err(|e| e.to_string())?;
        Ok((scene, traj))
    }
}

/// The `--mode` option of `simulate` and `figure` (default: the run
/// file's method with `--from`, else `numerical`).
#[derive(Args, Debug, Clone)]
pub struct MethodArg {
    #[arg(long = "mode", value_parser = parse_method, help = method_help())]
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
    let (scene, traj) = args.scene.run(method)?;
    let mut out = String::new();
    macro_rules! w {
        ($o:ident, $($arg:tt)*) => {{
            let _ = writeln!($o, $($arg)*);
        }};
    }
    if args.csv {
        return emit(&export::run_csv(&scene, &traj.steps));
    }
    if args.json {
        return emit(&format!("{}\n", RunFile::new(task, scene, traj).to_json()));
    }
    let s = &traj.summary;
    let first = &traj.steps[0];
    w!(
        out,
        "Task {} | mode {} | lambda {} | delta {}{} | dt {} s | tf {} s{}",
        task,
        traj.method,
        scene.lambda,
        scene.delta,
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
    w!(
        out,
        "end    theta = [{}]  X = ({:.6}, {:.6})  target ({}, {})",
        fmt_list(&last.theta),
        last.ee[0],
        last.ee[1],
        scene.target[0],
        scene.target[1]
    );
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

fn fmt_list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.4}"))
        .collect::<Vec<_>>()
        .join(", ")
}
