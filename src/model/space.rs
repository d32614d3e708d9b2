//! The chain in space as an arm model (`M = 3`): the modified-DH pass
//! ([`crate::space::SpacePose`]) and eq. (18) with a `3 x 3` Cholesky
//! solve.

use super::{Clearance, Model, PhiAlgebra};
use crate::arm::{JointLimits, RateLimits};
use crate::error::Result;
use crate::scene::SpaceScene;
use crate::space::linalg::{smallest_singular_value3, solve_spd3};
use crate::space::{
    criterion, dot, manipulability, phi, Chain, SpacePair, SpacePairs, SpacePose, Sphere,
};

/// The damping (m^2) of the pull's inverse in space: the elbow's
/// Jacobian `J_k` loses rank where its levers line up.
pub const PULL_DAMPING: f64 = 1e-3;

impl Model<3> for Chain {
    type Pose = SpacePose;
    type Scene = SpaceScene;
    type Pair = SpacePair;
    type Pairs = SpacePairs;
    type Point = [f64; 3];

    fn dof(&self) -> usize {
        Chain::dof(self)
    }
    fn pose(&self) -> SpacePose {
        SpacePose::of(self)
    }
    fn update(&self, pose: &mut SpacePose, theta: &[f64]) -> Result<()> {
        pose.update(self, theta)
    }
    fn joint_limits(&self) -> Option<&JointLimits> {
        Chain::joint_limits(self)
    }
    fn rate_limits(&self) -> Option<&RateLimits> {
        Chain::rate_limits(self)
    }
    fn pairs(n: usize) -> SpacePairs {
        SpacePairs::with_capacity(Self::most_pairs(n))
    }
    /// Every pair a chain can have ([`SpacePairs::most`]).
    fn most_pairs(n: usize) -> usize {
        SpacePairs::most(n)
    }
    fn update_pairs(scene: &SpaceScene, pose: &SpacePose, within: f64, pairs: &mut SpacePairs) {
        chain_pairs(
            &scene.arm,
            scene.floor,
            &scene.obstacles,
            pose,
            within,
            pairs,
        );
    }
    fn pair_list(pairs: &SpacePairs) -> &[SpacePair] {
        pairs.as_slice()
    }
    fn obstacle_centres(scene: &SpaceScene) -> impl Iterator<Item = [f64; 3]> + '_ {
        scene.obstacles.iter().map(|s| s.centre)
    }
    fn obstacle_vector_into(
        scene: &SpaceScene,
        pose: &SpacePose,
        lambda: f64,
        eps: f64,
        _scratch: &mut [f64],
        v: &mut [f64],
    ) {
        chain_obstacle_vector(&scene.arm, pose, &scene.obstacles, lambda, eps, v);
    }
    #[inline]
    fn theta(pose: &SpacePose) -> &[f64] {
        pose.theta()
    }
    #[inline]
    fn hand(pose: &SpacePose) -> [f64; 3] {
        pose.hand()
    }
    #[inline]
    fn jacobian(pose: &SpacePose) -> &[f64] {
        pose.jacobian()
    }
    #[inline]
    fn sigma_min(pose: &SpacePose) -> f64 {
        smallest_singular_value3(pose.jjt())
    }
    fn manipulability(pose: &SpacePose) -> f64 {
        manipulability::manipulability(pose)
    }
    fn manipulability_gradient_into(pose: &SpacePose, floor: f64, out: &mut [f64]) {
        manipulability::manipulability_gradient_into(pose, floor, out);
    }
    /// Joint `k`'s origin; the hand for `k = n`.
    fn joint_point(pose: &SpacePose, k: usize) -> [f64; 3] {
        if k < pose.dof() {
            pose.joint_origin(k)
        } else {
            pose.hand()
        }
    }
    /// In space the pull is `J_k^T (J_k J_k^T + delta I)^-1 f` rather than
    /// the plane's `J_k^T f`: the chain's elbow is moved by joints with
    /// short levers (the Panda's upper-arm roll turns its elbow on an
    /// 8 cm arm), so the plain transpose left it 20 times slower than the
    /// pointer (`tests/space/self_motion.rs` measured 0.2 px a move); the
    /// damped inverse makes the elbow's own velocity about `f` wherever
    /// the joints can move it that way.
    fn pull(pose: &SpacePose, k: usize, f: [f64; 3], v: &mut [f64]) {
        // Column i of J_k is z_i x (P(k) - o_i) for the joints before k.
        let p = pose.joint_origin(k);
        let col = |i: usize| pose.column(i, p);
        let mut a = [[0.0; 3]; 3];
        for i in 0..k.min(v.len()) {
            let c = col(i);
            for (r, row) in a.iter_mut().enumerate() {
                for (q, x) in row.iter_mut().enumerate() {
                    *x += c[r] * c[q];
                }
            }
        }
        for (r, row) in a.iter_mut().enumerate() {
            row[r] += PULL_DAMPING;
        }
        // A's damping makes it positive definite: the solve cannot fail
        // on finite numbers, and a non-finite pose pulls nothing.
        let phi = solve_spd3(a, f).unwrap_or([0.0; 3]);
        for (i, vi) in v.iter_mut().enumerate() {
            *vi = if i < k { dot(col(i), phi) } else { 0.0 };
        }
    }
    fn eq18(
        pose: &SpacePose,
        xdot: [f64; 3],
        v: &[f64],
        delta: f64,
        out: &mut [f64],
    ) -> Result<()> {
        let jac = pose.jacobian();
        let mut a = pose.jjt();
        for (i, row) in a.iter_mut().enumerate() {
            row[i] += delta;
        }
        let mut rhs = xdot;
        for (col, vi) in jac.chunks_exact(3).zip(v) {
            for r in 0..3 {
                rhs[r] -= col[r] * vi;
            }
        }
        let phi = solve_spd3(a, rhs)?;
        for ((o, col), vi) in out.iter_mut().zip(jac.chunks_exact(3)).zip(v) {
            *o = col[0] * phi[0] + col[1] * phi[1] + col[2] * phi[2] + vi;
        }
        Ok(())
    }
    fn solve_jjt(pose: &SpacePose, delta: f64, b: [f64; 3]) -> Result<[f64; 3]> {
        let mut a = pose.jjt();
        for (i, row) in a.iter_mut().enumerate() {
            row[i] += delta;
        }
        solve_spd3(a, b)
    }
    fn eq18_weighted(
        pose: &SpacePose,
        winv: &[f64],
        xdot: [f64; 3],
        v: &[f64],
        delta: f64,
        out: &mut [f64],
    ) -> Result<()> {
        let jac = pose.jacobian();
        let mut a = [[0.0; 3]; 3];
        let mut rhs = xdot;
        for ((col, vi), w) in jac.chunks_exact(3).zip(v).zip(winv) {
            for r in 0..3 {
                for c in 0..3 {
                    a[r][c] += col[r] * (w * col[c]);
                }
                rhs[r] -= col[r] * (w * vi);
            }
        }
        for (i, row) in a.iter_mut().enumerate() {
            row[i] += delta;
        }
        let phi = solve_spd3(a, rhs)?;
        for (((o, col), vi), w) in out.iter_mut().zip(jac.chunks_exact(3)).zip(v).zip(winv) {
            *o = w * ((col[0] * phi[0] + col[1] * phi[1] + col[2] * phi[2]) + vi);
        }
        Ok(())
    }
}

/// A chain's pairs, whatever its task reads of the pass (the hand's point
/// or its pose: [`AsRef<SpacePose>`]).
impl<P: AsRef<SpacePose>> Clearance<P> for SpacePair {
    #[inline]
    fn clearance(&self) -> f64 {
        self.distance
    }
    #[inline]
    fn is_self(&self) -> bool {
        self.is_link()
    }
    #[inline]
    fn row_into(&self, pose: &P, row: &mut [f64]) {
        self.gradient_into(pose.as_ref(), row);
    }
}

/// The pairs within `within` of each other that the chain's two models
/// (the hand's point and its pose) read: each capsule's with each sphere,
/// with the floor where it is an obstacle, and the chain's own.
pub(super) fn chain_pairs(
    chain: &Chain,
    floor: bool,
    spheres: &[Sphere],
    pose: &SpacePose,
    within: f64,
    pairs: &mut SpacePairs,
) {
    pairs.update(chain, pose, spheres, within);
    if floor {
        pairs.add_floor(chain, pose, within);
    }
    pairs.add_self(chain, pose, within);
}

/// The paper's obstacle vector (eqs. 12-16) of a chain past `spheres`
/// with gain `lambda` and floor `eps`, whatever its task.
pub(super) fn chain_obstacle_vector(
    chain: &Chain,
    pose: &SpacePose,
    spheres: &[Sphere],
    lambda: f64,
    eps: f64,
    v: &mut [f64],
) {
    let centres = spheres.iter().map(|s| s.centre);
    criterion::null_space_vector_into(chain, pose, centres, lambda, eps, v);
}

impl PhiAlgebra<3> for Chain {
    #[inline]
    fn refine_phi(phi_: &mut [f64], jac: &[f64], steps: u32) -> Result<bool> {
        phi::refine_phi(phi_, jac, steps)
    }
    #[inline]
    fn damp_phi(phi_: &mut [f64], delta: f64) -> Result<()> {
        phi::damp_phi(phi_, delta)
    }
    #[inline]
    fn weight_phi(phi_: &mut [f64], jac: &[f64], winv: &[f64], delta: f64) -> Result<()> {
        phi::weight_phi(phi_, jac, winv, delta)
    }
    #[inline]
    fn phi_into(jac: &[f64], winv: Option<&[f64]>, delta: f64, out: &mut [f64]) -> Result<()> {
        phi::damped_pseudoinverse(jac, winv, delta, out)
    }
    #[inline]
    fn eq21(
        phi_: &[f64],
        jac: &[f64],
        winv: Option<&[f64]>,
        xdot: [f64; 3],
        v: &[f64],
        out: &mut [f64],
    ) -> Result<()> {
        phi::theta_dot(phi_, jac, winv, xdot, v, out)
    }
}

scene_of!(SpaceScene, Chain);
