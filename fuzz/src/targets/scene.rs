//! The `scene` target.

use arbitrary::Unstructured;
use redundant_ik::arm::JointLimits;
use redundant_ik::ik::DampingSchedule;
use redundant_ik::planner::methods as m;
use redundant_ik::planner::{methods, Planner};
use redundant_ik::scene::{JointWeighting, Params, Path};
use redundant_ik::{Arm, Obstacle, Scene};

use super::checks::{shipped_surrogate, step_checked, Snapshot};
use super::gen::{arm, num, num_in, point, small};

/// Arms, obstacles and scenes from arbitrary numbers (or, 1 time in 4, a
/// scene as JSON, as the workers receive it), then a planner in every method
/// for up to 12 steps. A scene the planner accepts validates; no step
/// accepts a non-finite angle; a failed step changes nothing.
pub fn scene(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let scene = if u.ratio(1u8, 4u8).unwrap_or(false) {
        let text = String::from_utf8_lossy(u.take_rest());
        match serde_json::from_str::<Scene>(&text) {
            Ok(s) => s,
            Err(_) => return,
        }
    } else {
        let (post, links) = arm(&mut u);
        let Ok(arm) = Arm::new(post, links) else {
            return;
        };
        // The arm's own questions must answer for any point.
        let p = point(&mut u);
        let _ = arm.can_reach(&redundant_ik::nalgebra::Vector2::new(p[0], p[1]));
        let theta0 = (0..arm.dof().min(8))
            .map(|_| num(&mut u))
            .collect::<Vec<_>>();
        let _ = arm.check_angles(&theta0);
        let obstacles = (0..small(&mut u, 3))
            .map(|_| Obstacle::new(num(&mut u), num(&mut u), num_in(&mut u, 0.0, 0.3)))
            .collect::<Vec<_>>();
        for o in &obstacles {
            let _ = o.validate(&arm);
        }
        let dt = num_in(&mut u, 0.01, 0.2);
        let target = point(&mut u);
        let (lambda, delta) = (num_in(&mut u, 0.0, 10.0), num_in(&mut u, 0.0, 0.1));
        let damping = u
            .ratio(1u8, 2u8)
            .unwrap_or(false)
            .then(DampingSchedule::default);
        let tf = dt * small(&mut u, 30) as f64;
        let feedback_gain = num_in(&mut u, 0.0, 5.0);
        let mut values = vec![(&m::LAMBDA, lambda), (&m::DELTA, delta)];
        // Drawn last, and the defaults when the input has ended, so that
        // inputs written before they existed make the same scene.
        if !u.is_empty() {
            values.extend([
                (&m::INFLUENCE, num_in(&mut u, 0.05, 0.6)),
                (&m::STOP_DISTANCE, num_in(&mut u, 0.0, 0.04)),
                (&m::DAMPER_GAIN, num_in(&mut u, 0.1, 3.0)),
                (&m::ESCAPE_SPEED, num_in(&mut u, 0.0, 1.0)),
                (&m::SLACK_WEIGHT, num_in(&mut u, 1.0, 1e7)),
                (&m::DISTANCE_GAIN, num_in(&mut u, 0.0, 0.01)),
                (&m::RATE_LIMIT, num_in(&mut u, 0.05, 5.0)),
            ]);
        }
        // Drawn after those, 0 (the paper's) when the input has ended.
        if !u.is_empty() {
            values.push((&m::SIGN_SMOOTHING, num_in(&mut u, 0.0, 0.5)));
        }
        if !u.is_empty() {
            values.push((&m::REFINE, small(&mut u, 4) as f64));
        }
        // The lab's: joint limits around the start (sometimes excluding
        // it), the weighting and the new methods' and dampers' gains.
        let mut weighting = JointWeighting::None;
        let mut floor = false;
        let mut arm = arm;
        if !u.is_empty() {
            values.extend([
                (&m::MANIPULABILITY_GAIN, num_in(&mut u, 0.0, 5.0)),
                (&m::JOINT_RANGE_GAIN, num_in(&mut u, 0.0, 50.0)),
                (&m::LIMIT_INFLUENCE, num_in(&mut u, 0.1, 1.5)),
                (&m::LIMIT_STOP, num_in(&mut u, 0.0, 0.09)),
                (&m::LIMIT_GAIN, num_in(&mut u, 0.1, 3.0)),
            ]);
            if u.ratio(1u8, 2u8).unwrap_or(false) {
                weighting = JointWeighting::Wln;
            }
            floor = u.ratio(1u8, 2u8).unwrap_or(false);
            let ranges = theta0
                .iter()
                .map(|&t| [t - num_in(&mut u, -0.1, 3.0), t + num_in(&mut u, -0.1, 3.0)])
                .collect::<Vec<_>>();
            let Ok(limits) = JointLimits::new(ranges) else {
                return;
            };
            let Ok(limited) = arm.clone().with_limits(Some(limits), None) else {
                return;
            };
            arm = limited;
        }
        // The paths beyond the line, drawn last: the line when the input
        // has ended.
        let path = match (!u.is_empty()).then(|| small(&mut u, 3)) {
            Some(1) => Path::Circle {
                centre: point(&mut u),
                laps: 1 + small(&mut u, 3) as u32,
            },
            Some(2) => Path::Points((0..1 + small(&mut u, 4)).map(|_| point(&mut u)).collect()),
            _ => Path::Line,
        };
        let mut params = Params::default();
        if params.set_all(&values).is_err() {
            // Refused where it is set; nothing to plan.
            return;
        }
        Scene {
            weighting,
            floor,
            arm,
            theta0,
            target,
            path,
            obstacles,
            damping,
            dt,
            tf,
            feedback_gain,
            params,
        }
    };
    let networks = (scene.arm == Arm::paper()).then(shipped_surrogate);
    for &method in methods::ALL {
        let Ok(mut p) = Planner::new(scene.clone(), method, networks.clone()) else {
            continue;
        };
        scene.validate().expect("an accepted scene validates");
        Snapshot::of(&p).assert_finite();
        step_checked(&mut p, scene.steps().min(12));
    }
}
