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
//! gets a large but finite push out.

use crate::space::Chain;
use super::influence::{INFLUENCE, STOP_DISTANCE};
use super::paper::DELTA;
use super::weighting::JointWeights;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::clearance::Pairs;
use crate::error::Result;
use crate::kinematics::Pose;
use crate::scene::{Param, Scale};
use crate::space::{SpacePairs, SpacePose};

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
    rule: |n| {
        Box::new(Distance {
            pairs: Pairs::with_capacity(8 * n),
            row: vec![0.0; n],
            v: vec![0.0; n],
            weights: JointWeights::new(n),
        })
    },
    space: Some(space_rule),
};

#[derive(Clone)]
struct Distance {
    pairs: Pairs,
    row: Vec<f64>,
    v: Vec<f64>,
    weights: JointWeights,
}

/// `v = lambda_d sum (1/c - 1/d_i) / c^2 J_p^T n` over the pairs closer than
/// `d_i` (see the module documentation).
fn potential_gradient(
    cx: &Context<'_>,
    pose: &Pose,
    pairs: &mut Pairs,
    row: &mut [f64],
    v: &mut [f64],
) {
    let s = cx.scene;
    let (influence, gain) = (s.param(&INFLUENCE), s.param(&DISTANCE_GAIN));
    pairs.update(pose, &s.obstacles, influence);
    if let Some(post) = s.ground() {
        pairs.add_ground(pose, post, influence);
    }
    v.iter_mut().for_each(|x| *x = 0.0);
    let floor = s.param(&STOP_DISTANCE).max(1e-3);
    for pair in pairs.as_slice() {
        let c = pair.clearance.max(floor);
        let coef = gain * (1.0 / c - 1.0 / influence) / (c * c);
        pair.rate_row(pose, row);
        for (vi, ri) in v.iter_mut().zip(row.iter()) {
            *vi += coef * ri;
        }
    }
}

impl Rule for Distance {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        potential_gradient(cx, pose, &mut self.pairs, &mut self.row, &mut self.v);
        let delta = cx.scene.param(&DELTA) + cx.scheduled_delta(pose);
        self.weights.eq18(cx, pose, xdot, &self.v, delta, out)?;
        Ok(Note::default())
    }

    fn null_space(&mut self, cx: &Context<'_>, pose: &Pose, v: &mut [f64]) -> Result<bool> {
        potential_gradient(cx, pose, &mut self.pairs, &mut self.row, v);
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}

// ---- In space ----------------------------------------------------------
//
// Gradient projection on a clearance potential in space (`distance`,
// Liégeois 1977 with Khatib's FIRAS potential, 1986; the planar method's
// module documentation): over the capsule pairs closer than the influence
// distance `d_i` (the spheres', and the floor's where the scene has one;
// [`crate::space::SpacePairs`]: distance `d`, normal `n`, point Jacobian
// `J_Q`),
//
// `v = lambda_d sum (1/d - 1/d_i) / d^2 J_Q^T n`,
//
// `d` floored at the stop distance `d_s` (and at 1 mm), then eq. (18) with
// `m = 3`, weighted by the scene's joint weighting as in the plane.

/// The rule's scratch space: the pairs, one gradient row, `v` and the
/// joint weights (the scene's `weighting` reaches `distance`, as in the
/// plane).
#[derive(Clone)]
struct DistanceInSpace {
    pairs: SpacePairs,
    row: Vec<f64>,
    v: Vec<f64>,
    weights: JointWeights,
}

/// The rule of `distance` for an `n`-joint chain.
pub(in crate::planner::methods) fn space_rule(n: usize) -> Box<dyn Rule<Chain, 3>> {
    Box::new(DistanceInSpace {
        pairs: SpacePairs::with_capacity(SpacePairs::most(n)),
        row: vec![0.0; n],
        v: vec![0.0; n],
        weights: JointWeights::new(n),
    })
}

impl Rule<Chain, 3> for DistanceInSpace {
    fn theta_dot(
        &mut self,
        cx: &Context<'_, Chain, 3>,
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

    fn boxed_clone(&self) -> Box<dyn Rule<Chain, 3>> {
        Box::new(self.clone())
    }
}
