//! `redundant-ik eval`: accuracy of the embedded (or given) networks on a
//! fresh test set from their trained range, and the outcome of the paper's
//! five methods on both paper tasks.

use clap::Args;
use serde::Serialize;

use redundant_ik::evaluation::{self, ErrorStats, TaskOutcome};
use redundant_ik::networks::{self, NetworkSet, Networks};
use redundant_ik::networks::{NetKind, Variant};
use redundant_ik::Method;

/// Options of `redundant-ik eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Machine-readable JSON instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Test samples drawn afresh from the trained range.
    #[arg(long, default_value_t = 2000)]
    pub samples: usize,
    /// Seed of the fresh test set (differs from the training seeds).
    #[arg(long, default_value_t = 20240601)]
    pub seed: u64,
    /// Phi variant for the task runs: plain, rows or equivariant (default: the shipped default).
    #[arg(long)]
    pub variant: Option<String>,
    /// Closed-loop gain K for the task runs (0 = the paper's open loop).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub feedback: f64,
    /// Newton-Schulz steps refining the learned Phi with the pose's J in
    /// the task runs (Cases 1 and 3; 0 = the paper's).
    #[arg(long, default_value_t = 0)]
    pub refine: u32,
    /// Shipped network set to evaluate: paper or reach (docs/learning.md),
    /// or panda-reach with --arm panda (docs/space.md).
    #[arg(long, default_value = "paper", value_parser = ["paper", "reach", "panda-reach"])]
    pub networks: String,
    /// An arm in space (panda): the accuracy of its networks and the
    /// learned methods on its task.
    #[arg(long)]
    pub arm: Option<String>,
    /// A robot's URDF instead of --arm, with its networks as --phi and
    /// --v: their accuracy, and the learned methods on the robot's own
    /// line past a sphere in the way of its middle joint (docs/space.md).
    #[arg(long, conflicts_with = "arm")]
    pub urdf: Option<std::path::PathBuf>,
    /// With --urdf: the start pose, one value per moving joint (rad, or m
    /// for a sliding one; default: the middle of the joints' ranges, which
    /// for many arms is a straight, singular pose).
    #[arg(long, requires = "urdf", allow_hyphen_values = true)]
    pub theta0: Option<String>,
    #[command(flatten)]
    pub chain: super::robot::ChainArgs,
    /// A Phi weights file to evaluate instead of the embedded one (needs --v).
    #[arg(long, requires = "v")]
    pub phi: Option<String>,
    /// A v weights file to evaluate instead of the embedded one (needs --phi).
    #[arg(long, requires = "phi")]
    pub v: Option<String>,
}

#[derive(Serialize)]
struct PhiAccuracy {
    variant: Variant,
    sizes: Vec<Vec<usize>>,
    relative_error: ErrorStats,
}

#[derive(Serialize)]
struct Report {
    samples: usize,
    seed: u64,
    phi: Vec<PhiAccuracy>,
    v: ErrorStats,
    v_variant: Variant,
    v_sizes: Vec<Vec<usize>>,
    task_variant: Variant,
    feedback_gain: f64,
    refine: u32,
    outcomes: Vec<TaskOutcome>,
    generalisation: Vec<Generalisation>,
    case3_avoided: usize,
}

/// One generalisation scene: the obstacle moved off the canonical position.
#[derive(Serialize)]
struct Generalisation {
    task: u32,
    obstacle: [f64; 2],
    none_collided: bool,
    numerical_collided: bool,
    case3: TaskOutcome,
}

fn read(path: &str) -> Result<String, String> {
    super::read_weights_file(std::path::Path::new(path))
}

/// Refuses a sample count outside 1 to 1,000,000 (for every arm).
pub fn check_samples(args: &EvalArgs) -> Result<(), String> {
    if args.samples == 0 || args.samples > 1_000_000 {
        return Err("--samples must be between 1 and 1000000".into());
    }
    Ok(())
}

/// Runs `redundant-ik eval`.
pub fn run(args: &EvalArgs) -> Result<(), String> {
    if args.networks == "panda-reach" {
        return Err("--networks panda-reach is the Panda's: add --arm panda".into());
    }
    let e = |e: redundant_ik::Error| e.to_string();
    let (candidates, task_nets) = match (&args.phi, &args.v) {
        (Some(p), Some(v)) => {
            let nets = Networks::from_json(&read(p)?, &read(v)?).map_err(e)?;
            (vec![nets.clone()], nets)
        }
        _ if args.networks == "reach" => {
            if args.variant.is_some() {
                return Err(
                    "--variant chooses among the paper's set; the reach set has one Phi network"
                        .into(),
                );
            }
            let nets = Networks::embedded_set(NetworkSet::Reach).map_err(e)?;
            (vec![nets.clone()], nets)
        }
        _ => {
            let variant = match &args.variant {
                Some(s) => s.parse::<Variant>().map_err(e)?,
                None => networks::DEFAULT_PHI_VARIANT,
            };
            let all = [Variant::Plain, Variant::Rows, Variant::Equivariant]
                .into_iter()
                .map(Networks::embedded_with)
                .collect::<Result<Vec<_>, _>>()
                .map_err(e)?;
            let chosen = Networks::embedded_with(variant).map_err(e)?;
            (all, chosen)
        }
    };
    if !task_nets.arm().same_geometry(&redundant_ik::Arm::paper()) {
        return other_arm(&task_nets, args.json);
    }
    let test =
        evaluation::fresh_samples(&task_nets, NetKind::Phi, args.samples, args.seed).map_err(e)?;
    let v_test =
        evaluation::fresh_samples(&task_nets, NetKind::V, args.samples, args.seed).map_err(e)?;
    let mut phi = Vec::new();
    for nets in &candidates {
        phi.push(PhiAccuracy {
            variant: nets.phi_file().variant,
            sizes: nets
                .phi_file()
                .nets
                .iter()
                .map(|n| n.mlp.sizes.clone())
                .collect(),
            relative_error: ErrorStats::of(
                evaluation::phi_relative_errors(nets, &test).map_err(e)?,
            ),
        });
    }
    let v = ErrorStats::of(evaluation::v_relative_errors(&task_nets, &v_test).map_err(e)?);
    let outcomes = evaluation::task_outcomes(&task_nets, args.feedback, args.refine).map_err(e)?;
    let mut generalisation = Vec::new();
    for (task, o) in evaluation::GENERALISATION_SCENES {
        let run = |method| {
            evaluation::run_task_refined(
                &task_nets,
                task,
                method,
                Some(o),
                args.feedback,
                args.refine,
            )
        };
        generalisation.push(Generalisation {
            task,
            obstacle: o,
            none_collided: run(Method::NO_AVOIDANCE).map_err(e)?.collided,
            numerical_collided: run(Method::NUMERICAL).map_err(e)?.collided,
            case3: run(Method::CASE3).map_err(e)?,
        });
    }
    let case3_avoided = generalisation
        .iter()
        .filter(|g| g.case3.error.is_none() && !g.case3.collided)
        .count();
    let report = Report {
        samples: args.samples,
        seed: args.seed,
        phi,
        v,
        v_variant: task_nets.v_file().variant,
        v_sizes: task_nets
            .v_file()
            .nets
            .iter()
            .map(|n| n.mlp.sizes.clone())
            .collect(),
        task_variant: task_nets.phi_file().variant,
        feedback_gain: args.feedback,
        refine: args.refine,
        outcomes,
        generalisation,
        case3_avoided,
    };
    if args.json {
        let s = serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?;
        return super::emit(&(s + "\n"));
    }
    super::emit(&render(&report))
}

fn sizes(s: &[Vec<usize>]) -> String {
    let one = |v: &Vec<usize>| {
        v.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join("-")
    };
    if s.len() > 1 && s.iter().all(|v| v == &s[0]) {
        format!("{} x {}", s.len(), one(&s[0]))
    } else {
        s.iter().map(one).collect::<Vec<_>>().join(", ")
    }
}

fn render(r: &Report) -> String {
    let mut t = format!(
        "Accuracy on {} fresh samples from the trained range (seed {})\n\n",
        r.samples, r.seed
    );
    t.push_str("| network | variant | layers | relative error median | p99 | max |\n");
    t.push_str("|---|---|---|---|---|---|\n");
    let row = |net: &str, variant: Variant, layers: &[Vec<usize>], e: &ErrorStats| {
        format!(
            "| {net} | {} | {} | {:.2e} | {:.2e} | {:.2e} |\n",
            variant.name(),
            sizes(layers),
            e.median,
            e.p99,
            e.max
        )
    };
    for p in &r.phi {
        t.push_str(&row("Phi", p.variant, &p.sizes, &p.relative_error));
    }
    t.push_str(&row("v", r.v_variant, &r.v_sizes, &r.v));
    t.push('\n');
    t.push_str(&format!(
        "Task outcomes (Phi variant {}, feedback K = {}, refine {}, delta = 0)\n\n",
        r.task_variant.name(),
        r.feedback_gain,
        r.refine
    ));
    t.push_str("| task | method | min distance (m) | collided | final error (m) | out-of-range steps | ok |\n");
    t.push_str("|---|---|---|---|---|---|---|\n");
    for o in &r.outcomes {
        if let Some(err) = &o.error {
            t.push_str(&format!(
                "| {} | {} | failed: {err} | | | | no |\n",
                o.task, o.method
            ));
            continue;
        }
        let ok = if o.method == Method::NO_AVOIDANCE {
            "-"
        } else if o.success() {
            "yes"
        } else {
            "no"
        };
        t.push_str(&format!(
            "| {} | {} | {:.4} | {} | {:.2e} | {} | {ok} |\n",
            o.task,
            o.method,
            o.min_distance,
            if o.collided { "yes" } else { "no" },
            o.final_error,
            o.out_of_range_steps
        ));
    }
    t.push_str(&format!(
        "\nGeneralisation: obstacle moved to 10 other positions in the trained region; Case 3 avoided it in {} of 10\n\n",
        r.case3_avoided
    ));
    t.push_str("| task | obstacle | none collides | numerical collides | Case 3 min distance (m) | Case 3 final error (m) | Case 3 avoids |\n");
    t.push_str("|---|---|---|---|---|---|---|\n");
    let yn = |b: bool| if b { "yes" } else { "no" };
    for g in &r.generalisation {
        t.push_str(&format!(
            "| {} | ({}, {}) | {} | {} | {:.4} | {:.2e} | {} |\n",
            g.task,
            g.obstacle[0],
            g.obstacle[1],
            yn(g.none_collided),
            yn(g.numerical_collided),
            g.case3.min_distance,
            g.case3.final_error,
            yn(g.case3.error.is_none() && !g.case3.collided)
        ));
    }
    t
}

/// `eval` of networks for an arm other than the paper's, which has no
/// paper tasks: the check the page's training runs (500 fresh samples, and
/// the fixed random tasks in which the obstacle matters, open and closed
/// loop, unrefined and refined).
fn other_arm(nets: &Networks, json: bool) -> Result<(), String> {
    let r = redundant_ik::training_job::assess(nets, 500).map_err(|e| e.to_string())?;
    if json {
        let s = serde_json::to_string_pretty(&r).map_err(|e| e.to_string())?;
        return super::emit(&(s + "\n"));
    }
    let mut t = format!(
        "Networks for the arm {}: accuracy on {} fresh samples from the trained range\n\n",
        nets.arm(),
        r.phi_error.samples
    );
    t.push_str("| network | relative error median | p99 | max |\n|---|---|---|---|\n");
    for (name, e) in [("Phi", &r.phi_error), ("v", &r.v_error)] {
        t.push_str(&format!(
            "| {name} | {:.2e} | {:.2e} | {:.2e} |\n",
            e.median, e.p99, e.max
        ));
    }
    match &r.random_tasks_note {
        Some(why) => t.push_str(&format!("\nNo check on random tasks: {why}\n")),
        None => {
            t.push_str(&format!(
                "\nRandom tasks in which the obstacle matters (seed {})\n\n",
                redundant_ik::training_job::CHECK_SEED
            ));
            t.push_str(
                "| K | refine | method | ok | collided | failed | median final error (m) |\n",
            );
            t.push_str("|---|---|---|---|---|---|---|\n");
            for row in &r.random_tasks {
                let c = &row.check;
                t.push_str(&format!(
                    "| {} | {} | {} | {}/{} | {} | {} | {} |\n",
                    row.feedback,
                    row.refine,
                    c.method,
                    c.succeeded,
                    c.tasks,
                    c.collided,
                    c.failed,
                    c.median_final_error
                        .map_or("-".to_string(), |x| format!("{x:.2e}"))
                ));
            }
        }
    }
    super::emit(&t)
}
