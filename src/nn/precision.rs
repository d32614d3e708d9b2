//! The arithmetic the networks' run-time kernels compute in: `f64` (the
//! default, what the paper's figures and the command line use) or `f32`
//! (four lanes per wasm `simd128` register instead of two, for the page).
//! A kernel's precision is chosen when it is built
//! ([`crate::nn::Kernel::with_precision`]); the `f32` kernel gives the same
//! bits on every target (tested), so a run made in `f32` in the page
//! replays exactly on the command line (`--precision f32`).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// The kernels' arithmetic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    /// Double precision: the reference.
    #[default]
    F64,
    /// Single precision: weights, activations and sums in `f32`, inputs
    /// rounded to `f32` and outputs widened back; `tanh` by a rational
    /// approximation ([`crate::nn::activation::tansig32`]).
    F32,
}

impl Precision {
    /// Every precision, by name.
    pub const ALL: [Precision; 2] = [Precision::F64, Precision::F32];

    /// Whether this is the default, `f64` (a run file leaves it out then).
    pub fn is_f64(&self) -> bool {
        *self == Precision::F64
    }

    /// `f64` or `f32`.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
        }
    }

    /// What a menu says of it.
    pub fn label(self) -> &'static str {
        match self {
            Precision::F64 => "f64 (the reference)",
            Precision::F32 => "f32 (faster in the page)",
        }
    }
}

impl std::fmt::Display for Precision {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Precision {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        crate::error::by_name("precision", s, &Precision::ALL, Precision::name)
    }
}
