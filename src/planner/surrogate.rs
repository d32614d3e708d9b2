//! The learned replacements a planner may use: the interface the trained
//! networks implement for an arm model ([`crate::networks::Networks`] for
//! the planar arm, `crate::networks::space::SpaceNetworks` for a chain in
//! space).

use crate::arm::Arm;
use crate::error::Result;
use crate::model::Model;

/// Learned replacements for `Phi(theta)` (eq. 19) and for the obstacle
/// gradient of eqs. (14)-(15), for an arm `A` whose hand has `M`
/// coordinates (the planar arm's by default). Implemented by the trained
/// networks.
///
/// Every method reads a pose (the planner's one kinematics pass, whose
/// `theta` was validated when it entered the planner) and fills a slice, so
/// the planner's step allocates nothing.
pub trait Surrogate<A: Model<M> = Arm, const M: usize = 2>: Send + Sync {
    /// Refused unless the networks were trained for `arm`'s geometry (the
    /// planner refuses them for any other).
    fn check(&self, arm: &A) -> Result<()>;
    /// Learned `Phi(theta)` at `delta = 0`, row-major `n x M` into `out`
    /// (`M n` entries).
    fn phi(&self, pose: &A::Pose, out: &mut [f64]) -> Result<()>;
    /// Learned area gradient `g(theta, O)` into `out` (`n` entries), with
    /// `v = (lambda / 4) g` (see [`crate::obstacle::area_gradient`]).
    fn area_gradient(&self, pose: &A::Pose, o: A::Point, out: &mut [f64]) -> Result<()>;
    /// Whether the pose lies in the range the `Phi` network was trained on.
    fn phi_in_range(&self, pose: &A::Pose) -> bool;
    /// Whether `(theta, O)` lies in the range the `v` network was trained on.
    fn v_in_range(&self, pose: &A::Pose, o: A::Point) -> bool;
    /// Whether it has a `Phi` network for this task (the networks of an
    /// arm in space have none for its hand's pose: the planner refuses
    /// the methods that need one).
    fn has_phi(&self) -> bool {
        true
    }
}
