//! Levenberg-Marquardt training with Matlab `trainlm`'s behaviour (`docs/conventions.md`,
//! "The networks").
//!
//! Written by hand on purpose: no maintained Rust crate reproduces `trainlm`'s
//! semantics (the `mu` schedule, the 70/15/15 split with early stopping that
//! keeps the best-validation weights, Nguyen-Widrow starts) while keeping
//! memory small by accumulating `J^T J` over chunks of samples, and the
//! trainer must also run, deterministically and single-threaded, in a
//! browser (`wasm32-unknown-unknown`). The heavy part, `J^T J`, is built
//! from the layer structure of `J` ([`crate::nn::kronecker`]): a few large
//! `gemm`s through nalgebra (which hands them to `matrixmultiply`), with
//! about 8 times fewer multiply-adds than `J^T J` from `J`'s rows; the
//! `(J^T J + mu I) dx = J^T e` solve is a blocked Cholesky factorisation
//! ([`crate::nn::cholesky`]).

use nalgebra::{DMatrix, DVector};

use crate::nn::cholesky;
use crate::nn::kronecker::Normal;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
pub use crate::nn::data::Dataset;
use crate::nn::data::{fresh_network, Prepared};
use crate::nn::mlp::{Activations, Mlp};
pub use crate::nn::report::{EpochReport, StopReason, TrainReport};
use crate::nn::rng::Rng;

/// `trainlm`'s parameters; the defaults are Matlab's except `max_epochs`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LmOptions {
    /// Stop after this many epochs.
    pub max_epochs: usize,
    /// Initial `mu` (Matlab `mu = 1e-3`).
    pub mu: f64,
    /// Factor applied to `mu` after a successful step (0.1).
    pub mu_dec: f64,
    /// Factor applied to `mu` after a failed step (10).
    pub mu_inc: f64,
    /// Stop when `mu` exceeds this (1e10).
    pub mu_max: f64,
    /// Stop when the gradient norm falls below this (1e-7).
    pub min_grad: f64,
    /// Stop after this many consecutive epochs without a new best validation error (6).
    pub max_fail: usize,
    /// Stop when the training MSE reaches this (0).
    pub goal: f64,
    /// Samples per chunk when accumulating `J^T J`.
    pub chunk: usize,
    /// Fractions of samples used for training and validation; the rest is the test set.
    pub split: [f64; 2],
}

impl Default for LmOptions {
    fn default() -> Self {
        Self {
            max_epochs: 400,
            mu: 1e-3,
            mu_dec: 0.1,
            mu_inc: 10.0,
            mu_max: 1e10,
            min_grad: 1e-7,
            max_fail: 6,
            goal: 0.0,
            chunk: 64,
            split: [0.70, 0.15],
        }
    }
}

/// Smallest `mu` the trainer keeps (the smallest normal `f64`): `mu`
/// stays positive, so `mu_inc` always lifts it past `mu_max` in the end.
pub const MU_MIN: f64 = f64::MIN_POSITIVE;

/// Smallest `mu_inc` accepted: a failing epoch then tries at most
/// `ln(f64::MAX / MU_MIN) / ln 1.5`, about 3 500, values of `mu`
/// (with `trainlm`'s 10: 616 at most).
pub const MIN_MU_INC: f64 = 1.5;

impl LmOptions {
    /// Checks that the options make a trainer that ends: at least one
    /// epoch, `0 < mu <= mu_max` finite, `0 < mu_dec < 1`, `mu_inc` at
    /// least [`MIN_MU_INC`] (else `mu` creeps towards `mu_max` and a
    /// failing epoch takes for ever),
    /// `min_grad` and `goal` finite and non-negative, `chunk` positive.
    /// (The split is checked against the data by [`LmTrainer::new`].)
    pub fn validate(&self) -> Result<()> {
        let fine = |x: f64| x.is_finite() && x >= 0.0;
        let problem = if self.max_epochs == 0 {
            "max_epochs must be at least 1"
        } else if !(self.mu.is_finite()
            && self.mu > 0.0
            && self.mu_max.is_finite()
            && self.mu <= self.mu_max)
        {
            "mu must be positive and finite, at most mu_max"
        } else if !(self.mu_dec > 0.0 && self.mu_dec < 1.0) {
            "mu_dec must lie in (0, 1)"
        } else if !(self.mu_inc.is_finite() && self.mu_inc >= MIN_MU_INC) {
            "mu_inc must be finite and at least 1.5"
        } else if !(fine(self.min_grad) && fine(self.goal)) {
            "min_grad and goal must be finite and non-negative"
        } else if self.chunk == 0 {
            "chunk must be at least 1"
        } else {
            return Ok(());
        };
        Err(Error::Training(format!(
            "Levenberg-Marquardt options: {problem}"
        )))
    }
}

/// One of the three sets of the split.
#[derive(Debug, Clone, Copy)]
enum Set {
    Train,
    Val,
    Test,
}

/// A Levenberg-Marquardt run that can be advanced one epoch at a time (so a
/// browser can yield between epochs). Build with [`LmTrainer::new`], call
/// [`LmTrainer::epoch`] until it returns a stop reason, then [`LmTrainer::finish`].
#[derive(Debug, Clone)]
pub struct LmTrainer {
    mlp: Mlp,
    opts: LmOptions,
    /// The scaled data and its split.
    data: Prepared,
    params: DVector<f64>,
    mu: f64,
    perf: f64,
    best_params: DVector<f64>,
    best_val: f64,
    best_epoch: usize,
    fails: usize,
    epoch: usize,
    stopped: Option<StopReason>,
    acts: Activations,
    normal: Normal,
}

/// Most weights a network trained by Levenberg-Marquardt may have: its
/// `J^T J` holds the square of them in `f64`s, and each trial factors a
/// copy (6 000 weights: 288 MB each). Wider networks are Adam's
/// ([`crate::nn::adam`]); the paper's have 699 (`Phi`) and 559 (`v`).
pub const MAX_LM_WEIGHTS: usize = 6_000;

impl LmTrainer {
    /// Scales the data with `mlp`'s maps, splits it at random (seeded by
    /// `rng`) into training, validation and test sets and evaluates the
    /// starting weights.
    pub fn new(mlp: Mlp, data: &Dataset, opts: LmOptions, rng: &mut Rng) -> Result<Self> {
        opts.validate()?;
        let n = mlp.params().len();
        if n > MAX_LM_WEIGHTS {
            return Err(Error::Training(format!(
                "a network of {n} weights is too wide for Levenberg-Marquardt (its J^T J alone \
                 would take {:.0} MB; at most {MAX_LM_WEIGHTS} weights): train it by Adam \
                 (--optimiser adam)",
                (n * n * 8) as f64 / 1e6
            )));
        }
        let data = Prepared::new(&mlp, data, opts.split, rng)?;
        let params = DVector::from_vec(mlp.params());
        let acts = Activations::new(&mlp.sizes);
        let normal = Normal::new(&mlp.sizes, opts.chunk.min(data.train.len()));
        let mut tr = Self {
            mu: opts.mu,
            opts,
            data,
            best_params: params.clone(),
            params,
            perf: f64::INFINITY,
            best_val: f64::INFINITY,
            best_epoch: 0,
            fails: 0,
            epoch: 0,
            stopped: None,
            acts,
            normal,
            mlp,
        };
        tr.perf = tr.mse(Set::Train);
        tr.best_val = if tr.data.val.is_empty() {
            f64::INFINITY
        } else {
            tr.mse(Set::Val)
        };
        Ok(tr)
    }

    /// Mean squared error (scaled units) of the current weights on one set.
    fn mse(&mut self, set: Set) -> f64 {
        let idx = match set {
            Set::Train => &self.data.train,
            Set::Val => &self.data.val,
            Set::Test => &self.data.test,
        };
        self.data.mse(&self.mlp, idx, &mut self.acts)
    }

    /// `J^T J` and `J^T e` over the training set, `J = dy/dparams`, `e = t - y`,
    /// from the layer structure of `J` (see [`Normal`]).
    fn normal_equations(&mut self) -> (DMatrix<f64>, DVector<f64>) {
        let d = &self.data;
        self.normal
            .accumulate(&self.mlp, &d.x, &d.t, &d.train, &mut self.acts)
    }

    /// One `trainlm` epoch: build the normal equations, then try
    /// `(J^T J + mu I) dx = J^T e` with growing `mu` until the training error
    /// falls (then `mu *= mu_dec`) or `mu > mu_max`. Then the validation
    /// check. Returns the epoch's report and, when training is over, why.
    pub fn epoch(&mut self) -> (EpochReport, Option<StopReason>) {
        if let Some(stop) = self.stopped {
            return (self.report(0.0), Some(stop));
        }
        self.epoch += 1;
        let (jtj, jte) = self.normal_equations();
        let gradient = 2.0 * jte.norm();
        if gradient < self.opts.min_grad {
            self.stopped = Some(StopReason::MinGradient);
            return (self.report(gradient), self.stopped);
        }
        let mut improved = false;
        while self.mu <= self.opts.mu_max {
            let mut a = jtj.clone();
            for i in 0..a.nrows() {
                a[(i, i)] += self.mu;
            }
            if let Some(dx) = cholesky::solve_spd(a, &jte) {
                let trial = &self.params + dx;
                self.mlp.set_params(trial.as_slice());
                let perf = self.mse(Set::Train);
                if perf < self.perf {
                    self.params = trial;
                    self.perf = perf;
                    // Floored: the `trainlm` rule as `docs/conventions.md` states it (x0.1
                    // after a success, no floor) reaches 0 after about 320
                    // successes in a row; then `mu * mu_inc` stays 0 and a
                    // failing epoch never ends (found by fuzzing).
                    self.mu = (self.mu * self.opts.mu_dec).max(MU_MIN);
                    improved = true;
                    break;
                }
            }
            self.mu *= self.opts.mu_inc;
        }
        if !improved {
            self.mlp.set_params(self.params.as_slice());
            self.stopped = Some(StopReason::MuMax);
            return (self.report(gradient), self.stopped);
        }
        let val_mse = if self.data.val.is_empty() {
            f64::INFINITY
        } else {
            self.mse(Set::Val)
        };
        if self.data.val.is_empty() || val_mse < self.best_val {
            self.best_val = val_mse;
            self.best_params = self.params.clone();
            self.best_epoch = self.epoch;
            self.fails = 0;
        } else if val_mse > self.best_val {
            self.fails += 1;
        }
        let mut report = self.report(gradient);
        report.val_mse = val_mse;
        self.stopped = if self.perf <= self.opts.goal {
            Some(StopReason::Goal)
        } else if self.fails >= self.opts.max_fail {
            Some(StopReason::ValidationStop)
        } else if self.epoch >= self.opts.max_epochs {
            Some(StopReason::MaxEpochs)
        } else {
            None
        };
        (report, self.stopped)
    }

    fn report(&self, gradient: f64) -> EpochReport {
        EpochReport {
            epoch: self.epoch,
            train_mse: self.perf,
            val_mse: self.best_val,
            mu: self.mu,
            gradient,
        }
    }

    /// The network with the best-validation weights, and the run's figures.
    pub fn finish(mut self) -> (Mlp, TrainReport) {
        let stop = self.stopped.unwrap_or(StopReason::Cancelled);
        if self.best_epoch > 0 || !self.data.val.is_empty() {
            self.mlp.set_params(self.best_params.as_slice());
        } else {
            self.mlp.set_params(self.params.as_slice());
        }
        let train_mse = self.mse(Set::Train);
        let val_mse = self.mse(Set::Val);
        let test_mse = self.mse(Set::Test);
        let report = TrainReport {
            epochs: self.epoch,
            best_epoch: self.best_epoch,
            stop,
            train_mse,
            val_mse,
            test_mse,
            split: self.data.split(),
        };
        (self.mlp, report)
    }
}

/// Trains a fresh Nguyen-Widrow network of layer widths `sizes` on `data`
/// (mapminmax maps fitted to the data) with `trainlm` semantics. Everything
/// random (initial weights, split) comes from `seed`, so a seed fixes the
/// result. `on_epoch` sees every epoch; returning `false` stops training.
pub fn train(
    sizes: &[usize],
    data: &Dataset,
    opts: LmOptions,
    seed: u64,
    mut on_epoch: impl FnMut(&EpochReport) -> bool,
) -> Result<(Mlp, TrainReport)> {
    let mut rng = Rng::new(seed);
    let mlp = fresh_network(sizes, data, &mut rng)?;
    let mut trainer = LmTrainer::new(mlp, data, opts, &mut rng)?;
    loop {
        let (report, stop) = trainer.epoch();
        let go_on = on_epoch(&report);
        if stop.is_some() {
            break;
        }
        if !go_on {
            trainer.stopped = Some(StopReason::Cancelled);
            break;
        }
    }
    Ok(trainer.finish())
}
