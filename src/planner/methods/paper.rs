//! The paper's five methods are one computation with two switches (its
//! section VI): where the obstacle vector `v` of eqs. (14)-(16) comes from
//! (nowhere, computed exactly, or the `v` network), and how `v` becomes
//! joint rates (eq. 18 with the exact `J`, or eq. 21 with `Phi` from the
//! `Phi` network). Each method's file names its switches; the rule is here.

use super::space::{SpaceContext, SpaceRule};
use super::weighting::JointWeights;
use super::weighting::SpaceJointWeights;
use super::{Context, Method, Note, Rule};
use crate::error::Result;
use crate::ik;
use crate::kinematics::Pose;
use crate::obstacle;
use crate::scene::{Param, Scale};
use crate::space::{criterion, phi, SpacePose};

/// Gain `lambda` of the obstacle vector, eq. (14) (`v` is scaled by
/// `lambda / 4`; the paper's runs use 4). At most 250 times the paper's:
/// far larger gains only make the first RK4 step overflow (`lambda =
/// 1e308` did, found by the hostile-URL test).
pub static LAMBDA: Param = Param {
    name: "lambda",
    flag: "--lambda",
    label: "Obstacle gain λ",
    what: "lambda",
    #[cfg(feature = "cli")]
    help: "Gain lambda of the obstacle vector, eq. (14)",
    unit: "",
    bounds: (0.0, 1000.0),
    default: 4.0,
    slider: (0.0, 12.0, 0.5),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// Constant damping `delta` (m^2) of eqs. (6), (17), (20); the paper's 0.
/// With `J J^T` of order 1 m^2, 1000 already stops the arm.
pub static DELTA: Param = Param {
    name: "delta",
    flag: "--delta",
    label: "Damping δ",
    what: "damping factor delta",
    #[cfg(feature = "cli")]
    help: "Constant damping factor delta, eqs. (6), (17), (20)",
    unit: "m²",
    bounds: (0.0, 1000.0),
    default: 0.0,
    slider: (0.0, 0.05, 0.001),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// The smoothing `eps` (m^2) of the sign in eq. (15)
/// ([`crate::obstacle::smoothed_sign`]); the paper's 0 leaves the sign as
/// it is. The paper's arm's triangles have `|D| < 4 m^2`, so beyond 100
/// the criterion is flat everywhere.
pub static SIGN_SMOOTHING: Param = Param {
    name: "sign_smoothing",
    flag: "--sign-smoothing",
    label: "Sign smoothing ε",
    what: "sign smoothing eps",
    #[cfg(feature = "cli")]
    help: "Smoothing eps of the sign in eq. (15) of the exact obstacle vector (numerical, Case 1)",
    unit: "m²",
    bounds: (0.0, 100.0),
    default: 0.0,
    slider: (0.0, 0.3, 0.01),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// Newton-Schulz steps `Phi <- Phi (2I - J Phi)` that refine a learned
/// `Phi` toward the pseudoinverse of eq. (20) (`delta = 0`) with the pose's
/// `J` (Cases 1 and 3, [`ik::refine_phi`]); the paper's 0 uses the
/// network's `Phi` as it is. Right after the first step, and not counted
/// as one, the projection `Phi <- J^T (Phi^T Phi)` puts `Phi` in the range
/// of `J^T`: `J+` is its fixed point, so the steps converge to `J+` itself
/// and the null-space projector `I - Phi J` becomes the orthogonal one
/// (without it they converge to a right inverse with the network's range,
/// whose projector stays oblique). After the first step and the projection
/// the error `J Phi - I` is of the order of the network's error squared,
/// and each further step squares it, so from a network error of 0.1 the
/// error is at rounding after 5 and further steps change nothing a run
/// can see; where the network is far from any inverse the steps diverge
/// and the run stops with an error.
pub static REFINE: Param = Param {
    name: "refine",
    flag: "--refine",
    label: "Refinement steps",
    what: "refinement steps",
    #[cfg(feature = "cli")]
    help: "Newton-Schulz steps refining the learned Phi with the pose's J (Cases 1 and 3)",
    unit: "",
    bounds: (0.0, 8.0),
    default: 0.0,
    slider: (0.0, 4.0, 1.0),
    scale: Scale::Linear,
    count: true,
    below: None,
    above: None,
};

/// Where `v` comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum V {
    /// `v = 0`: no avoidance.
    Zero,
    /// Eqs. (14)-(16), computed exactly.
    Exact,
    /// The area gradient from the `v` network.
    Network,
}

/// Where `Phi` comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Phi {
    /// Eq. (18): the symmetric 2x2 solve with the exact `J`.
    Exact,
    /// Eq. (21): `Phi` from the `Phi` network.
    Network,
}

/// The rule of a paper's method, with its scratch space: `v`, one
/// obstacle's gradient, `Phi` (row-major `n x 2`), the undamped `Phi` kept
/// for the joint weighting, and the weights.
#[derive(Debug, Clone)]
pub(super) struct Paper {
    method: Method,
    v_from: V,
    phi_from: Phi,
    v: Vec<f64>,
    g: Vec<f64>,
    phi: Vec<f64>,
    phi0: Vec<f64>,
    weights: JointWeights,
}

/// The rule of `method` for an `n`-joint arm: `v` from `v_from`, joint
/// rates through `phi_from`.
pub(super) fn rule(n: usize, method: Method, v_from: V, phi_from: Phi) -> Box<dyn Rule> {
    Box::new(Paper {
        method,
        v_from,
        phi_from,
        v: vec![0.0; n],
        g: vec![0.0; n],
        phi: vec![0.0; 2 * n],
        phi0: vec![0.0; 2 * n],
        weights: JointWeights::new(n),
    })
}

/// `v` at `pose` into `v`: `(lambda / 4) sum_O sum_k sign(D_k) dD_k/dtheta`
/// (eqs. 14-15 summed over the obstacles), each obstacle's area gradient
/// (into the scratch `g`) exact (its sign smoothed by the scene's
/// `sign_smoothing`) or from the `v` network of `method` (which learned the
/// gradient at the smoothing its weights file records).
pub(super) fn obstacle_vector(
    method: Method,
    from: V,
    cx: &Context<'_>,
    pose: &Pose,
    g: &mut [f64],
    v: &mut [f64],
) -> Result<()> {
    let scene = cx.scene;
    match from {
        V::Zero => v.iter_mut().for_each(|x| *x = 0.0),
        V::Exact => obstacle::null_space_vector_into(
            &scene.arm,
            pose,
            &scene.obstacles,
            scene.param(&LAMBDA),
            scene.param(&SIGN_SMOOTHING),
            g,
            v,
        ),
        V::Network => {
            let nets = cx.networks_for(method)?;
            v.iter_mut().for_each(|x| *x = 0.0);
            for ob in &scene.obstacles {
                nets.area_gradient(pose, ob.centre, g)?;
                for (vi, gi) in v.iter_mut().zip(g.iter()) {
                    *vi += gi;
                }
            }
            let scale = scene.param(&LAMBDA) / 4.0;
            v.iter_mut().for_each(|x| *x *= scale);
        }
    }
    Ok(())
}

impl Rule for Paper {
    /// Eq. (18), `(J J^T + delta I) varphi = Xdot - J v`,
    /// `theta_dot = J^T varphi + v`, or eq. (21),
    /// `theta_dot = Phi (Xdot - J v) + v` with `Phi` from the network,
    /// refined toward the pseudoinverse by the scene's `refine`
    /// Newton-Schulz steps with the pose's `J` and the projection
    /// `Phi <- J^T (Phi^T Phi)` after the first ([`ik::refine_phi`]) and
    /// damped by a constant `delta` through
    /// [`ik::damp_phi`]. Where the damping
    /// schedule is active (a near-singular pose, where `Phi` is unbounded and
    /// no network fits it), the exact damped `Phi` of eq. (20) stands in for
    /// the network, and the note says so. With the scene's joint weighting
    /// (`super::weighting`), eq. (18) becomes its weighted form and the
    /// network's `Phi` is weighted by [`ik::weight_phi`] (the stand-in by
    /// [`ik::phi_weighted_into`]) where a joint moves toward a limit.
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        let Self {
            method,
            v_from,
            v,
            g,
            ..
        } = self;
        obstacle_vector(*method, *v_from, cx, pose, g, v)?;
        let scheduled = cx.scheduled_delta(pose);
        let jac = pose.jacobian();
        let delta = cx.scene.param(&DELTA);
        match self.phi_from {
            Phi::Exact => {
                self.weights
                    .eq18(cx, pose, xdot, &self.v, delta + scheduled, out)?;
                Ok(Note::default())
            }
            Phi::Network => {
                // The exact route stands in for the network where the
                // damping schedule is on, and where the refinement cannot
                // converge (|I - J Phi| >= 1: ik::refine_phi), as in space.
                let mut handover = scheduled > 0.0;
                let weighted = JointWeights::active(cx.scene);
                if !handover {
                    cx.networks_for(self.method)?.phi(pose, &mut self.phi)?;
                    handover = !ik::refine_phi(&mut self.phi, jac, cx.scene.params.count(&REFINE))?;
                }
                if handover {
                    ik::phi_into(jac, delta + scheduled, &mut self.phi)?;
                } else {
                    if weighted {
                        self.phi0.copy_from_slice(&self.phi);
                    }
                    ik::damp_phi(&mut self.phi, delta)?;
                }
                ik::theta_dot_network_into(&self.phi, jac, xdot, &self.v, out)?;
                let mut again = weighted && self.weights.update(cx.scene, pose, out);
                // At most n + 1 solves (JointWeights::widen).
                for _ in 0..=out.len() {
                    if !again {
                        break;
                    }
                    let winv = self.weights.inverse();
                    if handover {
                        ik::phi_weighted_into(jac, winv, delta + scheduled, &mut self.phi)?;
                    } else {
                        self.phi.copy_from_slice(&self.phi0);
                        ik::weight_phi(&mut self.phi, jac, winv, delta)?;
                    }
                    ik::theta_dot_network_weighted_into(&self.phi, jac, winv, xdot, &self.v, out)?;
                    again = self.weights.widen(out);
                }
                Ok(Note {
                    handover,
                    ..Note::default()
                })
            }
        }
    }

    fn null_space(&mut self, cx: &Context<'_>, pose: &Pose, v: &mut [f64]) -> Result<bool> {
        obstacle_vector(self.method, self.v_from, cx, pose, &mut self.g, v)?;
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}

// ---- In space ----------------------------------------------------------
//
// The paper's rule in space: eq. (18) with the hand's `3 x n` Jacobian and
// the obstacle vector of the criterion generalised to space
// ([`crate::space::criterion`]), or none; the learned routes (Cases 1-3)
// with the networks trained for the arm in space
// ([`crate::networks::space`]). With the scene's joint
// weighting, eq. (18) is weighted as in the plane (`super::weighting`).

/// The paper's rule for an arm in space, with its scratch space: `v`, one
/// sphere's learned gradient, the learned `Phi` (`n x 3`) and its
/// unweighted copy, and the weights.
#[derive(Debug, Clone)]
struct PaperInSpace {
    method: Method,
    v_from: V,
    phi_from: Phi,
    v: Vec<f64>,
    g: Vec<f64>,
    phi: Vec<f64>,
    phi0: Vec<f64>,
    weights: SpaceJointWeights,
}

/// The rule of `method` for an `n`-joint chain: `v` from `v_from`, joint
/// rates through `phi_from`.
pub(in crate::planner::methods) fn space_rule(
    n: usize,
    method: Method,
    v_from: V,
    phi_from: Phi,
) -> Box<dyn SpaceRule> {
    Box::new(PaperInSpace {
        method,
        v_from,
        phi_from,
        v: vec![0.0; n],
        g: vec![0.0; n],
        phi: vec![0.0; 3 * n],
        phi0: vec![0.0; 3 * n],
        weights: SpaceJointWeights::new(n),
    })
}

impl PaperInSpace {
    /// `v` at `pose`: zero, the criterion's exact gradient, or the `v`
    /// network's summed over the spheres, times `lambda / 4`.
    fn obstacle_vector(&mut self, cx: &SpaceContext<'_>, pose: &SpacePose) -> Result<()> {
        let scene = cx.scene;
        match self.v_from {
            V::Zero => self.v.iter_mut().for_each(|x| *x = 0.0),
            V::Exact => criterion::null_space_vector_into(
                &scene.chain,
                pose,
                scene.spheres.iter().map(|s| s.centre),
                scene.param(&LAMBDA),
                scene.param(&SIGN_SMOOTHING),
                &mut self.v,
            ),
            V::Network => {
                let nets = cx.networks_for(self.method)?;
                self.v.iter_mut().for_each(|x| *x = 0.0);
                for s in &scene.spheres {
                    nets.area_gradient(pose, s.centre, &mut self.g)?;
                    for (vi, gi) in self.v.iter_mut().zip(&self.g) {
                        *vi += gi;
                    }
                }
                let scale = scene.param(&LAMBDA) / 4.0;
                self.v.iter_mut().for_each(|x| *x *= scale);
            }
        }
        Ok(())
    }
}

impl SpaceRule for PaperInSpace {
    /// Eq. (18) with the exact `J`, or eq. (21) with the `Phi` network's
    /// output refined by the scene's `refine` steps ([`phi::refine_phi`]),
    /// damped by a constant `delta` ([`phi::damp_phi`]) and, with the joint
    /// weighting, weighted where a joint moves toward a limit
    /// ([`phi::weight_phi`]). Where the damping schedule is active (a
    /// near-singular pose, which no network fits), or where the refinement
    /// is not sure to converge from the network's `Phi`, the exact damped
    /// route stands in for the network, and the note says so (the run
    /// counts those steps as handovers).
    fn theta_dot(
        &mut self,
        cx: &SpaceContext<'_>,
        pose: &SpacePose,
        xdot: [f64; 3],
        out: &mut [f64],
    ) -> Result<Note> {
        self.obstacle_vector(cx, pose)?;
        let scene = cx.scene;
        let delta = scene.param(&DELTA);
        let scheduled = cx.scheduled_delta(pose);
        let jac = pose.jacobian();
        let learned = self.phi_from == Phi::Network && scheduled == 0.0 && {
            cx.networks_for(self.method)?.phi(pose, &mut self.phi)?;
            phi::refine_phi(&mut self.phi, jac, scene.params.count(&REFINE))?
        };
        if !learned {
            self.weights
                .eq18(cx, pose, xdot, &self.v, delta + scheduled, out)?;
            return Ok(Note {
                handover: self.phi_from == Phi::Network,
                ..Note::default()
            });
        }
        let weighted = SpaceJointWeights::active(scene);
        if weighted {
            self.phi0.copy_from_slice(&self.phi);
        }
        phi::damp_phi(&mut self.phi, delta)?;
        phi::theta_dot(&self.phi, jac, None, xdot, &self.v, out)?;
        let mut again = weighted && self.weights.update(scene, pose, out);
        // At most n + 1 solves, as in the plane.
        for _ in 0..=out.len() {
            if !again {
                break;
            }
            self.phi.copy_from_slice(&self.phi0);
            let winv = self.weights.inverse();
            phi::weight_phi(&mut self.phi, jac, winv, delta)?;
            phi::theta_dot(&self.phi, jac, Some(winv), xdot, &self.v, out)?;
            again = self.weights.widen(out);
        }
        Ok(Note::default())
    }

    fn boxed_clone(&self) -> Box<dyn SpaceRule> {
        Box::new(self.clone())
    }
}
