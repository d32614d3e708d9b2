//! The learned replacements a planner may use: the interfaces the trained
//! networks implement ([`crate::networks::Networks`] in the plane,
//! `crate::networks::space::SpaceNetworks` in space).

use crate::arm::Arm;
use crate::error::Result;
use crate::kinematics::Pose;

/// Learned replacements for `Phi(theta)` (eq. 19) and for the obstacle
/// gradient of eqs. (14)-(15). Implemented by the trained networks.
///
/// Every method reads a [`Pose`] (the planner's one kinematics pass, whose
/// `theta` was validated when it entered the planner) and fills a slice, so
/// the planner's step allocates nothing.
pub trait Surrogate: Send + Sync {
    /// The arm the networks were trained for; the planner refuses them for
    /// any other.
    fn arm(&self) -> &Arm;
    /// Learned `Phi(theta)` at `delta = 0`, row-major `n x 2` into `out`
    /// (`2n` entries).
    fn phi(&self, pose: &Pose, out: &mut [f64]) -> Result<()>;
    /// Learned area gradient `g(theta, O)` into `out` (`n` entries), with
    /// `v = (lambda / 4) g` (see [`crate::obstacle::area_gradient`]).
    fn area_gradient(&self, pose: &Pose, o: [f64; 2], out: &mut [f64]) -> Result<()>;
    /// Whether the pose lies in the range the `Phi` network was trained on.
    fn phi_in_range(&self, pose: &Pose) -> bool;
    /// Whether `(theta, O)` lies in the range the `v` network was trained on.
    fn v_in_range(&self, pose: &Pose, o: [f64; 2]) -> bool;
}

/// Learned replacements for an arm in space: `Phi(theta)` (`n x 3`) and
/// the area gradient of the criterion in space. Implemented by
/// `crate::networks::space::SpaceNetworks`.
pub trait SpaceSurrogate: Send + Sync {
    /// Refused unless the networks were trained for `chain`'s geometry.
    fn check_chain(&self, chain: &crate::space::Chain) -> Result<()>;
    /// Learned `Phi` at `pose`, row-major `n x 3` into `out`.
    fn phi(&self, pose: &crate::space::SpacePose, out: &mut [f64]) -> Result<()>;
    /// Learned area gradient `g(theta, O)` into `out` (`n` entries).
    fn area_gradient(
        &self,
        pose: &crate::space::SpacePose,
        o: crate::space::Vec3,
        out: &mut [f64],
    ) -> Result<()>;
}
