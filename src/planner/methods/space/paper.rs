//! The paper's rule in space: eq. (18) with the hand's `3 x n` Jacobian and
//! the obstacle vector of the criterion generalised to space
//! ([`crate::space::criterion`]), or none; the learned routes (Cases 1-3)
//! with the networks trained for the arm in space
//! ([`crate::networks::space`]). With the scene's joint
//! weighting, eq. (18) is weighted as in the plane (`super::weighting`).

use super::super::paper::{Phi, DELTA, LAMBDA, REFINE, SIGN_SMOOTHING, V};
use super::weighting::SpaceJointWeights;
use super::{SpaceContext, SpaceRule};
use crate::error::Result;
use crate::planner::methods::{Method, Note};
use crate::space::{criterion, phi, SpacePose};

/// The paper's rule for an arm in space, with its scratch space: `v`, one
/// sphere's learned gradient, the learned `Phi` (`n x 3`) and its
/// unweighted copy, and the weights.
#[derive(Debug, Clone)]
struct Paper {
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
pub(in crate::planner::methods) fn rule(
    n: usize,
    method: Method,
    v_from: V,
    phi_from: Phi,
) -> Box<dyn SpaceRule> {
    Box::new(Paper {
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

impl Paper {
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

impl SpaceRule for Paper {
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
