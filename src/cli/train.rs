//! `redundant-ik train`: draws a training set (from the numerical route, or
//! over the joint torus by the `reach` recipe), trains a network by
//! Levenberg-Marquardt (Matlab `trainlm` semantics) or Adam with a progress
//! bar, and writes a weights file.

use std::time::Instant;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use redundant_ik::networks::{NetKind, Variant};
use redundant_ik::training::{self, Recipe};

/// Options of `redundant-ik train`.
#[derive(Args, Debug)]
pub struct TrainArgs {
    /// Which network: `phi` (eq. 19) or `v` (the obstacle vector, eqs. 14-15).
    #[arg(long)]
    pub net: String,
    /// How to train: `paper` (section V: raw angles, data around the poses
    /// the tasks visit) or `reach` (networks for the whole workspace: angle
    /// features, Phi over the whole joint torus, v from runs with obstacles
    /// anywhere in the reach, the sign smoothed; docs/learning.md).
    /// Default: paper for a planar arm; an arm in space has reach only.
    #[arg(long, value_parser = ["paper", "reach"])]
    pub recipe: Option<String>,
    /// plain (paper), rows (phi only: one 2-output net per row of Phi) or
    /// equivariant (rotation-equivariant inputs). Default: plain for the
    /// paper's recipe, equivariant for reach.
    #[arg(long)]
    pub variant: Option<String>,
    /// How joint angles enter the networks: raw (the paper's) or angles
    /// (sin, cos). Default: the recipe's.
    #[arg(long, value_parser = ["raw", "angles"])]
    pub encoding: Option<String>,
    /// Smoothing eps (m^2) of the sign in eq. (15) for the v targets.
    /// Default: the recipe's (0 for paper, 0.1 for reach).
    #[arg(long)]
    pub sign_smoothing: Option<f64>,
    /// The arm to train for, POST:L1,L2,... in metres or a preset's name
    /// (default: the paper's). Other planar arms sample random
    /// straight-line tasks in their reach. An arm in space (panda, iiwa14)
    /// trains by the whole-reach recipe in space (docs/space.md).
    #[arg(long, value_parser = super::parse_arm, allow_hyphen_values = true)]
    pub arm: Option<super::ArmChoice>,
    /// A robot's URDF instead of --arm (docs/urdf.md): its networks by the
    /// whole-reach recipe in space, from the middle of its joints' ranges,
    /// with spheres 0.05 of its reach across (docs/space.md).
    #[arg(long, conflicts_with = "arm")]
    pub urdf: Option<std::path::PathBuf>,
    #[command(flatten)]
    pub chain: super::robot::ChainArgs,
    /// Seed for sampling, the train/validation/test split and initial weights.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Samples to draw (split 70/15/15). Default: the recipe's (3000; 10000
    /// for v by reach).
    #[arg(long)]
    pub samples: Option<usize>,
    /// Maximum epochs. Default: the recipe's (400 for Levenberg-Marquardt,
    /// 600 for Adam).
    #[arg(long)]
    pub epochs: Option<usize>,
    /// The optimiser: lm (Levenberg-Marquardt, the paper's) or adam (with
    /// minibatches, for networks too wide for LM). Default: the recipe's.
    #[arg(long, value_parser = ["lm", "adam"])]
    pub optimiser: Option<String>,
    /// Adam's minibatch size (default 64).
    #[arg(long)]
    pub batch: Option<usize>,
    /// Adam's first learning rate (default 2e-3).
    #[arg(long)]
    pub learning_rate: Option<f64>,
    /// Hidden layer widths, e.g. 35,14 (default: 35,14 for phi, 25,14 for v).
    #[arg(long)]
    pub hidden: Option<String>,
    /// Smallest singular value of J below which poses are left out (m).
    #[arg(long)]
    pub sigma_floor: Option<f64>,
    /// Noise added to visited joint angles (rad).
    #[arg(long)]
    pub noise: Option<f64>,
    /// Weights file to write.
    #[arg(long)]
    pub out: String,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

pub(super) fn parse_hidden(s: &str) -> Result<Vec<usize>, String> {
    let v: Vec<usize> = s
        .split(',')
        .map(|p| {
            p.trim()
                .parse::<usize>()
                .map_err(|_| format!("hidden layer width '{}' is not a whole number", p.trim()))
        })
        .collect::<Result<_, _>>()?;
    if v.is_empty() || v.contains(&0) || v.iter().any(|&w| w > 1000) {
        return Err(format!(
            "hidden layers '{s}': give one or more widths between 1 and 1000"
        ));
    }
    Ok(v)
}

/// The network `--net` names: `phi` or `v`.
pub fn net_kind(net: &str) -> Result<NetKind, String> {
    match net {
        "phi" => Ok(NetKind::Phi),
        "v" => Ok(NetKind::V),
        other => Err(format!("unknown network '{other}': use phi or v")),
    }
}

/// Runs `redundant-ik train`.
pub fn run(args: &TrainArgs, net: NetKind) -> Result<(), String> {
    let arm = match args.arm.clone() {
        Some(super::ArmChoice::Planar(a)) => a,
        // An arm in space is `space_networks::train`'s (cli/mod.rs routes it).
        Some(super::ArmChoice::Space(p)) => {
            return Err(format!(
                "{}: an arm in space trains through its own route",
                p.key
            ))
        }
        None => redundant_ik::Arm::paper(),
    };
    let recipe: Recipe = args
        .recipe
        .as_deref()
        .unwrap_or("paper")
        .parse()
        .map_err(|e| format!("{e}"))?;
    let mut spec = recipe.spec(&arm, net, args.seed);
    match (&args.variant, recipe) {
        (Some(v), _) => spec.variant = v.parse().map_err(|e| format!("{e}"))?,
        (None, Recipe::Paper) => spec.variant = Variant::Plain,
        (None, Recipe::Reach) => {}
    }
    if let Some(e) = &args.encoding {
        spec.encoding = e.parse().map_err(|e| format!("{e}"))?;
    }
    if let Some(eps) = args.sign_smoothing {
        spec.sampling.sign_smoothing = eps;
    }
    let variant = spec.variant;
    match args.optimiser.as_deref() {
        Some("adam") => spec.adam = Some(spec.adam.unwrap_or_default()),
        Some(_) => spec.adam = None,
        None => {}
    }
    if args.batch.is_some() || args.learning_rate.is_some() {
        let a = spec
            .adam
            .as_mut()
            .ok_or("--batch and --learning-rate are Adam's: add --optimiser adam")?;
        if let Some(b) = args.batch {
            a.batch = b;
        }
        if let Some(r) = args.learning_rate {
            a.learning_rate = r;
        }
    }
    if let Some(n) = args.samples {
        spec.samples = n;
    }
    if let Some(n) = args.epochs {
        if n == 0 {
            return Err("--epochs must be at least 1".into());
        }
        spec.set_max_epochs(n);
    }
    let epochs = spec.max_epochs();
    if let Some(h) = &args.hidden {
        spec.hidden = parse_hidden(h)?;
    }
    if let Some(f) = args.sigma_floor {
        spec.sampling.sigma_floor = f;
    }
    if let Some(n) = args.noise {
        spec.sampling.theta_noise = n;
    }
    spec.sampling.validate().map_err(|e| e.to_string())?;
    let nets = redundant_ik::networks::file::shape(net, variant, spec.encoding, spec.arm.dof(), 2)
        .map_err(|e| e.to_string())?
        .0;

    let bar = epochs_bar(args.quiet, nets * epochs)?;
    let stopped = std::cell::Cell::new(false);
    #[allow(clippy::disallowed_methods)] // the native CLI has a clock
    let start = Instant::now();
    let mut file = training::train_weights(&spec, |k, r| {
        bar.set_position((k * epochs + r.epoch) as u64);
        bar.set_message(format!(
            "net {}/{nets}  train {:.3e}  val {:.3e}  mu {:.0e}  grad {:.2e}",
            k + 1,
            r.train_mse,
            r.val_mse,
            r.mu,
            r.gradient
        ));
        // Ctrl-C in the Python package stops between epochs.
        stopped.set(super::embed::interrupted());
        !stopped.get()
    })
    .map_err(|e| e.to_string())?;
    let seconds = trained_in(&bar, stopped.get(), start)?;
    file.training.seconds = Some(seconds);
    write_weights(file.to_json(), &args.out)?;

    let mut text = format!(
        "{} network(s), recipe {}, variant {}, encoding {}, {} samples, seed {}, trained in {seconds:.1} s -> {}\n",
        args.net,
        recipe.name(),
        variant.name(),
        spec.encoding.name(),
        spec.samples,
        spec.seed,
        args.out
    );
    for (k, e) in file.nets.iter().enumerate() {
        let r = &e.report;
        text.push_str(&format!(
            "  net {} {:?}: {} epochs (best {}), stop: {:?}; MSE (mapminmax units) train {:.3e}, val {:.3e}, test {:.3e}\n",
            k + 1,
            e.mlp.sizes,
            r.epochs,
            r.best_epoch,
            r.stop,
            r.train_mse,
            r.val_mse,
            r.test_mse
        ));
    }
    super::emit(&text)
}

/// The progress bar of a training of `epochs` epochs in all (hidden with
/// `--quiet`): every arm's.
pub(super) fn epochs_bar(quiet: bool, epochs: usize) -> Result<ProgressBar, String> {
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(epochs as u64)
    };
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} epochs  {msg}")
            .map_err(|e| e.to_string())?
            .progress_chars("=> "),
    );
    Ok(bar)
}

/// Ends a training begun at `start`: refused if Ctrl-C `stopped` it (the
/// Python package's), so that nothing is written; else the seconds it took
/// to the tenth. Every arm's.
pub(super) fn trained_in(bar: &ProgressBar, stopped: bool, start: Instant) -> Result<f64, String> {
    bar.finish_and_clear();
    if stopped {
        return Err(super::embed::INTERRUPTED.into());
    }
    Ok((start.elapsed().as_secs_f64() * 10.0).round() / 10.0)
}

/// Writes a weights file's `json` to `out`, with the line's end.
pub(super) fn write_weights(json: redundant_ik::Result<String>, out: &str) -> Result<(), String> {
    let json = json.map_err(|e| e.to_string())?;
    std::fs::write(out, json + "\n").map_err(|e| format!("cannot write {out}: {e}"))
}
