//! The hand's full pose as the task (`M = 6`): the chain's pass with the
//! hand's rotation and the `6 x n` geometric Jacobian
//! ([`crate::space::HandPose`]), eq. (6)'s solve with the paper's metric
//! `Z` (`(J W^-1 J^T + delta Z^-1)`, a `6 x 6` Cholesky factorisation on
//! the stack: no allocation), and the pose's error and shortest path.
//! The obstacles, the volumes and the criterion are the chain's
//! (`model/space.rs`), read from the same pass.

use nalgebra::{Matrix6, SymmetricEigen, Vector6};

use super::space::{chain_obstacle_vector, chain_pairs};
use super::{Model, PhiAlgebra};
use crate::arm::{JointLimits, RateLimits};
use crate::error::{Error, Result};
use crate::scene::PoseScene;
use crate::space::{
    pose_distance, pose_error, pose_geodesic, HandPose, PoseChain, SpacePair, SpacePairs,
};

/// `J W^-1 J^T + delta Z^-1` of `pose` (`winv`: `W^-1`'s diagonal, `None`
/// for `W = I`).
fn gram(pose: &HandPose, winv: Option<&[f64]>, delta: f64) -> Matrix6<f64> {
    let mut a = match winv {
        None => Matrix6::from_fn(|r, c| pose.jjt()[r][c]),
        Some(w) => {
            let mut a = Matrix6::zeros();
            for (col, wi) in pose.jacobian().chunks_exact(6).zip(w) {
                let v = Vector6::from_column_slice(col);
                a += (v * *wi) * v.transpose();
            }
            a
        }
    };
    for (i, d) in pose.damping(delta).into_iter().enumerate() {
        a[(i, i)] += d;
    }
    a
}

/// `a^-1 b` for the symmetric positive definite `a` (Cholesky); refused
/// where it is not (numerically: a pivot below `1e-14` of the largest
/// diagonal entry, as the `3 x 3` solve refuses): a singular pose with no
/// damping.
fn solve(a: Matrix6<f64>, b: [f64; 6]) -> Result<[f64; 6]> {
    let singular =
        || Error::Singular("J W^-1 J^T + delta Z^-1 (6 x 6) is not positive definite".into());
    let scale = (0..6).map(|i| a[(i, i)].abs()).fold(0.0, f64::max);
    let tiny = 1e-14 * scale.max(f64::MIN_POSITIVE);
    let chol = a.cholesky().ok_or_else(singular)?;
    let l = chol.l_dirty();
    // Each pivot (the square of L's diagonal) must exceed `tiny`; NaN does not.
    if !(0..6)
        .all(|i| (l[(i, i)] * l[(i, i)]).partial_cmp(&tiny) == Some(std::cmp::Ordering::Greater))
    {
        return Err(singular());
    }
    let x = chol.solve(&Vector6::from(b));
    if x.iter().all(|v| v.is_finite()) {
        Ok(x.into())
    } else {
        Err(Error::Singular(
            "the 6 x 6 solve gave a non-finite rate".into(),
        ))
    }
}

/// `theta_dot = W^-1 (J^T varphi + v)` with
/// `(J W^-1 J^T + delta Z^-1) varphi = Xdot - J W^-1 v`.
fn resolve(
    pose: &HandPose,
    winv: Option<&[f64]>,
    xdot: [f64; 6],
    v: &[f64],
    delta: f64,
    out: &mut [f64],
) -> Result<()> {
    let jac = pose.jacobian();
    let w = |i: usize| winv.map_or(1.0, |w| w[i]);
    let mut rhs = xdot;
    for (i, (col, vi)) in jac.chunks_exact(6).zip(v).enumerate() {
        for (r, x) in rhs.iter_mut().enumerate() {
            *x -= col[r] * (w(i) * vi);
        }
    }
    let phi = solve(gram(pose, winv, delta), rhs)?;
    for (i, ((o, col), vi)) in out.iter_mut().zip(jac.chunks_exact(6)).zip(v).enumerate() {
        let jt_phi: f64 = col.iter().zip(&phi).map(|(c, p)| c * p).sum();
        *o = w(i) * (jt_phi + vi);
    }
    Ok(())
}

/// The eigenvalues and eigenvectors of `J J^T` (nalgebra's symmetric
/// eigensolver on the stack).
fn eigen(pose: &HandPose) -> SymmetricEigen<f64, nalgebra::U6> {
    SymmetricEigen::new(Matrix6::from_fn(|r, c| pose.jjt()[r][c]))
}

/// `det(J J^T)` and its adjugate `sum_k (prod_{l != k} lambda_l) v_k v_k^T`
/// (defined at a singular pose too, where the inverse is not).
fn det_and_adjugate(pose: &HandPose) -> (f64, Matrix6<f64>) {
    let e = eigen(pose);
    let det = e.eigenvalues.iter().product();
    let mut adj = Matrix6::zeros();
    for k in 0..6 {
        let others: f64 = (0..6)
            .filter(|&l| l != k)
            .map(|l| e.eigenvalues[l])
            .product();
        let v = e.eigenvectors.column(k);
        adj += v * v.transpose() * others;
    }
    (det, adj)
}

impl Model<6> for PoseChain {
    type Pose = HandPose;
    type Scene = PoseScene;
    type Pair = SpacePair;
    type Pairs = SpacePairs;
    type Point = [f64; 3];

    fn dof(&self) -> usize {
        self.chain.dof()
    }
    fn pose(&self) -> HandPose {
        PoseChain::pose(self)
    }
    fn update(&self, pose: &mut HandPose, theta: &[f64]) -> Result<()> {
        pose.update(self, theta)
    }
    fn joint_limits(&self) -> Option<&JointLimits> {
        self.chain.joint_limits()
    }
    fn rate_limits(&self) -> Option<&RateLimits> {
        self.chain.rate_limits()
    }
    fn obstacle_centres(scene: &PoseScene) -> impl Iterator<Item = [f64; 3]> + '_ {
        scene.obstacles.iter().map(|s| s.centre)
    }
    fn obstacle_vector_into(
        scene: &PoseScene,
        pose: &HandPose,
        lambda: f64,
        eps: f64,
        _scratch: &mut [f64],
        v: &mut [f64],
    ) {
        let chain = &scene.arm.chain;
        chain_obstacle_vector(chain, pose.space(), &scene.obstacles, lambda, eps, v);
    }
    fn pairs(n: usize) -> SpacePairs {
        SpacePairs::with_capacity(Self::most_pairs(n))
    }
    fn most_pairs(n: usize) -> usize {
        SpacePairs::most(n)
    }
    fn update_pairs(scene: &PoseScene, pose: &HandPose, within: f64, pairs: &mut SpacePairs) {
        let chain = &scene.arm.chain;
        chain_pairs(
            chain,
            scene.floor,
            &scene.obstacles,
            pose.space(),
            within,
            pairs,
        );
    }
    fn pair_list(pairs: &SpacePairs) -> &[SpacePair] {
        pairs.as_slice()
    }
    #[inline]
    fn theta(pose: &HandPose) -> &[f64] {
        pose.theta()
    }
    #[inline]
    fn hand(pose: &HandPose) -> [f64; 6] {
        pose.hand()
    }
    #[inline]
    fn jacobian(pose: &HandPose) -> &[f64] {
        pose.jacobian()
    }
    fn sigma_min(pose: &HandPose) -> f64 {
        eigen(pose).eigenvalues.min().max(0.0).sqrt()
    }
    /// `sqrt(det(J J^T))`, the determinant by LU on the stack (every
    /// sample records it: the eigensolver the gradient needs costs more).
    fn manipulability(pose: &HandPose) -> f64 {
        Matrix6::from_fn(|r, c| pose.jjt()[r][c])
            .determinant()
            .max(0.0)
            .sqrt()
    }
    /// `dw/dtheta_j = sum_i (B J_i) . dJ_ij / w` with `B = adj(J J^T)`
    /// (Jacobi's formula, as in `space::manipulability`), the columns'
    /// derivatives `dJ_ij = z_j x (J_v,i, z_i)` for `j <= i` and
    /// `(z_i x J_v,j, 0)` for `j > i`: a suffix and a prefix sum,
    /// `out_j = z_j . sum_{i >= j} (J_v,i x b_v,i + z_i x b_w,i)
    /// + J_v,j . sum_{i < j} b_v,i x z_i` with `b_i = B J_i`.
    fn manipulability_gradient_into(pose: &HandPose, floor: f64, out: &mut [f64]) {
        use crate::space::{add, cross, dot};
        let (det, adj) = det_and_adjugate(pose);
        let w = det.max(0.0).sqrt().max(floor);
        let jac = pose.jacobian();
        let n = pose.space().dof().min(out.len());
        let parts = |i: usize| {
            let c = &jac[6 * i..6 * i + 6];
            let b = adj * Vector6::from_column_slice(c);
            (
                [c[0], c[1], c[2]],
                [c[3], c[4], c[5]],
                [b[0], b[1], b[2]],
                [b[3], b[4], b[5]],
            )
        };
        // A joint that slides turns nothing (its angular column `w` is
        // zero, and so are its `z_j x ...` and `z_i x J_v,j` terms).
        let space = pose.space();
        let mut suffix = [0.0; 3];
        for j in (0..n).rev() {
            let (v, w_j, bv, bw) = parts(j);
            suffix = add(suffix, add(cross(v, bv), cross(w_j, bw)));
            out[j] = if space.is_prismatic(j) {
                0.0
            } else {
                dot(space.axis(j), suffix)
            };
        }
        let mut prefix = [0.0; 3];
        for (j, o) in out.iter_mut().enumerate().take(n) {
            let (v, _, bv, _) = parts(j);
            *o = (*o + dot(v, prefix)) / w;
            if !space.is_prismatic(j) {
                prefix = add(prefix, cross(bv, space.axis(j)));
            }
        }
    }
    fn joint_point(pose: &HandPose, k: usize) -> [f64; 3] {
        <crate::space::Chain as Model<3>>::joint_point(pose.space(), k)
    }
    fn pull(pose: &HandPose, k: usize, f: [f64; 3], v: &mut [f64]) {
        <crate::space::Chain as Model<3>>::pull(pose.space(), k, f, v);
    }
    #[inline]
    fn task_weights(pose: &HandPose) -> [f64; 6] {
        pose.weights()
    }
    #[inline]
    fn task_error(a: [f64; 6], b: [f64; 6]) -> [f64; 6] {
        pose_error(a, b)
    }
    #[inline]
    fn errors(a: [f64; 6], b: [f64; 6]) -> (f64, Option<f64>) {
        let (p, o) = pose_distance(a, b);
        (p, Some(o))
    }
    #[inline]
    fn geodesic(a: [f64; 6], b: [f64; 6], s: f64) -> ([f64; 6], [f64; 6]) {
        pose_geodesic(a, b, s)
    }
    fn eq18(pose: &HandPose, xdot: [f64; 6], v: &[f64], delta: f64, out: &mut [f64]) -> Result<()> {
        resolve(pose, None, xdot, v, delta, out)
    }
    fn solve_jjt(pose: &HandPose, delta: f64, b: [f64; 6]) -> Result<[f64; 6]> {
        solve(gram(pose, None, delta), b)
    }
    fn eq18_weighted(
        pose: &HandPose,
        winv: &[f64],
        xdot: [f64; 6],
        v: &[f64],
        delta: f64,
        out: &mut [f64],
    ) -> Result<()> {
        resolve(pose, Some(winv), xdot, v, delta, out)
    }
}

/// No `Phi` network is trained for the pose task: the planner refuses
/// Cases 1 and 3 on it before any of these could run (their networks have
/// no `Phi` for the pose, `Surrogate::has_phi`), and each says so. Case 2,
/// whose `Phi` is exact, never calls them.
impl PhiAlgebra<6> for PoseChain {
    fn refine_phi(_: &mut [f64], _: &[f64], _: u32) -> Result<bool> {
        Err(no_networks())
    }
    fn damp_phi(_: &mut [f64], _: f64) -> Result<()> {
        Err(no_networks())
    }
    fn weight_phi(_: &mut [f64], _: &[f64], _: &[f64], _: f64) -> Result<()> {
        Err(no_networks())
    }
    fn phi_into(_: &[f64], _: Option<&[f64]>, _: f64, _: &mut [f64]) -> Result<()> {
        Err(no_networks())
    }
    fn eq21(
        _: &[f64],
        _: &[f64],
        _: Option<&[f64]>,
        _: [f64; 6],
        _: &[f64],
        _: &mut [f64],
    ) -> Result<()> {
        Err(no_networks())
    }
}

fn no_networks() -> Error {
    Error::NetworksUnavailable(
        "no Phi network is trained for the hand's pose task (Case 2, whose Phi is exact, runs it)"
            .into(),
    )
}

scene_of!(PoseScene, PoseChain);
