//! What a trainer reports: one [`EpochReport`] per epoch to the caller's
//! callback, and a [`TrainReport`] with the [`StopReason`] at the end. Shared
//! by Levenberg-Marquardt ([`crate::nn::lm`]) and Adam ([`crate::nn::adam`]),
//! so the command-line tool, the page and the weights files read both alike.

use serde::{Deserialize, Serialize};

/// What one epoch did; passed to the per-epoch callback.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EpochReport {
    /// Epoch number, from 1.
    pub epoch: usize,
    /// Mean squared error on the training set (in mapminmax units).
    /// Levenberg-Marquardt: of the weights after the epoch. Adam: the mean
    /// of the epoch's minibatch losses (each before its step).
    pub train_mse: f64,
    /// Mean squared error on the validation set.
    pub val_mse: f64,
    /// Levenberg-Marquardt: `mu` after this epoch. Adam: the learning rate
    /// of this epoch's steps.
    pub mu: f64,
    /// Levenberg-Marquardt: norm of the gradient of the training sum of
    /// squares, `2 |J^T e|`. Adam: norm of the gradient of the last
    /// minibatch's mean squared error.
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
    /// `max_fail` (Adam: `patience`) epochs in a row without a new best
    /// validation error.
    ValidationStop,
    /// Training MSE reached `goal`.
    Goal,
    /// The callback asked to stop.
    Cancelled,
    /// Adam: a minibatch's loss or gradient was not finite (the learning
    /// rate is too large for the data); the best weights so far are kept.
    Diverged,
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
