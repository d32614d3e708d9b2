//! The weights file of the networks of every arm: a serde JSON document
//! holding one trained network family (the `Phi` networks or the `v`
//! network), the arm whole (a planar arm, or a chain in space), how the
//! networks were trained (including how the samples were drawn, as plain
//! data: [`Sampling`] in the plane, [`crate::networks::space::SpaceSampling`]
//! in space) and the input range they were trained on; one validator for
//! both. Schema documented in `docs/networks.md`.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer, Serialize};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::nn::adam::AdamOptions;
use crate::nn::lm::{LmOptions, TrainReport};
use crate::nn::mlp::Mlp;
use crate::planner::Method;

/// Value of the `format` field this version writes.
pub const FORMAT: &str = "redundant-ik-weights/2";
/// The planar files of the version before (the shipped planar sets), whose
/// layout is this one's: read as they are.
pub const FORMAT_1: &str = "redundant-ik-weights/1";

/// What a weights file holds of an arm beyond the arm itself.
pub trait Learned: Serialize + DeserializeOwned + Clone + PartialEq + std::fmt::Debug {
    /// The coordinates of the hand (the rows of `Phi`'s transpose, the
    /// obstacle's inputs to `v`).
    const M: usize;
    /// How its networks are trained.
    type Training: Serialize + DeserializeOwned + Clone + PartialEq + std::fmt::Debug;
    /// The joints.
    fn joints(&self) -> usize;
    /// Refused where this arm's networks are not built of `variant` and
    /// `encoding`.
    fn check_form(variant: Variant, encoding: Encoding) -> Result<()>;
    /// Whether networks trained for `other` serve this arm: the same
    /// kinematics (a planar arm's post and links; a chain's base, rows and
    /// flange, whatever its volumes and limits).
    fn same_kinematics(&self, other: &Self) -> bool;
}

impl Learned for Arm {
    const M: usize = 2;
    type Training = Training;
    fn joints(&self) -> usize {
        self.dof()
    }
    fn check_form(_: Variant, _: Encoding) -> Result<()> {
        Ok(())
    }
    fn same_kinematics(&self, other: &Self) -> bool {
        self.same_geometry(other)
    }
}

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
                choices: "plain, rows or equivariant".into(),
            }),
        }
    }
}

/// How joint angles enter a network (`networks::inputs` builds the inputs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Encoding {
    /// Each angle as it is, in radians (the paper's networks).
    #[default]
    Raw,
    /// Each angle as `(sin theta_i, cos theta_i)`: periodic, bounded.
    Angles,
}

impl Encoding {
    /// The name in weights files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Encoding::Raw => "raw",
            Encoding::Angles => "angles",
        }
    }

    /// Whether this is the paper's encoding (the weights file then omits
    /// the field, so files written before it existed stay as they were).
    pub fn is_raw(&self) -> bool {
        *self == Encoding::Raw
    }

    /// Inputs that `angles` joint angles become.
    pub fn width(self, angles: usize) -> usize {
        match self {
            Encoding::Raw => angles,
            Encoding::Angles => 2 * angles,
        }
    }
}

impl std::str::FromStr for Encoding {
    type Err = crate::error::Error;
    fn from_str(s: &str) -> crate::error::Result<Self> {
        match s {
            "raw" => Ok(Encoding::Raw),
            "angles" => Ok(Encoding::Angles),
            other => Err(crate::error::Error::UnknownName {
                kind: "encoding",
                name: other.into(),
                choices: "raw or angles".into(),
            }),
        }
    }
}

/// Read by name through [`std::str::FromStr`], as [`crate::Method`] is:
/// serde's derived enum reader would cost the page's module 1.1 KB.
impl<'de> Deserialize<'de> for Encoding {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        name.parse().map_err(serde::de::Error::custom)
    }
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
        self.contains_within(x, 0.0)
    }

    /// Whether every input lies in its `[min, max]` widened by `slack` on
    /// each side (`0`: [`InputRange::contains`]).
    pub fn contains_within(&self, x: &[f64], slack: f64) -> bool {
        x.len() == self.min.len()
            && x.iter()
                .zip(self.min.iter().zip(&self.max))
                .all(|(v, (lo, hi))| *v >= lo - slack && *v <= hi + slack)
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
    /// Levenberg-Marquardt options (unused when `adam` is set).
    pub options: LmOptions,
    /// Adam's options, when Adam trained the networks instead of
    /// Levenberg-Marquardt; absent in older files.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub adam: Option<AdamOptions>,
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

/// A weights file of an arm `A` (the planar arm's by default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, bound(serialize = "", deserialize = ""))]
pub struct WeightsFile<A: Learned = Arm> {
    /// [`FORMAT`] (or [`FORMAT_1`], the planar files of the version
    /// before).
    pub format: String,
    /// `phi` or `v`.
    pub net: NetKind,
    /// How inputs and outputs are mapped.
    pub variant: Variant,
    /// How the joint angles enter the networks; absent (raw, the paper's)
    /// in files written before angle features existed.
    #[serde(default, skip_serializing_if = "Encoding::is_raw")]
    pub encoding: Encoding,
    /// `redundant-ik` version that wrote the file.
    pub tool_version: String,
    /// Arm the networks were trained for (checked as it is read).
    pub arm: A,
    /// Range of network inputs seen in training.
    pub range: InputRange,
    /// How the networks were trained.
    pub training: A::Training,
    /// The networks: one, or one per row of `Phi` for the `rows` variant.
    pub nets: Vec<NetEntry>,
}

/// Network count, inputs and outputs per network for a kind, variant and
/// encoding on an `n`-joint arm whose hand has `m` coordinates (2 in the
/// plane, 3 in space).
pub fn shape(
    kind: NetKind,
    variant: Variant,
    encoding: Encoding,
    n: usize,
    m: usize,
) -> Result<(usize, usize, usize)> {
    let angles = |k: usize| encoding.width(k);
    match (kind, variant) {
        (NetKind::Phi, Variant::Plain) => Ok((1, angles(n), m * n)),
        (NetKind::Phi, Variant::Rows) => Ok((n, angles(n), m)),
        (NetKind::Phi, Variant::Equivariant) => Ok((1, angles(n - 1), m * n)),
        (NetKind::V, Variant::Plain) => Ok((1, angles(n) + m, n)),
        (NetKind::V, Variant::Equivariant) => Ok((1, angles(n - 1) + m, n)),
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

impl<A: Learned> WeightsFile<A> {
    /// Pretty JSON (f64 values round-trip exactly).
    pub fn to_json(&self) -> Result<String> {
        serde_json::to_string_pretty(self)
            .map_err(|e| Error::Weights(format!("cannot serialise weights: {e}")))
    }

    /// Checks that the file is consistent: format, arm, network count and
    /// input/output counts for the kind and variant, every network's shapes
    /// and finiteness, and the range.
    pub fn validate(&self) -> Result<()> {
        if self.format != FORMAT && !(A::M == 2 && self.format == FORMAT_1) {
            return Err(Error::Weights(format!(
                "format '{}' is not supported (expected '{FORMAT}')",
                crate::error::clip(&self.format)
            )));
        }
        A::check_form(self.variant, self.encoding)?;
        let n = self.arm.joints();
        let (count, n_in, n_out) = shape(self.net, self.variant, self.encoding, n, A::M)?;
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
                    "network {}: {} inputs and {} outputs, but {kind} variant '{}' with {} angles on a {n}-joint arm needs {n_in} and {n_out}",
                    i + 1,
                    entry.mlp.inputs(),
                    entry.mlp.outputs(),
                    self.variant.name(),
                    self.encoding.name()
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

/// How training poses and obstacle points are drawn; stored in the weights file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sampling {
    /// Paper tasks whose trajectories seed the pose pool (3-link arms only).
    pub tasks: Vec<u32>,
    /// Random straight-line tasks inside the arm's reach that seed it too
    /// ([`crate::training::tasks::random_task`]); absent in files written before
    /// arms other than the paper's could be trained, hence the default 0.
    #[serde(default, skip_serializing_if = "is_zero_count")]
    pub random_tasks: usize,
    /// Methods run on each task and obstacle (`none`, `numerical`);
    /// `modes` in files written before this name (the shipped weights).
    #[serde(alias = "modes")]
    pub methods: Vec<Method>,
    /// Obstacle positions drawn per task.
    pub obstacles_per_task: usize,
    /// Lower corner of the obstacle region (also the canonical obstacles are run).
    pub obstacle_min: [f64; 2],
    /// Upper corner of the obstacle region.
    pub obstacle_max: [f64; 2],
    /// Standard deviation of the Gaussian noise added to visited joint angles (rad).
    pub theta_noise: f64,
    /// Poses whose smallest singular value of `J` is below this are rejected (m).
    pub sigma_floor: f64,
    /// Share of `v` samples whose obstacle point is the one of the run the pose
    /// came from (plus `obstacle_noise`); the rest are uniform in the region.
    pub paired_obstacle_share: f64,
    /// Standard deviation of the noise on paired obstacle points (m).
    pub obstacle_noise: f64,
    /// When positive, the obstacles of the random tasks are drawn near the
    /// links' sweep in the no-avoidance run (a point on a link at a random
    /// step, moved by Gaussian noise of this standard deviation, m), where
    /// they matter, instead of uniformly in the region. Absent in older
    /// files, hence the default 0.
    #[serde(default, skip_serializing_if = "is_zero_length")]
    pub obstacle_spread: f64,
    /// When set, poses are drawn uniformly over the whole joint torus
    /// (`[-pi, pi)` per joint; poses below the sigma floor rejected)
    /// instead of around the poses the tasks visit: the `reach` recipe's
    /// `Phi`, which must hold wherever a run may go. Absent in older files.
    #[serde(default, skip_serializing_if = "is_false")]
    pub whole_torus: bool,
    /// The smoothing `eps` (m^2) of the sign in eq. (15) that the `v`
    /// targets were computed with ([`crate::obstacle::smoothed_sign`]); 0,
    /// the paper's sign, in older files.
    #[serde(default, skip_serializing_if = "is_zero_length")]
    pub sign_smoothing: f64,
}

fn is_false(b: &bool) -> bool {
    !*b
}

// The paper's sampling writes neither field, so its files stay as shipped.
fn is_zero_count(n: &usize) -> bool {
    *n == 0
}

fn is_zero_length(x: &f64) -> bool {
    *x == 0.0
}

impl Default for Sampling {
    fn default() -> Self {
        Self {
            tasks: vec![1, 2],
            random_tasks: 0,
            methods: vec![Method::NO_AVOIDANCE, Method::NUMERICAL],
            obstacles_per_task: 60,
            obstacle_min: [0.3, 0.3],
            obstacle_max: [0.8, 0.8],
            theta_noise: 0.08,
            sigma_floor: 0.2,
            paired_obstacle_share: 0.5,
            obstacle_noise: 0.03,
            obstacle_spread: 0.0,
            whole_torus: false,
            sign_smoothing: 0.0,
        }
    }
}

impl Sampling {
    /// Checks the numbers make sense.
    pub fn validate(&self) -> Result<()> {
        let ok = |x: f64| x.is_finite() && x >= 0.0;
        if !(ok(self.theta_noise)
            && ok(self.obstacle_spread)
            && ok(self.sign_smoothing)
            && ok(self.sigma_floor)
            && ok(self.obstacle_noise)
            && (0.0..=1.0).contains(&self.paired_obstacle_share))
        {
            return Err(Error::Training(
                "sampling: noise, sigma floor and shares must be finite and non-negative".into(),
            ));
        }
        for i in 0..2 {
            if !(self.obstacle_min[i].is_finite()
                && self.obstacle_max[i].is_finite()
                && self.obstacle_min[i] <= self.obstacle_max[i])
            {
                return Err(Error::Training(
                    "sampling: obstacle region must be finite with min <= max".into(),
                ));
            }
        }
        if !self.whole_torus
            && ((self.tasks.is_empty() && self.random_tasks == 0) || self.methods.is_empty())
        {
            return Err(Error::Training(
                "sampling: need at least one task and one method".into(),
            ));
        }
        if self.random_tasks > 10_000 || self.obstacles_per_task > 10_000 {
            return Err(Error::Training(
                "sampling: at most 10 000 random tasks and 10 000 obstacles per task".into(),
            ));
        }
        if self.methods.iter().any(|m| m.uses_networks()) {
            return Err(Error::Training(
                "sampling: only the numerical methods (none, numerical) can seed training data"
                    .into(),
            ));
        }
        Ok(())
    }
}
