//! The networks of an arm in space on the command line: which ones a
//! learned method runs with (`--networks panda-reach`, `--phi-weights`,
//! `--v-weights`), `train --arm panda` and `eval --arm panda`.

use std::fmt::Write as _;
use std::sync::Arc;

use redundant_ik::networks::space::{SpaceNetworkSet, SpaceNetworks};
use redundant_ik::networks::{NetKind, NetworkSet};
use redundant_ik::planner::{Networks, Planner};
use redundant_ik::space::SpacePreset;
use redundant_ik::training::space::TrainArm;
use redundant_ik::Method;

use super::emit;

/// The user's own networks for an arm in space, `--phi-weights` and
/// `--v-weights` (both, or neither: `None`), in `--precision`.
pub fn own(args: &super::NetworkArgs) -> Result<Option<Arc<SpaceNetworks>>, String> {
    match (&args.phi_weights, &args.v_weights) {
        (Some(phi), Some(v)) => {
            let (phi, v) = (super::read_weights_file(phi)?, super::read_weights_file(v)?);
            SpaceNetworks::read(&phi, &v)
                .map(|n| Some(Arc::new(n).in_precision(args.precision)))
                .map_err(|e| e.to_string())
        }
        (None, None) => Ok(None),
        _ => Err(
            "an arm in space takes its own networks as --phi-weights and --v-weights together"
                .into(),
        ),
    }
}

/// The networks the learned methods among `methods` run with on the preset
/// `p`, in `--precision`: `--phi-weights` and `--v-weights` (spatial
/// weights files, both), else `--networks` (a set trained for `p`; left at
/// its planar default, the set shipped for `p`). `None` when no method of
/// `methods` learns.
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
    if let Some(nets) = own(args)? {
        return Ok(Some(nets));
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
    set.load()
        .map(|n| Some(n.in_precision(args.precision)))
        .map_err(|e| e.to_string())
}

/// The networks the learned methods among `methods` run with on `robot`
/// (whose chain is `chain`): a preset's as [`networks`]
/// finds them; for another robot only the user's weights files, checked
/// against its chain.
pub fn networks_for(
    args: &super::NetworkArgs,
    robot: &super::robot::Robot,
    chain: &redundant_ik::space::Chain,
    methods: &[Method],
) -> Result<Option<Arc<SpaceNetworks>>, String> {
    if let Some(p) = robot.preset {
        return networks(args, p, methods);
    }
    if !methods.iter().any(|m| m.uses_networks()) {
        return Ok(None);
    }
    let Some(nets) = own(args)? else {
        return Err(format!(
            "no networks are shipped for {}: give its own as --phi-weights and --v-weights",
            robot.label
        ));
    };
    nets.check_chain(chain).map_err(|e| e.to_string())?;
    Ok(Some(nets))
}

/// The robot of the URDF at `path` as a training's arm: its own scene
/// (from `theta0`, else the middle of its joints' ranges) with a sphere in
/// the way of its middle joint ([`redundant_ik::training::space::TrainArm::new`]); with
/// `--srdf`, self-collision checked in that scene.
pub fn urdf_arm(
    path: &std::path::Path,
    chain: &super::robot::ChainArgs,
    theta0: Option<&str>,
) -> Result<TrainArm, String> {
    let super::robot::UrdfRobot {
        robot,
        mut scene,
        volumes,
        ..
    } = super::robot::urdf_scene(path, chain, None)?;
    if let Some(text) = theta0 {
        scene.theta0 = super::parse_list(text).map_err(|e| format!("--theta0: {e}"))?;
        scene
            .arm
            .check_angles(&scene.theta0)
            .map_err(|e| format!("--theta0: {e}"))?;
        super::robot::own_line_from_start(&mut scene)?;
    }
    if let Some(srdf) = &chain.srdf {
        let disabled = super::robot::srdf_pairs(srdf, &volumes)?;
        scene.arm = super::robot::with_self_collision(scene.arm, &disabled, &scene.theta0)?;
    }
    TrainArm::new(&robot.key, scene).map_err(|e| e.to_string())
}

/// `redundant-ik train --arm panda`: the whole-reach recipe in space
/// ([`redundant_ik::training::space`]), by Adam, with a progress bar.
pub fn train(args: &super::train::TrainArgs, net: NetKind, arm: TrainArm) -> Result<(), String> {
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
    if args.chain.srdf.is_some() {
        return Err(
            "--srdf: self-collision does not enter the networks' training (the sphere's does)"
                .into(),
        );
    }
    let name = arm.name.clone();
    let mut spec = SpaceTrainSpec::reach(arm, net, args.seed);
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
    let bar = super::train::epochs_bar(args.quiet, epochs)?;
    let stopped = std::cell::Cell::new(false);
    #[allow(clippy::disallowed_methods)] // the native CLI has a clock
    let start = std::time::Instant::now();
    let mut file = train_space(&spec, |r| {
        bar.set_position(r.epoch as u64);
        bar.set_message(format!("train {:.3e}  val {:.3e}", r.train_mse, r.val_mse));
        // Ctrl-C in the Python package stops between epochs.
        stopped.set(super::embed::interrupted());
        !stopped.get()
    })
    .map_err(|e| e.to_string())?;
    let seconds = super::train::trained_in(&bar, stopped.get(), start)?;
    file.training.seconds = Some(seconds);
    super::train::write_weights(file.to_json(), &args.out)?;
    let r = &file.nets[0].report;
    emit(&format!(
        "{} network for {}, whole reach in space, {} samples, seed {}, trained in {seconds:.1} s -> {}\n  {:?}: {} epochs (best {}), stop: {:?}; MSE (mapminmax units) train {:.3e}, val {:.3e}, test {:.3e}\n",
        args.net, name, spec.samples, spec.seed, args.out,
        file.nets[0].mlp.sizes, r.epochs, r.best_epoch, r.stop, r.train_mse, r.val_mse, r.test_mse
    ))
}

/// `redundant-ik eval --arm panda`: the median relative errors of the
/// networks on fresh samples of their training distributions, and the
/// preset's task in every paper method with the given refinement and
/// feedback.
pub fn eval(args: &super::eval::EvalArgs, arm: TrainArm) -> Result<(), String> {
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
            SpaceNetworks::read(
                &super::read_weights_file(std::path::Path::new(phi))?,
                &super::read_weights_file(std::path::Path::new(v))?,
            )
            .map_err(|e| e.to_string())?,
        ),
        // The set shipped for the chain's preset; a chain read from URDF
        // is never a preset's rows, even where its robot has the name.
        _ => match SpacePreset::of(arm.chain()).and_then(|p| SpaceNetworkSet::for_arm(p.key)) {
            Some(set) => set.load().map_err(|e| e.to_string())?,
            None => {
                return Err(match SpaceNetworkSet::for_arm(&arm.name) {
                    Some(set) => format!(
                        "the shipped {} networks were trained for the preset's chain of modified-DH rows, not for this {} read from URDF (a chain of joint frames): give --phi and --v (train --urdf writes them)",
                        set.name(),
                        arm.name
                    ),
                    None => format!(
                        "no networks are shipped for {}: give --phi and --v (train --urdf writes them)",
                        arm.name
                    ),
                })
            }
        },
    };
    nets.check_chain(arm.chain()).map_err(|e| e.to_string())?;
    let (phi_err, v_err) =
        space_accuracy(&arm, &nets, args.samples, args.seed).map_err(|e| e.to_string())?;
    let mut scene = arm.scene.clone();
    scene.feedback_gain = args.feedback;
    scene
        .params
        .set(&REFINE, f64::from(args.refine))
        .map_err(|e| e.to_string())?;
    let sphere = scene.obstacles.first().map_or(String::new(), |s| {
        let [x, y, z] = s.centre;
        format!(
            ", past the sphere at ({x:.3}, {y:.3}, {z:.3}) m of radius {:.3} m",
            s.radius
        )
    });
    let mut out = format!(
        "Networks for {}: median relative error on {} fresh samples (seed {})\n  Phi {:?}: {phi_err:.3e}\n  v   {:?}: {v_err:.3e}\n\nThe task (refine {}, K = {}{sphere}):\n",
        arm.name,
        args.samples,
        args.seed,
        nets.phi_file().nets[0].mlp.sizes,
        nets.v_file().nets[0].mlp.sizes,
        args.refine,
        args.feedback
    );
    for m in methods::PAPER {
        let run = Planner::run(scene.clone(), m, Some(nets.clone() as Networks<_, 3>))
            .map_err(|e| e.to_string())?;
        let s = run.summary;
        let _ = writeln!(
            out,
            "  {:<14} clearance {:>8.4} m  collision steps {:>3}{}  final error {:.3e} m",
            m.label(),
            s.min_clearance.unwrap_or(f64::INFINITY),
            s.collision_steps,
            if scene.arm.self_pairs().is_empty() {
                String::new()
            } else {
                format!("  self-collision steps {:>3}", s.self_collision_steps)
            },
            s.final_error
        );
    }
    emit(&out)
}

/// The networks the job of a run file runs `method` with: those the file
/// names, in its arithmetic (no network option may change them); else the
/// user's own given again, in the file's arithmetic unless `--precision`
/// says otherwise. Checked against the file's `chain`.
pub fn of_run_file(
    args: &super::NetworkArgs,
    given: &super::params::Given,
    named: Option<redundant_ik::run::NetworkChoice<SpaceNetworkSet>>,
    precision: redundant_ik::nn::Precision,
    robot: &super::robot::Robot,
    chain: &redundant_ik::space::Chain,
    method: Method,
) -> Result<Option<Arc<SpaceNetworks>>, String> {
    match named.filter(|_| method.uses_networks()) {
        Some(choice) => {
            if let Some(flag) = args.given(given) {
                return Err(format!(
                    "--from names the networks its run used; {flag} cannot change them"
                ));
            }
            let nets = choice.load().map_err(|e| e.to_string())?;
            nets.check_chain(chain).map_err(|e| e.to_string())?;
            Ok(Some(nets.in_precision(precision)))
        }
        None => Ok(networks_for(args, robot, chain, &[method])?.map(|n| {
            if given.has("precision") {
                n
            } else {
                n.in_precision(precision)
            }
        })),
    }
}

/// What a run file records of the networks a run used: the shipped set
/// by name, else the files whole; and their arithmetic (`f64` without
/// networks).
pub fn recorded(
    used: Option<&SpaceNetworks>,
) -> (
    Option<redundant_ik::run::NetworkChoice<SpaceNetworkSet>>,
    redundant_ik::nn::Precision,
) {
    use redundant_ik::run::NetworkChoice;
    let choice = used.map(|n| {
        shipped_set(n).map_or_else(
            || NetworkChoice::Files {
                phi: n.phi_file().to_json().unwrap_or_default(),
                v: n.v_file().to_json().unwrap_or_default(),
            },
            NetworkChoice::Set,
        )
    });
    let precision = used.map_or(redundant_ik::nn::Precision::F64, |n| n.precision());
    (choice, precision)
}

/// The shipped set `nets` is, if it is one (the user's files are not).
pub fn shipped_set(nets: &SpaceNetworks) -> Option<SpaceNetworkSet> {
    SpaceNetworkSet::ALL.into_iter().find(|s| {
        let (phi, v) = s.files();
        SpaceNetworks::read(phi, v)
            .is_ok_and(|n| n.phi_file() == nets.phi_file() && n.v_file() == nets.v_file())
    })
}
