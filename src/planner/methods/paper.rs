//! The paper's five methods are one computation with two switches (its
//! section VI): where the obstacle vector `v` of eqs. (14)-(16) comes from
//! (nowhere, computed exactly, or the `v` network), and how `v` becomes
//! joint rates (eq. 18 with the exact `J`, or eq. 21 with `Phi` from the
//! `Phi` network). Each method's file names its switches; the rule is here.

use super::weighting::JointWeights;
use super::{Context, Method, Note, Rule};
use crate::error::Result;
use crate::model::{Model, Scene as _};
use crate::scene::{Param, Scale};
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
/// `J` (Cases 1 and 3, [`crate::ik::refine_phi`]); the paper's 0 uses the
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
    /// Eq. (18): the small symmetric solve with the exact `J`.
    Exact,
    /// Eq. (21): `Phi` from the `Phi` network.
    Network,
}

/// The rule of a paper's method, with its scratch space: `v`, one
/// obstacle's gradient, `Phi` (row-major `n x M`), the undamped `Phi` kept
/// for the joint weighting, and the weights.
#[derive(Debug, Clone)]
struct Paper {
    method: Method,
    v_from: V,
    phi_from: Phi,
    v: Vec<f64>,
    g: Vec<f64>,
    phi: Vec<f64>,
    phi0: Vec<f64>,
    weights: JointWeights,
}

/// The rule of `method` for an `n`-joint arm whose hand has `M`
/// coordinates: `v` from `v_from`, joint rates through `phi_from`.
pub(super) fn rule<A: Model<M>, const M: usize>(
    n: usize,
    method: Method,
    v_from: V,
    phi_from: Phi,
) -> Box<dyn Rule<A, M>> {
    Box::new(Paper {
        method,
        v_from,
        phi_from,
        v: vec![0.0; n],
        g: vec![0.0; n],
        phi: vec![0.0; M * n],
        phi0: vec![0.0; M * n],
        weights: JointWeights::new(n),
    })
}

/// `v` at `pose` into `v`: `(lambda / 4) sum_O sum_k sign(D_k) dD_k/dtheta`
/// (eqs. 14-15 summed over the obstacles; in space, the criterion
/// generalised to space, [`crate::space::criterion`]), each obstacle's
/// area gradient (into the scratch `g`) exact (its sign smoothed by the
/// scene's `sign_smoothing`) or from the `v` network of `method` (which
/// learned the gradient at the smoothing its weights file records).
pub(super) fn obstacle_vector<A: Model<M>, const M: usize>(
    method: Method,
    from: V,
    cx: &Context<'_, A, M>,
    pose: &A::Pose,
    g: &mut [f64],
    v: &mut [f64],
) -> Result<()> {
    let scene = cx.scene;
    match from {
        V::Zero => v.iter_mut().for_each(|x| *x = 0.0),
        V::Exact => A::obstacle_vector_into(
            scene,
            pose,
            scene.value(&LAMBDA),
            scene.value(&SIGN_SMOOTHING),
            g,
            v,
        ),
        V::Network => {
            let nets = cx.networks_for(method)?;
            v.iter_mut().for_each(|x| *x = 0.0);
            for o in A::obstacle_centres(scene) {
                nets.area_gradient(pose, o, g)?;
                for (vi, gi) in v.iter_mut().zip(g.iter()) {
                    *vi += gi;
                }
            }
            let scale = scene.value(&LAMBDA) / 4.0;
            v.iter_mut().for_each(|x| *x *= scale);
        }
    }
    Ok(())
}

impl<A: Model<M>, const M: usize> Rule<A, M> for Paper {
    /// Eq. (18), `(J J^T + delta I) varphi = Xdot - J v`,
    /// `theta_dot = J^T varphi + v`, or eq. (21),
    /// `theta_dot = Phi (Xdot - J v) + v` with `Phi` from the network,
    /// refined toward the pseudoinverse by the scene's `refine`
    /// Newton-Schulz steps with the pose's `J` and the projection
    /// `Phi <- J^T (Phi^T Phi)` after the first ([`crate::ik::refine_phi`])
    /// and damped by a constant `delta` ([`crate::ik::damp_phi`]). Where the
    /// damping schedule is active (a near-singular pose, where `Phi` is
    /// unbounded and no network fits it), or where the refinement is not
    /// sure to converge from the network's `Phi`, the exact damped `Phi` of
    /// eq. (20) stands in for the network, and the note says so. With the
    /// scene's joint weighting (`super::weighting`), eq. (18) becomes its
    /// weighted form and the network's `Phi` is weighted
    /// ([`crate::ik::weight_phi`]; the stand-in by the weighted eq. 20)
    /// where a joint moves toward a limit.
    fn theta_dot(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        xdot: [f64; M],
        out: &mut [f64],
    ) -> Result<Note> {
        obstacle_vector(self.method, self.v_from, cx, pose, &mut self.g, &mut self.v)?;
        let scheduled = cx.scheduled_delta(pose);
        let jac = A::jacobian(pose);
        let delta = cx.scene.value(&DELTA);
        if self.phi_from == Phi::Exact {
            self.weights
                .eq18(cx, pose, xdot, &self.v, delta + scheduled, out)?;
            return Ok(Note::default());
        }
        let mut handover = scheduled > 0.0;
        let weighted = JointWeights::active(cx);
        if !handover {
            cx.networks_for(self.method)?.phi(pose, &mut self.phi)?;
            let steps = cx.scene.params().count(&REFINE);
            handover = !A::refine_phi(&mut self.phi, jac, steps)?;
        }
        if handover {
            A::phi_into(jac, None, delta + scheduled, &mut self.phi)?;
        } else {
            if weighted {
                self.phi0.copy_from_slice(&self.phi);
            }
            A::damp_phi(&mut self.phi, delta)?;
        }
        A::eq21(&self.phi, jac, None, xdot, &self.v, out)?;
        let mut again = weighted && self.weights.update(cx, pose, out);
        // At most n + 1 solves (JointWeights::widen).
        for _ in 0..=out.len() {
            if !again {
                break;
            }
            let winv = self.weights.inverse();
            if handover {
                A::phi_into(jac, Some(winv), delta + scheduled, &mut self.phi)?;
            } else {
                self.phi.copy_from_slice(&self.phi0);
                A::weight_phi(&mut self.phi, jac, winv, delta)?;
            }
            A::eq21(&self.phi, jac, Some(winv), xdot, &self.v, out)?;
            again = self.weights.widen(out);
        }
        Ok(Note {
            handover,
            ..Note::default()
        })
    }

    fn null_space(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        v: &mut [f64],
    ) -> Result<bool> {
        obstacle_vector(self.method, self.v_from, cx, pose, &mut self.g, v)?;
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule<A, M>> {
        Box::new(self.clone())
    }
}
