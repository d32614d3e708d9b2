//! Gradient projection on a clearance potential in space (`distance`,
//! Liégeois 1977 with Khatib's FIRAS potential, 1986; the planar method's
//! module documentation): over the capsule pairs closer than the influence
//! distance `d_i` (the spheres', and the floor's where the scene has one;
//! [`crate::space::SpacePairs`]: distance `d`, normal `n`, point Jacobian
//! `J_Q`),
//!
//! `v = lambda_d sum (1/d - 1/d_i) / d^2 J_Q^T n`,
//!
//! `d` floored at the stop distance `d_s` (and at 1 mm), then eq. (18) with
//! `m = 3`, weighted by the scene's joint weighting as in the plane.

use super::super::distance::DISTANCE_GAIN;
use super::super::influence::{INFLUENCE, STOP_DISTANCE};
use super::super::paper::DELTA;
use super::super::Note;
use super::weighting::SpaceJointWeights;
use super::{SpaceContext, SpaceRule};
use crate::error::Result;
use crate::space::{SpacePairs, SpacePose};

/// The rule's scratch space: the pairs, one gradient row, `v` and the
/// joint weights (the scene's `weighting` reaches `distance`, as in the
/// plane).
#[derive(Clone)]
struct Distance {
    pairs: SpacePairs,
    row: Vec<f64>,
    v: Vec<f64>,
    weights: SpaceJointWeights,
}

/// The rule of `distance` for an `n`-joint chain.
pub(in crate::planner::methods) fn rule(n: usize) -> Box<dyn SpaceRule> {
    Box::new(Distance {
        pairs: SpacePairs::with_capacity(SpacePairs::most(n)),
        row: vec![0.0; n],
        v: vec![0.0; n],
        weights: SpaceJointWeights::new(n),
    })
}

impl SpaceRule for Distance {
    fn theta_dot(
        &mut self,
        cx: &SpaceContext<'_>,
        pose: &SpacePose,
        xdot: [f64; 3],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = cx.scene;
        let (influence, gain) = (s.param(&INFLUENCE), s.param(&DISTANCE_GAIN));
        self.pairs.update(&s.chain, pose, &s.spheres, influence);
        if s.floor {
            self.pairs.add_floor(&s.chain, pose, influence);
        }
        self.v.iter_mut().for_each(|x| *x = 0.0);
        let floor = s.param(&STOP_DISTANCE).max(1e-3);
        for pair in self.pairs.as_slice() {
            let d = pair.distance.max(floor);
            let coef = gain * (1.0 / d - 1.0 / influence) / (d * d);
            pair.gradient_into(pose, &mut self.row);
            for (vi, ri) in self.v.iter_mut().zip(&self.row) {
                *vi += coef * ri;
            }
        }
        let delta = s.param(&DELTA) + cx.scheduled_delta(pose);
        self.weights.eq18(cx, pose, xdot, &self.v, delta, out)?;
        Ok(Note::default())
    }

    fn boxed_clone(&self) -> Box<dyn SpaceRule> {
        Box::new(self.clone())
    }
}
