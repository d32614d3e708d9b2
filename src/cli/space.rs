//! `simulate` for an arm in space (`--arm panda`, `--arm iiwa14`): the
//! scene from the preset's task and the scene options (or a spatial run
//! file's, `--from`), the run through the spatial planner, and its summary,
//! the run file (JSON, `redundant_ik::export::SpaceRunFile`) or CSV.

use std::fmt::Write as _;
use std::sync::Arc;

use redundant_ik::export::{is_space_run, SpaceRunFile};
use redundant_ik::ik::DampingSchedule;
use redundant_ik::networks::space::{SpaceNetworkSet, SpaceNetworks};
use redundant_ik::networks::{NetKind, NetworkSet};
use redundant_ik::planner::space::{SpacePlanner, SpaceTrajectory};
use redundant_ik::scene::{SpacePath, SpaceScene};
use redundant_ik::space::{SpacePreset, Sphere};
use redundant_ik::Method;

use super::simulate::{PathArg, SceneArgs, SimulateArgs};
use super::{emit, parse_list, Numbers};

/// The scene of `args` for the preset `p`: its task, with the options
/// given. Options a spatial run does not take yet are refused by name.
pub fn scene(args: &SceneArgs, p: &'static SpacePreset) -> Result<SpaceScene, String> {
    if args.from.is_some() {
        return Err("--from gives the whole scene; --arm cannot change it".into());
    }
    let mut s = SpaceScene::preset(p);
    if args.joint_limits.is_some() || args.rate_limits.is_some() {
        let c = s.chain.clone();
        s.chain = c
            .with_limits(
                args.joint_limits
                    .clone()
                    .or(s.chain.joint_limits().cloned()),
                args.rate_limits.clone().or(s.chain.rate_limits().cloned()),
            )
            .map_err(|e| e.to_string())?;
    }
    let radius = args.radius.unwrap_or(s.spheres[0].radius);
    if !args.obstacle.is_empty() {
        s.spheres = args
            .obstacle
            .iter()
            .map(|o| sphere(o, radius))
            .collect::<Result<_, _>>()?;
    } else {
        for o in &mut s.spheres {
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

/// `simulate --from` of a spatial run: its scene again, with its method
/// unless `--method` is given.
pub fn replay(args: &SimulateArgs, file: SpaceRunFile) -> Result<(), String> {
    let p = SpacePreset::by_key(file.arm).ok_or("the run file's arm is not a preset")?;
    let method = args.method.method.unwrap_or(file.method);
    let nets = match file.networks.filter(|_| method.uses_networks()) {
        Some(set) => Some(set.load().map_err(|e| e.to_string())?),
        None => networks(&args.scene.networks, p, &[method])?,
    };
    output(args, p, file.scene, method, nets)
}

/// Runs `simulate` for the arm in space `p`.
pub fn simulate(args: &SimulateArgs, p: &'static SpacePreset) -> Result<(), String> {
    let scene = scene(&args.scene, p)?;
    let method = args.method.method.unwrap_or(Method::NUMERICAL);
    let nets = networks(&args.scene.networks, p, &[method])?;
    output(args, p, scene, method, nets)
}

/// The shipped set `nets` is, if it is one (the user's files are not).
fn shipped_set(nets: &SpaceNetworks) -> Option<SpaceNetworkSet> {
    SpaceNetworkSet::ALL.into_iter().find(|s| {
        let (phi, v) = s.files();
        SpaceNetworks::from_json(phi, v)
            .is_ok_and(|n| n.phi_file() == nets.phi_file() && n.v_file() == nets.v_file())
    })
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
    let traj = SpacePlanner::with_networks(scene.clone(), method, nets)
        .and_then(SpacePlanner::run)
        .map_err(|e| e.to_string())?;
    if args.json {
        let mut file = SpaceRunFile::new(p, scene, traj);
        file.networks = used.as_deref().and_then(shipped_set);
        let text = file.to_json();
        return emit(&format!("{text}\n"));
    }
    if args.csv {
        return emit(&csv(&traj));
    }
    emit(&summary(p, &scene, &traj))
}

/// One line per sample: t, the angles, the hand, the reference, the
/// error, the clearance, the joints past a limit.
fn csv(traj: &SpaceTrajectory) -> String {
    let n = traj.samples.first().map_or(0, |s| s.theta.len());
    let mut out = String::from("t");
    for i in 1..=n {
        let _ = write!(out, ",theta{i}");
    }
    out.push_str(",x,y,z,x_ref,y_ref,z_ref,tracking_error,clearance,past_limits\n");
    for s in &traj.samples {
        let _ = write!(out, "{}", s.t);
        for th in &s.theta {
            let _ = write!(out, ",{th}");
        }
        let [x, y, z] = s.hand;
        let [rx, ry, rz] = s.reference;
        let c = s.clearance.map_or(String::new(), |c| c.to_string());
        let _ = writeln!(
            out,
            ",{x},{y},{z},{rx},{ry},{rz},{},{c},{}",
            s.tracking_error, s.past_limits
        );
    }
    out
}

fn summary(p: &SpacePreset, scene: &SpaceScene, traj: &SpaceTrajectory) -> String {
    let s = &traj.summary;
    let mut out = String::new();
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let point = |v: [f64; 3]| format!("({:.4}, {:.4}, {:.4})", v[0], v[1], v[2]);
    let first = &traj.samples[0];
    let last = traj.samples.last().unwrap_or(first);
    let _ = writeln!(
        out,
        "{} | method {} | dt {} s | tf {} s",
        p.label, traj.method, scene.dt, scene.tf
    );
    let _ = writeln!(
        out,
        "start  theta = [{}]  hand {}",
        list(&first.theta),
        point(first.hand)
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
        point(last.hand)
    );
    for sp in &scene.spheres {
        let _ = writeln!(
            out,
            "sphere at {}, radius {} m (the links' capsules: radius {} m)",
            point(sp.centre),
            sp.radius,
            scene.chain.radius()
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
        s.max_error
    );
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

/// `atlas` for the arm in space `p`: the sphere over a grid on a slice, in
/// every method that runs in space (or those asked for); a table, JSON or
/// CSV.
pub fn atlas(args: &super::atlas::AtlasArgs, p: &'static SpacePreset) -> Result<(), String> {
    use redundant_ik::atlas::space::{default_region, slice, Plane};
    use redundant_ik::atlas::{Class, Grid};
    if args.out.is_some() {
        return Err("--out: the maps of an atlas in space are not drawn yet; --json and --csv give the cells".into());
    }
    let scene = scene(&args.scene, p)?;
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
    let nets = networks(&args.scene.networks, p, &methods)?;
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

/// The networks the learned methods among `methods` run with on the preset
/// `p`: `--phi-weights` and `--v-weights` (spatial weights files, both),
/// else `--networks` (a set trained for `p`; left at its planar default,
/// the set shipped for `p`). `None` when no method of `methods` learns.
pub fn networks(
    args: &super::NetworkArgs,
    p: &SpacePreset,
    methods: &[Method],
) -> Result<Option<Arc<SpaceNetworks>>, String> {
    if !methods.iter().any(|m| m.uses_networks()) {
        return Ok(None);
    }
    if args.phi_variant.is_some() {
        return Err("--phi-variant picks among the paper set's planar Phi networks".into());
    }
    match (&args.phi_weights, &args.v_weights) {
        (Some(phi), Some(v)) => {
            let (phi, v) = (super::read_weights_file(phi)?, super::read_weights_file(v)?);
            return SpaceNetworks::from_json(&phi, &v)
                .map(|n| Some(Arc::new(n)))
                .map_err(|e| e.to_string());
        }
        (None, None) => {}
        _ => {
            return Err(
                "an arm in space takes its own networks as --phi-weights and --v-weights together"
                    .into(),
            )
        }
    }
    let set = match args.networks {
        super::SetArg::Space(s) => s,
        super::SetArg::Planar(NetworkSet::Paper) => SpaceNetworkSet::for_arm(p.key).ok_or_else(|| {
            format!(
                "no networks are shipped for {}: train them (redundant-ik train --arm {} --net phi|v --out FILE) and give --phi-weights and --v-weights",
                p.key, p.key
            )
        })?,
        super::SetArg::Planar(s) => {
            return Err(format!(
                "--networks {}: a set for the planar arm, not for {}",
                s.name(),
                p.key
            ))
        }
    };
    if set.arm() != p.key {
        return Err(format!(
            "--networks {} was trained for {}, not for {}",
            set.name(),
            set.arm(),
            p.key
        ));
    }
    set.load().map(Some).map_err(|e| e.to_string())
}

/// `redundant-ik train --arm panda`: the whole-reach recipe in space
/// ([`redundant_ik::training::space`]), by Adam, with a progress bar.
pub fn train(
    args: &super::train::TrainArgs,
    net: NetKind,
    p: &'static SpacePreset,
) -> Result<(), String> {
    use indicatif::{ProgressBar, ProgressStyle};
    use redundant_ik::training::space::{train_space, SpaceTrainSpec};
    for (given, flag) in [
        (args.variant.is_some(), "--variant"),
        (args.encoding.is_some(), "--encoding"),
        (args.optimiser.is_some(), "--optimiser"),
        (
            args.recipe.as_deref().is_some_and(|r| r != "reach"),
            "--recipe paper",
        ),
    ] {
        if given {
            return Err(format!(
                "{flag}: an arm in space trains by the whole-reach recipe in space only (equivariant, (sin, cos) angles, Adam)"
            ));
        }
    }
    let mut spec = SpaceTrainSpec::reach(p, net, args.seed);
    if let Some(n) = args.samples {
        spec.samples = n;
    }
    if let Some(n) = args.epochs {
        if n == 0 {
            return Err("--epochs must be at least 1".into());
        }
        spec.adam.max_epochs = n;
    }
    if let Some(b) = args.batch {
        spec.adam.batch = b;
    }
    if let Some(r) = args.learning_rate {
        spec.adam.learning_rate = r;
    }
    if let Some(h) = &args.hidden {
        spec.hidden = super::train::parse_hidden(h)?;
    }
    if let Some(f) = args.sigma_floor {
        spec.sampling.sigma_floor = f;
    }
    if let Some(n) = args.noise {
        spec.sampling.theta_noise = n;
    }
    if let Some(eps) = args.sign_smoothing {
        spec.sampling.sign_smoothing = eps;
    }
    let epochs = spec.adam.max_epochs;
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(epochs as u64)
    };
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} epochs  {msg}")
            .map_err(|e| e.to_string())?
            .progress_chars("=> "),
    );
    #[allow(clippy::disallowed_methods)] // the native CLI has a clock
    let start = std::time::Instant::now();
    let mut file = train_space(&spec, |r| {
        bar.set_position(r.epoch as u64);
        bar.set_message(format!("train {:.3e}  val {:.3e}", r.train_mse, r.val_mse));
        true
    })
    .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    file.training.seconds = Some((seconds * 10.0).round() / 10.0);
    let json = file.to_json().map_err(|e| e.to_string())?;
    std::fs::write(&args.out, json + "\n")
        .map_err(|e| format!("cannot write {}: {e}", args.out))?;
    let r = &file.nets[0].report;
    emit(&format!(
        "{} network for {}, whole reach in space, {} samples, seed {}, trained in {seconds:.1} s -> {}\n  {:?}: {} epochs (best {}), stop: {:?}; MSE (mapminmax units) train {:.3e}, val {:.3e}, test {:.3e}\n",
        args.net, p.key, spec.samples, spec.seed, args.out,
        file.nets[0].mlp.sizes, r.epochs, r.best_epoch, r.stop, r.train_mse, r.val_mse, r.test_mse
    ))
}

/// `redundant-ik eval --arm panda`: the median relative errors of the
/// networks on fresh samples of their training distributions, and the
/// preset's task in every paper method with the given refinement and
/// feedback.
pub fn eval(args: &super::eval::EvalArgs, p: &'static SpacePreset) -> Result<(), String> {
    use redundant_ik::planner::methods::{self, REFINE};
    use redundant_ik::training::space::space_accuracy;
    if args.samples == 0 || args.samples > 100_000 {
        return Err("--samples must be between 1 and 100000 for an arm in space".into());
    }
    if args.json || args.variant.is_some() {
        return Err("--json and --variant are not built for an arm in space (one Phi network, a text report)".into());
    }
    let nets = match (&args.phi, &args.v) {
        (Some(phi), Some(v)) => Arc::new(
            SpaceNetworks::from_json(
                &super::read_weights_file(std::path::Path::new(phi))?,
                &super::read_weights_file(std::path::Path::new(v))?,
            )
            .map_err(|e| e.to_string())?,
        ),
        _ => SpaceNetworkSet::for_arm(p.key)
            .ok_or_else(|| format!("no networks are shipped for {}: give --phi and --v", p.key))?
            .load()
            .map_err(|e| e.to_string())?,
    };
    let (phi_err, v_err) =
        space_accuracy(p, &nets, args.samples, args.seed).map_err(|e| e.to_string())?;
    let mut scene = SpaceScene::preset(p);
    scene.feedback_gain = args.feedback;
    scene
        .params
        .set(&REFINE, f64::from(args.refine))
        .map_err(|e| e.to_string())?;
    let mut out = format!(
        "Networks for {}: median relative error on {} fresh samples (seed {})\n  Phi {:?}: {phi_err:.3e}\n  v   {:?}: {v_err:.3e}\n\nThe task (refine {}, K = {}):\n",
        p.key,
        args.samples,
        args.seed,
        nets.phi_file().nets[0].mlp.sizes,
        nets.v_file().nets[0].mlp.sizes,
        args.refine,
        args.feedback
    );
    for m in methods::PAPER {
        let run = SpacePlanner::with_networks(scene.clone(), m, Some(nets.clone()))
            .and_then(SpacePlanner::run)
            .map_err(|e| e.to_string())?;
        let s = run.summary;
        let _ = writeln!(
            out,
            "  {:<14} clearance {:>8.4} m  collision steps {:>3}  final error {:.3e} m",
            m.label(),
            s.min_clearance.unwrap_or(f64::INFINITY),
            s.collision_steps,
            s.final_error
        );
    }
    emit(&out)
}
