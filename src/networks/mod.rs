//! The trained networks of section V: `Phi(theta)` (eq. 19) and the obstacle
//! vector's area gradient `g(theta, O)` (eqs. 14-15, `v = lambda / 4 g`),
//! loaded from weights files and plugged into the planner as its
//! [`Surrogate`].
//!
//! The shipped weights are embedded in the build, so the command-line tool and
//! the page need no files; users may load their own with
//! [`Networks::from_json`]. The file format is [`mod@file`]; how the networks
//! are trained is `crate::training`; the schema and the measured accuracy
//! are in `docs/networks.md`. Which networks a method runs with, and
//! whether they fit the arm, is decided here, in one place ([`for_method`]).

mod builtin;
pub mod file;
pub mod inputs;
mod reader;
pub mod space;
pub mod space_pose;

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::kinematics::Pose;
use crate::nn::{Kernel, Precision};
use crate::planner::Surrogate;

pub use builtin::*;
pub use file::{
    Encoding, InputRange, Learned, NetEntry, NetKind, Sampling, Training, Variant, WeightsFile,
    FORMAT, FORMAT_1, MAX_FILE_BYTES,
};
pub use inputs::MAX_INPUTS;
pub use reader::Readable;

/// A `Phi` network family and a `v` network for the same arm: the planar
/// arm's (`A` = [`Arm`], the default) or a chain's in space
/// ([`space::SpaceNetworks`] names `Networks<Chain>`). What is written here
/// holds for every arm (pairing two files, their kernels, the precision);
/// each kind's inputs and outputs are its own (below, and
/// [`mod@space`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Networks<A: Learned = Arm> {
    /// The files, shared by the same networks in another precision
    /// ([`Networks::in_precision`] builds kernels, and copies no weights).
    phi: Arc<WeightsFile<A>>,
    v: Arc<WeightsFile<A>>,
    arm: A,
    /// The run-time form of each `Phi` network and of the `v` network
    /// (`mapminmax` folded in, padded, vectorised), built at load.
    phi_kernels: Vec<Kernel>,
    v_kernel: Kernel,
}

/// What the networks were trained on, for the page to show and to warn when a
/// state leaves it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainedRange {
    /// Variant of the `Phi` networks.
    pub phi_variant: Variant,
    /// Variant of the `v` network.
    pub v_variant: Variant,
    /// Box of the `Phi` networks' inputs, and the `sigma_min(J)` floor.
    pub phi: InputRange,
    /// Box of the `v` network's inputs.
    pub v: InputRange,
    /// Region obstacle centres were drawn from, lower corner.
    pub obstacle_min: [f64; 2],
    /// Region obstacle centres were drawn from, upper corner.
    pub obstacle_max: [f64; 2],
    /// Arm post height the networks were trained for.
    pub post: f64,
    /// Link lengths the networks were trained for.
    pub links: Vec<f64>,
}

impl<A: Learned> Networks<A> {
    /// Pairs a `Phi` file and a `v` file of any arm; both must be valid,
    /// of the right kind and trained for the same arm (the planar arm's
    /// [`Networks::new`] too).
    pub fn pair(phi: WeightsFile<A>, v: WeightsFile<A>) -> Result<Self> {
        phi.validate()?;
        v.validate()?;
        if phi.net != NetKind::Phi {
            return Err(Error::Weights(
                "the first file holds a v network, expected the Phi network(s)".into(),
            ));
        }
        if v.net != NetKind::V {
            return Err(Error::Weights(
                "the second file holds Phi networks, expected the v network".into(),
            ));
        }
        if !phi.arm.same_kinematics(&v.arm) {
            return Err(Error::Weights(
                "the Phi and v files were trained for different arms".into(),
            ));
        }
        Ok(Self::with_kernels(
            Arc::new(phi),
            Arc::new(v),
            Precision::F64,
        ))
    }

    /// The networks of two checked files, their kernels built in `precision`.
    fn with_kernels(
        phi: Arc<WeightsFile<A>>,
        v: Arc<WeightsFile<A>>,
        precision: Precision,
    ) -> Self {
        let phi_kernels = phi
            .nets
            .iter()
            .map(|e| Kernel::with_precision(&e.mlp, precision))
            .collect();
        let v_kernel = Kernel::with_precision(&v.nets[0].mlp, precision);
        Self {
            arm: phi.arm.clone(),
            phi,
            v,
            phi_kernels,
            v_kernel,
        }
    }

    /// The same networks computing in `precision` (their kernels built
    /// again; `f64` is what [`Networks::new`] builds).
    pub fn with_precision(self, precision: Precision) -> Self {
        Self::with_kernels(self.phi, self.v, precision)
    }

    /// The arithmetic of the networks' kernels.
    pub fn precision(&self) -> Precision {
        self.v_kernel.precision()
    }

    /// These networks computing in `precision`: the same ones where they
    /// already do (a shipped set stays shared), else a copy with its
    /// kernels built again.
    pub fn in_precision(self: Arc<Self>, precision: Precision) -> Arc<Self> {
        if self.precision() == precision {
            self
        } else {
            Arc::new(Self::with_kernels(
                self.phi.clone(),
                self.v.clone(),
                precision,
            ))
        }
    }

    /// Networks of any arm from the JSON text of a `Phi` weights file and
    /// a `v` weights file (the planar arm's [`Networks::from_json`] too).
    /// Corrupt or mismatched files give [`Error::Weights`].
    pub fn read(phi_json: &str, v_json: &str) -> Result<Self>
    where
        A: Readable,
    {
        let phi = WeightsFile::<A>::from_json(phi_json)
            .map_err(|e| Error::Weights(format!("Phi file: {}", inner(&e))))?;
        let v = WeightsFile::<A>::from_json(v_json)
            .map_err(|e| Error::Weights(format!("v file: {}", inner(&e))))?;
        Self::pair(phi, v)
    }

    /// The `Phi` weights file.
    pub fn phi_file(&self) -> &WeightsFile<A> {
        &self.phi
    }

    /// The `v` weights file.
    pub fn v_file(&self) -> &WeightsFile<A> {
        &self.v
    }

    /// The arm the networks were trained for (the planner refuses them for
    /// another arm).
    pub fn arm(&self) -> &A {
        &self.arm
    }
}

impl Networks {
    /// Pairs a `Phi` file and a `v` file of the planar arm ([`Networks::pair`]).
    pub fn new(phi: WeightsFile, v: WeightsFile) -> Result<Self> {
        Self::pair(phi, v)
    }

    /// The planar arm's networks from the JSON text of a `Phi` weights file
    /// and a `v` weights file ([`Networks::read`]).
    pub fn from_json(phi_json: &str, v_json: &str) -> Result<Self> {
        Self::read(phi_json, v_json)
    }

    /// The trained range, for the page.
    pub fn trained_range(&self) -> TrainedRange {
        TrainedRange {
            phi_variant: self.phi.variant,
            v_variant: self.v.variant,
            phi: self.phi.range.clone(),
            v: self.v.range.clone(),
            obstacle_min: self.v.training.sampling.obstacle_min,
            obstacle_max: self.v.training.sampling.obstacle_max,
            post: self.arm.post(),
            links: self.arm.links().to_vec(),
        }
    }

    /// Learned `Phi(theta)` row-major into `out` (`2n` entries),
    /// allocation-free. `theta` is checked (length, finiteness).
    pub fn phi_into(&self, theta: &[f64], out: &mut [f64]) -> Result<()> {
        self.arm.check_angles(theta)?;
        let (s, c) = crate::kinematics::sin_cos(theta[0]);
        self.phi_raw(theta, s, c, out)
    }

    /// The `Phi` networks at `theta` (length checked by the caller), with
    /// `(sin, cos)` of `theta_1` for the equivariant variant's rotation.
    #[inline]
    fn phi_raw(&self, theta: &[f64], s1: f64, c1: f64, out: &mut [f64]) -> Result<()> {
        let n = self.arm.dof();
        if out.len() != 2 * n {
            return Err(dimension("Phi (n x 2) output", 2 * n, out.len()));
        }
        let k = &self.phi_kernels;
        let mut buf = [0.0; MAX_INPUTS];
        let x = inputs::phi_inputs(self.phi.variant, self.phi.encoding, theta, &mut buf);
        match self.phi.variant {
            Variant::Plain => k[0].forward(x, out),
            Variant::Rows => {
                for (kernel, row) in k.iter().zip(out.chunks_exact_mut(2)) {
                    kernel.forward(x, row);
                }
            }
            Variant::Equivariant => {
                k[0].forward(x, out);
                // Phi(theta) = Phi(0, theta_2, ..) R(theta_1)^T,
                // R(a) = [[cos a, sin a], [-sin a, cos a]].
                for row in out.chunks_exact_mut(2) {
                    let (p0, p1) = (row[0], row[1]);
                    row[0] = p0 * c1 + p1 * s1;
                    row[1] = -p0 * s1 + p1 * c1;
                }
            }
        }
        if out.iter().any(|x| !x.is_finite()) {
            return Err(Error::NonFinite {
                what: "Phi network output".into(),
            });
        }
        Ok(())
    }

    /// Learned area gradient `g(theta, O)` into `out` (`n` entries),
    /// allocation-free. `theta` and `O` are checked.
    pub fn area_gradient_into(&self, theta: &[f64], o: [f64; 2], out: &mut [f64]) -> Result<()> {
        self.arm.check_angles(theta)?;
        if !(o[0].is_finite() && o[1].is_finite()) {
            return Err(Error::NonFinite {
                what: "obstacle point".into(),
            });
        }
        let (s, c) = crate::kinematics::sin_cos(theta[0]);
        self.area_gradient_raw(theta, s, c, o, out)
    }

    #[inline]
    fn area_gradient_raw(
        &self,
        theta: &[f64],
        s1: f64,
        c1: f64,
        o: [f64; 2],
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.arm.dof();
        if out.len() != n {
            return Err(dimension("v network output", n, out.len()));
        }
        let mut input = [0.0; MAX_INPUTS];
        self.v_kernel
            .forward(self.v_input(theta, (s1, c1), o, &mut input), out);
        if out.iter().any(|x| !x.is_finite()) {
            return Err(Error::NonFinite {
                what: "v network output".into(),
            });
        }
        Ok(())
    }

    /// Whether `theta` is inside the `Phi` networks' trained box and away from
    /// singular poses (`sigma_min(J) >=` the floor).
    pub fn phi_in_range_slice(&self, theta: &[f64]) -> bool {
        self.arm.check_angles(theta).is_ok()
            && self.phi_in_range_at(&Pose::lenient(&self.arm, theta))
    }

    fn phi_in_range_at(&self, pose: &Pose) -> bool {
        let mut buf = [0.0; MAX_INPUTS];
        let x = inputs::phi_inputs(self.phi.variant, self.phi.encoding, pose.theta(), &mut buf);
        self.phi.range.contains(x) && pose.sigma_min() >= self.phi.range.sigma_floor
    }

    /// Whether `(theta, O)` is inside the `v` network's trained box.
    pub fn v_in_range_slice(&self, theta: &[f64], o: [f64; 2]) -> bool {
        if self.arm.check_angles(theta).is_err() || !(o[0].is_finite() && o[1].is_finite()) {
            return false;
        }
        let (s, c) = crate::kinematics::sin_cos(theta[0]);
        self.v_in_range_raw(theta, s, c, o)
    }

    fn v_in_range_raw(&self, theta: &[f64], s1: f64, c1: f64, o: [f64; 2]) -> bool {
        let mut input = [0.0; MAX_INPUTS];
        self.v
            .range
            .contains(self.v_input(theta, (s1, c1), o, &mut input))
    }

    /// The `v` network's inputs for this arm and variant (see [`v_inputs`]).
    fn v_input<'a>(
        &self,
        theta: &[f64],
        sc: (f64, f64),
        o: [f64; 2],
        buf: &'a mut [f64; MAX_INPUTS],
    ) -> &'a [f64] {
        inputs::v_inputs(
            self.v.variant,
            self.v.encoding,
            self.arm.post(),
            theta,
            sc,
            o,
            buf,
        )
    }

    /// Whether `pose` is a pose of an arm with as many joints as the networks'.
    #[inline]
    fn check_pose(&self, pose: &Pose) -> Result<()> {
        if pose.dof() == self.arm.dof() {
            Ok(())
        } else {
            Err(dimension(
                "pose for the networks",
                self.arm.dof(),
                pose.dof(),
            ))
        }
    }
}

#[cold]
fn dimension(what: &str, expected: usize, found: usize) -> Error {
    Error::DimensionMismatch {
        what: what.into(),
        expected,
        found,
    }
}

fn inner(e: &Error) -> String {
    match e {
        Error::Weights(m) => m.clone(),
        other => other.to_string(),
    }
}

impl Surrogate for Networks {
    fn check(&self, arm: &Arm) -> Result<()> {
        if self.arm.same_geometry(arm) {
            return Ok(());
        }
        let spec = |a: &Arm| (a.post(), a.links().to_vec());
        Err(Error::NetworksForAnotherArm {
            trained: spec(&self.arm),
            arm: spec(arm),
        })
    }

    fn phi(&self, pose: &Pose, out: &mut [f64]) -> Result<()> {
        self.check_pose(pose)?;
        self.phi_raw(pose.theta(), pose.sin()[0], pose.cos()[0], out)
    }

    fn area_gradient(&self, pose: &Pose, o: [f64; 2], out: &mut [f64]) -> Result<()> {
        self.check_pose(pose)?;
        self.area_gradient_raw(pose.theta(), pose.sin()[0], pose.cos()[0], o, out)
    }

    fn phi_in_range(&self, pose: &Pose) -> bool {
        self.check_pose(pose).is_ok() && self.phi_in_range_at(pose)
    }

    fn v_in_range(&self, pose: &Pose, o: [f64; 2]) -> bool {
        self.check_pose(pose).is_ok()
            && o[0].is_finite()
            && o[1].is_finite()
            && self.v_in_range_raw(pose.theta(), pose.sin()[0], pose.cos()[0], o)
    }
}

/// A chain from its JSON text (the layout a weights file or a run file
/// writes), checked as its constructors check it: by serde's derived reader
/// in the tool, by hand (the page's reader of spatial weights files) in
/// the wasm modules, which have no serde reader of a chain. The page's
/// module reads a robot the workers' module made of a URDF so.
pub fn chain_from_json(json: &str) -> Result<crate::space::Chain> {
    #[cfg(feature = "cli")]
    let read = serde_json::from_str::<crate::space::Chain>(json).map_err(|e| e.to_string());
    #[cfg(not(feature = "cli"))]
    let read = reader::space::read_chain(json);
    read.map_err(|e| Error::Weights(format!("a chain: {e}")))
}
