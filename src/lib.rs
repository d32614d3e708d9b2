#![doc = include_str!("../README.md")]
// One audited exception: the run-time AVX2/FMA dispatch in `nn::kernel`.
#![deny(unsafe_code)]
#![warn(missing_docs)]

// The command-line shell (module `cli`) names the library as a user does,
// `redundant_ik::...`, inside the library too.
extern crate self as redundant_ik;

pub mod arm;
pub mod atlas;
#[cfg(any(feature = "embedded-weights", feature = "worker"))]
pub mod bench;
pub mod clearance;
// The command-line shell: the binary's, and the Python module's (which runs
// its commands in process). Its interface is its `--help`, whose text its
// doc comments are, so it stays out of the library's documentation.
#[cfg(all(feature = "cli", not(target_family = "wasm")))]
#[doc(hidden)]
pub mod cli;
pub mod error;
#[cfg(feature = "eval")]
pub mod evaluation;
pub mod export;
#[cfg(feature = "figure")]
pub mod figure;
pub mod geometry;
pub mod ik;
mod json;
pub mod kinematics;
pub mod model;
pub mod networks;
pub mod nn;
pub mod obstacle;
pub mod palette;
pub mod planner;
// The Python package's native module (feature python; docs/python.md).
#[cfg(all(feature = "python", not(target_family = "wasm")))]
pub mod python;
pub mod qp;
pub mod run;
pub mod scene;
pub mod session;
pub mod space;
pub mod training;
#[cfg(feature = "eval")]
pub mod training_job;
pub mod twin;
pub mod urdf;
pub mod view;
#[cfg(target_family = "wasm")]
pub mod web;

pub use arm::Arm;
pub use error::{Error, Result};
pub use ik::DampingSchedule;
pub use kinematics::Pose;
pub use networks::{Networks, TrainedRange};
pub use obstacle::Obstacle;
pub use planner::{Line, Method, Planner, Sample, Summary, Surrogate, Trajectory};
pub use scene::Scene;

/// Re-export of the linear-algebra crate used in the public API.
pub use nalgebra;
