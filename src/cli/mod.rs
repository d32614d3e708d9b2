//! Argument parsing and dispatch. Each subcommand lives in its own file and
//! returns `Err(message)` on bad input; `main` prints it on one line and exits
//! with status 2.

// The shell's public items are documented by its `--help` (their doc
// comments are the help text); clap's flattened groups carry none.
#![allow(missing_docs)]
// Its doc comments are help text (`[,LAPS]` is an optional part, not a link).
#![allow(rustdoc::broken_intra_doc_links)]

use clap::{Parser, Subcommand};
use redundant_ik::networks::{self, NetworkSet, Variant};
use redundant_ik::run::NetworkChoice;
use redundant_ik::space::{Named, SpacePreset};
use redundant_ik::{Arm, Method};

pub mod atlas;
pub mod bench;
pub mod embed;
pub mod eval;
pub mod figure;
pub mod from;
pub mod job;
pub mod params;
pub mod path_arg;
pub mod planner;
pub mod pose;
pub mod robot;
pub mod simulate;
pub mod space;
pub mod space_atlas;
pub mod space_networks;
pub mod summary;
pub mod task;
pub mod train;

/// Motion planning for redundant arms: planar ones (2 to 32 links; the
/// paper's has 3) and, in space, the Franka Panda, the KUKA iiwa 14 or any
/// serial arm from its URDF, the hand's position or its full pose as the
/// task.
/// Damped-least-squares inverse kinematics with a null-space
/// obstacle-avoidance vector, the neural networks that replace them (Cases
/// 1-3 of the paper, trained by Levenberg-Marquardt or Adam), and methods
/// beyond the paper.
#[derive(Parser, Debug)]
#[command(name = "redundant-ik", version, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run one planning task and print a summary (or JSON).
    Simulate(simulate::SimulateArgs),
    /// Draw the paper-style stroboscopic figure(s) as SVG.
    Figure(figure::FigureArgs),
    /// Train a network (Levenberg-Marquardt or Adam) and write a weights file.
    Train(train::TrainArgs),
    /// Evaluate the embedded networks: accuracy and task outcomes.
    Eval(eval::EvalArgs),
    /// Map where each method keeps the arm clear: the obstacle on every cell of a grid.
    Atlas(atlas::AtlasArgs),
    /// Measure theta_dot, RK4 steps, forward passes, an LM epoch, an atlas and allocations per step.
    Bench(bench::BenchArgs),
    /// Describe a robot's URDF: the chain from its base to its tip, the
    /// joints' limits, the links' volumes and how each was made.
    Robot(robot::RobotArgs),
}

// Each command for every arm: an arm in space (or a spatial run file) goes
// to `space` or `space_networks`, a planar one to the command's own file.
// The routing lives here, above both, so neither imports the other both
// ways.

/// The arm in space `--arm` names, if it names one.
fn space_arm(arm: &Option<ArmChoice>) -> Option<&'static SpacePreset> {
    match arm {
        Some(ArmChoice::Space(p)) => Some(p),
        _ => None,
    }
}

/// `simulate`: a spatial run file or arm, else a planar run.
fn simulate_any(a: &simulate::SimulateArgs) -> Result<(), String> {
    match space::job(&a.scene, a.method.method, space_arm(&a.scene.arm))? {
        Some(job) => space::simulate(a, job),
        None => simulate::run(a),
    }
}

/// `figure`: a spatial run file's or arm's figures, else a planar run's.
fn figure_any(a: &figure::FigureArgs) -> Result<(), String> {
    match space::job(&a.scene, a.method.method, space_arm(&a.scene.arm))? {
        Some(job) => figure::space(a, job),
        None => figure::run(a),
    }
}

/// `atlas`: the slice atlas of an arm in space (or of a spatial run
/// file's scene), else the planar atlas.
fn atlas_any(a: &atlas::AtlasArgs) -> Result<(), String> {
    match space::job(&a.scene, None, space_arm(&a.scene.arm))? {
        Some(job) => space_atlas::atlas(a, job),
        None => atlas::run(a),
    }
}

/// `train`: the networks of an arm in space, else a planar arm's.
fn train_any(a: &train::TrainArgs) -> Result<(), String> {
    let net = train::net_kind(&a.net)?;
    a.chain.need_urdf(a.urdf.as_deref())?;
    match (&a.arm, &a.urdf) {
        (Some(ArmChoice::Space(p)), _) => space_networks::train(a, net, (*p).into()),
        (_, Some(path)) => {
            space_networks::train(a, net, space_networks::urdf_arm(path, &a.chain, None)?)
        }
        _ => train::run(a, net),
    }
}

/// `eval`: an arm in space's networks (`--arm`), else the planar sets.
fn eval_any(a: &eval::EvalArgs) -> Result<(), String> {
    eval::check_samples(a)?;
    a.chain.need_urdf(a.urdf.as_deref())?;
    match (&a.arm, &a.urdf) {
        (Some(key), _) => {
            let p = SpacePreset::named(key)
                .map_err(|e| format!("--arm: {e} (eval --arm takes an arm in space)"))?;
            space_networks::eval(a, p.into())
        }
        (_, Some(path)) => space_networks::eval(
            a,
            space_networks::urdf_arm(path, &a.chain, a.theta0.as_deref())?,
        ),
        _ => eval::run(a),
    }
}

/// The binary's allocation counter (heap allocations since it started),
/// which `bench` reports per step; set once by [`main`].
static ALLOCATIONS: std::sync::OnceLock<fn() -> u64> = std::sync::OnceLock::new();

/// The allocation counter [`main`] was given; `bench` runs only where one
/// was (the command-line tool), so this is never reached without one.
fn allocation_counter() -> fn() -> u64 {
    *ALLOCATIONS.get().unwrap_or(&((|| 0) as fn() -> u64))
}

/// Runs the command `cli` parsed.
fn dispatch(cli: &Cli) -> Result<(), String> {
    match &cli.command {
        Command::Simulate(a) => simulate_any(a),
        Command::Figure(a) => figure_any(a),
        Command::Train(a) => train_any(a),
        Command::Eval(a) => eval_any(a),
        Command::Atlas(a) => atlas_any(a),
        Command::Bench(a) if ALLOCATIONS.get().is_some() => bench::run(a),
        Command::Bench(_) => Err("bench runs in the command-line tool, whose allocator counts the allocations it reports (redundant-ik bench)".into()),
        Command::Robot(a) => robot::run(a),
    }
}

/// Parses the command line, runs it, and returns the exit status.
/// `allocations` counts the process's heap allocations (the binary's global
/// allocator), for `bench`.
pub fn main(allocations: Option<fn() -> u64>) -> i32 {
    if let Some(count) = allocations {
        let _ = ALLOCATIONS.set(count);
    }
    let cli = Cli::parse();
    match dispatch(&cli) {
        Ok(()) => 0,
        Err(msg) => {
            eprintln!("error: {msg}");
            2
        }
    }
}

/// An arm as `--arm` names it: a planar arm (a preset's name or
/// `POST:L1,L2,...`), or a chain in space by its preset's name (`panda`,
/// `iiwa14`).
#[derive(Debug, Clone)]
pub enum ArmChoice {
    /// A planar arm.
    Planar(Arm),
    /// An arm in space.
    Space(&'static SpacePreset),
}

/// Parses an arm: a planar preset's name (`paper`, `four`, `five`,
/// `iiwa-planar`), an arm in space by name (`panda`, `iiwa14`), or
/// `POST:L1,L2,...` (post height and link lengths, m), as the core reads
/// the syntax.
pub fn parse_arm(s: &str) -> Result<ArmChoice, String> {
    match Named::find(s) {
        Some(Named::Space(p)) => Ok(ArmChoice::Space(p)),
        // A word that names no arm: every name, and the planar arm's text.
        None if !s.contains(':') && s.trim().parse::<f64>().is_err() => Err(format!(
            "unknown arm '{}': {}, or a planar arm POST:L1,L2,... (e.g. 0.5:0.6,0.85,0.6)",
            s.trim(),
            Named::choices()
        )),
        _ => parse_planar_arm(s).map(ArmChoice::Planar),
    }
}

/// Parses a planar arm (a planar preset's name or `POST:L1,L2,...`); an
/// arm in space is refused by name.
pub fn parse_planar_arm(s: &str) -> Result<Arm, String> {
    match Named::find(s) {
        Some(Named::Space(p)) => Err(format!(
            "{} is an arm in space; this takes a planar arm",
            p.key
        )),
        Some(Named::Planar(p)) => Ok(p.arm()),
        None => s.parse().map_err(|e: redundant_ik::Error| e.to_string()),
    }
}

/// Numbers as written, `A,B,...`: an obstacle (`X,Y[,R]` for a planar
/// arm, `X,Y,Z[,R]` for one in space) or a target (`X,Y` or `X,Y,Z`),
/// read by the arm's kind once the arm is known.
#[derive(Debug, Clone, PartialEq)]
pub struct Numbers(pub Vec<f64>);

/// Parses a comma-separated list of numbers (their count is the arm's to
/// check).
pub fn parse_numbers(s: &str) -> Result<Numbers, String> {
    parse_list(s).map(Numbers)
}

/// Parses a method name (`--method`), refused at once when unknown.
pub fn parse_method(s: &str) -> Result<Method, String> {
    s.parse().map_err(|e: redundant_ik::Error| e.to_string())
}

/// The help of a `--method` option: every method's name and what it is.
pub fn method_help() -> String {
    let list: Vec<String> = redundant_ik::planner::methods::ALL
        .iter()
        .map(|m| format!("{} ({})", m.name(), m.label()))
        .collect();
    format!("The method: {}", list.join(", "))
}

/// Parses a comma-separated list of numbers.
pub fn parse_list(s: &str) -> Result<Vec<f64>, String> {
    s.split(',')
        .map(|p| {
            p.trim()
                .parse::<f64>()
                .map_err(|_| format!("'{}' is not a number (in '{s}')", p.trim()))
        })
        .collect()
}

/// Writes `text` to standard output; a closed pipe (`| head`) is not an error.
pub fn emit(text: &str) -> Result<(), String> {
    use std::io::Write;
    if embed::capture(text) {
        return Ok(());
    }
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(format!("cannot write output: {e}"))
        }
        _ => Ok(()),
    }
}

/// Which networks the network methods use: a shipped set (with a choice of
/// `Phi` variant for the paper's) or a user's pair of weights files.
#[derive(clap::Args, Debug, Clone)]
pub struct NetworkArgs {
    /// Shipped network set: paper (trained by the paper's recipe, near its
    /// tasks) or reach (angle features, trained over the whole reach;
    /// docs/learning.md); for the Panda in space, panda-reach (its
    /// default; docs/space.md).
    #[arg(long, default_value = "paper", value_parser = parse_set)]
    pub networks: SetArg,
    /// The paper's set's Phi network: equivariant (default, most accurate),
    /// plain (the paper's 3-35-14-6) or rows (the paper's three 3-35-14-2
    /// nets).
    #[arg(long, value_parser = parse_variant)]
    pub phi_variant: Option<Variant>,
    /// Your own Phi weights file (JSON written by `train`, see docs/networks.md);
    /// replaces the embedded Phi network.
    #[arg(long)]
    pub phi_weights: Option<std::path::PathBuf>,
    /// Your own v weights file (JSON written by `train`); replaces the embedded
    /// v network.
    #[arg(long)]
    pub v_weights: Option<std::path::PathBuf>,
    /// The networks' arithmetic: f64 (the default) or f32 (weights,
    /// activations and sums in single precision, as the page runs them
    /// with precision=f32; docs/networks.md).
    #[arg(long, default_value = "f64")]
    pub precision: redundant_ik::nn::Precision,
}

impl NetworkArgs {
    /// Whether any of these options was given (not left at its default).
    pub fn given(&self, given: &params::Given) -> Option<String> {
        given.flags_of::<NetworkArgs>(|_| false).into_iter().next()
    }

    /// The networks these options choose, as a run names them: the shipped
    /// set, or, where a file or the paper set's other `Phi` is asked for,
    /// the weights files themselves (a run file then replays without them).
    pub fn choice(&self) -> Result<NetworkChoice, String> {
        if self.phi_weights.is_none() && self.v_weights.is_none() && self.phi_variant.is_none() {
            return Ok(NetworkChoice::Set(self.planar_set()?));
        }
        let (phi, v) = self.texts()?;
        Ok(NetworkChoice::Files { phi, v })
    }

    /// The JSON text of the selected weights files.
    fn texts(&self) -> Result<(String, String), String> {
        let (phi_shipped, v_shipped) = match (self.planar_set()?, self.phi_variant) {
            (NetworkSet::Paper, variant) => (
                networks::embedded_phi_json(variant.unwrap_or(networks::DEFAULT_PHI_VARIANT)),
                networks::V_PLAIN_JSON,
            ),
            (NetworkSet::Reach, None) => (networks::PHI_REACH_JSON, networks::V_REACH_JSON),
            (NetworkSet::Reach, Some(_)) => return Err(
                "--phi-variant chooses among the paper's set; the reach set has one Phi network"
                    .into(),
            ),
        };
        let phi = match &self.phi_weights {
            Some(f) => read_weights_file(f)?,
            None => phi_shipped.to_owned(),
        };
        let v = match &self.v_weights {
            Some(f) => read_weights_file(f)?,
            None => v_shipped.to_owned(),
        };
        Ok((phi, v))
    }
}

/// A `--networks` set, refused at once when unknown.
/// A shipped set named by `--networks`: a planar one or one for an arm in
/// space.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetArg {
    /// A set for the paper's planar arm.
    Planar(NetworkSet),
    /// A set for an arm in space.
    Space(redundant_ik::networks::space::SpaceNetworkSet),
}

impl NetworkArgs {
    /// The planar set; a set for an arm in space is refused by name.
    pub fn planar_set(&self) -> Result<NetworkSet, String> {
        match self.networks {
            SetArg::Planar(s) => Ok(s),
            SetArg::Space(s) => Err(format!(
                "--networks {} is for the arm in space '{}', not a planar arm",
                s.name(),
                s.arm()
            )),
        }
    }
}

fn parse_set(s: &str) -> Result<SetArg, String> {
    if let Ok(set) = s.parse() {
        return Ok(SetArg::Planar(set));
    }
    s.parse().map(SetArg::Space).map_err(|_| {
        format!("unknown --networks '{s}': use paper or reach (planar) or panda-reach (the Panda)")
    })
}

/// A `--phi-variant`, refused at once when unknown (even where no network runs).
fn parse_variant(s: &str) -> Result<Variant, String> {
    s.parse()
        .map_err(|_| format!("unknown --phi-variant '{s}': use equivariant, plain or rows"))
}

/// Reads the text of `path`, refusing one larger than `max` bytes before
/// reading it (`what` names the kind of file in the refusal).
pub fn read_at_most(path: &std::path::Path, max: usize, what: &str) -> Result<String, String> {
    let size = std::fs::metadata(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?
        .len();
    if size > max as u64 {
        return Err(format!(
            "{}: {size} bytes, more than the {max} {what} may have",
            path.display()
        ));
    }
    std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

/// Reads a weights file, refusing one larger than
/// [`redundant_ik::networks::MAX_FILE_BYTES`] before reading it.
pub(crate) fn read_weights_file(f: &std::path::Path) -> Result<String, String> {
    let max = redundant_ik::networks::MAX_FILE_BYTES;
    let size = std::fs::metadata(f)
        .map_err(|e| format!("cannot read {}: {e}", f.display()))?
        .len();
    if size > max as u64 {
        return Err(format!(
            "bad network weights: {} has {:.1} MB; weights files are at most {} MB",
            f.display(),
            size as f64 / 1048576.0,
            max >> 20
        ));
    }
    std::fs::read_to_string(f).map_err(|e| format!("cannot read {}: {e}", f.display()))
}
