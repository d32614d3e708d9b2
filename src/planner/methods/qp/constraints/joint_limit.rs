//! The joint-limit damper (NEO, Haviland and Corke 2021, eq. 14; mink's
//! `ConfigurationLimit` in velocity form): for every joint closer to a
//! limit than the influence angle `rho_infl`, its rate toward that limit is
//! bounded so that the distance `rho` to the limit decays no faster than
//! the damper allows,
//!
//! `theta_dot_i <= xi_q (rho_i - rho_s) / (rho_infl - rho_s)`,
//! `rho_i = hi_i - theta_i` (toward the upper limit), and the mirror
//! `-theta_dot_i <= xi_q (rho_i - rho_s) / (rho_infl - rho_s)`,
//! `rho_i = theta_i - lo_i` (toward the lower),
//!
//! with the gain `xi_q` (rad/s, the rate allowed at `rho_infl`) and the
//! stop angle `rho_s`: at `rho = rho_s` the joint may not move toward the
//! limit, inside it the joint must move back. As rows `G theta_dot <= h`:
//! `+e_i` for the upper limit, `-e_i` for the lower, joint by joint, only
//! where `rho_i < rho_infl`. An arm without position limits gets no rows.
//! NEO's defaults: `rho_infl = 0.9 rad`, `rho_s = 0.05 rad`, `xi_q = 1`.
//! A chain in space gets the same rows from its own limits
//! ([`crate::space::Chain::joint_limits`]).

use super::{Constraint, ConstraintInfo, Entry, Rows};
use crate::error::Result;
use crate::arm::JointLimits;
use crate::model::{Model, Scene as _};
use crate::planner::methods::Context;
use crate::scene::{Param, Params, Scale};

/// The joint-limit dampers (`joint_limit`).
pub static JOINT_LIMIT: Entry = Entry {
    info: ConstraintInfo {
        name: "joint_limit",
        label: "joint-limit damper",
        description: "±θ̇_i ≤ ξ_q (ρ_i − ρ_s) / (ρ_infl − ρ_s) for every joint within ρ_infl of a limit",
        params: PARAMS,
    },
    build: |_| Box::new(JointLimit),
    space: |_| Box::new(JointLimit),
    pose: |_| Box::new(JointLimit),
};

/// Influence angle `rho_infl` (rad): a joint closer than this to a limit
/// gets a damper (NEO's 0.9 rad).
pub static LIMIT_INFLUENCE: Param = Param {
    name: "limit_influence",
    flag: "--limit-influence",
    label: "Limit influence ρᵢ",
    what: "limit influence rho_infl",
    #[cfg(feature = "cli")]
    help: "Influence angle rho_infl of the joint-limit dampers: joints closer to a limit get one (qp)",
    unit: "rad",
    bounds: (1e-3, 10.0),
    default: 0.9,
    slider: (0.1, 2.0, 0.05),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: Some(&LIMIT_STOP),
};

/// Stop angle `rho_s` (rad): the distance to a limit the dampers keep
/// (NEO's 0.05 rad). Below `rho_infl`.
pub static LIMIT_STOP: Param = Param {
    name: "limit_stop",
    flag: "--limit-stop",
    label: "Limit stop ρₛ",
    what: "limit stop rho_s",
    #[cfg(feature = "cli")]
    help: "Stop angle rho_s of the joint-limit dampers: the distance to a limit they keep (qp)",
    unit: "rad",
    bounds: (0.0, 10.0),
    default: 0.05,
    slider: (0.0, 0.5, 0.01),
    scale: Scale::Linear,
    count: false,
    below: Some(&LIMIT_INFLUENCE),
    above: None,
};

/// Gain `xi_q` (rad/s): the rate toward a limit allowed at `rho_infl`
/// (NEO's 1).
pub static LIMIT_GAIN: Param = Param {
    name: "limit_gain",
    flag: "--limit-gain",
    label: "Limit gain ξq",
    what: "limit gain xi_q",
    #[cfg(feature = "cli")]
    help: "Gain xi_q of the joint-limit dampers: the rate toward a limit allowed at rho_infl (qp)",
    unit: "rad/s",
    bounds: (1e-3, 100.0),
    default: 1.0,
    slider: (0.1, 5.0, 0.1),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// The scene's parameters the dampers read.
const PARAMS: &[&Param] = &[&LIMIT_INFLUENCE, &LIMIT_STOP, &LIMIT_GAIN];

/// The dampers have no scratch space: their rows depend on the joints only.
#[derive(Clone, Copy)]
struct JointLimit;

/// The dampers' rows for joints at `theta` within `limits` (none without
/// limits), with the parameters of [`PARAMS`] in `params`.
fn limit_rows(params: &Params, limits: Option<&JointLimits>, theta: &[f64], rows: &mut Rows) {
    let Some(limits) = limits else {
        return;
    };
    let (infl, stop, gain) = (
        params.get(&LIMIT_INFLUENCE),
        params.get(&LIMIT_STOP),
        params.get(&LIMIT_GAIN),
    );
    let damper = |rho: f64| gain * (rho - stop) / (infl - stop);
    for (i, (&[lo, hi], &t)) in limits.ranges().iter().zip(theta).enumerate() {
        for (rho, sign) in [(hi - t, 1.0), (t - lo, -1.0)] {
            if rho < infl {
                rows.push(damper(rho))[i] = sign;
            }
        }
    }
}

impl<A: Model<M>, const M: usize> Constraint<A, M> for JointLimit {
    fn rows(&mut self, cx: &Context<'_, A, M>, pose: &A::Pose, rows: &mut Rows) -> Result<()> {
        let scene = cx.scene;
        limit_rows(scene.params(), scene.arm().joint_limits(), A::theta(pose), rows);
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Constraint<A, M>> {
        Box::new(*self)
    }

    fn info(&self) -> &'static ConstraintInfo {
        &JOINT_LIMIT.info
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Pose;
    use crate::scene::Scene;

    #[test]
    fn a_joint_near_a_limit_gets_neos_damper_toward_it_and_none_away() {
        let mut scene = Scene::task1();
        let limits: JointLimits = "-1:1,-2:2.1,-3:3".parse().unwrap();
        scene.arm = scene.arm.clone().with_limits(Some(limits), None).unwrap();
        // theta_2 = 1.8: 0.3 rad below its upper limit, 3.8 above its lower.
        let pose = Pose::new(&scene.arm, &[0.5, 1.8, 0.0]).unwrap();
        let cx: Context = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::default();
        rows.clear(3);
        JointLimit.rows(&cx, &pose, &mut rows).unwrap();
        // Joint 1 at 0.5 is 0.5 from its upper limit and 1.5 from its
        // lower: one row; joint 2 one row; joint 3 none.
        assert_eq!(rows.len(), 2);
        let (g, h) = rows.row(0);
        assert_eq!(g, [1.0, 0.0, 0.0]);
        assert!((h - (0.5 - 0.05) / 0.85).abs() < 1e-15);
        let (g, h) = rows.row(1);
        assert_eq!(g, [0.0, 1.0, 0.0]);
        assert!((h - (0.3 - 0.05) / 0.85).abs() < 1e-12);
        // Past the stop angle the joint must move back.
        let pose = Pose::new(&scene.arm, &[-0.98, 0.0, 0.0]).unwrap();
        rows.clear(3);
        JointLimit.rows(&cx, &pose, &mut rows).unwrap();
        let (g, h) = rows.row(0);
        assert_eq!(g, [-1.0, 0.0, 0.0]);
        assert!(h < 0.0, "{h}");
        assert!(rows.broken_by(&[0.0, 0.0, 0.0]));
    }

    #[test]
    fn an_arm_without_limits_gets_no_rows() {
        let scene = Scene::task1();
        let pose = Pose::new(&scene.arm, &scene.theta0).unwrap();
        let cx: Context = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::default();
        rows.clear(3);
        JointLimit.rows(&cx, &pose, &mut rows).unwrap();
        assert!(rows.is_empty());
    }
}
