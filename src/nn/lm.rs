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
use crate::nn::mlp::{Activations, MapMinMax, Mlp};
use crate::nn::rng::Rng;

/// Training samples: `inputs` and `targets` row-major, one row per sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    /// Inputs per sample.
    pub n_in: usize,
    /// Targets per sample.
    pub n_out: usize,
    /// `len() * n_in` raw inputs.
    pub inputs: Vec<f64>,
    /// `len() * n_out` raw targets.
    pub targets: Vec<f64>,
}

impl Dataset {
    /// An empty set with the given widths.
    pub fn new(n_in: usize, n_out: usize) -> Self {
        Self {
            n_in,
            n_out,
            inputs: Vec::new(),
            targets: Vec::new(),
        }
    }

    /// Appends one sample.
    pub fn push(&mut self, input: &[f64], target: &[f64]) {
        self.inputs.extend_from_slice(&input[..self.n_in]);
        self.targets.extend_from_slice(&target[..self.n_out]);
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.inputs.len().checked_div(self.n_in).unwrap_or(0)
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

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

/// What one epoch did; passed to the per-epoch callback.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EpochReport {
    /// Epoch number, from 1.
    pub epoch: usize,
    /// Mean squared error on the training set (in mapminmax units).
    pub train_mse: f64,
    /// Mean squared error on the validation set.
    pub val_mse: f64,
    /// `mu` after this epoch.
    pub mu: f64,
    /// Norm of the gradient of the training sum of squares, `2 |J^T e|`.
    pub gradient: f64,
}

/// Why training stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// `max_epochs` reached.
    MaxEpochs,
    /// Gradient below `min_grad`.
    MinGradient,
    /// `mu` grew above `mu_max`.
    MuMax,
    /// `max_fail` consecutive validation failures.
    ValidationStop,
    /// Training MSE reached `goal`.
    Goal,
    /// The callback asked to stop.
    Cancelled,
}

/// Outcome of a training run. The returned network has the weights of the
/// epoch with the best validation error (as Matlab keeps them).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TrainReport {
    /// Epochs run.
    pub epochs: usize,
    /// Epoch whose weights were kept (best validation error).
    pub best_epoch: usize,
    /// Why training stopped.
    pub stop: StopReason,
    /// Training MSE of the kept weights (mapminmax units).
    pub train_mse: f64,
    /// Validation MSE of the kept weights.
    pub val_mse: f64,
    /// Test MSE of the kept weights.
    pub test_mse: f64,
    /// Samples in the training, validation and test sets.
    pub split: [usize; 3],
}

/// A Levenberg-Marquardt run that can be advanced one epoch at a time (so a
/// browser can yield between epochs). Build with [`LmTrainer::new`], call
/// [`LmTrainer::epoch`] until it returns a stop reason, then [`LmTrainer::finish`].
#[derive(Debug, Clone)]
pub struct LmTrainer {
    mlp: Mlp,
    opts: LmOptions,
    n_in: usize,
    n_out: usize,
    /// Scaled inputs and targets, row-major.
    x: Vec<f64>,
    t: Vec<f64>,
    train: Vec<usize>,
    val: Vec<usize>,
    test: Vec<usize>,
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

impl LmTrainer {
    /// Scales the data with `mlp`'s maps, splits it at random (seeded by
    /// `rng`) into training, validation and test sets and evaluates the
    /// starting weights.
    pub fn new(mlp: Mlp, data: &Dataset, opts: LmOptions, rng: &mut Rng) -> Result<Self> {
        mlp.validate()?;
        if data.n_in != mlp.inputs() || data.n_out != mlp.outputs() {
            return Err(Error::Training(format!(
                "data has {} inputs and {} targets, the network {} and {}",
                data.n_in,
                data.n_out,
                mlp.inputs(),
                mlp.outputs()
            )));
        }
        if data
            .inputs
            .iter()
            .chain(&data.targets)
            .any(|v| !v.is_finite())
        {
            return Err(Error::NonFinite {
                what: "training data".into(),
            });
        }
        let n = data.len();
        let [ftrain, fval] = opts.split;
        let ok = ftrain > 0.0 && fval >= 0.0 && ftrain + fval <= 1.0;
        if !ok {
            return Err(Error::Training(format!(
                "split fractions {ftrain} / {fval} must be positive and sum to at most 1"
            )));
        }
        let n_train = ((n as f64) * ftrain).round() as usize;
        let n_val = ((n as f64) * fval).round() as usize;
        if n_train == 0 || n_train + n_val > n {
            return Err(Error::Training(format!(
                "{n} samples are too few to split {ftrain} / {fval}"
            )));
        }
        opts.validate()?;
        let mut idx: Vec<usize> = (0..n).collect();
        rng.shuffle(&mut idx);
        let train = idx[..n_train].to_vec();
        let val = idx[n_train..n_train + n_val].to_vec();
        let test = idx[n_train + n_val..].to_vec();
        let (n_in, n_out) = (data.n_in, data.n_out);
        let mut x = Vec::with_capacity(data.inputs.len());
        for row in data.inputs.chunks_exact(n_in) {
            x.extend(
                row.iter()
                    .enumerate()
                    .map(|(i, &v)| mlp.input_map.apply(i, v)),
            );
        }
        let mut t = Vec::with_capacity(data.targets.len());
        for row in data.targets.chunks_exact(n_out) {
            t.extend(
                row.iter()
                    .enumerate()
                    .map(|(i, &v)| mlp.output_map.apply(i, v)),
            );
        }
        let params = DVector::from_vec(mlp.params());
        let acts = Activations::new(&mlp.sizes);
        let normal = Normal::new(&mlp.sizes, opts.chunk.min(n_train));
        let mut tr = Self {
            mu: opts.mu,
            opts,
            n_in,
            n_out,
            x,
            t,
            train,
            val,
            test,
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
        tr.perf = tr.mse(&tr.train.clone());
        tr.best_val = if tr.val.is_empty() {
            f64::INFINITY
        } else {
            tr.mse(&tr.val.clone())
        };
        Ok(tr)
    }

    /// Mean squared error (scaled units) of the current weights on the samples `idx`.
    fn mse(&mut self, idx: &[usize]) -> f64 {
        if idx.is_empty() {
            return 0.0;
        }
        let mut sse = 0.0;
        for &i in idx {
            self.mlp
                .forward_scaled(&self.x[i * self.n_in..(i + 1) * self.n_in], &mut self.acts);
            let y = self.acts.output();
            sse += y
                .iter()
                .zip(&self.t[i * self.n_out..(i + 1) * self.n_out])
                .map(|(a, b)| (b - a) * (b - a))
                .sum::<f64>();
        }
        sse / (idx.len() * self.n_out) as f64
    }

    /// `J^T J` and `J^T e` over the training set, `J = dy/dparams`, `e = t - y`,
    /// from the layer structure of `J` (see [`Normal`]).
    fn normal_equations(&mut self) -> (DMatrix<f64>, DVector<f64>) {
        let mut normal = std::mem::take(&mut self.normal);
        let train = std::mem::take(&mut self.train);
        let out = normal.accumulate(&self.mlp, &self.x, &self.t, &train, &mut self.acts);
        self.train = train;
        self.normal = normal;
        out
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
        let train = self.train.clone();
        let mut improved = false;
        while self.mu <= self.opts.mu_max {
            let mut a = jtj.clone();
            for i in 0..a.nrows() {
                a[(i, i)] += self.mu;
            }
            if let Some(dx) = cholesky::solve_spd(a, &jte) {
                let trial = &self.params + dx;
                self.mlp.set_params(trial.as_slice());
                let perf = self.mse(&train);
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
        let val_mse = if self.val.is_empty() {
            f64::INFINITY
        } else {
            self.mse(&self.val.clone())
        };
        if self.val.is_empty() || val_mse < self.best_val {
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
        if self.best_epoch > 0 || !self.val.is_empty() {
            self.mlp.set_params(self.best_params.as_slice());
        } else {
            self.mlp.set_params(self.params.as_slice());
        }
        let train_mse = self.mse(&self.train.clone());
        let val_mse = self.mse(&self.val.clone());
        let test_mse = self.mse(&self.test.clone());
        let report = TrainReport {
            epochs: self.epoch,
            best_epoch: self.best_epoch,
            stop,
            train_mse,
            val_mse,
            test_mse,
            split: [self.train.len(), self.val.len(), self.test.len()],
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
    if sizes.first() != Some(&data.n_in) || sizes.last() != Some(&data.n_out) {
        return Err(Error::Training(format!(
            "layer sizes {sizes:?} do not fit data with {} inputs and {} targets",
            data.n_in, data.n_out
        )));
    }
    let mut rng = Rng::new(seed);
    let input_map = MapMinMax::fit(&data.inputs, data.n_in);
    let output_map = MapMinMax::fit(&data.targets, data.n_out);
    let mlp = Mlp::nguyen_widrow(sizes, input_map, output_map, &mut rng)?;
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
