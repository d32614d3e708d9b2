//! The paper's obstacle vector `v` (eqs. 14-16), exactly or by the `v`
//! network: what the numerical route and Cases 1 to 3 add in the null
//! space.

use super::{Context, Method};
use crate::error::Result;
use crate::kinematics::Pose;
use crate::obstacle;

/// Buffers of one rate evaluation of the paper's methods: `v`, one
/// obstacle's gradient and `Phi` (row-major `n x 2`).
#[derive(Debug, Clone)]
pub(super) struct Scratch {
    pub(super) v: Vec<f64>,
    pub(super) g: Vec<f64>,
    pub(super) phi: Vec<f64>,
}

impl Scratch {
    pub(super) fn new(n: usize) -> Self {
        Self {
            v: vec![0.0; n],
            g: vec![0.0; n],
            phi: vec![0.0; 2 * n],
        }
    }
}

/// `v = (lambda / 4) sum_O sum_k sign(D_k) dD_k/dtheta`, eqs. (14)-(15)
/// summed over the obstacles, computed exactly (the numerical route, Case 1).
pub(super) fn exact(cx: &Context<'_>, pose: &Pose, g: &mut [f64], v: &mut [f64]) {
    let scene = cx.scene;
    obstacle::null_space_vector_into(&scene.arm, pose, &scene.obstacles, scene.lambda, g, v);
}

/// The same with the area gradient of each obstacle from the `v` network
/// (Cases 2 and 3).
pub(super) fn learned(
    method: Method,
    cx: &Context<'_>,
    pose: &Pose,
    g: &mut [f64],
    v: &mut [f64],
) -> Result<()> {
    let nets = cx.networks_for(method)?;
    let scene = cx.scene;
    v.iter_mut().for_each(|x| *x = 0.0);
    for ob in &scene.obstacles {
        nets.area_gradient(pose, ob.centre, g)?;
        for (vi, gi) in v.iter_mut().zip(g.iter()) {
            *vi += gi;
        }
    }
    let scale = scene.lambda / 4.0;
    v.iter_mut().for_each(|x| *x *= scale);
    Ok(())
}
