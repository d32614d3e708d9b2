//! Adam with minibatches (Kingma and Ba, 2015), for networks too wide for
//! Levenberg-Marquardt.
//!
//! Levenberg-Marquardt ([`crate::nn::lm`]) forms `J^T J`, which grows as the
//! square of the parameter count: the 4-96-96-6 network (10,374 weights and
//! biases) needs an 861 MB matrix, as much again for the copy each trial
//! step factors, and `P^3 / 6 = 1.9e11` multiply-adds per factorisation;
//! 4-128-128-6 (17,926) needs 2.6 GB. Adam keeps three vectors of the parameters'
//! size (the two moments and the gradient) and the activations of one
//! minibatch ([`Backprop`]), so it trains them in a few megabytes.
//!
//! It mirrors [`lm::train`](crate::nn::lm::train): the same [`Dataset`],
//! the same mapminmax scaling, Nguyen-Widrow start and 70/15/15 split for a
//! seed ([`crate::nn::data`]), the same [`EpochReport`] per epoch and
//! [`TrainReport`] at the end, with the best-validation weights kept. An
//! epoch shuffles the training set (the crate's [`Rng`], so a seed fixes the
//! run), takes one Adam step per minibatch with the epoch's learning rate
//! ([`Decay`]), then measures the validation error; `patience` epochs in a
//! row without a new best stop the run.
//!
//! Written by hand rather than taken from burn, candle or dfdx: an update
//! is a dozen lines, the batched passes three `gemm`s per layer through
//! [`crate::nn::gemm`] (nalgebra natively, which the crate already has, and
//! a wasm SIMD kernel in the page's build), and the trainer must run
//! deterministically and single-threaded in the page's worker. Measured:
//! made reachable from the workers' SIMD module (a probe export calling
//! [`train`]), it adds 11.8 KB to its 546 KB (5.1 KB gzipped to its 201 KB);
//! one epoch of 4-96-96-6 on 14,000 samples takes about 50 ms natively, and
//! the recipe of [`AdamOptions::default`] trains that network on the
//! Phi-over-the-torus workload to a median relative error of 4.9e-3 in
//! about 30 s (`docs/speed.md`, "Adam"). Those crates each bring a tensor
//! library with its own kernels and dependencies; we did not build them
//! for wasm, so their cost is not measured here.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::nn::backprop::Backprop;
use crate::nn::data::{fresh_network, Dataset, Prepared};
use crate::nn::mlp::{Activations, Mlp};
use crate::nn::report::{EpochReport, StopReason, TrainReport};
use crate::nn::rng::Rng;

/// How the learning rate changes from epoch to epoch. In JSON an object
/// tagged by `kind`: `{"kind": "constant"}`, `{"kind": "cosine", "floor":
/// 0.01}`, `{"kind": "step", "every": 250, "factor": 0.3}`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "DecayFields", into = "DecayFields")]
pub enum Decay {
    /// The same rate every epoch.
    Constant,
    /// Half a cosine from `learning_rate` in the first epoch down to
    /// `floor * learning_rate` in epoch `max_epochs` (`0 <= floor <= 1`).
    Cosine {
        /// Last rate as a fraction of the first.
        floor: f64,
    },
    /// The rate multiplied by `factor` (`0 < factor <= 1`) after every
    /// `every` epochs.
    Step {
        /// Epochs per step (at least 1).
        every: usize,
        /// Factor per step.
        factor: f64,
    },
}

/// [`Decay`] as it reads and writes: one flat object rather than serde's
/// internally tagged enum, which buffers every value it reads and put
/// 7.8 KB (gzipped) on the page's module, which reads weights files
/// (`docs/web.md`).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct DecayFields {
    kind: DecayKind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    floor: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    every: Option<usize>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    factor: Option<f64>,
}

#[derive(Clone, Copy, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum DecayKind {
    Constant,
    Cosine,
    Step,
}

impl TryFrom<DecayFields> for Decay {
    type Error = String;

    fn try_from(f: DecayFields) -> std::result::Result<Self, String> {
        let missing = |field: &str, kind: &str| format!("decay '{kind}' needs '{field}'");
        let extra = |kind: &str| format!("decay '{kind}' takes no other fields");
        match f.kind {
            DecayKind::Constant if f.floor.is_none() && f.every.is_none() && f.factor.is_none() => {
                Ok(Decay::Constant)
            }
            DecayKind::Constant => Err(extra("constant")),
            DecayKind::Cosine if f.every.is_some() || f.factor.is_some() => Err(extra("cosine")),
            DecayKind::Cosine => Ok(Decay::Cosine {
                floor: f.floor.ok_or_else(|| missing("floor", "cosine"))?,
            }),
            DecayKind::Step if f.floor.is_some() => Err(extra("step")),
            DecayKind::Step => Ok(Decay::Step {
                every: f.every.ok_or_else(|| missing("every", "step"))?,
                factor: f.factor.ok_or_else(|| missing("factor", "step"))?,
            }),
        }
    }
}

impl From<Decay> for DecayFields {
    fn from(d: Decay) -> Self {
        let (kind, floor, every, factor) = match d {
            Decay::Constant => (DecayKind::Constant, None, None, None),
            Decay::Cosine { floor } => (DecayKind::Cosine, Some(floor), None, None),
            Decay::Step { every, factor } => (DecayKind::Step, None, Some(every), Some(factor)),
        };
        Self {
            kind,
            floor,
            every,
            factor,
        }
    }
}

/// Adam's parameters. Missing fields take the defaults, unknown ones are
/// refused (a misspelt option would otherwise be silently ignored).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AdamOptions {
    /// Stop after this many epochs.
    pub max_epochs: usize,
    /// Samples per minibatch (the last one of an epoch may be smaller).
    pub batch: usize,
    /// Step size of the first epoch.
    pub learning_rate: f64,
    /// How the step size falls over the epochs.
    pub decay: Decay,
    /// Decay of the first-moment (mean) estimate, in `[0, 1)`.
    pub beta1: f64,
    /// Decay of the second-moment estimate, in `[0, 1)`.
    pub beta2: f64,
    /// Added to the root of the second moment, positive.
    pub eps: f64,
    /// Stop after this many epochs in a row without a new best validation
    /// error (at least 1).
    pub patience: usize,
    /// Fractions of samples used for training and validation; the rest is
    /// the test set.
    pub split: [f64; 2],
}

/// The recipe measured on `Phi` over the whole joint torus with a
/// 4-96-96-6 network and 20,000 samples (`docs/speed.md`, "Adam"): median
/// relative error 4.9e-3 on fresh samples. The betas and `eps` are Kingma
/// and Ba's.
impl Default for AdamOptions {
    fn default() -> Self {
        Self {
            max_epochs: 600,
            batch: 64,
            learning_rate: 2e-3,
            decay: Decay::Cosine { floor: 0.01 },
            beta1: 0.9,
            beta2: 0.999,
            eps: 1e-8,
            patience: 100,
            split: [0.70, 0.15],
        }
    }
}

impl AdamOptions {
    /// Checks every number: at least one epoch, a batch of at least one,
    /// a positive finite learning rate, a decay with a floor in `[0, 1]` or
    /// a step of at least one epoch with a factor in `(0, 1]`, `beta1` and
    /// `beta2` in `[0, 1)`, a positive finite `eps`, a patience of at least
    /// one epoch. (The split is checked against the data when training
    /// starts.)
    pub fn validate(&self) -> Result<()> {
        let problem = if self.max_epochs == 0 {
            "max_epochs must be at least 1".to_string()
        } else if self.batch == 0 {
            "batch must be at least 1 sample".to_string()
        } else if !(self.learning_rate.is_finite() && self.learning_rate > 0.0) {
            format!(
                "learning_rate must be positive and finite (got {})",
                self.learning_rate
            )
        } else if let Some(p) = self.decay.problem() {
            p
        } else if !(0.0..1.0).contains(&self.beta1) || !(0.0..1.0).contains(&self.beta2) {
            format!(
                "beta1 and beta2 must lie in [0, 1) (got {} and {})",
                self.beta1, self.beta2
            )
        } else if !(self.eps.is_finite() && self.eps > 0.0) {
            format!("eps must be positive and finite (got {})", self.eps)
        } else if self.patience == 0 {
            "patience must be at least 1 epoch".to_string()
        } else {
            return Ok(());
        };
        Err(Error::Training(format!("Adam options: {problem}")))
    }

    /// The learning rate of epoch `epoch` (from 1).
    pub fn rate(&self, epoch: usize) -> f64 {
        let lr = self.learning_rate;
        match self.decay {
            Decay::Constant => lr,
            Decay::Cosine { floor } => {
                let span = self.max_epochs.saturating_sub(1).max(1) as f64;
                let x = (epoch.saturating_sub(1) as f64 / span).min(1.0);
                lr * (floor + (1.0 - floor) * 0.5 * (1.0 + (std::f64::consts::PI * x).cos()))
            }
            Decay::Step { every, factor } => {
                let steps = (epoch.saturating_sub(1) / every.max(1)).min(i32::MAX as usize);
                lr * factor.powi(steps as i32)
            }
        }
    }
}

impl Decay {
    fn problem(&self) -> Option<String> {
        match *self {
            Decay::Constant => None,
            Decay::Cosine { floor } => (!(0.0..=1.0).contains(&floor))
                .then(|| format!("the cosine floor must lie in [0, 1] (got {floor})")),
            Decay::Step { every, factor } => {
                if every == 0 {
                    Some("a step decay needs at least 1 epoch per step".into())
                } else if !(factor > 0.0 && factor <= 1.0) {
                    Some(format!("the step factor must lie in (0, 1] (got {factor})"))
                } else {
                    None
                }
            }
        }
    }
}

/// An Adam run that can be advanced one epoch at a time (so a browser can
/// yield between epochs): [`AdamTrainer::new`], [`AdamTrainer::epoch`] until
/// it returns a stop reason, then [`AdamTrainer::finish`].
#[derive(Debug, Clone)]
pub struct AdamTrainer {
    mlp: Mlp,
    opts: AdamOptions,
    data: Prepared,
    rng: Rng,
    /// The training rows in this epoch's order.
    order: Vec<usize>,
    params: Vec<f64>,
    grad: Vec<f64>,
    /// First and second moment estimates.
    m: Vec<f64>,
    v: Vec<f64>,
    /// `beta1^t` and `beta2^t` after `t` steps.
    beta1_t: f64,
    beta2_t: f64,
    best_params: Vec<f64>,
    best_val: f64,
    best_epoch: usize,
    fails: usize,
    epoch: usize,
    stopped: Option<StopReason>,
    passes: Backprop,
    acts: Activations,
}

impl AdamTrainer {
    /// Scales the data with `mlp`'s maps and splits it at random (the first
    /// draws of `rng`, which then shuffles every epoch).
    pub fn new(mlp: Mlp, data: &Dataset, opts: AdamOptions, mut rng: Rng) -> Result<Self> {
        opts.validate()?;
        let data = Prepared::new(&mlp, data, opts.split, &mut rng)?;
        let params = mlp.params();
        let n = params.len();
        let passes = Backprop::new(&mlp.sizes, opts.batch.min(data.train.len()));
        let mut tr = Self {
            opts,
            rng,
            order: data.train.clone(),
            grad: vec![0.0; n],
            m: vec![0.0; n],
            v: vec![0.0; n],
            beta1_t: 1.0,
            beta2_t: 1.0,
            best_params: params.clone(),
            params,
            best_val: f64::INFINITY,
            best_epoch: 0,
            fails: 0,
            epoch: 0,
            stopped: None,
            passes,
            acts: Activations::new(&mlp.sizes),
            data,
            mlp,
        };
        if !tr.data.val.is_empty() {
            tr.best_val = tr.batched_mse(Set::Val);
        }
        Ok(tr)
    }

    /// Mean squared error (scaled units) of the current parameters on one
    /// set, through the batched forward pass.
    fn batched_mse(&mut self, set: Set) -> f64 {
        let rows = match set {
            Set::Val => &self.data.val,
            Set::Train => &self.data.train,
        };
        if rows.is_empty() {
            return 0.0;
        }
        let (n_in, n_out) = (self.data.n_in, self.data.n_out);
        let mut sse = 0.0;
        for chunk in rows.chunks(self.passes.capacity()) {
            for (c, &i) in chunk.iter().enumerate() {
                let (x, _) = self.passes.slots(c);
                x.copy_from_slice(&self.data.x[i * n_in..(i + 1) * n_in]);
            }
            self.passes.forward(&self.params, chunk.len());
            let y = self.passes.outputs(chunk.len());
            for (yc, &i) in y.chunks_exact(n_out).zip(chunk) {
                let t = &self.data.t[i * n_out..(i + 1) * n_out];
                sse += yc
                    .iter()
                    .zip(t)
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>();
            }
        }
        sse / (rows.len() * n_out) as f64
    }

    /// One epoch: shuffle, one Adam step per minibatch, the validation
    /// check. Returns the epoch's report and, when training is over, why.
    pub fn epoch(&mut self) -> (EpochReport, Option<StopReason>) {
        if let Some(stop) = self.stopped {
            return (self.report(0.0, 0.0, 0.0), Some(stop));
        }
        self.epoch += 1;
        let lr = self.opts.rate(self.epoch);
        let AdamOptions {
            beta1, beta2, eps, ..
        } = self.opts;
        self.rng.shuffle(&mut self.order);
        let (n_in, n_out) = (self.data.n_in, self.data.n_out);
        let (mut loss_sum, mut grad_norm) = (0.0, 0.0);
        for chunk in self.order.chunks(self.passes.capacity()) {
            let b = chunk.len();
            for (c, &i) in chunk.iter().enumerate() {
                let (x, t) = self.passes.slots(c);
                x.copy_from_slice(&self.data.x[i * n_in..(i + 1) * n_in]);
                t.copy_from_slice(&self.data.t[i * n_out..(i + 1) * n_out]);
            }
            self.passes.forward(&self.params, b);
            let loss = self.passes.backward(&self.params, b, &mut self.grad);
            let norm2: f64 = self.grad.iter().map(|g| g * g).sum();
            if !(loss.is_finite() && norm2.is_finite()) {
                self.params.copy_from_slice(&self.best_params);
                self.stopped = Some(StopReason::Diverged);
                return (self.report(lr, f64::NAN, f64::NAN), self.stopped);
            }
            loss_sum += loss * b as f64;
            grad_norm = norm2.sqrt();
            self.beta1_t *= beta1;
            self.beta2_t *= beta2;
            let step = lr / (1.0 - self.beta1_t);
            let root2 = 1.0 / (1.0 - self.beta2_t).sqrt();
            for (((p, g), m), v) in self
                .params
                .iter_mut()
                .zip(&self.grad)
                .zip(&mut self.m)
                .zip(&mut self.v)
            {
                *m = beta1 * *m + (1.0 - beta1) * g;
                *v = beta2 * *v + (1.0 - beta2) * g * g;
                *p -= step * *m / ((*v).sqrt() * root2 + eps);
            }
        }
        let train_mse = loss_sum / self.order.len() as f64;
        let val_mse = if self.data.val.is_empty() {
            f64::INFINITY
        } else {
            self.batched_mse(Set::Val)
        };
        if !val_mse.is_nan() && (self.data.val.is_empty() || val_mse < self.best_val) {
            self.best_val = val_mse;
            self.best_params.copy_from_slice(&self.params);
            self.best_epoch = self.epoch;
            self.fails = 0;
        } else {
            self.fails += 1;
        }
        self.stopped = if self.fails >= self.opts.patience {
            Some(StopReason::ValidationStop)
        } else if self.epoch >= self.opts.max_epochs {
            Some(StopReason::MaxEpochs)
        } else {
            None
        };
        (self.report(lr, train_mse, grad_norm), self.stopped)
    }

    fn report(&self, lr: f64, train_mse: f64, gradient: f64) -> EpochReport {
        EpochReport {
            epoch: self.epoch,
            train_mse,
            val_mse: self.best_val,
            mu: lr,
            gradient,
        }
    }

    /// The current training-set error through the batched pass (scaled units).
    pub fn train_mse(&mut self) -> f64 {
        self.batched_mse(Set::Train)
    }

    /// The network with the best-validation weights, and the run's figures.
    pub fn finish(mut self) -> (Mlp, TrainReport) {
        let stop = self.stopped.unwrap_or(StopReason::Cancelled);
        self.mlp.set_params(&self.best_params);
        let d = &self.data;
        let train_mse = d.mse(&self.mlp, &d.train, &mut self.acts);
        let val_mse = d.mse(&self.mlp, &d.val, &mut self.acts);
        let test_mse = d.mse(&self.mlp, &d.test, &mut self.acts);
        let report = TrainReport {
            epochs: self.epoch,
            best_epoch: self.best_epoch,
            stop,
            train_mse,
            val_mse,
            test_mse,
            split: d.split(),
        };
        (self.mlp, report)
    }

    /// Stops the run as if the callback had asked to.
    pub fn cancel(&mut self) {
        self.stopped.get_or_insert(StopReason::Cancelled);
    }
}

/// The sets [`AdamTrainer`] measures with the batched pass.
#[derive(Debug, Clone, Copy)]
enum Set {
    Train,
    Val,
}

/// Trains a fresh Nguyen-Widrow network of layer widths `sizes` on `data`
/// (mapminmax maps fitted to the data) by Adam. Everything random (initial
/// weights, split, the order of every epoch) comes from `seed`, so a seed
/// fixes the result on a given build. `on_epoch` sees every epoch; returning
/// `false` stops training. The initial weights and the split are those
/// [`lm::train`](crate::nn::lm::train) draws for the same seed.
pub fn train(
    sizes: &[usize],
    data: &Dataset,
    opts: AdamOptions,
    seed: u64,
    mut on_epoch: impl FnMut(&EpochReport) -> bool,
) -> Result<(Mlp, TrainReport)> {
    opts.validate()?;
    let mut rng = Rng::new(seed);
    let mlp = fresh_network(sizes, data, &mut rng)?;
    let mut trainer = AdamTrainer::new(mlp, data, opts, rng)?;
    loop {
        let (report, stop) = trainer.epoch();
        let go_on = on_epoch(&report);
        if stop.is_some() {
            break;
        }
        if !go_on {
            trainer.cancel();
            break;
        }
    }
    Ok(trainer.finish())
}
