//! The networks of section V for an arm in space: `Phi(theta)`, the
//! pseudoinverse of the hand's `3 x n` Jacobian (`n x 3`), and the area
//! gradient `g(theta, O)` of the criterion generalised to space
//! ([`crate::space::criterion`], `v = lambda / 4 g`), with their weights
//! file (the one [`WeightsFile`] of every arm, of a chain:
//! [`SpaceWeightsFile`]) and the shipped set for the Panda
//! ([`SpaceNetworkSet::PandaReach`]).
//!
//! Both networks are rotation-equivariant about the first joint's axis, as
//! the planar `reach` networks are about `theta_1`: every joint beyond the
//! first turns rigidly with it, so with `R = R(a_1, theta_1)` the rotation
//! by `theta_1` about that (fixed) axis, `J(theta) = R J(0, theta_2..)`,
//! `J+(theta) = J+(0, theta_2..) R^T`, and the areas of the arm at
//! `theta` about `O` are those of the arm at `(0, theta_2..)` about `O' =
//! R^T (O - p_1) + p_1` (`p_1` a point of the axis). The networks read
//! `(sin, cos)` of `theta_2..theta_n` (and `O'`); `docs/space.md` has how
//! they were trained and how they do.

#[cfg(feature = "embedded-weights")]
use std::sync::{Arc, OnceLock};

use serde::{Deserialize, Serialize};

use super::file::{Encoding, InputRange, Learned, NetEntry, NetKind, Variant, WeightsFile, FORMAT};
use super::Networks;
use crate::error::{Error, Result};
use crate::kinematics::sin_cos;
use crate::nn::adam::AdamOptions;
use crate::space::pose::{cross, dot, sub};
use crate::space::{Chain, Row, SpacePose, SpacePreset, Vec3, MAX_JOINTS};

/// The `format` of the spatial weights files of the version before the
/// one weights file (the shipped Panda set's): read, and turned into
/// this version's.
pub const SPACE_FORMAT_1: &str = "redundant-ik-space-weights-1";

/// Most inputs of a spatial network: `2 (n - 1) + 3`.
const MAX_SPACE_INPUTS: usize = 2 * MAX_JOINTS + 1;

/// The weights file of one network of an arm in space: the one
/// [`WeightsFile`] whose arm is a chain (the variant `equivariant`, the
/// encoding `angles`).
pub type SpaceWeightsFile = WeightsFile<Chain>;

impl Learned for Chain {
    const M: usize = 3;
    type Training = SpaceTraining;
    fn joints(&self) -> usize {
        self.dof()
    }
    fn same_kinematics(&self, other: &Self) -> bool {
        Chain::same_kinematics(self, other)
    }
    fn check_form(variant: Variant, encoding: Encoding) -> Result<()> {
        if variant == Variant::Equivariant && encoding == Encoding::Angles {
            Ok(())
        } else {
            Err(Error::Weights(format!(
                "an arm in space's networks are of the variant 'equivariant' with the encoding 'angles', not '{}' with '{}'",
                variant.name(),
                encoding.name()
            )))
        }
    }
}

/// A spatial weights file of version 1 ([`SPACE_FORMAT_1`]): its preset's
/// name, rows and flange in place of the chain, the variant and encoding
/// implied.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceWeightsFile1 {
    /// Always [`SPACE_FORMAT_1`].
    pub format: String,
    /// `phi` or `v`.
    pub net: NetKind,
    /// The tool's version that wrote it.
    pub tool_version: String,
    /// The preset the networks were trained for (`panda`).
    pub arm: String,
    /// Its rows.
    pub rows: Vec<Row>,
    /// The flange offset in the last frame (m).
    pub flange: Vec3,
    /// The inputs' names and the box training saw.
    pub range: InputRange,
    /// How it was trained.
    pub training: SpaceTraining,
    /// The network (one).
    pub nets: Vec<NetEntry>,
}

impl SpaceWeightsFile1 {
    /// This version's file: the chain the preset named, with its limits,
    /// where the rows and flange are the preset's; else the bare chain of
    /// the rows (refused where they do not make one).
    pub fn into_current(self) -> Result<SpaceWeightsFile> {
        if self.format != SPACE_FORMAT_1 {
            return Err(Error::Weights(format!(
                "format '{}' is not supported (expected '{FORMAT}' or '{SPACE_FORMAT_1}')",
                crate::error::clip(&self.format)
            )));
        }
        let bare = Chain::new(self.rows, self.flange, 0.0)?;
        let arm = SpacePreset::by_key(&self.arm)
            .map(SpacePreset::chain)
            .filter(|c| c.same_kinematics(&bare))
            .unwrap_or(bare);
        Ok(WeightsFile {
            format: FORMAT.into(),
            net: self.net,
            variant: Variant::Equivariant,
            encoding: Encoding::Angles,
            tool_version: self.tool_version,
            arm,
            range: self.range,
            training: self.training,
            nets: self.nets,
        })
    }
}

/// How a spatial network was trained.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceTraining {
    /// Seed of sampling, split and initial weights.
    pub seed: u64,
    /// Samples drawn.
    pub samples: usize,
    /// Hidden layer widths.
    pub hidden: Vec<usize>,
    /// The optimiser's options.
    pub adam: AdamOptions,
    /// How the samples were drawn.
    pub sampling: SpaceSampling,
    /// Wall-clock time of the training (s), when measured.
    #[serde(default)]
    pub seconds: Option<f64>,
}

/// How the samples of a spatial network were drawn.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpaceSampling {
    /// `Phi`: poses uniform within the joint limits, those with
    /// `sigma_min(J)` below this floor left out (m).
    pub sigma_floor: f64,
    /// `v`: random straight-line tasks whose numerical runs give the poses.
    pub tasks: usize,
    /// `v`: spheres per task, each a run.
    pub obstacles_per_task: usize,
    /// `v`: the lines' length (m).
    pub line_length: f64,
    /// `v`: the box the spheres' centres are drawn from, lower corner (m).
    pub obstacle_min: Vec3,
    /// `v`: its upper corner (m).
    pub obstacle_max: Vec3,
    /// `v`: noise added to each visited angle (rad).
    pub theta_noise: f64,
    /// `v`: noise added to each coordinate of the run's centre (m).
    pub obstacle_noise: f64,
    /// `v`: the smoothing `eps` of the criterion's norm in the targets (m^2).
    pub sign_smoothing: f64,
}

/// Inputs and outputs of a spatial network of `kind` for `n` joints.
pub fn space_shape(kind: NetKind, n: usize) -> (usize, usize) {
    let angles = 2 * (n - 1);
    match kind {
        NetKind::Phi => (angles, 3 * n),
        NetKind::V => (angles + 3, n),
    }
}

/// The inputs' names, as the file's range lists them.
pub fn space_input_names(kind: NetKind, n: usize) -> Vec<String> {
    let mut names: Vec<String> = (2..=n)
        .flat_map(|i| [format!("sin theta{i}"), format!("cos theta{i}")])
        .collect();
    if kind == NetKind::V {
        names.extend(["o1_rotated", "o2_rotated", "o3_rotated"].map(String::from));
    }
    names
}

/// A `Phi` network and a `v` network for one arm in space, in their
/// run-time form: the one [`Networks`] of every arm, of a chain.
pub type SpaceNetworks = Networks<Chain>;

impl Networks<Chain> {
    /// Refused unless the networks were trained for `chain`'s kinematics
    /// (its base, rows and flange; the capsules and limits may differ).
    pub fn check_chain(&self, chain: &Chain) -> Result<()> {
        if chain.same_kinematics(&self.arm) {
            Ok(())
        } else {
            Err(Error::NetworksUnavailable(match SpacePreset::of(&self.arm) {
                Some(p) => format!("the networks were trained for the arm '{}', not for this one", p.key),
                None => "the networks were trained for another chain (the one their file records), not for this one".into(),
            }))
        }
    }

    /// Learned `Phi` at `pose`, row-major `n x 3` into `out`, allocation-free.
    pub fn phi(&self, pose: &SpacePose, out: &mut [f64]) -> Result<()> {
        let n = pose.dof();
        self.check_dof(n, out.len(), 3 * n)?;
        let mut buf = [0.0; MAX_SPACE_INPUTS];
        let k = encode(pose.theta(), &mut buf);
        self.phi_kernels[0].forward(&buf[..k], out);
        let (s, c) = sin_cos(pose.theta()[0]);
        let axis = pose.axis(0);
        for row in out.chunks_exact_mut(3) {
            let r = rotate([row[0], row[1], row[2]], axis, s, c);
            row.copy_from_slice(&r);
        }
        finite(out, "Phi network output")
    }

    /// Learned area gradient `g(theta, O)` at `pose` into `out` (`n`),
    /// allocation-free.
    pub fn area_gradient(&self, pose: &SpacePose, o: Vec3, out: &mut [f64]) -> Result<()> {
        let n = pose.dof();
        self.check_dof(n, out.len(), n)?;
        let mut buf = [0.0; MAX_SPACE_INPUTS];
        let k = encode(pose.theta(), &mut buf);
        let o = rotated_obstacle(pose, o);
        buf[k..k + 3].copy_from_slice(&o);
        self.v_kernel.forward(&buf[..k + 3], out);
        finite(out, "v network output")
    }

    /// Whether `pose` (and the obstacle `o`) lie in the boxes training saw.
    pub fn in_range(&self, pose: &SpacePose, o: Option<Vec3>) -> bool {
        let mut buf = [0.0; MAX_SPACE_INPUTS];
        let k = encode(pose.theta(), &mut buf);
        let mut ok = self.phi.range.contains_within(&buf[..k], RANGE_SLACK);
        if let Some(o) = o {
            buf[k..k + 3].copy_from_slice(&rotated_obstacle(pose, o));
            ok &= self.v.range.contains_within(&buf[..k + 3], RANGE_SLACK);
        }
        ok
    }

    fn check_dof(&self, n: usize, len: usize, want: usize) -> Result<()> {
        if n != self.arm.dof() || len != want {
            return Err(Error::DimensionMismatch {
                what: "pose or output for the spatial networks".into(),
                expected: self.arm.dof(),
                found: n,
            });
        }
        Ok(())
    }
}

/// `(sin, cos)` of `theta_2..theta_n` into `buf`; how many entries.
fn encode(theta: &[f64], buf: &mut [f64]) -> usize {
    let rest = &theta[1..theta.len().min(MAX_JOINTS)];
    for (pair, a) in buf.chunks_exact_mut(2).zip(rest) {
        let (s, c) = sin_cos(*a);
        pair[0] = s;
        pair[1] = c;
    }
    2 * rest.len()
}

/// How far outside the box training saw an input still counts as inside
/// it: the inputs are sines and cosines and positions in metres, and a box
/// drawn from samples stops just short of their exact extremes (the
/// Panda's `cos theta3` reaches 0.9999999974 in training, and its start
/// pose has `theta3 = 0`, a cosine of exactly 1).
const RANGE_SLACK: f64 = 1e-6;

/// `x` turned by the angle of `(s, c)` about the unit `axis` (Rodrigues).
fn rotate(x: Vec3, axis: Vec3, s: f64, c: f64) -> Vec3 {
    let (k, ax) = (cross(axis, x), dot(axis, x) * (1.0 - c));
    [0, 1, 2].map(|i| x[i] * c + k[i] * s + axis[i] * ax)
}

/// `O' = R^T (O - p_1) + p_1`: the obstacle as the arm at `theta_1 = 0`
/// sees it.
pub fn rotated_obstacle(pose: &SpacePose, o: Vec3) -> Vec3 {
    let (s, c) = sin_cos(pose.theta()[0]);
    let p1 = pose.joint_origin(0);
    let r = rotate(sub(o, p1), pose.axis(0), -s, c);
    [0, 1, 2].map(|i| r[i] + p1[i])
}

fn finite(out: &[f64], what: &str) -> Result<()> {
    if out.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite { what: what.into() })
    }
}

/// The shipped network sets for arms in space.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SpaceNetworkSet {
    /// The Panda's, trained by `redundant-ik train --arm panda` (the
    /// whole-reach recipe in space): `weights/phi-panda-reach.json` and
    /// `weights/v-panda-reach.json`.
    #[serde(rename = "panda-reach")]
    PandaReach,
}

impl SpaceNetworkSet {
    /// Every set.
    pub const ALL: [SpaceNetworkSet; 1] = [SpaceNetworkSet::PandaReach];

    /// The name in `--networks` and the address.
    pub fn name(self) -> &'static str {
        match self {
            SpaceNetworkSet::PandaReach => "panda-reach",
        }
    }

    /// The preset it was trained for.
    pub fn arm(self) -> &'static str {
        match self {
            SpaceNetworkSet::PandaReach => "panda",
        }
    }

    /// The set shipped for the preset `key`, if there is one.
    pub fn for_arm(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.arm() == key)
    }

    /// The networks, parsed once per process (from the files built into
    /// the tool; a module built without them, the page's and the workers',
    /// is handed their text, [`Self::file_names`]).
    #[cfg(feature = "embedded-weights")]
    pub fn load(self) -> Result<Arc<SpaceNetworks>> {
        static PANDA: OnceLock<std::result::Result<Arc<SpaceNetworks>, String>> = OnceLock::new();
        let cell = match self {
            SpaceNetworkSet::PandaReach => &PANDA,
        };
        cell.get_or_init(|| {
            let (phi, v) = self.files();
            SpaceNetworks::read(phi, v)
                .map(Arc::new)
                .map_err(|e| e.to_string())
        })
        .clone()
        .map_err(Error::Weights)
    }

    /// The names of its `Phi` and `v` files in `weights/` (where the page
    /// fetches them from).
    pub fn file_names(self) -> [&'static str; 2] {
        match self {
            SpaceNetworkSet::PandaReach => ["phi-panda-reach.json", "v-panda-reach.json"],
        }
    }

    /// The JSON text of its `Phi` and `v` files.
    #[cfg(feature = "embedded-weights")]
    pub fn files(self) -> (&'static str, &'static str) {
        match self {
            SpaceNetworkSet::PandaReach => (
                include_str!("../../weights/phi-panda-reach.json"),
                include_str!("../../weights/v-panda-reach.json"),
            ),
        }
    }
}

impl std::str::FromStr for SpaceNetworkSet {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        crate::error::by_name("network set in space", s, &Self::ALL, Self::name)
    }
}

impl crate::planner::Surrogate<Chain, 3> for SpaceNetworks {
    fn check(&self, chain: &Chain) -> Result<()> {
        SpaceNetworks::check_chain(self, chain)
    }

    fn phi(&self, pose: &SpacePose, out: &mut [f64]) -> Result<()> {
        SpaceNetworks::phi(self, pose, out)
    }

    fn area_gradient(&self, pose: &SpacePose, o: Vec3, out: &mut [f64]) -> Result<()> {
        SpaceNetworks::area_gradient(self, pose, o, out)
    }

    fn phi_in_range(&self, pose: &SpacePose) -> bool {
        self.in_range(pose, None)
    }

    fn v_in_range(&self, pose: &SpacePose, o: Vec3) -> bool {
        let mut buf = [0.0; MAX_SPACE_INPUTS];
        let k = encode(pose.theta(), &mut buf);
        buf[k..k + 3].copy_from_slice(&rotated_obstacle(pose, o));
        self.v.range.contains_within(&buf[..k + 3], RANGE_SLACK)
    }
}
