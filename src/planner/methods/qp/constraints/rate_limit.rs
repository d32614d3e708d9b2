//! The joint-rate limit `L`: `|theta_dot_i| <= L` for every joint, as NEO
//! (Haviland and Corke 2021) bounds a robot's joint velocities and mink's
//! `VelocityLimit` does. This implementation's addition to the program:
//! without it, where a damper and the task pull apart, the program buys the
//! task with unbounded rates (`docs/methods.md` has the atlases that chose
//! `L`). Where the arm carries its own rate limits `R_i` (a robot's
//! datasheet, `--rate-limits`), joint `i`'s bound is the smaller,
//! `L_i = min(L, R_i)`: the program's limit and the robot's are one
//! constraint, so no two parallel rows meet in the solver's active set. As
//! rows `G theta_dot <= h`, two per joint `i`, in the joints' order: `-e_i`
//! (`theta_dot_i >= -L_i`), then `+e_i` (`theta_dot_i <= L_i`), each with
//! `h = L_i`. A chain in space gets the same rows from its own rate
//! limits ([`crate::space::Chain::rate_limits`]).

use super::{Constraint, ConstraintInfo, Entry, Rows};
use crate::arm::RateLimits;
use crate::error::Result;
use crate::model::{Model, Scene as _};
use crate::planner::methods::Context;
use crate::scene::{Param, Params, Scale};

/// The joint-rate limit (`rate_limit`).
pub static RATE_BOUNDS: Entry = Entry {
    info: ConstraintInfo {
        name: "rate_limit",
        label: "joint-rate limit",
        description: "−L_i ≤ θ̇_i ≤ L_i for every joint, L_i = min(L, the arm's rate limit)",
        params: PARAMS,
    },
    build: |_| Box::new(RateLimit),
    space: |_| Box::new(RateLimit),
    pose: |_| Box::new(RateLimit),
};

/// The joints' rate limit (rad/s), as NEO bounds a robot's joint
/// velocities: without it, where a damper and the task pull apart the
/// program buys the task with unbounded rates. The paper's tasks need 0.54.
pub static RATE_LIMIT: Param = Param {
    name: "rate_limit",
    flag: "--rate-limit",
    label: "Joint rate limit",
    what: "joint rate limit",
    #[cfg(feature = "cli")]
    help: "Limit of every joint's rate (qp)",
    unit: "rad/s",
    bounds: (1e-3, 1000.0),
    default: 1.5,
    slider: (0.2, 10.0, 0.1),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// The scene's parameters the limit reads: [`limit_of`] reads them.
const PARAMS: &[&Param] = &[&RATE_LIMIT];

/// The limit `L` (rad/s) of [`PARAMS`] in a scene's `params`.
fn limit_of(params: &Params) -> f64 {
    params.get(&RATE_LIMIT)
}

/// The rows of `n` joints with the arm's own rate limits `own`, if any.
fn rate_rows(params: &Params, own: Option<&RateLimits>, n: usize, rows: &mut Rows) {
    let limit = limit_of(params);
    let own = own.map(|r| r.rates());
    for i in 0..n {
        let bound = own
            .and_then(|r| r.get(i))
            .copied()
            .map_or(limit, |r| r.min(limit));
        for sign in [-1.0, 1.0] {
            rows.push(bound)[i] = sign;
        }
    }
}

/// The limit has no scratch space: its rows depend on the arm's joints only.
#[derive(Clone, Copy)]
struct RateLimit;

impl<A: Model<M>, const M: usize> Constraint<A, M> for RateLimit {
    fn rows(&mut self, cx: &Context<'_, A, M>, pose: &A::Pose, rows: &mut Rows) -> Result<()> {
        let scene = cx.scene;
        let n = A::theta(pose).len();
        rate_rows(scene.params(), scene.arm().rate_limits(), n, rows);
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Constraint<A, M>> {
        Box::new(*self)
    }

    fn info(&self) -> &'static ConstraintInfo {
        &RATE_BOUNDS.info
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Pose;
    use crate::scene::Scene;

    #[test]
    fn each_joint_gets_the_rows_minus_e_i_and_plus_e_i_bounded_by_the_limit() {
        let mut scene = Scene::task1();
        scene.set_param(&RATE_LIMIT, 0.7).unwrap();
        let pose = Pose::new(&scene.arm, &scene.theta0).unwrap();
        let cx: Context = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::default();
        rows.clear(3);
        RateLimit.rows(&cx, &pose, &mut rows).unwrap();
        assert_eq!(rows.len(), 6);
        for i in 0..3 {
            for (k, sign) in [-1.0, 1.0].into_iter().enumerate() {
                let (g, h) = rows.row(2 * i + k);
                let mut e = [0.0; 3];
                e[i] = sign;
                assert_eq!(g, e, "row {}", 2 * i + k);
                assert_eq!(h, 0.7);
            }
        }
        // Within the limit no row is broken; beyond it in either direction
        // one is.
        assert!(!rows.broken_by(&[0.7, -0.7, 0.0]));
        assert!(rows.broken_by(&[0.0, 0.71, 0.0]));
        assert!(rows.broken_by(&[0.0, 0.0, -0.71]));
    }

    #[test]
    fn the_arms_own_rate_limits_tighten_the_bound_joint_by_joint() {
        let mut scene = Scene::task1();
        scene.set_param(&RATE_LIMIT, 0.7).unwrap();
        let rates = "0.5,2,0.7".parse().unwrap();
        scene.arm = scene.arm.clone().with_limits(None, Some(rates)).unwrap();
        let pose = Pose::new(&scene.arm, &scene.theta0).unwrap();
        let cx: Context = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::default();
        rows.clear(3);
        RateLimit.rows(&cx, &pose, &mut rows).unwrap();
        let bounds: Vec<f64> = rows.h().to_vec();
        assert_eq!(bounds, [0.5, 0.5, 0.7, 0.7, 0.7, 0.7]);
    }
}
