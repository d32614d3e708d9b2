//! The planar arm as an arm model (`M = 2`): the pass of eqs. (1)-(3)
//! ([`crate::kinematics::Pose`]) and eq. (18)'s closed-form `2 x 2` solve
//! ([`crate::ik`]).

use super::{Clearance, Model, PhiAlgebra};
use crate::arm::{Arm, JointLimits, RateLimits};
use crate::clearance::{Pair, Pairs};
use crate::error::Result;
use crate::ik;
use crate::kinematics::Pose;
use crate::obstacle;
use crate::scene;

impl Model<2> for Arm {
    type Pose = Pose;
    type Scene = scene::Scene;
    type Pair = Pair;
    type Pairs = Pairs;
    type Point = [f64; 2];

    fn dof(&self) -> usize {
        Arm::dof(self)
    }
    fn pose(&self) -> Pose {
        Pose::zeros(Arm::dof(self))
    }
    fn update(&self, pose: &mut Pose, theta: &[f64]) -> Result<()> {
        pose.update(self, theta)
    }
    fn joint_limits(&self) -> Option<&JointLimits> {
        Arm::joint_limits(self)
    }
    fn rate_limits(&self) -> Option<&RateLimits> {
        Arm::rate_limits(self)
    }
    fn pairs(n: usize) -> Pairs {
        Pairs::with_capacity(Self::most_pairs(n))
    }
    /// 8 obstacles per link before the buffer grows.
    fn most_pairs(n: usize) -> usize {
        8 * n
    }
    fn update_pairs(scene: &scene::Scene, pose: &Pose, within: f64, pairs: &mut Pairs) {
        pairs.update(pose, &scene.obstacles, within);
        if let Some(post) = scene.ground() {
            pairs.add_ground(pose, post, within);
        }
    }
    fn pair_list(pairs: &Pairs) -> &[Pair] {
        pairs.as_slice()
    }
    fn obstacle_centres(scene: &scene::Scene) -> impl Iterator<Item = [f64; 2]> + '_ {
        scene.obstacles.iter().map(|o| o.centre)
    }
    fn obstacle_vector_into(
        scene: &scene::Scene,
        pose: &Pose,
        lambda: f64,
        eps: f64,
        scratch: &mut [f64],
        v: &mut [f64],
    ) {
        obstacle::null_space_vector_into(
            &scene.arm,
            pose,
            &scene.obstacles,
            lambda,
            eps,
            scratch,
            v,
        );
    }
    #[inline]
    fn theta(pose: &Pose) -> &[f64] {
        pose.theta()
    }
    #[inline]
    fn hand(pose: &Pose) -> [f64; 2] {
        pose.end_effector()
    }
    #[inline]
    fn jacobian(pose: &Pose) -> &[f64] {
        pose.jacobian()
    }
    #[inline]
    fn sigma_min(pose: &Pose) -> f64 {
        pose.sigma_min()
    }
    fn manipulability(pose: &Pose) -> f64 {
        pose.manipulability()
    }
    fn manipulability_gradient_into(pose: &Pose, floor: f64, out: &mut [f64]) {
        pose.manipulability_gradient_into(floor, out);
    }
    fn joint_point(pose: &Pose, k: usize) -> [f64; 2] {
        pose.joints()[k]
    }
    fn pull(pose: &Pose, k: usize, f: [f64; 2], v: &mut [f64]) {
        // The joints before k move P(k) as crate::clearance's point
        // Jacobian says, the others not.
        let joints = pose.joints();
        let p = joints[k];
        for (i, vi) in v.iter_mut().enumerate() {
            *vi = if i < k {
                let q = joints[i];
                f[0] * (p[1] - q[1]) - f[1] * (p[0] - q[0])
            } else {
                0.0
            };
        }
    }
    #[inline]
    fn eq18(pose: &Pose, xdot: [f64; 2], v: &[f64], delta: f64, out: &mut [f64]) -> Result<()> {
        ik::theta_dot_symmetric_into(pose.jacobian(), xdot, v, delta, out)
    }
    #[inline]
    fn solve_jjt(pose: &Pose, delta: f64, b: [f64; 2]) -> Result<[f64; 2]> {
        let [a11, a12, a22] = pose.jjt();
        ik::solve_spd2([a11 + delta, a12, a22 + delta], b)
    }
    #[inline]
    fn eq18_weighted(
        pose: &Pose,
        winv: &[f64],
        xdot: [f64; 2],
        v: &[f64],
        delta: f64,
        out: &mut [f64],
    ) -> Result<()> {
        ik::theta_dot_weighted_into(pose.jacobian(), winv, xdot, v, delta, out)
    }
}

impl Clearance<Pose> for Pair {
    #[inline]
    fn clearance(&self) -> f64 {
        self.clearance
    }
    #[inline]
    fn row_into(&self, pose: &Pose, row: &mut [f64]) {
        self.rate_row(pose, row);
    }
}

impl PhiAlgebra<2> for Arm {
    #[inline]
    fn refine_phi(phi: &mut [f64], jac: &[f64], steps: u32) -> Result<bool> {
        ik::refine_phi(phi, jac, steps)
    }
    #[inline]
    fn damp_phi(phi: &mut [f64], delta: f64) -> Result<()> {
        ik::damp_phi(phi, delta)
    }
    #[inline]
    fn weight_phi(phi: &mut [f64], jac: &[f64], winv: &[f64], delta: f64) -> Result<()> {
        ik::weight_phi(phi, jac, winv, delta)
    }
    #[inline]
    fn phi_into(jac: &[f64], winv: Option<&[f64]>, delta: f64, out: &mut [f64]) -> Result<()> {
        match winv {
            None => ik::phi_into(jac, delta, out),
            Some(w) => ik::phi_weighted_into(jac, w, delta, out),
        }
    }
    #[inline]
    fn eq21(
        phi: &[f64],
        jac: &[f64],
        winv: Option<&[f64]>,
        xdot: [f64; 2],
        v: &[f64],
        out: &mut [f64],
    ) -> Result<()> {
        match winv {
            None => ik::theta_dot_network_into(phi, jac, xdot, v, out),
            Some(w) => ik::theta_dot_network_weighted_into(phi, jac, w, xdot, v, out),
        }
    }
}

scene_of!(scene::Scene, Arm);
