//! A training job: both networks for an arm in one go, as the page's
//! Training panel and `window.demo.train()` run it: presets for the size
//! of the job, a progress event per epoch, and a report of the test errors
//! and of how the trained networks fare on tasks. It sits above both
//! [`crate::training`] and [`crate::evaluation`] (feature `eval`, which the
//! workers' module and the command-line tool carry).

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{within, Error, Result};
use crate::evaluation::{self, ErrorStats};
use crate::networks::{NetKind, Networks, WeightsFile, DEFAULT_PHI_VARIANT, DEFAULT_V_VARIANT};
use crate::nn::lm::EpochReport;
use crate::planner::{Method, Surrogate};
use crate::training::{tasks, train_weights, TrainSpec};

/// How big a training job is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// 1 000 samples, at most 100 epochs: seconds for the paper's arm.
    Quick,
    /// The paper's 3 000 samples and at most 400 epochs: the shipped files.
    Thorough,
}

impl Preset {
    /// Samples drawn.
    pub fn samples(self) -> usize {
        match self {
            Preset::Quick => 1000,
            Preset::Thorough => 3000,
        }
    }

    /// Most Levenberg-Marquardt epochs per network.
    pub fn epochs(self) -> usize {
        match self {
            Preset::Quick => 100,
            Preset::Thorough => 400,
        }
    }
}

/// Which networks to train.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Which {
    /// The `Phi` network (Cases 1 and 3).
    Phi,
    /// The `v` network (Cases 2 and 3).
    V,
    /// Both.
    Both,
}

/// Most samples a request may ask for.
pub const MAX_SAMPLES: usize = 20_000;
/// Most epochs a request may ask for.
pub const MAX_EPOCHS: usize = 2_000;
/// Random avoidance tasks the trained networks are checked on.
pub const CHECK_TASKS: usize = 10;
/// Seed of those tasks (fixed, so every training of an arm is checked on
/// the same tasks).
pub const CHECK_SEED: u64 = 20_261_123;

/// A training job: the arm, the networks, the preset and what overrides it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// The arm to train for.
    pub arm: Arm,
    /// Which networks.
    pub net: Which,
    /// Size of the job.
    pub preset: Preset,
    /// Samples, instead of the preset's.
    #[serde(default)]
    pub samples: Option<usize>,
    /// Most epochs, instead of the preset's.
    #[serde(default)]
    pub epochs: Option<usize>,
    /// Seed of the sampling, the split and the initial weights (default 1).
    #[serde(default)]
    pub seed: Option<u64>,
}

/// One epoch of one network, for live curves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Progress {
    /// `"phi"` or `"v"`.
    pub net: &'static str,
    /// The epoch's numbers (MSE in mapminmax units).
    #[serde(flatten)]
    pub report: EpochReport,
    /// Most epochs of this network.
    pub max_epochs: usize,
}

/// How one trained weights file came out.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NetReport {
    /// Layer sizes.
    pub sizes: Vec<usize>,
    /// Epochs run.
    pub epochs: usize,
    /// Why training stopped.
    pub stop: crate::nn::lm::StopReason,
    /// MSE on the training, validation and test splits (mapminmax units).
    pub train_mse: f64,
    /// See `train_mse`.
    pub val_mse: f64,
    /// See `train_mse`.
    pub test_mse: f64,
}

impl NetReport {
    fn of(file: &WeightsFile) -> Self {
        let e = &file.nets[0];
        Self {
            sizes: e.mlp.sizes.clone(),
            epochs: e.report.epochs,
            stop: e.report.stop,
            train_mse: e.report.train_mse,
            val_mse: e.report.val_mse,
            test_mse: e.report.test_mse,
        }
    }
}

/// The networks a job produced and how good they are.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Samples drawn per network.
    pub samples: usize,
    /// The `Phi` file's training, if it was trained.
    pub phi: Option<NetReport>,
    /// The `v` file's.
    pub v: Option<NetReport>,
    /// Relative error of `Phi` on 500 fresh samples (the test errors).
    pub phi_error: ErrorStats,
    /// Relative error of the area gradient on the same samples.
    pub v_error: ErrorStats,
    /// The paper's tasks with their obstacles, open loop (paper's arm only):
    /// Cases 1 to 3.
    pub paper_tasks: Vec<evaluation::TaskOutcome>,
    /// [`CHECK_TASKS`] random tasks of this arm in which the obstacle
    /// matters ([`tasks::avoidance_tasks`]), open loop (`K = 0`) and with
    /// the drift corrected (`K = 1`): numerical and Cases 1 to 3.
    pub random_tasks: Vec<CheckRow>,
    /// Why there are no random tasks, when the arm has none in which the
    /// obstacle matters (a 2-link arm has no redundancy to avoid with).
    /// The networks are kept all the same.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub random_tasks_note: Option<String>,
    /// Whether the networks pass this check ([`Verdict`]).
    pub verdict: Verdict,
}

/// Share of the tasks the numerical route succeeds on that a network case
/// must succeed on too (with the drift corrected) to pass the check.
pub const PASS_SHARE: f64 = 0.5;

/// Whether trained networks pass their own check: on the paper's arm, the
/// network cases that use them reach both of the paper's targets without
/// collision (the tasks the paper's arm is trained on); on another arm,
/// each of those cases succeeds, with the drift corrected, on at least
/// [`PASS_SHARE`] of the random tasks the numerical route succeeds on.
/// Networks that fail it are not swapped in unless the user asks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    /// Whether they pass.
    pub passed: bool,
    /// What was checked.
    pub checked: String,
    /// What failed, one sentence each (empty when they pass).
    pub failures: Vec<String>,
}

impl Verdict {
    /// The verdict on `report` for networks `which` were trained.
    pub fn of(report: &Report, which: Which) -> Self {
        let cases: &[Method] = match which {
            Which::Both => &[Method::CASE1, Method::CASE2, Method::CASE3],
            Which::Phi => &[Method::CASE1, Method::CASE3],
            Which::V => &[Method::CASE2, Method::CASE3],
        };
        let labels = cases
            .iter()
            .map(|m| m.label())
            .collect::<Vec<_>>()
            .join(", ");
        let mut failures = Vec::new();
        let checked = if !report.paper_tasks.is_empty() {
            for t in &report.paper_tasks {
                if cases.contains(&t.mode) && !t.success() {
                    failures.push(format!(
                        "{} misses Task {} ({}, {:.1} mm from the target)",
                        t.mode.label(),
                        t.task,
                        if t.collided {
                            "collides"
                        } else {
                            "no collision"
                        },
                        t.final_error * 1000.0
                    ));
                }
            }
            format!("{labels} on the paper's Tasks 1 and 2")
        } else if let Some(numerical) = report
            .random_tasks
            .iter()
            .find(|r| r.feedback > 0.0 && r.check.mode == Method::NUMERICAL.name())
        {
            let wanted = (PASS_SHARE * numerical.check.succeeded as f64).ceil() as usize;
            for r in &report.random_tasks {
                let Some(case) = cases.iter().find(|m| m.name() == r.check.mode) else {
                    continue;
                };
                if r.feedback > 0.0 && r.check.succeeded < wanted.max(1) {
                    failures.push(format!(
                        "{} succeeds on {} of {} random tasks with the drift corrected (the numerical route on {})",
                        case.label(),
                        r.check.succeeded,
                        r.check.tasks,
                        numerical.check.succeeded
                    ));
                }
            }
            format!(
                "{labels} on {} random tasks of this arm, with the drift corrected",
                numerical.check.tasks
            )
        } else {
            "nothing: this arm has no task in which the obstacle matters".into()
        };
        Self {
            passed: failures.is_empty(),
            checked,
            failures,
        }
    }
}

/// One line of the task check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckRow {
    /// Closed-loop gain `K`.
    pub feedback: f64,
    /// The outcome.
    #[serde(flatten)]
    pub check: tasks::Check,
}

/// What a job hands back: the weights files and the report.
#[derive(Debug, Clone, PartialEq)]
pub struct Trained {
    /// The `Phi` weights file in use afterwards (trained, or the one kept).
    pub phi: WeightsFile,
    /// The `v` weights file in use afterwards.
    pub v: WeightsFile,
    /// The report.
    pub report: Report,
}

impl Request {
    /// The samples and epochs this request means, checked.
    pub fn size(&self) -> Result<(usize, usize)> {
        let samples = self.samples.unwrap_or(self.preset.samples());
        let epochs = self.epochs.unwrap_or(self.preset.epochs());
        within("training samples", samples as f64, 20.0, MAX_SAMPLES as f64)?;
        within("training epochs", epochs as f64, 1.0, MAX_EPOCHS as f64)?;
        Ok((samples, epochs))
    }

    /// The training spec of network `net` this request means (checked
    /// sizes, the page's variants, the arm's sampling).
    pub fn spec(&self, net: NetKind) -> Result<TrainSpec> {
        let (samples, epochs) = self.size()?;
        let variant = match net {
            NetKind::Phi => DEFAULT_PHI_VARIANT,
            NetKind::V => DEFAULT_V_VARIANT,
        };
        // One seed for both, as the shipped files (scripts/train-weights.sh):
        // the thorough preset on the paper's arm retrains them.
        let seed = self.seed.unwrap_or(1);
        let mut spec = TrainSpec::for_arm(&self.arm, net, variant, seed);
        spec.samples = samples;
        spec.options.max_epochs = epochs;
        Ok(spec)
    }
}

/// Trains what `request` asks for (the variants the page uses: the
/// rotation-equivariant `Phi` and the plain `v`, with the paper's layer
/// sizes), keeps the other network from `current` when only one is
/// trained, and reports. `on_epoch` sees every epoch; returning `false`
/// stops that network early (what it learnt so far is kept). Nothing is
/// installed anywhere: the caller swaps the networks in, so a failed or
/// abandoned job leaves the ones in use untouched.
pub fn train(
    request: &Request,
    current: Option<&Networks>,
    mut on_epoch: impl FnMut(&Progress) -> bool,
) -> Result<Trained> {
    let arm = &request.arm;
    Arm::new(arm.post(), arm.links().to_vec())?;
    let (samples, _) = request.size()?;
    let kept = |net: NetKind| -> Result<WeightsFile> {
        let nets = current.filter(|n| n.arm() == arm).ok_or_else(|| {
            Error::Training(format!(
                "training only the {} network needs the other one for this arm: train both",
                match net {
                    NetKind::Phi => "v",
                    NetKind::V => "Φ",
                }
            ))
        })?;
        Ok(match net {
            NetKind::Phi => nets.phi_file().clone(),
            NetKind::V => nets.v_file().clone(),
        })
    };
    let mut run = |net: NetKind| -> Result<WeightsFile> {
        let spec = request.spec(net)?;
        let name = match net {
            NetKind::Phi => "phi",
            NetKind::V => "v",
        };
        let max_epochs = spec.options.max_epochs;
        train_weights(&spec, |_, report| {
            on_epoch(&Progress {
                net: name,
                report: *report,
                max_epochs,
            })
        })
    };
    let (phi, v, phi_report, v_report) = match request.net {
        Which::Both => {
            let phi = run(NetKind::Phi)?;
            let v = run(NetKind::V)?;
            let (a, b) = (NetReport::of(&phi), NetReport::of(&v));
            (phi, v, Some(a), Some(b))
        }
        Which::Phi => {
            let v = kept(NetKind::V)?;
            let phi = run(NetKind::Phi)?;
            let a = NetReport::of(&phi);
            (phi, v, Some(a), None)
        }
        Which::V => {
            let phi = kept(NetKind::Phi)?;
            let v = run(NetKind::V)?;
            let b = NetReport::of(&v);
            (phi, v, None, Some(b))
        }
    };
    let nets = Networks::new(phi.clone(), v.clone())?;
    let mut report = assess(&nets, samples)?;
    report.phi = phi_report;
    report.v = v_report;
    report.verdict = Verdict::of(&report, request.net);
    Ok(Trained { phi, v, report })
}

/// The report of [`train`] for networks already trained.
pub fn assess(nets: &Networks, samples: usize) -> Result<Report> {
    let fresh = evaluation::fresh_samples(nets, 500, 0x7e57)?;
    let phi_error = ErrorStats::of(evaluation::phi_relative_errors(nets, &fresh)?);
    let v_error = ErrorStats::of(evaluation::v_relative_errors(nets, &fresh)?);
    let arm = nets.arm();
    let mut paper_tasks = Vec::new();
    if *arm == Arm::paper() {
        for task in [1, 2] {
            for mode in [Method::CASE1, Method::CASE2, Method::CASE3] {
                paper_tasks.push(evaluation::run_task(nets, task, mode, None, 0.0)?);
            }
        }
    }
    // An arm without such tasks still gets its networks: the check says why
    // it is empty instead of failing the whole job (found by the soak).
    let (scenes, random_tasks_note) =
        match tasks::avoidance_tasks(arm, CHECK_TASKS, tasks::obstacle_region(arm), CHECK_SEED) {
            Ok(scenes) => (scenes, None),
            Err(Error::Training(why)) => (Vec::new(), Some(why)),
            Err(e) => (Vec::new(), Some(e.to_string())),
        };
    let surrogate: Arc<dyn Surrogate> = Arc::new(nets.clone());
    let mut random_tasks = Vec::new();
    for feedback in [0.0, 1.0] {
        if scenes.is_empty() {
            break;
        }
        let scenes: Vec<_> = scenes
            .iter()
            .cloned()
            .map(|mut s| {
                s.feedback_gain = feedback;
                s
            })
            .collect();
        for mode in [
            Method::NUMERICAL,
            Method::CASE1,
            Method::CASE2,
            Method::CASE3,
        ] {
            random_tasks.push(CheckRow {
                feedback,
                check: tasks::check(&scenes, mode, Some(surrogate.clone())),
            });
        }
    }
    let mut report = Report {
        samples,
        phi: None,
        v: None,
        phi_error,
        v_error,
        paper_tasks,
        random_tasks,
        random_tasks_note,
        verdict: Verdict {
            passed: true,
            checked: String::new(),
            failures: Vec::new(),
        },
    };
    report.verdict = Verdict::of(&report, Which::Both);
    Ok(report)
}
