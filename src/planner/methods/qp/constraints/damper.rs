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
//! In space ([`SpaceDamper`]) the pairs are a moving capsule and a sphere,
//! or the floor `z = 0` where the scene has one
//! ([`crate::space::SpacePairs`]: signed surface distance `d`, normal `n`,
//! point Jacobian `J_Q`), with the same bound:
//! `n . J_Q theta_dot >= -xi (d - d_s) / (d_i - d_s)`.

use super::{Constraint, ConstraintInfo, Entry, Rows};
use crate::clearance::Pairs;
use crate::error::Result;
use crate::kinematics::Pose;
use crate::planner::methods::Context;
use crate::planner::methods::{INFLUENCE, STOP_DISTANCE};
use crate::scene::{Param, Params, Scale};

/// The velocity dampers (`damper`).
pub static DAMPER: Entry = Entry {
    info: ConstraintInfo {
        name: "damper",
        label: "velocity damper",
        description: "n^T J_p θ̇ ≥ −ξ (c − d_s) / (d_i − d_s) for every link-obstacle pair with c < d_i",
        params: PARAMS,
    },
    build: |n| Box::new(Damper::new(n)),
    space: |n| Box::new(space::SpaceDamper::new(n)),
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

/// The scene's parameters the dampers read: [`Gains::of`] reads them.
const PARAMS: &[&Param] = &[&INFLUENCE, &STOP_DISTANCE, &DAMPER_GAIN];

/// The dampers' parameters, read from the scene in one place.
struct Gains {
    /// The influence distance `d_i` (m).
    influence: f64,
    /// The stop distance `d_s` (m).
    stop: f64,
    /// The damper gain `xi` (m/s).
    gain: f64,
}

impl Gains {
    /// The parameters of [`PARAMS`] in a scene's `params`.
    fn of(params: &Params) -> Self {
        Self {
            influence: params.get(&INFLUENCE),
            stop: params.get(&STOP_DISTANCE),
            gain: params.get(&DAMPER_GAIN),
        }
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
struct Damper {
    pairs: Pairs,
}

impl Damper {
    fn new(n: usize) -> Self {
        // 8 obstacles per link before the buffer grows.
        Self {
            pairs: Pairs::with_capacity(8 * n),
        }
    }
}

impl Constraint for Damper {
    fn rows(&mut self, cx: &Context<'_>, pose: &Pose, rows: &mut Rows) -> Result<()> {
        let gains = Gains::of(&cx.scene.params);
        self.pairs.update(pose, &cx.scene.obstacles, gains.influence);
        if let Some(post) = cx.scene.ground() {
            self.pairs.add_ground(pose, post, gains.influence);
        }
        for pair in self.pairs.as_slice() {
            let row = rows.push(gains.bound(pair.clearance));
            pair.rate_row(pose, row);
            row.iter_mut().for_each(|g| *g = -*g);
        }
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Constraint> {
        Box::new(self.clone())
    }

    fn info(&self) -> &'static ConstraintInfo {
        &DAMPER.info
    }
}

/// The dampers for a chain in space.
mod space {
    use super::super::{ConstraintInfo, Rows, SpaceConstraint};
    use super::{Gains, DAMPER};
    use crate::error::Result;
    use crate::planner::methods::Context;
    use crate::space::{Chain, SpacePairs, SpacePose};

    /// The capsule pairs of a pose within the influence distance, kept
    /// between poses.
    #[derive(Clone)]
    pub struct SpaceDamper {
        pairs: SpacePairs,
    }

    impl SpaceDamper {
        pub fn new(n: usize) -> Self {
            // Every pair a chain can have: the buffer never grows.
            Self {
                pairs: SpacePairs::with_capacity(SpacePairs::most(n)),
            }
        }
    }

    impl SpaceConstraint for SpaceDamper {
        fn rows(&mut self, cx: &Context<'_, Chain, 3>, pose: &SpacePose, rows: &mut Rows) -> Result<()> {
            let scene = cx.scene;
            let gains = Gains::of(&scene.params);
            self.pairs
                .update(&scene.chain, pose, &scene.spheres, gains.influence);
            if scene.floor {
                self.pairs.add_floor(&scene.chain, pose, gains.influence);
            }
            for pair in self.pairs.as_slice() {
                let row = rows.push(gains.bound(pair.distance));
                pair.gradient_into(pose, row);
                row.iter_mut().for_each(|g| *g = -*g);
            }
            Ok(())
        }

        fn boxed_clone(&self) -> Box<dyn SpaceConstraint> {
            Box::new(self.clone())
        }

        fn info(&self) -> &'static ConstraintInfo {
            &DAMPER.info
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
        let cx = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::with_capacity(3, 0);
        rows.clear(3);
        Damper::new(3).rows(&cx, &pose, &mut rows).unwrap();
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
        let cx = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::with_capacity(3, 4);
        rows.clear(3);
        Damper::new(3).rows(&cx, &pose, &mut rows).unwrap();
        assert!(rows.is_empty());
    }
}
