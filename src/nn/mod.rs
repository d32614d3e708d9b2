//! Small feed-forward networks and their training, as in the paper's
//! section V: a Matlab-`newff`-style [`Mlp`] with its [`activation`], a
//! `trainlm`-style Levenberg-Marquardt trainer ([`lm`], with [`kronecker`]
//! and [`cholesky`]), Adam with minibatches for networks too wide for it
//! ([`adam`], with the batched passes of [`backprop`]), what both share
//! ([`data`], [`report`]), the run-time [`kernel`] in either [`precision`] and a seeded PRNG ([`Rng`]).
//! Nothing here knows the planner, the paper's networks or their training
//! (the weights file is [`crate::networks::file`], the training data are
//! drawn in `crate::training`). Everything here is single-threaded and
//! free of OS entropy and clocks, so it runs unchanged in the browser.

pub mod activation;
pub mod adam;
pub mod backprop;
pub mod cholesky;
pub mod data;
pub mod gemm;
pub mod kernel;
pub mod kronecker;
pub mod lm;
pub mod mlp;
pub mod precision;
pub mod report;
pub mod rng;

pub use adam::{AdamOptions, AdamTrainer, Decay};
pub use data::Dataset;
pub use kernel::Kernel;
pub use lm::{LmOptions, LmTrainer};
pub use mlp::{MapMinMax, Mlp};
pub use precision::Precision;
pub use report::{EpochReport, StopReason, TrainReport};
pub use rng::Rng;
