//! The velocity damper (Faverjon and Tournassoud 1987; NEO, Haviland and
//! Corke 2021; the collision-avoidance limit of mink and dm_robotics): for
//! every link-obstacle pair closer than the influence distance `d_i`
//! ([`crate::clearance`]: clearance `c`, unit normal `n`, point Jacobian
//! `J_p`), the clearance may shrink no faster than
//!
//! `n^T J_p theta_dot >= -xi (c - d_s) / (d_i - d_s)`
//!
//! with the damper gain `xi` (the approach speed allowed at `d_i`) and the
//! stop distance `d_s`: at `c = d_s` the link may not approach at all, and
//! below `d_s` it must move away. As rows `G theta_dot <= h`:
//! `G = -n^T J_p`, `h = xi (c - d_s) / (d_i - d_s)`, one per pair, obstacle
//! by obstacle, each from the first link.
//!
//! In space the pairs are a moving capsule and a sphere, or the floor
//! `z = 0` where the scene has one ([`crate::space::SpacePairs`]: signed
//! surface distance `d`, normal `n`, point Jacobian `J_Q`), with the same
//! bound: one constraint for every arm, over its model's pairs.
//!
//! A pair of two capsules of the chain (self-collision, NEO's
//! `n^T (J_a - J_b) theta_dot` row, [`crate::space::self_pairs`]) has its
//! own influence distance, stop distance and gain ([`SELF_INFLUENCE`],
//! [`SELF_STOP_DISTANCE`], [`SELF_DAMPER_GAIN`]): links sit close to each
//! other by design, and a user may want them held at another distance
//! than the obstacles.

use super::{Constraint, ConstraintInfo, Entry, Rows};
use crate::arm::Arm;
use crate::error::Result;
use crate::model::{Clearance, Model, Scene as _};
use crate::planner::methods::Context;
use crate::space::{Chain, PoseChain};
use crate::planner::methods::{INFLUENCE, STOP_DISTANCE};
use crate::scene::{Param, Params, Scale};

/// The velocity dampers (`damper`).
pub static DAMPER: Entry = Entry {
    info: ConstraintInfo {
        name: "damper",
        label: "velocity damper",
        description: "n^T J_p θ̇ ≥ −ξ (c − d_s) / (d_i − d_s) for every link-obstacle pair with c < d_i (link-link pairs with their own d_i, d_s, ξ)",
        params: PARAMS,
    },
    build: build::<Arm, 2>,
    space: build::<Chain, 3>,
    pose: build::<PoseChain, 6>,
};

/// Damper gain `xi` (m/s): how fast a link may approach an obstacle at the
/// influence distance (NEO's order of magnitude).
pub static DAMPER_GAIN: Param = Param {
    name: "damper_gain",
    flag: "--damper-gain",
    label: "Damper gain ξ",
    what: "damper gain xi",
    #[cfg(feature = "cli")]
    help: "Damper gain xi: the approach speed allowed at d_i (qp)",
    unit: "m/s",
    bounds: (1e-3, 100.0),
    default: 1.0,
    slider: (0.1, 5.0, 0.1),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// Influence distance (m) of the dampers between two links of the chain
/// (self-collision): link-link pairs closer than this get a row. The
/// obstacles' default.
pub static SELF_INFLUENCE: Param = Param {
    name: "self_influence",
    flag: "--self-influence",
    label: "Self influence dᵢ",
    what: "self-collision influence distance",
    #[cfg(feature = "cli")]
    help: "Influence distance of qp's link-link dampers (self-collision): pairs of links closer than this get a row",
    unit: "m",
    bounds: (1e-3, 100.0),
    default: 0.3,
    slider: (0.02, 0.5, 0.01),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: Some(&SELF_STOP_DISTANCE),
};

/// Stop distance (m) of the dampers between two links of the chain: the
/// clearance they keep between links. Below [`SELF_INFLUENCE`].
pub static SELF_STOP_DISTANCE: Param = Param {
    name: "self_stop_distance",
    flag: "--self-stop-distance",
    label: "Self stop distance dₛ",
    what: "self-collision stop distance",
    #[cfg(feature = "cli")]
    help: "Stop distance of qp's link-link dampers (self-collision): the clearance kept between two links",
    unit: "m",
    bounds: (0.0, 100.0),
    default: 0.02,
    slider: (0.0, 0.1, 0.005),
    scale: Scale::Linear,
    count: false,
    below: Some(&SELF_INFLUENCE),
    above: None,
};

/// Damper gain (m/s) between two links of the chain: how fast two links
/// may approach at [`SELF_INFLUENCE`].
pub static SELF_DAMPER_GAIN: Param = Param {
    name: "self_damper_gain",
    flag: "--self-damper-gain",
    label: "Self damper gain ξ",
    what: "self-collision damper gain",
    #[cfg(feature = "cli")]
    help: "Damper gain of qp's link-link dampers (self-collision): the approach speed allowed at their influence distance",
    unit: "m/s",
    bounds: (1e-3, 100.0),
    default: 1.0,
    slider: (0.1, 5.0, 0.1),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// The scene's parameters the dampers read: [`Gains::of`] reads them.
const PARAMS: &[&Param] = &[
    &INFLUENCE,
    &STOP_DISTANCE,
    &DAMPER_GAIN,
    &SELF_INFLUENCE,
    &SELF_STOP_DISTANCE,
    &SELF_DAMPER_GAIN,
];

/// One kind of pair's damper parameters, read from the scene in one
/// place.
struct Gains {
    /// The influence distance `d_i` (m).
    influence: f64,
    /// The stop distance `d_s` (m).
    stop: f64,
    /// The damper gain `xi` (m/s).
    gain: f64,
}

impl Gains {
    /// The link-obstacle and the link-link parameters of [`PARAMS`] in a
    /// scene's `params`.
    fn of(params: &Params) -> [Self; 2] {
        [
            Self {
                influence: params.get(&INFLUENCE),
                stop: params.get(&STOP_DISTANCE),
                gain: params.get(&DAMPER_GAIN),
            },
            Self {
                influence: params.get(&SELF_INFLUENCE),
                stop: params.get(&SELF_STOP_DISTANCE),
                gain: params.get(&SELF_DAMPER_GAIN),
            },
        ]
    }

    /// The damper's bound `h = xi (c - d_s) / (d_i - d_s)` at clearance `c`.
    #[inline]
    fn bound(&self, clearance: f64) -> f64 {
        self.gain * (clearance - self.stop) / (self.influence - self.stop)
    }
}

/// The pairs of a pose within the influence distance, kept between poses
/// (grown once when more pairs appear than ever before).
#[derive(Clone)]
struct Damper<A: Model<M>, const M: usize> {
    pairs: A::Pairs,
}

/// The dampers of an `n`-joint arm.
fn build<A: Model<M>, const M: usize>(n: usize) -> Box<dyn Constraint<A, M>> {
    Box::new(Damper::<A, M> { pairs: A::pairs(n) })
}

impl<A: Model<M>, const M: usize> Constraint<A, M> for Damper<A, M> {
    fn rows(&mut self, cx: &Context<'_, A, M>, pose: &A::Pose, rows: &mut Rows) -> Result<()> {
        let [obstacle, link] = Gains::of(cx.scene.params());
        let within = obstacle.influence.max(link.influence);
        A::update_pairs(cx.scene, pose, within, &mut self.pairs);
        for pair in A::pair_list(&self.pairs) {
            let gains = if pair.is_self() { &link } else { &obstacle };
            if pair.clearance() >= gains.influence {
                continue;
            }
            let row = rows.push(gains.bound(pair.clearance()));
            pair.row_into(pose, row);
            row.iter_mut().for_each(|g| *g = -*g);
        }
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Constraint<A, M>> {
        Box::new(self.clone())
    }

    fn info(&self) -> &'static ConstraintInfo {
        &DAMPER.info
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Pose;
    use crate::obstacle::Obstacle;
    use crate::scene::Scene;

    #[test]
    fn a_pair_within_the_influence_distance_gives_the_row_minus_n_jp_and_the_damper_bound() {
        // The paper's arm stretched straight up (theta = 0): joints at
        // (0, 0.5), (0, 1.1), (0, 1.95), (0, 2.55). An obstacle of radius
        // 0.05 at (0.15, 1.5), beside the second link: the closest point is
        // p = (0, 1.5), n = (-1, 0), c = 0.15 - 0.05 = 0.1.
        let mut scene = Scene::task1();
        scene.obstacles = vec![Obstacle::new(0.15, 1.5, 0.05)];
        let pose = Pose::new(&scene.arm, &[0.0, 0.0, 0.0]).unwrap();
        let cx: Context = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::with_capacity(3, 0);
        rows.clear(3);
        build::<Arm, 2>(3).rows(&cx, &pose, &mut rows).unwrap();
        assert_eq!(rows.len(), 1, "only the second link is within d_i = 0.3");
        // n^T J_p: column i <= link is (p_y - P(i-1)_y, -(p_x - P(i-1)_x))
        // = (1.5 - 0.5, 0) and (1.5 - 1.1, 0); n^T of those is -1.0, -0.4,
        // and the third joint does not move p.
        let (g, h) = rows.row(0);
        let expected = [1.0, 0.4, 0.0];
        for (x, y) in g.iter().zip(expected) {
            assert!((x - y).abs() < 1e-12, "{g:?}");
        }
        // xi (c - d_s) / (d_i - d_s) = 1 (0.1 - 0.02) / (0.3 - 0.02).
        assert!((h - 0.08 / 0.28).abs() < 1e-12, "{h}");
    }

    #[test]
    fn pairs_beyond_the_influence_distance_give_no_row() {
        let mut scene = Scene::task1();
        scene.obstacles = vec![Obstacle::new(1.5, 1.5, 0.05)];
        let pose = Pose::new(&scene.arm, &[0.0, 0.0, 0.0]).unwrap();
        let cx: Context = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::with_capacity(3, 4);
        rows.clear(3);
        build::<Arm, 2>(3).rows(&cx, &pose, &mut rows).unwrap();
        assert!(rows.is_empty());
    }
}
