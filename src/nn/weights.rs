//! The weights file: a serde JSON document holding one trained network
//! family (the `Phi` networks or the `v` network), how it was trained and the
//! input range it was trained on. Schema documented in `docs/networks.md`.

use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::nn::lm::{LmOptions, TrainReport};
use crate::nn::mlp::Mlp;
use crate::training::Sampling;

/// Value of the `format` field this version reads and writes.
pub const FORMAT: &str = "redundant-ik-weights/1";

/// Which quantity a file's networks compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NetKind {
    /// `Phi(theta)`, eq. (19).
    Phi,
    /// The area gradient `g(theta, O)`, `v = lambda / 4 g` (eqs. 14-15).
    V,
}

/// How the network inputs and outputs map to the quantity (see `docs/networks.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Variant {
    /// The paper's form. `Phi`: one net, `theta (n) -> Phi row-major (2n)`.
    /// `v`: one net, `(theta, O) (n + 2) -> g (n)`.
    Plain,
    /// `Phi` only: one net per row of `Phi`, `theta (n) -> (Phi_i1, Phi_i2)`
    /// (the paper's "35-14-2").
    Rows,
    /// Rotation-equivariant. `Phi`: one net over `(theta_2..theta_n)` giving
    /// `Phi(0, theta_2, ..)`, then `Phi(theta) = Phi(0, ..) R(theta_1)^T`.
    /// `v`: one net over `(theta_2..theta_n, O')` with `O'` the obstacle
    /// rotated by `-theta_1` about `P(0)`; `g` is invariant under that rotation.
    Equivariant,
}

impl Variant {
    /// The name used on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Plain => "plain",
            Variant::Rows => "rows",
            Variant::Equivariant => "equivariant",
        }
    }
}

impl std::str::FromStr for Variant {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "plain" => Ok(Variant::Plain),
            "rows" => Ok(Variant::Rows),
            "equivariant" => Ok(Variant::Equivariant),
            other => Err(Error::UnknownName {
                kind: "variant",
                name: other.into(),
                choices: "plain, rows or equivariant",
            }),
        }
    }
}

/// The arm the networks were trained for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmSpec {
    /// Post height `L0` (m).
    pub post: f64,
    /// Link lengths `L1..Ln` (m).
    pub links: Vec<f64>,
}

/// The box of network inputs seen in training (per-input min/max over the
/// training samples, which already include the sampling noise), plus the
/// smallest singular value of `J` admitted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputRange {
    /// Names of the network inputs, e.g. `["theta2", "theta3"]`.
    pub names: Vec<String>,
    /// Smallest value of each input seen in training.
    pub min: Vec<f64>,
    /// Largest value of each input seen in training.
    pub max: Vec<f64>,
    /// Poses with a smaller `sigma_min(J)` were excluded (m).
    pub sigma_floor: f64,
}

impl InputRange {
    /// Whether every input lies in its `[min, max]`.
    pub fn contains(&self, x: &[f64]) -> bool {
        x.len() == self.min.len()
            && x.iter()
                .zip(self.min.iter().zip(&self.max))
                .all(|(v, (lo, hi))| *v >= *lo && *v <= *hi)
    }
}

/// How the networks were trained.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Training {
    /// Seed of the crate's PRNG (sampling, split and initial weights).
    pub seed: u64,
    /// Samples drawn (before the 70/15/15 split).
    pub samples: usize,
    /// Hidden layer widths.
    pub hidden: Vec<usize>,
    /// Levenberg-Marquardt options.
    pub options: LmOptions,
    /// How the samples were drawn.
    pub sampling: Sampling,
    /// Wall-clock training time in seconds, when the trainer could measure it.
    pub seconds: Option<f64>,
}

/// One network and its training outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NetEntry {
    /// The network.
    pub mlp: Mlp,
    /// Epochs, stop reason and final train/validation/test MSE (mapminmax units).
    pub report: TrainReport,
}

/// A weights file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WeightsFile {
    /// Always [`FORMAT`].
    pub format: String,
    /// `phi` or `v`.
    pub net: NetKind,
    /// How inputs and outputs are mapped.
    pub variant: Variant,
    /// `redundant-ik` version that wrote the file.
    pub tool_version: String,
    /// Arm the networks were trained for.
    pub arm: ArmSpec,
    /// Range of network inputs seen in training.
    pub range: InputRange,
    /// How the networks were trained.
    pub training: Training,
    /// The networks: one, or one per row of `Phi` for the `rows` variant.
    pub nets: Vec<NetEntry>,
}

/// Network count, inputs and outputs per network for a kind and variant on an `n`-link arm.
pub fn shape(kind: NetKind, variant: Variant, n: usize) -> Result<(usize, usize, usize)> {
    match (kind, variant) {
        (NetKind::Phi, Variant::Plain) => Ok((1, n, 2 * n)),
        (NetKind::Phi, Variant::Rows) => Ok((n, n, 2)),
        (NetKind::Phi, Variant::Equivariant) => Ok((1, n - 1, 2 * n)),
        (NetKind::V, Variant::Plain) => Ok((1, n + 2, n)),
        (NetKind::V, Variant::Equivariant) => Ok((1, n + 1, n)),
        (NetKind::V, Variant::Rows) => Err(Error::Weights(
            "variant 'rows' exists only for the phi network".into(),
        )),
    }
}

/// Largest weights file read (bytes). The shipped files are under 80 KB;
/// the paper's networks at any width the page trains stay far below. A
/// larger file is refused before it is parsed, so a wrong or hostile file
/// cannot hold the page for seconds or its memory.
pub const MAX_FILE_BYTES: usize = 8 << 20;

impl WeightsFile {
    /// Parses and validates a weights file (at most [`MAX_FILE_BYTES`]).
    pub fn from_json(json: &str) -> Result<Self> {
        if json.len() > MAX_FILE_BYTES {
            return Err(Error::Weights(format!(
                "the file has {:.1} MB; weights files are at most {} MB",
                json.len() as f64 / 1048576.0,
                MAX_FILE_BYTES >> 20
            )));
        }
        let file: WeightsFile = serde_json::from_str(json)
            .map_err(|e| Error::Weights(format!("not a valid weights file: {e}")))?;
        file.validate()?;
        Ok(file)
    }

    /// Pretty JSON (f64 values round-trip exactly).
    pub fn to_json(&self) -> Result<String> {
        serde_json::to_string_pretty(self)
            .map_err(|e| Error::Weights(format!("cannot serialise weights: {e}")))
    }

    /// The arm the file was trained for.
    pub fn arm(&self) -> Result<Arm> {
        Arm::new(self.arm.post, self.arm.links.clone())
            .map_err(|e| Error::Weights(format!("arm in weights file: {e}")))
    }

    /// Checks that the file is consistent: format, arm, network count and
    /// input/output counts for the kind and variant, every network's shapes
    /// and finiteness, and the range.
    pub fn validate(&self) -> Result<()> {
        if self.format != FORMAT {
            return Err(Error::Weights(format!(
                "format '{}' is not supported (expected '{FORMAT}')",
                self.format
            )));
        }
        let arm = self.arm()?;
        let n = arm.dof();
        let (count, n_in, n_out) = shape(self.net, self.variant, n)?;
        let kind = match self.net {
            NetKind::Phi => "phi",
            NetKind::V => "v",
        };
        if self.nets.len() != count {
            return Err(Error::Weights(format!(
                "{kind} variant '{}' needs {count} network(s), the file has {}",
                self.variant.name(),
                self.nets.len()
            )));
        }
        for (i, entry) in self.nets.iter().enumerate() {
            entry
                .mlp
                .validate()
                .map_err(|e| Error::Weights(format!("network {}: {}", i + 1, strip(&e))))?;
            if entry.mlp.inputs() != n_in || entry.mlp.outputs() != n_out {
                return Err(Error::Weights(format!(
                    "network {}: {} inputs and {} outputs, but {kind} variant '{}' on a {n}-link arm needs {n_in} and {n_out}",
                    i + 1,
                    entry.mlp.inputs(),
                    entry.mlp.outputs(),
                    self.variant.name()
                )));
            }
        }
        let r = &self.range;
        if r.min.len() != n_in || r.max.len() != n_in || r.names.len() != n_in {
            return Err(Error::Weights(format!(
                "trained range has {} names / {} min / {} max entries, expected {n_in}",
                r.names.len(),
                r.min.len(),
                r.max.len()
            )));
        }
        if r.min.iter().chain(&r.max).any(|x| !x.is_finite())
            || r.min.iter().zip(&r.max).any(|(a, b)| a > b)
            || !(r.sigma_floor.is_finite() && r.sigma_floor >= 0.0)
        {
            return Err(Error::Weights(
                "trained range must be finite with min <= max and a non-negative sigma floor"
                    .into(),
            ));
        }
        Ok(())
    }
}

fn strip(e: &Error) -> String {
    match e {
        Error::Weights(m) => m.clone(),
        other => other.to_string(),
    }
}
