//! `redundant-ik bench`: the library's in-process benchmarks
//! ([`redundant_ik::bench`]) timed with `std::time::Instant`, with heap
//! allocations counted by the binary's global allocator.

use std::time::Instant;

use clap::Args;
use redundant_ik::bench::{self, Options, Report};
use redundant_ik::Method;

use super::emit;

/// Options of `redundant-ik bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Timed batches per figure (the median is reported; at least 5).
    #[arg(long, default_value_t = 7)]
    pub batches: usize,
    /// Shortest batch in milliseconds.
    #[arg(long, default_value_t = 20.0)]
    pub batch_ms: f64,
    /// Skip the Levenberg-Marquardt epoch (about a second in all).
    #[arg(long)]
    pub no_lm: bool,
    /// Skip the atlas (three runs of 8,405 tasks, about two seconds in all).
    #[arg(long)]
    pub no_atlas: bool,
    /// Methods to time, comma-separated; `paper` (the default) for the
    /// paper's five, `all` for every method (with --arm, every method by
    /// default).
    #[arg(long = "methods", alias = "modes", default_value = "paper")]
    pub methods: String,
    /// The shipped network set the network methods run: paper or reach.
    #[arg(long, default_value = "paper", value_parser = ["paper", "reach"])]
    pub networks: String,
    /// Newton-Schulz steps on the learned Phi (Cases 1 and 3; 0 = the paper's).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=8))]
    pub refine: u32,
    /// An arm in space (panda or iiwa14): time the RK4 step of its own task
    /// in every method that runs it, and count its allocations, instead of
    /// the planar figures.
    #[arg(long)]
    pub arm: Option<String>,
    /// With --arm or --urdf: the task, position (the hand's, the default)
    /// or pose (the hand's full pose, the start orientation kept; for a
    /// preset with a second sphere and self-collision, issue 40's goal
    /// scene; the methods without networks).
    #[arg(long, value_parser = super::task::parse_task)]
    pub task: Option<super::task::TaskArg>,
    /// A robot's URDF instead of --arm: time the RK4 step of its own scene
    /// (the middle of its ranges, the hand's line 0.15 m along y, no
    /// sphere; self-collision with --srdf) in every method without
    /// networks.
    #[arg(long, conflicts_with = "arm")]
    pub urdf: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub chain: super::robot::ChainArgs,
    /// The networks' arithmetic: f64 (the default) or f32 (the kernels the
    /// page can run, `window.demo.bench({ precision: 'f32' })`).
    #[arg(long, default_value = "f64")]
    pub precision: redundant_ik::nn::Precision,
    /// Run the networks on the portable x86-64 baseline kernels instead of
    /// the AVX2 + FMA ones chosen at run time (to measure what that choice buys).
    #[arg(long)]
    pub baseline_kernels: bool,
}

/// Runs `redundant-ik bench`.
pub fn run(args: &BenchArgs) -> Result<(), String> {
    if !(args.batch_ms.is_finite() && args.batch_ms > 0.0 && args.batch_ms <= 10_000.0) {
        return Err("--batch-ms must lie between 0 and 10000".into());
    }
    if !(5..=1000).contains(&args.batches) {
        return Err("--batches must lie between 5 and 1000".into());
    }
    let opts = Options {
        batch_ms: args.batch_ms,
        batches: args.batches,
        lm_epoch: !args.no_lm,
        paper_variants: true,
        atlas: !args.no_atlas,
        methods: Method::parse_list(&args.methods).map_err(|e| e.to_string())?,
        networks: args
            .networks
            .parse()
            .map_err(|e: redundant_ik::Error| e.to_string())?,
        refine: args.refine,
        precision: args.precision,
    };
    redundant_ik::nn::kernel::set_runtime_dispatch(!args.baseline_kernels);
    #[allow(clippy::disallowed_methods)] // the native CLI has a clock
    let origin = Instant::now();
    let now = move || origin.elapsed().as_secs_f64() * 1e3;
    let count = super::allocation_counter();
    let probes = bench::Probes {
        now_ms: &now,
        allocations: Some(&count),
    };
    let pose = match args.task {
        None | Some(super::task::TaskArg::Position) => false,
        Some(super::task::TaskArg::Pose) => true,
        Some(t) => {
            return Err(format!(
                "--task {}: bench --arm and --urdf time the task position or pose",
                t.name()
            ))
        }
    };
    if let Some(key) = &args.arm {
        // For an arm in space the default is every method.
        let all = args.methods == "paper";
        let p = redundant_ik::space::SpacePreset::named(key)
            .map_err(|e| format!("--arm: {e} (bench --arm takes an arm in space)"))?;
        return space(Subject::Preset(p), pose, &opts, all, &probes, args.json);
    }
    if let Some(path) = &args.urdf {
        let super::robot::UrdfRobot {
            robot,
            mut scene,
            volumes,
            ..
        } = super::robot::urdf_scene(path, &args.chain, None)?;
        if let Some(srdf) = &args.chain.srdf {
            let disabled = super::robot::srdf_pairs(srdf, &volumes)?;
            scene.arm = super::robot::with_self_collision(scene.arm, &disabled, &scene.theta0)?;
        }
        let all = args.methods == "paper";
        return space(
            Subject::Robot(robot, Box::new(scene)),
            pose,
            &opts,
            all,
            &probes,
            args.json,
        );
    }
    let c = &args.chain;
    if args.task.is_some() {
        return Err(
            "--task goes with --arm or --urdf: the planar benchmark times the paper's tasks".into(),
        );
    }
    c.need_urdf(None)?;
    let report = bench::run(&opts, &probes).map_err(|e| e.to_string())?;
    if args.json {
        let json = serde_json::to_string(&report).map_err(|e| e.to_string())?;
        return emit(&format!("{json}\n"));
    }
    let nets = redundant_ik::networks::builtin_set(opts.networks).map_err(|e| e.to_string())?;
    let sizes = |f: &redundant_ik::networks::WeightsFile| {
        let s: Vec<String> = f.nets[0].mlp.sizes.iter().map(|n| n.to_string()).collect();
        format!("{} {}", f.variant.name(), s.join("-"))
    };
    emit(&table(
        &report,
        [sizes(nets.phi_file()), sizes(nets.v_file())],
    ))
}

/// The report as a table; `layers` names the set's `Phi` and `v` networks.
fn table(r: &Report, layers: [String; 2]) -> String {
    let mut s = format!(
        "median of timed batches after a warm-up; Task 1, start pose; network kernels: {}\n\n\
         method              theta_dot      RK4 step   allocs/step\n",
        r.kernels
    );
    let allocs = |m: Method| {
        r.allocs_per_step
            .as_ref()
            .and_then(|a| a.get(m))
            .map_or("-".to_string(), |a| format!("{a}"))
    };
    for &(m, theta_dot) in &r.theta_dot_ns.0 {
        s.push_str(&format!(
            "{:<14} {:>14.1} ns {:>10.1} ns {:>12}\n",
            m.name(),
            theta_dot,
            r.step_ns.get(m).unwrap_or(f64::NAN),
            allocs(m)
        ));
    }
    let f = &r.forward_ns;
    s.push_str(&format!(
        "\nforward pass: Phi {} {:.1} ns, v {} {:.1} ns\n",
        layers[0], f.phi, layers[1], f.v
    ));
    if let (Some(plain), Some(rows)) = (f.phi_plain, f.phi_rows) {
        s.push_str(&format!(
            "              Phi plain 3-35-14-6 {plain:.1} ns, Phi rows 3 x 3-35-14-2 {rows:.1} ns\n"
        ));
    }
    if let Some(ms) = r.atlas_ms {
        s.push_str(&format!(
            "atlas of Task 1, 41 x 41 cells, five methods (8,405 runs), one thread: {:.2} s\n",
            ms / 1e3
        ));
    }
    if let Some(ms) = r.lm_epoch_ms {
        s.push_str(&format!(
            "one LM epoch, Phi 2-35-14-6, 3,000 samples (2,100 training): {ms:.1} ms\n"
        ));
    }
    s
}

/// What `bench` times in space: a preset's own task, or a robot read
/// from URDF in its own scene (`--urdf`).
pub enum Subject {
    /// `--arm KEY`.
    Preset(&'static redundant_ik::space::SpacePreset),
    /// `--urdf FILE`: its name, key and scene (self-collision checked
    /// where `--srdf` is given).
    Robot(super::robot::Robot, Box<redundant_ik::scene::SpaceScene>),
}

/// `bench --arm KEY` or `--urdf FILE`: the RK4 step of the arm's own task
/// (`pose`: the hand's pose; for a preset issue 40's goal scene,
/// [`redundant_ik::bench::space::pose_task`]) in every method that runs
/// it (ns, median of the timed batches) and its allocations per step. A
/// robot from URDF has no networks.
fn space(
    subject: Subject,
    pose: bool,
    opts: &Options,
    all: bool,
    probes: &bench::Probes,
    json: bool,
) -> Result<(), String> {
    use redundant_ik::bench::space as sb;
    use redundant_ik::scene::PoseScene;
    let (key, label, learned) = match &subject {
        Subject::Preset(p) => (
            p.key.to_string(),
            p.label.to_string(),
            redundant_ik::networks::space::SpaceNetworkSet::for_arm(p.key).is_some() && !pose,
        ),
        Subject::Robot(r, _) => (r.key.clone(), r.label.clone(), false),
    };
    let count = super::allocation_counter();
    let e = |e: redundant_ik::Error| e.to_string();
    let mut rows = Vec::new();
    for &m in redundant_ik::planner::methods::ALL
        .iter()
        .filter(|m| all || opts.methods.contains(m))
        .filter(|m| !m.uses_networks() || learned)
    {
        let (ns, allocs) = match (&subject, pose) {
            (Subject::Preset(p), false) => (
                sb::step_ns(p.key, m, opts, probes),
                sb::allocs_per_step(p.key, m, opts, &count),
            ),
            (Subject::Preset(p), true) => {
                let scene = sb::pose_task(p.key).map_err(e)?;
                (
                    sb::scene_step_ns(scene.clone(), m, None, opts, probes),
                    sb::scene_allocs_per_step(scene, m, None, &count),
                )
            }
            (Subject::Robot(_, scene), false) => (
                sb::scene_step_ns((**scene).clone(), m, None, opts, probes),
                sb::scene_allocs_per_step((**scene).clone(), m, None, &count),
            ),
            (Subject::Robot(_, scene), true) => {
                let scene = PoseScene::from_space(
                    (**scene).clone(),
                    None,
                    redundant_ik::space::ORIENTATION_WEIGHT,
                )
                .map_err(e)?;
                (
                    sb::scene_step_ns(scene.clone(), m, None, opts, probes),
                    sb::scene_allocs_per_step(scene, m, None, &count),
                )
            }
        };
        rows.push((m.name(), ns.map_err(e)?, allocs.map_err(e)?));
    }
    if json {
        let obj: serde_json::Map<String, serde_json::Value> = rows
            .iter()
            .map(|(m, ns, a)| {
                (
                    m.to_string(),
                    serde_json::json!({ "step_ns": ns, "allocs_per_step": a }),
                )
            })
            .collect();
        return emit(&format!(
            "{}\n",
            serde_json::json!({ "arm": key, "task": if pose { "pose" } else { "position" }, "methods": obj })
        ));
    }
    let mut s = format!(
        "median of timed batches after a warm-up; {label}, its own task{}\n\nmethod              RK4 step   allocs/step\n",
        if pose { " (the hand's pose)" } else { "" }
    );
    for (m, ns, a) in rows {
        s.push_str(&format!("{m:<14} {ns:>10.1} ns {a:>12}\n"));
    }
    emit(&s)
}
