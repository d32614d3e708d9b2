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
use crate::networks::{NetKind, Networks, WeightsFile};
use crate::nn::lm::EpochReport;
use crate::planner::methods::REFINE;
use crate::planner::{Method, Surrogate};
use crate::training::{tasks, train_weights, TrainSpec};

mod verdict;
pub use verdict::{Verdict, PASS_SHARE};

pub use crate::training::Preset;

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
    /// The optimiser: `"lm"` (its `mu` is the damping) or `"adam"` (its
    /// `mu` is the learning rate).
    pub optimiser: &'static str,
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
    /// the drift corrected (`K = 1`), each unrefined and refined
    /// ([`CHECK_LOOPS`]): numerical and Cases 1 to 3.
    pub random_tasks: Vec<CheckRow>,
    /// Why there are no random tasks, when the arm has none in which the
    /// obstacle matters (a 2-link arm has no redundancy to avoid with).
    /// The networks are kept all the same.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub random_tasks_note: Option<String>,
    /// Whether the networks pass this check ([`Verdict`]).
    pub verdict: Verdict,
}

/// The loops the task check runs in, `(K, refine)`: open and closed, each
/// as the paper (no refinement) and with two Newton-Schulz steps on the
/// learned `Phi` (`docs/learning.md`).
pub const CHECK_LOOPS: [(f64, u32); 4] = [(0.0, 0), (1.0, 0), (0.0, 2), (1.0, 2)];

/// One line of the task check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckRow {
    /// Closed-loop gain `K`.
    pub feedback: f64,
    /// Newton-Schulz steps on the learned `Phi`.
    pub refine: u32,
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
    /// The training spec of network `net` this request means: the preset's
    /// recipe for the arm (the paper's: the page's variants and the arm's
    /// sampling), its sizes or the request's, checked.
    pub fn spec(&self, net: NetKind) -> Result<TrainSpec> {
        // One seed for both, as the shipped files (scripts/train-weights.sh):
        // the thorough and reach presets on the paper's arm retrain them.
        let seed = self.seed.unwrap_or(1);
        let mut spec = self.preset.recipe().spec(&self.arm, net, seed);
        if let Some(n) = self.samples.or(self.preset.samples()) {
            spec.samples = n;
        }
        if let Some(n) = self.epochs.or(self.preset.epochs()) {
            spec.set_max_epochs(n);
        }
        within(
            "training samples",
            spec.samples as f64,
            20.0,
            MAX_SAMPLES as f64,
        )?;
        within(
            "training epochs",
            spec.max_epochs() as f64,
            1.0,
            MAX_EPOCHS as f64,
        )?;
        Ok(spec)
    }
}

/// Trains what `request` asks for (by its preset's recipe: for the
/// paper's, the variants the page uses, the rotation-equivariant `Phi` and
/// the plain `v`, with the paper's layer sizes), keeps the other network
/// from `current` when only one is trained, and reports. `on_epoch` sees
/// every epoch; returning `false` stops that network early (what it learnt
/// so far is kept). Nothing is installed anywhere: the caller swaps the
/// networks in, so a failed or abandoned job leaves the ones in use
/// untouched.
///
/// The same job in pieces, for callers with several cores (the page's
/// workers): [`train_net`] for each network, at once, then [`conclude`].
/// Each network's seed depends on the request alone, not on the order, so
/// the pieces give the very same networks and report.
pub fn train(
    request: &Request,
    current: Option<&Networks>,
    mut on_epoch: impl FnMut(&Progress) -> bool,
) -> Result<Trained> {
    let arm = &request.arm;
    arm.validate()?;
    let kept = |net: NetKind| -> Result<WeightsFile> {
        let nets = current
            .filter(|n| n.arm().same_geometry(arm))
            .ok_or_else(|| {
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
    let (phi, v) = match request.net {
        Which::Both => {
            let phi = train_net(request, NetKind::Phi, &mut on_epoch)?;
            (phi, train_net(request, NetKind::V, &mut on_epoch)?)
        }
        Which::Phi => {
            let v = kept(NetKind::V)?;
            (train_net(request, NetKind::Phi, &mut on_epoch)?, v)
        }
        Which::V => {
            let phi = kept(NetKind::Phi)?;
            (phi, train_net(request, NetKind::V, &mut on_epoch)?)
        }
    };
    conclude(request, phi, v)
}

/// Trains network `net` of `request` alone, as [`train`] does.
pub fn train_net(
    request: &Request,
    net: NetKind,
    mut on_epoch: impl FnMut(&Progress) -> bool,
) -> Result<WeightsFile> {
    let spec = request.spec(net)?;
    let name = match net {
        NetKind::Phi => "phi",
        NetKind::V => "v",
    };
    let max_epochs = spec.max_epochs();
    let optimiser = if spec.adam.is_some() { "adam" } else { "lm" };
    train_weights(&spec, |_, report| {
        on_epoch(&Progress {
            net: name,
            optimiser,
            report: *report,
            max_epochs,
        })
    })
}

/// The end of a job whose networks are trained: `phi` and `v` (the one
/// `request` did not train kept from before) checked and reported as
/// [`train`] reports them. Refuses files of another arm than the request's.
pub fn conclude(request: &Request, phi: WeightsFile, v: WeightsFile) -> Result<Trained> {
    let arm = &request.arm;
    if !phi.arm.same_geometry(arm) || !v.arm.same_geometry(arm) {
        return Err(Error::Training(
            "the networks to check were trained for another arm than the request's".into(),
        ));
    }
    let samples = request
        .spec(match request.net {
            Which::V => NetKind::V,
            _ => NetKind::Phi,
        })?
        .samples;
    let trained = |yes: bool, file: &WeightsFile| yes.then(|| NetReport::of(file));
    let phi_report = trained(request.net != Which::V, &phi);
    let v_report = trained(request.net != Which::Phi, &v);
    let nets = Networks::new(phi.clone(), v.clone())?;
    let mut report = assess(&nets, samples)?;
    report.phi = phi_report;
    report.v = v_report;
    report.verdict = Verdict::of(&report, request.net);
    Ok(Trained { phi, v, report })
}

/// The report of [`train`] for networks already trained.
pub fn assess(nets: &Networks, samples: usize) -> Result<Report> {
    let fresh = |net| evaluation::fresh_samples(nets, net, 500, 0x7e57);
    let phi_error = ErrorStats::of(evaluation::phi_relative_errors(
        nets,
        &fresh(NetKind::Phi)?,
    )?);
    let v_error = ErrorStats::of(evaluation::v_relative_errors(nets, &fresh(NetKind::V)?)?);
    let arm = nets.arm();
    let mut paper_tasks = Vec::new();
    if arm.same_geometry(&Arm::paper()) {
        for (feedback, refine) in CHECK_LOOPS {
            for task in [1, 2] {
                for method in [Method::CASE1, Method::CASE2, Method::CASE3] {
                    // Case 2 runs the exact Phi: nothing to refine.
                    if refine > 0 && !method.networks().phi {
                        continue;
                    }
                    paper_tasks.push(evaluation::run_task_refined(
                        nets, task, method, None, feedback, refine,
                    )?);
                }
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
    for (feedback, refine) in CHECK_LOOPS {
        if scenes.is_empty() {
            break;
        }
        let scenes: Vec<_> = scenes
            .iter()
            .cloned()
            .map(|mut s| {
                s.feedback_gain = feedback;
                // Refine is a count within its bounds (CHECK_LOOPS).
                let _ = s.set_param(&REFINE, f64::from(refine));
                s
            })
            .collect();
        for method in [
            Method::NUMERICAL,
            Method::CASE1,
            Method::CASE2,
            Method::CASE3,
        ] {
            // The exact route takes no refinement: once is enough.
            if refine > 0 && !method.networks().phi {
                continue;
            }
            random_tasks.push(CheckRow {
                feedback,
                refine,
                check: tasks::check(&scenes, method, Some(surrogate.clone())),
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
