//! The joint-rate limit `L`: `|theta_dot_i| <= L` for every joint, as NEO
//! (Haviland and Corke 2021) bounds a robot's joint velocities and mink's
//! `VelocityLimit` does. This implementation's addition to the program:
//! without it, where a damper and the task pull apart, the program buys the
//! task with unbounded rates (`docs/methods.md` has the atlases that chose
//! `L`). As rows `G theta_dot <= h`, two per joint `i`, in the joints'
//! order: `-e_i` (`theta_dot_i >= -L`), then `+e_i` (`theta_dot_i <= L`),
//! each with `h = L`.

use super::{Constraint, ConstraintInfo, Entry, Rows};
use crate::error::Result;
use crate::kinematics::Pose;
use crate::planner::methods::Context;
use crate::scene::{Param, Scene};

/// The joint-rate limit (`rate_limit`).
pub static RATE_LIMIT: Entry = Entry {
    info: ConstraintInfo {
        name: "rate_limit",
        label: "joint-rate limit",
        description: "−L ≤ θ̇_i ≤ L for every joint",
        params: PARAMS,
    },
    build: |_| Box::new(RateLimit),
};

/// The scene's parameters the limit reads: [`limit_of`] reads them.
const PARAMS: &[Param] = &[Param::RateLimit];

/// The limit `L` (rad/s) of [`PARAMS`] in `scene`.
fn limit_of(scene: &Scene) -> f64 {
    scene.avoidance.rate_limit
}

/// The limit has no scratch space: its rows depend on the arm's joints only.
#[derive(Clone, Copy)]
struct RateLimit;

impl Constraint for RateLimit {
    fn rows(&mut self, cx: &Context<'_>, pose: &Pose, rows: &mut Rows) -> Result<()> {
        let limit = limit_of(cx.scene);
        for i in 0..pose.dof() {
            for sign in [-1.0, 1.0] {
                rows.push(limit)[i] = sign;
            }
        }
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Constraint> {
        Box::new(*self)
    }

    fn info(&self) -> &'static ConstraintInfo {
        &RATE_LIMIT.info
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_joint_gets_the_rows_minus_e_i_and_plus_e_i_bounded_by_the_limit() {
        let mut scene = Scene::task1();
        scene.avoidance.rate_limit = 0.7;
        let pose = Pose::new(&scene.arm, &scene.theta0).unwrap();
        let cx = Context {
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
}
