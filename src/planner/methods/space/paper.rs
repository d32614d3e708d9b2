//! The paper's rule in space: eq. (18) with the hand's `3 x n` Jacobian and
//! the obstacle vector of the criterion generalised to space
//! ([`crate::space::criterion`]), or none. The learned routes (Cases 1-3)
//! need networks trained for the arm in space. With the scene's joint
//! weighting, eq. (18) is weighted as in the plane (`super::weighting`).

use super::super::paper::{DELTA, LAMBDA, SIGN_SMOOTHING, V};
use super::weighting::SpaceJointWeights;
use super::{SpaceContext, SpaceRule};
use crate::error::{Error, Result};
use crate::planner::methods::{Method, Note};
use crate::space::{criterion, SpacePose};

/// The paper's rule for an arm in space, with its scratch `v`.
#[derive(Debug, Clone)]
struct Paper {
    method: Method,
    v_from: V,
    v: Vec<f64>,
    weights: SpaceJointWeights,
}

/// The rule of `method` for an `n`-joint chain, `v` from `v_from`.
pub(in crate::planner::methods) fn rule(n: usize, method: Method, v_from: V) -> Box<dyn SpaceRule> {
    Box::new(Paper {
        method,
        v_from,
        v: vec![0.0; n],
        weights: SpaceJointWeights::new(n),
    })
}

impl SpaceRule for Paper {
    fn theta_dot(
        &mut self,
        cx: &SpaceContext<'_>,
        pose: &SpacePose,
        xdot: [f64; 3],
        out: &mut [f64],
    ) -> Result<Note> {
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
                return Err(Error::NetworksUnavailable(format!(
                    "method {} needs networks trained for this arm in space",
                    self.method
                )))
            }
        }
        let delta = scene.param(&DELTA) + cx.scheduled_delta(pose);
        self.weights.eq18(cx, pose, xdot, &self.v, delta, out)?;
        Ok(Note::default())
    }

    fn boxed_clone(&self) -> Box<dyn SpaceRule> {
        Box::new(self.clone())
    }
}
