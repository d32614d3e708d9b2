//! Gradient projection on a clearance potential (Liégeois 1977, with
//! Khatib's FIRAS potential, 1986): the paper's eq. (5) with another
//! null-space vector. For every link-obstacle pair closer than the
//! influence distance `d_i` (clearance `c`, normal `n`, point Jacobian
//! `J_p`; [`crate::clearance`]),
//!
//! `U = sum (1/2) (1/c - 1/d_i)^2`, `v = -lambda_d grad U
//!    = lambda_d sum (1/c - 1/d_i) / c^2 J_p^T n`,
//!
//! then eq. (18), `theta_dot = J^T (J J^T + delta I)^-1 (Xdot - J v) + v`.
//! The potential is unbounded at contact: `c` is floored at the stop
//! distance `d_s` (and at 1 mm), so a link that touches or enters a disc
//! gets a large but finite push out. In space the pairs are the moving
//! capsules' with the spheres and the floor ([`crate::space::SpacePairs`]):
//! one rule for every arm, over its model's pairs.

use super::influence::{INFLUENCE, STOP_DISTANCE};
use super::paper::DELTA;
use super::weighting::JointWeights;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::arm::Arm;
use crate::error::Result;
use crate::model::{Clearance, Model, Scene as _};
use crate::scene::{Param, Scale};
use crate::space::{Chain, PoseChain};

/// Gain `lambda_d` of the clearance potential, chosen on the atlas
/// (`docs/methods.md`).
pub static DISTANCE_GAIN: Param = Param {
    name: "distance_gain",
    flag: "--distance-gain",
    label: "Distance gain λd",
    what: "distance gain lambda_d",
    #[cfg(feature = "cli")]
    help: "Gain lambda_d of the clearance potential (distance)",
    unit: "",
    bounds: (0.0, 1000.0),
    default: 1e-3,
    slider: (0.0, 0.01, 1e-4),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// Gradient projection on the clearance potential (`distance`).
pub const DISTANCE: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "distance",
        label: "Distance gradient",
        description: "v pushes each close link away from the obstacle (FIRAS potential), eq. (5)",
        group: Group::Beyond,
        paper_figures: None,
        networks: Needs::NOTHING,
        avoids: true,
        weighting: true,
        limits: false,
        colour: "#9467bd",
        params: &[&DISTANCE_GAIN, &INFLUENCE, &STOP_DISTANCE, &DELTA],
    },
    rule: rule::<Arm, 2>,
    space: Some(rule::<Chain, 3>),
    pose: Some(rule::<PoseChain, 6>),
};

/// The rule's scratch space: the pairs, one gradient row, `v` and the
/// joint weights.
#[derive(Clone)]
struct Distance<A: Model<M>, const M: usize> {
    pairs: A::Pairs,
    row: Vec<f64>,
    v: Vec<f64>,
    weights: JointWeights,
}

/// The rule of `distance` for an `n`-joint arm.
fn rule<A: Model<M>, const M: usize>(n: usize) -> Box<dyn Rule<A, M>> {
    Box::new(Distance::<A, M> {
        pairs: A::pairs(n),
        row: vec![0.0; n],
        v: vec![0.0; n],
        weights: JointWeights::new(n),
    })
}

/// `v = lambda_d sum (1/c - 1/d_i) / c^2 J_p^T n` over the pairs closer
/// than `d_i` (see the module documentation) into `v`; `pairs` and `row`
/// are scratch.
fn potential_gradient<A: Model<M>, const M: usize>(
    cx: &Context<'_, A, M>,
    pose: &A::Pose,
    pairs: &mut A::Pairs,
    row: &mut [f64],
    v: &mut [f64],
) {
    let s = cx.scene;
    let (influence, gain) = (s.value(&INFLUENCE), s.value(&DISTANCE_GAIN));
    A::update_pairs(s, pose, influence, pairs);
    v.iter_mut().for_each(|x| *x = 0.0);
    let floor = s.value(&STOP_DISTANCE).max(1e-3);
    for pair in A::pair_list(pairs) {
        let c = pair.clearance().max(floor);
        let coef = gain * (1.0 / c - 1.0 / influence) / (c * c);
        pair.row_into(pose, row);
        for (vi, ri) in v.iter_mut().zip(row.iter()) {
            *vi += coef * ri;
        }
    }
}

impl<A: Model<M>, const M: usize> Rule<A, M> for Distance<A, M> {
    fn theta_dot(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        xdot: [f64; M],
        out: &mut [f64],
    ) -> Result<Note> {
        potential_gradient(cx, pose, &mut self.pairs, &mut self.row, &mut self.v);
        let delta = cx.scene.value(&DELTA) + cx.scheduled_delta(pose);
        self.weights.eq18(cx, pose, xdot, &self.v, delta, out)?;
        Ok(Note::default())
    }

    fn null_space(&mut self, cx: &Context<'_, A, M>, pose: &A::Pose, v: &mut [f64]) -> Result<bool> {
        potential_gradient(cx, pose, &mut self.pairs, &mut self.row, v);
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule<A, M>> {
        Box::new(self.clone())
    }
}
