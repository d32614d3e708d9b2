//! How the planner evaluates joint rates: the learned replacements it may
//! use ([`Surrogate`]), the scratch space it owns, and the rate evaluation
//! itself (eqs. 14-21).

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::ik;
use crate::kinematics::Pose;
use crate::obstacle;
use crate::scene::Scene;

use super::Mode;

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
    /// `v = (lambda / 4) g` (see [`obstacle::area_gradient`]).
    fn area_gradient(&self, pose: &Pose, o: [f64; 2], out: &mut [f64]) -> Result<()>;
    /// Whether the pose lies in the range the `Phi` network was trained on.
    fn phi_in_range(&self, pose: &Pose) -> bool;
    /// Whether `(theta, O)` lies in the range the `v` network was trained on.
    fn v_in_range(&self, pose: &Pose, o: [f64; 2]) -> bool;
}

/// Scratch space the planner owns and reuses at every step (as rapier keeps
/// a solver workspace), so that [`Planner::step`] allocates nothing once the
/// planner exists, in every mode and for any arm.
#[derive(Debug, Clone)]
pub(super) struct Workspace {
    /// The kinematics of the current state; always up to date. A step's first
    /// RK4 stage reads it, and so does the sample.
    pub(super) pose: Pose,
    /// The kinematics at an RK4 stage (and for [`Planner::theta_dot_into`]).
    pub(super) stage: Pose,
    /// `theta` at a stage.
    pub(super) theta_stage: Vec<f64>,
    /// The state after the step, before it is accepted.
    pub(super) next: Vec<f64>,
    /// The stage rates `k1..k4`.
    pub(super) k: [Vec<f64>; 4],
    /// What one rate evaluation needs.
    pub(super) scratch: Scratch,
}

/// Buffers of one rate evaluation: `v`, one obstacle's gradient and `Phi`.
#[derive(Debug, Clone)]
pub(super) struct Scratch {
    pub(super) v: Vec<f64>,
    pub(super) g: Vec<f64>,
    pub(super) phi: Vec<f64>,
}

impl Scratch {
    pub(super) fn new(n: usize) -> Self {
        Self {
            v: vec![0.0; n],
            g: vec![0.0; n],
            phi: vec![0.0; 2 * n],
        }
    }
}

impl Workspace {
    pub(super) fn new(n: usize) -> Self {
        Self {
            pose: Pose::zeros(n),
            stage: Pose::zeros(n),
            theta_stage: vec![0.0; n],
            next: vec![0.0; n],
            k: [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            scratch: Scratch::new(n),
        }
    }
}

/// What a rate evaluation reads: the scene, the mode and the networks.
#[derive(Clone, Copy)]
pub(super) struct Rates<'a> {
    pub(super) scene: &'a Scene,
    pub(super) mode: Mode,
    pub(super) networks: Option<&'a dyn Surrogate>,
}

impl Rates<'_> {
    fn nets(&self) -> Result<&dyn Surrogate> {
        self.networks.ok_or_else(|| {
            Error::NetworksUnavailable(format!("mode {} needs trained networks", self.mode))
        })
    }

    /// Null-space vector `v` at `pose` into `s.v` (zero in mode `none`),
    /// eqs. (14)-(15) summed over the obstacles, numerically or by the network.
    pub(super) fn null_space(&self, pose: &Pose, s: &mut Scratch) -> Result<()> {
        let scene = self.scene;
        match self.mode {
            Mode::None => s.v.iter_mut().for_each(|x| *x = 0.0),
            Mode::Numerical | Mode::Case1 => obstacle::null_space_vector_into(
                &scene.arm,
                pose,
                &scene.obstacles,
                scene.lambda,
                &mut s.g,
                &mut s.v,
            ),
            Mode::Case2 | Mode::Case3 => {
                let nets = self.nets()?;
                s.v.iter_mut().for_each(|x| *x = 0.0);
                for ob in &scene.obstacles {
                    nets.area_gradient(pose, ob.centre, &mut s.g)?;
                    for (vi, gi) in s.v.iter_mut().zip(&s.g) {
                        *vi += gi;
                    }
                }
                let scale = scene.lambda / 4.0;
                s.v.iter_mut().for_each(|x| *x *= scale);
            }
        }
        Ok(())
    }

    /// The damping schedule's share of `delta` at `pose` (zero when off).
    #[inline]
    fn scheduled_delta(&self, pose: &Pose) -> f64 {
        self.scene
            .damping
            .map_or(0.0, |d| d.delta_at_sigma(pose.sigma_min()))
    }

    /// Joint rates at `pose` for the commanded task velocity `xdot` into
    /// `out`: eq. (18) in modes `none`, `numerical` and Case 2, eq. (21) in
    /// Cases 1 and 3. Returns whether the exact damped `Phi` stood in for the
    /// network (the damping schedule is active: the pose is near-singular,
    /// where `Phi` is unbounded and no network fits it).
    ///
    /// A constant `delta` is applied in every mode; in Cases 1 and 3 to the
    /// network's `Phi` by [`ik::damp_phi`].
    pub(super) fn theta_dot(
        &self,
        pose: &Pose,
        xdot: [f64; 2],
        s: &mut Scratch,
        out: &mut [f64],
    ) -> Result<bool> {
        self.null_space(pose, s)?;
        let scheduled = self.scheduled_delta(pose);
        let delta = self.scene.delta + scheduled;
        let jac = pose.jacobian();
        if !self.mode.learned_phi() {
            ik::theta_dot_symmetric_into(jac, xdot, &s.v, delta, out)?;
            return Ok(false);
        }
        let handover = scheduled > 0.0;
        if handover {
            ik::phi_into(jac, delta, &mut s.phi)?;
        } else {
            self.nets()?.phi(pose, &mut s.phi)?;
            ik::damp_phi(&mut s.phi, self.scene.delta)?;
        }
        ik::theta_dot_network_into(&s.phi, jac, xdot, &s.v, out)?;
        Ok(handover)
    }
}
