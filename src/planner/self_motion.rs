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
//! it needs of an arm's kinematics is its [`Model`]: the planar arm
//! (`M = 2`, eqs. 1-3) and the chain in space (`M = 3`).

use crate::error::{Error, Result};
use crate::model::Model;

/// RK4 step of the self-motion (s).
pub const SELF_MOTION_DT: f64 = 0.02;
/// Gain `K` (1/s) of the loop that holds the hand.
pub const HOLD_GAIN: f64 = 10.0;
/// Stiffness `G` (1/(m s)) of the pull on a dragged elbow: the force is
/// `f = G (to - P(k))`. Only the null space's share of `J_k^T f` moves
/// the arm, so the elbow approaches the pointer more slowly than
/// `1 / (G |J_k|^2)` (a quarter of a second on the paper's arm) would
/// say. A pointer move integrates a fixed number of steps
/// ([`crate::session::self_motion::DRAG_STEPS`]), so the elbow trails a
/// fast pointer and stops where the last move left it.
pub const PULL_GAIN: f64 = 10.0;

/// The self-motion's scratch space for an `n`-joint arm `A` whose hand has
/// `M` coordinates (the planar arm's 2, the chain in space's 3).
#[derive(Debug, Clone)]
pub struct SelfMotion<A: Model<M>, const M: usize> {
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
struct Pull<P, const M: usize> {
    joint: usize,
    to: Option<P>,
    sign: f64,
    hold: [f64; M],
}

impl<A: Model<M>, const M: usize> SelfMotion<A, M> {
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
        to: A::Point,
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
        for (c, axis) in to.as_ref().iter().zip(["x", "y", "z"]) {
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
    fn integrate(
        &mut self,
        arm: &A,
        theta: &mut [f64],
        pull: Pull<A::Point, M>,
        steps: usize,
    ) -> Result<()> {
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
    fn rk4(&mut self, arm: &A, theta: &mut [f64], pull: Pull<A::Point, M>) -> Result<()> {
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
fn rates<A: Model<M>, const M: usize>(
    pose: &A::Pose,
    pull: Pull<A::Point, M>,
    v: &mut [f64],
    dir: &[f64],
    out: &mut [f64],
) -> Result<()> {
    match pull.to {
        Some(to) => {
            let p = A::joint_point(pose, pull.joint);
            let mut f = A::Point::default();
            for ((fi, ti), pi) in f.as_mut().iter_mut().zip(to.as_ref()).zip(p.as_ref()) {
                *fi = PULL_GAIN * (ti - pi);
            }
            A::pull(pose, pull.joint, f, v);
        }
        None => {
            // (I - J+ J) e_j = J+ (0 - J e_j) + e_j, then unit length.
            v.iter_mut()
                .enumerate()
                .for_each(|(i, x)| *x = f64::from(u8::from(i == pull.joint)));
            A::eq18(pose, [0.0; M], v, 0.0, out)?;
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
    A::eq18(pose, xdot, v, 0.0, out)
}
