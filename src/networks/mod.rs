//! The trained networks of section V: `Phi(theta)` (eq. 19) and the obstacle
//! vector's area gradient `g(theta, O)` (eqs. 14-15, `v = lambda / 4 g`),
//! loaded from weights files and plugged into the planner as its
//! [`Surrogate`].
//!
//! The shipped weights are embedded in the build, so the command-line tool and
//! the page need no files; users may load their own with
//! [`Networks::from_json`]. The file format is [`file`]; how the networks
//! are trained is `crate::training`; the schema and the measured accuracy
//! are in `docs/networks.md`. Which networks a method runs with, and
//! whether they fit the arm, is decided here, in one place ([`for_method`]).

pub mod file;

use std::sync::{Arc, OnceLock};

use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::kinematics::Pose;
use crate::nn::Kernel;
use crate::planner::{Method, Surrogate};

pub use file::{
    InputRange, NetEntry, NetKind, Sampling, Training, Variant, WeightsFile, MAX_FILE_BYTES,
};

/// Shipped `Phi` networks, paper form: one 3-35-14-6 net over `theta`.
#[cfg(feature = "embedded-weights")]
pub const PHI_PLAIN_JSON: &str = include_str!("../../weights/phi-plain.json");
/// Shipped `Phi` networks, paper form: three 3-35-14-2 nets, one per row of `Phi`.
#[cfg(feature = "embedded-weights")]
pub const PHI_ROWS_JSON: &str = include_str!("../../weights/phi-rows.json");
/// Shipped `Phi` network, rotation-equivariant: 2-35-14-6 over `(theta_2, theta_3)`.
#[cfg(feature = "embedded-weights")]
pub const PHI_EQUIVARIANT_JSON: &str = include_str!("../../weights/phi-equivariant.json");
/// Shipped `v` network, paper form: 5-25-14-3 over `(theta, O)`.
#[cfg(feature = "embedded-weights")]
pub const V_PLAIN_JSON: &str = include_str!("../../weights/v-plain.json");

/// The files of `weights/` that hold the built-in networks
/// ([`DEFAULT_PHI_VARIANT`] and [`DEFAULT_V_VARIANT`]): `[phi, v]`. A build
/// without `embedded-weights` (the page's) fetches these and hands them to
/// [`provide_builtin`].
pub const BUILTIN_FILES: [&str; 2] = ["phi-equivariant.json", "v-plain.json"];

/// The `Phi` variant [`Networks::embedded`] uses.
pub const DEFAULT_PHI_VARIANT: Variant = Variant::Equivariant;
/// The `v` variant [`Networks::embedded`] uses.
pub const DEFAULT_V_VARIANT: Variant = Variant::Plain;

/// The shipped `Phi` weights file of a variant (JSON text).
#[cfg(feature = "embedded-weights")]
pub fn embedded_phi_json(variant: Variant) -> &'static str {
    match variant {
        Variant::Plain => PHI_PLAIN_JSON,
        Variant::Rows => PHI_ROWS_JSON,
        Variant::Equivariant => PHI_EQUIVARIANT_JSON,
    }
}

/// The built-in networks, once loaded, or why they are not.
static BUILTIN: OnceLock<Result<Arc<Networks>>> = OnceLock::new();

/// The shipped networks, loaded on first use and shared; or why they
/// cannot load. Compiled in with `embedded-weights` ([`Networks::embedded`]);
/// otherwise what [`provide_builtin`] was given.
pub fn builtin() -> Result<Arc<Networks>> {
    #[cfg(feature = "embedded-weights")]
    let loaded = BUILTIN.get_or_init(|| {
        Networks::embedded().map(Arc::new).map_err(|e| {
            Error::NetworksUnavailable(format!("the built-in weights could not be loaded ({e})"))
        })
    });
    #[cfg(not(feature = "embedded-weights"))]
    let loaded = BUILTIN.get().ok_or_else(|| {
        Error::NetworksUnavailable("the built-in networks have not been loaded yet".into())
    })?;
    loaded.clone()
}

/// Hands a build without `embedded-weights` its built-in networks: the JSON
/// text of the files [`BUILTIN_FILES`] names, or why they could not be
/// fetched. Only the first call counts (the built-in networks never
/// change); a corrupt file is kept as the reason [`builtin`] gives.
pub fn provide_builtin(files: std::result::Result<(&str, &str), String>) -> Result<()> {
    let result = match files {
        Ok((phi, v)) => Networks::from_json(phi, v).map(Arc::new),
        Err(why) => Err(Error::NetworksUnavailable(why)),
    };
    let answer = result.as_ref().map(|_| ()).map_err(Clone::clone);
    let _ = BUILTIN.set(result);
    answer
}

/// The networks `method` runs with on `arm`: none for a method without
/// networks; else the `installed` ones if they were trained for `arm`, else
/// the built-in ones if they were (the paper's arm). The one place that
/// decides which networks a method uses and whether they fit: the session,
/// the page's off-screen runs and its workers ask here.
pub fn for_method(
    method: Method,
    arm: &Arm,
    installed: Option<&Arc<Networks>>,
) -> Result<Option<Arc<dyn Surrogate>>> {
    if !method.uses_networks() {
        return Ok(None);
    }
    Ok(Some(available(arm, installed)? as Arc<dyn Surrogate>))
}

/// The networks for `arm`: the `installed` ones if they fit it, else the
/// built-in ones if they do; else why there are none.
pub fn available(arm: &Arm, installed: Option<&Arc<Networks>>) -> Result<Arc<Networks>> {
    if let Some(n) = installed.filter(|n| n.arm() == arm) {
        return Ok(n.clone());
    }
    if builtin_fits(arm) {
        return builtin();
    }
    Err(Error::NetworksUnavailable(
        "the built-in ones were trained for the paper's arm, not for this one; train networks for this arm (the Training panel, or redundant-ik train) or load weights trained for it".into(),
    ))
}

/// Whether the built-in networks were trained for `arm` (the paper's).
pub fn builtin_fits(arm: &Arm) -> bool {
    *arm == Arm::paper()
}

/// A `Phi` network family and a `v` network for the same arm.
#[derive(Debug, Clone, PartialEq)]
pub struct Networks {
    phi: WeightsFile,
    v: WeightsFile,
    arm: Arm,
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

impl Networks {
    /// Pairs a `Phi` file and a `v` file; both must be valid, of the right
    /// kind and trained for the same arm.
    pub fn new(phi: WeightsFile, v: WeightsFile) -> Result<Self> {
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
        if phi.arm != v.arm {
            return Err(Error::Weights(
                "the Phi and v files were trained for different arms".into(),
            ));
        }
        let arm = phi.arm.clone();
        let phi_kernels = phi.nets.iter().map(|e| Kernel::new(&e.mlp)).collect();
        let v_kernel = Kernel::new(&v.nets[0].mlp);
        Ok(Self {
            phi,
            v,
            arm,
            phi_kernels,
            v_kernel,
        })
    }

    /// Networks from the JSON text of a `Phi` weights file and a `v` weights
    /// file. Corrupt or mismatched files give [`Error::Weights`].
    pub fn from_json(phi_json: &str, v_json: &str) -> Result<Self> {
        let phi = WeightsFile::from_json(phi_json)
            .map_err(|e| Error::Weights(format!("Phi file: {}", inner(&e))))?;
        let v = WeightsFile::from_json(v_json)
            .map_err(|e| Error::Weights(format!("v file: {}", inner(&e))))?;
        Self::new(phi, v)
    }

    /// The shipped networks: the default `Phi` variant ([`DEFAULT_PHI_VARIANT`])
    /// and the `v` network.
    #[cfg(feature = "embedded-weights")]
    pub fn embedded() -> Result<Self> {
        Self::embedded_with(DEFAULT_PHI_VARIANT)
    }

    /// The shipped networks with the chosen `Phi` variant (`plain` and `rows`
    /// are the paper's form, `equivariant` the measured improvement).
    #[cfg(feature = "embedded-weights")]
    pub fn embedded_with(phi_variant: Variant) -> Result<Self> {
        Self::from_json(embedded_phi_json(phi_variant), V_PLAIN_JSON)
    }

    /// The `Phi` weights file.
    pub fn phi_file(&self) -> &WeightsFile {
        &self.phi
    }

    /// The `v` weights file.
    pub fn v_file(&self) -> &WeightsFile {
        &self.v
    }

    /// The arm the networks were trained for (the planner refuses them for
    /// another arm).
    pub fn arm(&self) -> &Arm {
        &self.arm
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
        let (s, c) = theta[0].sin_cos();
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
        match self.phi.variant {
            Variant::Plain => k[0].forward(theta, out),
            Variant::Rows => {
                for (kernel, row) in k.iter().zip(out.chunks_exact_mut(2)) {
                    kernel.forward(theta, row);
                }
            }
            Variant::Equivariant => {
                k[0].forward(&theta[1..], out);
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
        let (s, c) = theta[0].sin_cos();
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
        let mut input = [0.0; MAX_V_INPUTS];
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
        let theta = pose.theta();
        self.phi.range.contains(phi_inputs(self.phi.variant, theta))
            && pose.sigma_min() >= self.phi.range.sigma_floor
    }

    /// Whether `(theta, O)` is inside the `v` network's trained box.
    pub fn v_in_range_slice(&self, theta: &[f64], o: [f64; 2]) -> bool {
        if self.arm.check_angles(theta).is_err() || !(o[0].is_finite() && o[1].is_finite()) {
            return false;
        }
        let (s, c) = theta[0].sin_cos();
        self.v_in_range_raw(theta, s, c, o)
    }

    fn v_in_range_raw(&self, theta: &[f64], s1: f64, c1: f64, o: [f64; 2]) -> bool {
        let mut input = [0.0; MAX_V_INPUTS];
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
        buf: &'a mut [f64; MAX_V_INPUTS],
    ) -> &'a [f64] {
        v_inputs(self.v.variant, self.arm.post(), theta, sc, o, buf)
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

/// The `Phi` networks' inputs for a pose.
pub(crate) fn phi_inputs(variant: Variant, theta: &[f64]) -> &[f64] {
    match variant {
        Variant::Equivariant => &theta[1..],
        _ => theta,
    }
}

/// Most links the `v` network's input buffer holds (`n + 2` inputs); weights
/// files for longer arms are refused when they load.
pub const MAX_V_INPUTS: usize = 64;

/// The `v` network's inputs for a pose and obstacle point, written into `buf`
/// (`sc` = sine and cosine of `theta_1`).
pub(crate) fn v_inputs<'a>(
    variant: Variant,
    post: f64,
    theta: &[f64],
    (s, c): (f64, f64),
    o: [f64; 2],
    buf: &'a mut [f64; MAX_V_INPUTS],
) -> &'a [f64] {
    let n = theta.len().min(MAX_V_INPUTS - 2);
    match variant {
        Variant::Equivariant => {
            // Rotate O by -theta_1 about P(0): the arm at theta_1 is the arm at
            // theta_1 = 0 turned by R(theta_1), so O' = R(theta_1)^T (O - P(0)) + P(0).
            let (dx, dy) = (o[0], o[1] - post);
            buf[..n - 1].copy_from_slice(&theta[1..n]);
            buf[n - 1] = c * dx - s * dy;
            buf[n] = s * dx + c * dy + post;
            &buf[..n + 1]
        }
        _ => {
            buf[..n].copy_from_slice(&theta[..n]);
            buf[n] = o[0];
            buf[n + 1] = o[1];
            &buf[..n + 2]
        }
    }
}

impl Surrogate for Networks {
    fn arm(&self) -> &Arm {
        &self.arm
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
