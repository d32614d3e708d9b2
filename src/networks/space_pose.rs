//! The networks of an arm in space serving its hand's pose task (`m = 6`).
//!
//! The `v` network learned the area gradient `g(theta, O)` of the paper's
//! criterion, which depends on the links and the obstacle only, not on the
//! task: it serves the pose task as it is, so Case 2 (`Phi` exact by the
//! pose's eq. 18, `v` by the network) runs the pose task. The `Phi`
//! network learned the `n x 3` pseudoinverse of the hand's point: the
//! pose's is `n x 6`, and none is trained, so Cases 1 and 3 are refused by
//! name ([`crate::planner::Surrogate::has_phi`]).

use super::space::SpaceNetworks;
use crate::error::{Error, Result};
use crate::planner::Surrogate;
use crate::space::{Chain, HandPose, PoseChain, Vec3};

/// Why the pose task has no learned `Phi`.
pub const NO_POSE_PHI: &str = "no Phi network is trained for the hand's pose (its pseudoinverse is n x 6, the networks' n x 3): Case 2, whose Phi is exact, runs with the v network";

impl Surrogate<PoseChain, 6> for SpaceNetworks {
    fn check(&self, arm: &PoseChain) -> Result<()> {
        self.check_chain(&arm.chain)
    }

    fn phi(&self, _: &HandPose, _: &mut [f64]) -> Result<()> {
        Err(Error::NetworksUnavailable(NO_POSE_PHI.into()))
    }

    fn area_gradient(&self, pose: &HandPose, o: Vec3, out: &mut [f64]) -> Result<()> {
        SpaceNetworks::area_gradient(self, pose.space(), o, out)
    }

    fn phi_in_range(&self, _: &HandPose) -> bool {
        false
    }

    fn v_in_range(&self, pose: &HandPose, o: Vec3) -> bool {
        <Self as Surrogate<Chain, 3>>::v_in_range(self, pose.space(), o)
    }

    fn has_phi(&self) -> bool {
        false
    }
}
