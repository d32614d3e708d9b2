//! Self-motion: the arm moving in the null space of its Jacobian, the hand
//! holding still (the motion eq. (5)'s `(I - J+ J) v` term makes, on its
//! own). A joint dragged toward a point is pulled by a force
//! `f = G (to - P(k))` at that joint, `theta_dot = (I - J+ J) J_k^T f`, with `J_k` the Jacobian of the
//! joint's position `P(k)` and `J+ = J^T (J J^T)^-1` (eq. 6 with `W = I`,
//! `delta = 0`: the exact projector, so the hand's velocity is zero to
//! rounding); a closed loop `J+ K (X_hold - X)` brings back what RK4 and
//! rounding let drift. Integrated by RK4 in small steps.
//!
//! Written once for every arm, generic over the hand's dimension `M`: what
//! it needs of an arm's kinematics is [`NullSpaceArm`], which the planar
//! arm (`M = 2`, eqs. 1-3) and the chain in space (`M = 3`) implement.

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::ik;
use crate::kinematics::Pose;
use crate::space::linalg::solve_spd3;
use crate::space::{cross, dot, sub, Chain, SpacePose};

use super::methods::space::eq18;

/// What self-motion needs of an arm's kinematics, for a hand of `M`
/// coordinates: a pose it updates in place, the hand and the joints'
/// positions, the pull of a force at a joint (`J_k^T f`) and the exact
/// route (`J+ (Xdot - J v) + v`, eq. 18 with `delta = 0`).
pub trait NullSpaceArm<const M: usize> {
    /// The pose, with its scratch space.
    type Pose: Clone + std::fmt::Debug;
    /// The number of joints.
    fn dof(&self) -> usize;
    /// A pose of the arm's size, to be updated.
    fn pose(&self) -> Self::Pose;
    /// `pose` at `theta` (one kinematics pass).
    fn update(&self, pose: &mut Self::Pose, theta: &[f64]) -> Result<()>;
    /// The hand at `pose`.
    fn hand(pose: &Self::Pose) -> [f64; M];
    /// The position `P(k)` of joint `k` (`1 <= k < n`: an elbow).
    fn joint_point(pose: &Self::Pose, k: usize) -> [f64; M];
    /// `v = J_k^T f` into `v`: the joint rates of a force `f` at `P(k)`
    /// (the joints before `k` move it, the others not).
    fn pull(pose: &Self::Pose, k: usize, f: [f64; M], v: &mut [f64]);
    /// The exact route `J+ (xdot - J v) + v` (`delta = 0`) into `out`.
    fn exact(pose: &Self::Pose, xdot: [f64; M], v: &[f64], out: &mut [f64]) -> Result<()>;
}

impl NullSpaceArm<2> for Arm {
    type Pose = Pose;
    fn dof(&self) -> usize {
        Arm::dof(self)
    }
    fn pose(&self) -> Pose {
        Pose::zeros(Arm::dof(self))
    }
    fn update(&self, pose: &mut Pose, theta: &[f64]) -> Result<()> {
        pose.update(self, theta)
    }
    fn hand(pose: &Pose) -> [f64; 2] {
        pose.end_effector()
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
    fn exact(pose: &Pose, xdot: [f64; 2], v: &[f64], out: &mut [f64]) -> Result<()> {
        ik::theta_dot_symmetric_into(pose.jacobian(), xdot, v, 0.0, out)
    }
}

impl NullSpaceArm<3> for Chain {
    type Pose = SpacePose;
    fn dof(&self) -> usize {
        Chain::dof(self)
    }
    fn pose(&self) -> SpacePose {
        SpacePose::zeros(Chain::dof(self))
    }
    fn update(&self, pose: &mut SpacePose, theta: &[f64]) -> Result<()> {
        pose.update(self, theta)
    }
    fn hand(pose: &SpacePose) -> [f64; 3] {
        pose.hand()
    }
    fn joint_point(pose: &SpacePose, k: usize) -> [f64; 3] {
        pose.joint_origin(k)
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
        let col = |i: usize| cross(pose.axis(i), sub(p, pose.joint_origin(i)));
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
    fn exact(pose: &SpacePose, xdot: [f64; 3], v: &[f64], out: &mut [f64]) -> Result<()> {
        eq18(pose, xdot, v, 0.0, out)
    }
}

/// RK4 step of the self-motion (s).
pub const SELF_MOTION_DT: f64 = 0.02;
/// Gain `K` (1/s) of the loop that holds the hand.
pub const HOLD_GAIN: f64 = 10.0;
/// Stiffness `G` (1/(m s)) of the pull on a dragged elbow: the force is
/// `f = G (to - P(k))`, so the elbow follows the pointer within about
/// `1 / (G |J_k|^2)`, a quarter of a second for the paper's arm.
pub const PULL_GAIN: f64 = 10.0;

/// The damping (m^2) of the pull's inverse in space: the elbow's
/// Jacobian `J_k` loses rank where its levers line up.
pub const PULL_DAMPING: f64 = 1e-3;

/// The self-motion's scratch space for an `n`-joint arm `A` whose hand has
/// `M` coordinates (the planar arm's 2, the chain in space's 3).
#[derive(Debug, Clone)]
pub struct SelfMotion<A: NullSpaceArm<M>, const M: usize> {
    pose: A::Pose,
    stage: Vec<f64>,
    k: [Vec<f64>; 4],
    v: Vec<f64>,
    /// The last direction of a motion along the null space, which the next
    /// keeps the orientation of.
    dir: Vec<f64>,
}

/// What moves the arm, the hand held at `hold`: elbow `joint` pulled
/// toward `to`, or (`to` absent) the joint-space direction `(I - J+ J) e_j`
/// of joint `joint` at unit speed, times `sign`.
#[derive(Debug, Clone, Copy)]
struct Pull<const M: usize> {
    joint: usize,
    to: Option<[f64; M]>,
    sign: f64,
    hold: [f64; M],
}

impl<A: NullSpaceArm<M>, const M: usize> SelfMotion<A, M> {
    /// Room for the arm's `n` joints.
    pub fn new(arm: &A) -> Self {
        let n = arm.dof();
        let v = || vec![0.0; n];
        Self {
            pose: arm.pose(),
            stage: v(),
            k: [v(), v(), v(), v()],
            v: v(),
            dir: v(),
        }
    }

    /// Moves `theta` in place by `steps` RK4 steps of [`SELF_MOTION_DT`]
    /// with the elbow `joint` (its position `P(joint)`, `1 <= joint < n`)
    /// pulled toward `to` and the hand held at `hold`; refused, leaving
    /// `theta` as it was, for a joint that is not an elbow, a non-finite
    /// point or a singular pose.
    pub fn drag(
        &mut self,
        arm: &A,
        theta: &mut [f64],
        joint: usize,
        to: [f64; M],
        hold: [f64; M],
        steps: usize,
    ) -> Result<()> {
        let n = arm.dof();
        if !(1..n).contains(&joint) || theta.len() != n || self.v.len() != n {
            return Err(Error::OutOfRange {
                what: "dragged joint".into(),
                value: joint as f64,
                min: 1.0,
                max: n.saturating_sub(1) as f64,
            });
        }
        for (c, axis) in to.iter().zip(["x", "y", "z"]) {
            crate::error::finite(&format!("drag point {axis}"), *c)?;
        }
        let pull = Pull {
            joint,
            to: Some(to),
            sign: 1.0,
            hold,
        };
        self.integrate(arm, theta, pull, steps)
    }

    /// Moves `theta` in place along the self-motion through joint `joint`
    /// (`0 <= joint < n`): the direction `(I - J+ J) e_j`, normalised, for
    /// an arc length of `amount` rad in joint space, the hand held at
    /// `hold`. It sets out the way that `theta_j` grows for `amount > 0`
    /// and keeps its orientation from step to step (the direction of
    /// `(I - J+ J) e_j` itself turns over where `theta_j` is extreme on the
    /// self-motion, which would stop the arm there). The page's slider, for
    /// a keyboard. Refused as [`SelfMotion::drag`] is.
    pub fn along(
        &mut self,
        arm: &A,
        theta: &mut [f64],
        joint: usize,
        amount: f64,
        hold: [f64; M],
    ) -> Result<()> {
        let n = arm.dof();
        crate::error::finite("self-motion", amount)?;
        if joint >= n || theta.len() != n || self.v.len() != n {
            return Err(Error::OutOfRange {
                what: "moved joint".into(),
                value: joint as f64,
                min: 0.0,
                max: n.saturating_sub(1) as f64,
            });
        }
        let steps = (amount.abs() / SELF_MOTION_DT).ceil().min(1e4) as usize;
        if steps == 0 {
            return Ok(());
        }
        let pull = Pull {
            joint,
            to: None,
            sign: amount.abs() / (steps as f64 * SELF_MOTION_DT),
            hold,
        };
        self.dir.iter_mut().enumerate().for_each(|(i, d)| {
            *d = if i == joint { amount.signum() } else { 0.0 };
        });
        self.integrate(arm, theta, pull, steps)
    }

    /// `steps` RK4 steps of `pull`; `theta` as it was if one fails.
    fn integrate(&mut self, arm: &A, theta: &mut [f64], pull: Pull<M>, steps: usize) -> Result<()> {
        let start = theta.to_vec();
        for _ in 0..steps {
            if let Err(e) = self.rk4(arm, theta, pull) {
                theta.copy_from_slice(&start);
                return Err(e);
            }
        }
        Ok(())
    }

    /// One classical RK4 step of [`SELF_MOTION_DT`].
    fn rk4(&mut self, arm: &A, theta: &mut [f64], pull: Pull<M>) -> Result<()> {
        let h = SELF_MOTION_DT;
        let Self {
            pose,
            stage,
            k,
            v,
            dir,
        } = self;
        for s in 0..4 {
            let a = [0.0, 0.5, 0.5, 1.0][s] * h;
            for i in 0..theta.len() {
                stage[i] = theta[i] + if s == 0 { 0.0 } else { a * k[s - 1][i] };
            }
            arm.update(pose, stage)?;
            rates::<A, M>(pose, pull, v, dir, &mut k[s])?;
        }
        if pull.to.is_none() {
            dir.copy_from_slice(&k[0]);
        }
        for (i, t) in theta.iter_mut().enumerate() {
            *t += h / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
        }
        Ok(())
    }
}

/// `theta_dot = (I - J+ J) v + J+ K (hold - X)` at `pose` into `out`, with
/// `v = J_k^T f`, `f = G (to - P(k))`, or `v` the unit `(I - J+ J) e_j`
/// oriented as `dir` and times the pull's speed; `v` is scratch.
fn rates<A: NullSpaceArm<M>, const M: usize>(
    pose: &A::Pose,
    pull: Pull<M>,
    v: &mut [f64],
    dir: &[f64],
    out: &mut [f64],
) -> Result<()> {
    match pull.to {
        Some(to) => {
            let p = A::joint_point(pose, pull.joint);
            let f: [f64; M] = std::array::from_fn(|i| PULL_GAIN * (to[i] - p[i]));
            A::pull(pose, pull.joint, f, v);
        }
        None => {
            // (I - J+ J) e_j = J+ (0 - J e_j) + e_j, then unit length.
            v.iter_mut()
                .enumerate()
                .for_each(|(i, x)| *x = f64::from(u8::from(i == pull.joint)));
            A::exact(pose, [0.0; M], v, out)?;
            let norm = out.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm < 1e-9 {
                return Err(Error::Singular(format!(
                    "joint {} has no self-motion at this pose",
                    pull.joint + 1
                )));
            }
            let along: f64 = out.iter().zip(dir).map(|(o, d)| o * d).sum();
            let scale = pull.sign.copysign(along) / norm;
            v.iter_mut()
                .zip(out.iter())
                .for_each(|(x, o)| *x = scale * o);
        }
    }
    // (I - J+ J) v + J+ K (hold - X) = J+ (K (hold - X) - J v) + v.
    let x = A::hand(pose);
    let xdot: [f64; M] = std::array::from_fn(|i| HOLD_GAIN * (pull.hold[i] - x[i]));
    A::exact(pose, xdot, v, out)
}
