//! `simulate` for an arm in space (`--arm panda`, `--arm iiwa14`): the
//! scene from the preset's task and the scene options (or a spatial run
//! file's, `--from`), the run through the planner, and its summary,
//! the run file (JSON, `redundant_ik::export::SpaceRunFile`) or CSV.

use std::fmt::Write as _;
use std::sync::Arc;

use redundant_ik::export::{is_space_run, SpaceRunFile};
use redundant_ik::ik::DampingSchedule;
use redundant_ik::networks::space::{SpaceNetworkSet, SpaceNetworks};
use redundant_ik::nn::Precision;
use redundant_ik::planner::{Networks, Planner, Trajectory};
use redundant_ik::run::NetworkChoice;
use redundant_ik::scene::{SpacePath, SpaceScene};
use redundant_ik::space::{SpacePreset, Sphere};
use redundant_ik::Method;

use super::path_arg::PathArg;
use super::simulate::{SceneArgs, SimulateArgs};
use super::{emit, parse_list, Numbers};

/// The scene of `args` for the preset `p`: its task, with the options
/// given. Options a spatial run does not take yet are refused by name.
pub fn scene(args: &SceneArgs, p: &'static SpacePreset) -> Result<SpaceScene, String> {
    if args.from.is_some() {
        return Err("--from gives the whole scene; --arm cannot change it".into());
    }
    let mut s = SpaceScene::preset(p);
    if args.joint_limits.is_some() || args.rate_limits.is_some() {
        let c = s.arm.clone();
        s.arm = c
            .with_limits(
                args.joint_limits.clone().or(s.arm.joint_limits().cloned()),
                args.rate_limits.clone().or(s.arm.rate_limits().cloned()),
            )
            .map_err(|e| e.to_string())?;
    }
    let radius = args.radius.unwrap_or(s.obstacles[0].radius);
    if !args.obstacle.is_empty() {
        s.obstacles = args
            .obstacle
            .iter()
            .map(|o| sphere(o, radius))
            .collect::<Result<_, _>>()?;
    } else {
        for o in &mut s.obstacles {
            o.radius = radius;
        }
    }
    if let Some(Numbers(v)) = &args.target {
        s.target = match v[..] {
            [x, y, z] => [x, y, z],
            _ => {
                return Err(format!(
                    "--target: the hand of an arm in space goes to X,Y,Z, got {} numbers",
                    v.len()
                ))
            }
        };
    }
    if args.damping {
        s.damping = Some(DampingSchedule::default());
    }
    s.weighting = args.joint_weighting;
    s.floor = args.floor;
    if let Some(v) = args.dt {
        s.dt = v;
    }
    if let Some(v) = args.tf {
        s.tf = v;
    }
    if let Some(v) = &args.theta0 {
        s.theta0 = parse_list(v).map_err(|e| format!("--theta0: {e}"))?;
    }
    if let Some(v) = args.feedback {
        s.feedback_gain = v;
    }
    if let Some(v) = &args.path {
        s.path = space_path(v)?;
    }
    s.params
        .set_all(&args.params.values)
        .map_err(|e| e.to_string())?;
    s.validate().map_err(|e| e.to_string())?;
    Ok(s)
}

/// A sphere: `X,Y,Z` or `X,Y,Z,R`; a planar disc's `X,Y` is refused with
/// a reason.
fn sphere(n: &Numbers, radius: f64) -> Result<Sphere, String> {
    match n.0[..] {
        [x, y, z] => Ok(Sphere::new([x, y, z], radius)),
        [x, y, z, r] => Ok(Sphere::new([x, y, z], r)),
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
    let (Some(path), Some(text)) = (&args.from, args.run_text()?) else {
        return Ok(None);
    };
    if !is_space_run(&text) {
        return Ok(None);
    }
    let file = SpaceRunFile::from_json(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    if let Some(flag) = args.beside_from().first() {
        return Err(format!(
            "--from gives the whole scene; {flag} cannot change it"
        ));
    }
    Ok(Some(file))
}

/// What a command runs on an arm in space: the preset, the scene, the
/// method and the networks of a learned method, from `--arm A` and the
/// scene options, or from a spatial run file (`--from`: its scene, its
/// method unless `--method` is given, the networks it names in its
/// arithmetic).
pub struct Job {
    /// The arm.
    pub preset: &'static SpacePreset,
    /// The scene.
    pub scene: SpaceScene,
    /// The method.
    pub method: Method,
    /// The networks, for a learned method.
    pub nets: Option<Arc<SpaceNetworks>>,
}

/// The spatial job of `args` (`p`: the arm in space `--arm` names, if it
/// names one), or `None` for a planar one.
pub fn job(
    args: &SceneArgs,
    method: Option<Method>,
    p: Option<&'static SpacePreset>,
) -> Result<Option<Job>, String> {
    if let Some(file) = run_file(args)? {
        return from_file(args, method, file).map(Some);
    }
    let Some(p) = p else {
        return Ok(None);
    };
    let scene = scene(args, p)?;
    let method = method.unwrap_or(Method::NUMERICAL);
    let nets = super::space_networks::networks(&args.networks, p, &[method])?;
    Ok(Some(Job {
        preset: p,
        scene,
        method,
        nets,
    }))
}

/// A spatial run file's job: its scene again, with its method unless
/// `method` is given.
fn from_file(args: &SceneArgs, method: Option<Method>, file: SpaceRunFile) -> Result<Job, String> {
    let p = SpacePreset::of(&file.scene.arm)
        .ok_or("the run file's arm is none of the arms in space this tool knows")?;
    let method = method.unwrap_or(file.method);
    let nets = match file.networks.filter(|_| method.uses_networks()) {
        Some(choice) => {
            // The file names its networks and their arithmetic.
            if let Some(flag) = args.networks.given(&args.given) {
                return Err(format!(
                    "--from names the networks its run used; {flag} cannot change them"
                ));
            }
            let nets = choice.load().map_err(|e| e.to_string())?;
            nets.check_chain(&file.scene.arm)
                .map_err(|e| e.to_string())?;
            Some(nets.in_precision(file.precision))
        }
        // The user's own weights, given again: in the file's arithmetic
        // unless --precision says otherwise.
        None => super::space_networks::networks(&args.networks, p, &[method])?.map(|n| {
            if args.given.has("precision") {
                n
            } else {
                n.in_precision(file.precision)
            }
        }),
    };
    Ok(Job {
        preset: p,
        scene: file.scene,
        method,
        nets,
    })
}

/// Runs `simulate` for a spatial job: `--arm A`, or `--from` a spatial
/// run file.
pub fn simulate(args: &SimulateArgs, job: Job) -> Result<(), String> {
    output(args, job.preset, job.scene, job.method, job.nets)
}

/// Runs `scene` with `method` (and the networks of the learned methods)
/// and prints what `args` ask for: the run file (`--json`, what `--from`
/// replays), CSV or a summary.
fn output(
    args: &SimulateArgs,
    p: &'static SpacePreset,
    scene: SpaceScene,
    method: Method,
    nets: Option<Arc<SpaceNetworks>>,
) -> Result<(), String> {
    let used = nets.clone();
    let planner = Planner::new(scene.clone(), method, nets.map(|n| n as Networks<_, 3>))
        .map_err(|e| e.to_string())?;
    let traj = planner.run_to_end().map_err(|e| e.to_string())?;
    if args.json {
        let networks = used.as_deref().map(|n| {
            super::space_networks::shipped_set(n).map_or_else(
                || NetworkChoice::Files {
                    phi: n.phi_file().to_json().unwrap_or_default(),
                    v: n.v_file().to_json().unwrap_or_default(),
                },
                NetworkChoice::Set,
            )
        });
        let precision = used.map_or(Precision::F64, |n| n.precision());
        let text = SpaceRunFile::of(None, scene, traj, networks, precision).to_json();
        return emit(&format!("{text}\n"));
    }
    if args.csv {
        return emit(&redundant_ik::export::run_csv(&traj.steps));
    }
    emit(&summary(p, &scene, &traj))
}

fn summary(p: &SpacePreset, scene: &SpaceScene, traj: &Trajectory<3>) -> String {
    let s = &traj.summary;
    let mut out = String::new();
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let point = |v: [f64; 3]| format!("({:.4}, {:.4}, {:.4})", v[0], v[1], v[2]);
    let first = &traj.steps[0];
    let last = traj.steps.last().unwrap_or(first);
    let _ = writeln!(
        out,
        "{} | method {} | dt {} s | tf {} s",
        p.label, traj.method, scene.dt, scene.tf
    );
    let _ = writeln!(
        out,
        "start  theta = [{}]  hand {}",
        list(&first.theta),
        point(first.ee)
    );
    let goal = if scene.path.is_line() {
        format!("target {}", point(scene.target))
    } else {
        format!("path {} ending at {}", scene.path, point(scene.path_end()))
    };
    let _ = writeln!(
        out,
        "end    theta = [{}]  hand {}  {goal}",
        list(&last.theta),
        point(last.ee)
    );
    for sp in &scene.obstacles {
        let _ = writeln!(
            out,
            "sphere at {}, radius {} m (the links' capsules: radius {} m)",
            point(sp.centre),
            sp.radius,
            scene.arm.radius()
        );
    }
    match s.min_clearance {
        Some(c) => {
            let _ = writeln!(
                out,
                "smallest capsule-to-sphere clearance  {c:.4} m  -> {}",
                if s.collision_steps > 0 {
                    format!("COLLISION in {} steps", s.collision_steps)
                } else {
                    "no collision".into()
                }
            );
        }
        None => {
            let _ = writeln!(out, "no spheres");
        }
    }
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
    if s.limit_steps > 0 {
        let _ = writeln!(out, "a joint past its limit in {} steps", s.limit_steps);
    }
    if s.relaxed_steps > 0 {
        let _ = writeln!(
            out,
            "the program's constraints were relaxed in {} steps",
            s.relaxed_steps
        );
    }
    out
}

/// `atlas` for a spatial job (`--arm A`, or `--from` a spatial run file:
/// its scene): the sphere over a grid on a slice, in every method that
/// runs in space (or those asked for); a table, JSON or CSV.
pub fn atlas(args: &super::atlas::AtlasArgs, job: Job) -> Result<(), String> {
    use redundant_ik::atlas::space::{default_region, slice, Plane};
    use redundant_ik::atlas::{Class, Grid};
    if args.out.is_some() {
        return Err("--out: the maps of an atlas in space are not drawn yet; --json and --csv give the cells".into());
    }
    let (p, scene) = (job.preset, job.scene);
    let plane = match &args.slice {
        Some(t) => t.parse::<Plane>().map_err(|e| format!("--slice: {e}"))?,
        None => Plane::through_line(&scene),
    };
    let methods = match &args.methods {
        Some(list) => super::atlas::parse_methods(list)?,
        None => redundant_ik::planner::methods::ALL
            .iter()
            .copied()
            .filter(|m| m.in_space())
            .filter(|m| !m.uses_networks() || SpaceNetworkSet::for_arm(p.key).is_some())
            .collect(),
    };
    // A run file's networks where it names them, else those the flags give.
    let nets = match job.nets {
        Some(n) if methods.iter().any(|m| m.uses_networks()) => Some(n),
        _ => super::space_networks::networks(&args.scene.networks, p, &methods)?,
    };
    let region = match &args.region {
        Some(r) => match parse_list(r).map_err(|e| format!("--region: {e}"))?[..] {
            [a, b, c, d] => [a, b, c, d],
            _ => {
                return Err(format!(
                    "--region needs four numbers u0,u1,v0,v1 in the slice's axes, got '{r}'"
                ))
            }
        },
        None => default_region(&scene, plane),
    };
    let grid = Grid::new(region, args.grid).map_err(|e| e.to_string())?;
    if let Some(t) = args.threads {
        if t == 0 {
            return Err("--threads must be at least 1".into());
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build_global()
            .map_err(|e| format!("cannot start {t} threads: {e}"))?;
    }
    #[allow(clippy::disallowed_methods)] // the native CLI has a clock
    let start = std::time::Instant::now();
    let mut a = slice(&scene, plane, grid, &methods, nets.as_ref()).map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    a.arm = Some(p.key);
    if args.json {
        let json = serde_json::to_string(&a).map_err(|e| e.to_string())?;
        return emit(&format!("{json}\n"));
    }
    if args.csv {
        let mut out = String::from("x,y,z");
        for m in &a.methods {
            let _ = write!(out, ",{m},{m}_clearance,{m}_final_error");
        }
        out.push('\n');
        for c in &a.cells {
            let _ = write!(out, "{},{},{}", c.centre[0], c.centre[1], c.centre[2]);
            for o in &c.outcomes {
                let opt = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
                let _ = write!(
                    out,
                    ",{},{},{}",
                    o.class.name(),
                    opt(o.min_clearance),
                    opt(o.final_error)
                );
            }
            out.push('\n');
        }
        return emit(&out);
    }
    let [u, v] = plane.axes();
    let [u0, u1, v0, v1] = a.grid.region;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Atlas of the {} task on the slice {plane}: {n} x {n} sphere centres over {u} {u0:.3}..{u1:.3} m, {v} {v0:.3}..{v1:.3} m (radius {} m)",
        p.label,
        a.radius,
        n = a.grid.n
    );
    let _ = writeln!(
        out,
        "{} runs in {seconds:.2} s; {} cells where avoidance is possible\n",
        a.cells.len() * a.methods.len(),
        a.avoidable()
    );
    let _ = writeln!(out, "{:<22} {:>8}   cells: success / collision / limit / missed / failed / path_blocked / start_overlap; relaxed steps", "method", "success");
    for (k, m) in a.methods.iter().enumerate() {
        let counts: Vec<String> = Class::ALL
            .iter()
            .map(|&c| a.count(k, c).to_string())
            .collect();
        let relaxed: usize = a.cells.iter().map(|c| c.outcomes[k].relaxed_steps).sum();
        let _ = writeln!(
            out,
            "{:<22} {:>8}   {}; {relaxed}",
            m.label(),
            a.success_rate(k)
                .map_or("–".into(), |r| format!("{:.1}%", 100.0 * r)),
            counts.join(" / ")
        );
    }
    let _ = writeln!(out, "\nsuccess: no collision, no joint past a limit and within 5 mm of the target, over the cells where avoidance is possible");
    emit(&out)
}
