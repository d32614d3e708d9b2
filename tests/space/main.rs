//! Arms in space as a specification: the presets' tasks, the spatial
//! planner, and the planar arm as a chain whose axes are parallel.

mod atlas;
mod atlas_job;
mod kinematics;
mod lab;
mod modern;
mod networks;
mod paths;
mod planner;
mod self_motion;
mod session;
mod session_pose;
mod session_self;

use redundant_ik::space::{Chain, Row};
use redundant_ik::Arm;

/// The planar arm as a chain in space: the base turned so that its `z`
/// (every joint's axis) is the world's `+y`, at the top of the post; the
/// first joint's zero pointing up; each link an `a` along the previous `x`.
/// The planar `(x, y)` is the world's `(x, z)`.
pub fn planar_as_chain(arm: &Arm) -> Chain {
    use std::f64::consts::FRAC_PI_2;
    let links = arm.links();
    let n = links.len();
    let mut rows = vec![Row {
        a: 0.0,
        alpha: 0.0,
        d: 0.0,
        offset: -FRAC_PI_2,
    }];
    rows.extend(links[..n - 1].iter().map(|&l| Row::new(l, 0.0, 0.0)));
    // Rx(-pi/2): the base's z is the world's +y, its y the world's -z.
    let turn = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]];
    Chain::placed(
        turn,
        [0.0, 0.0, arm.post()],
        rows,
        [links[n - 1], 0.0, 0.0],
        0.0,
    )
    .unwrap()
}
