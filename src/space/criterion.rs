//! The paper's obstacle criterion in space (its eqs. 12-16 generalised):
//! for each moving segment `k` of the volume from `P(k-1)` to `P(k)` and
//! the obstacle's centre `O`,
//! `V_k = |(O - P(k-1)) x (P(k) - P(k-1))|`, twice the triangle's area.
//! In the plane the cross product has one component, the paper's
//! determinant `D_k` of eq. (16), and `V_k = |D_k|` (eq. 12). The
//! null-space vector is `v = (lambda / 4) sum_O sum_k dV_k/dtheta` (eq. 14),
//! with the norm smoothed by `eps` as the planar sign is
//! ([`crate::obstacle::smoothed_sign`]): `sqrt(|c|^2 + eps^2)`, whose
//! gradient at `eps = 0` is the planar `sign(D_k) dD_k/dtheta` on a chain
//! whose axes are parallel.
//!
//! The gradient is analytic: with `u = O - A`, `w = B - A` and `c = u x w`,
//! `dc/dtheta_i = -dA_i x w + u x (dB_i - dA_i)`, where `dA_i = z_i x (A -
//! o_i)` is the velocity of the segment's start for a unit rate of joint
//! `i` (zero for a joint that does not move it), and
//! `dV_k/dtheta_i = c . dc/dtheta_i / sqrt(|c|^2 + eps^2)`.

use super::pose::{cross, dot, sub, SpacePose, Vec3};
use super::Chain;

/// `V_k` for each moving segment of `chain` at `pose`, the fixed base left
/// out, in the segments' order.
pub fn triangle_areas<'a>(
    chain: &'a Chain,
    pose: &'a SpacePose,
    o: Vec3,
) -> impl Iterator<Item = f64> + 'a {
    chain
        .segments()
        .iter()
        .filter(|s| s.moved_by > 0)
        .map(move |s| {
            let (a, b) = pose.segment(s);
            let c = cross(sub(o, a), sub(b, a));
            dot(c, c).sqrt()
        })
}

/// The gradient `g = sum_k dV_k/dtheta` for one obstacle centre `o`
/// (`lambda = 4`, so `v = (lambda / 4) g`), the norm smoothed by `eps`,
/// added into `out` (`n` entries). No allocation.
pub fn area_gradient_add(chain: &Chain, pose: &SpacePose, o: Vec3, eps: f64, out: &mut [f64]) {
    for s in chain.segments().iter().filter(|s| s.moved_by > 0) {
        let (a, b) = pose.segment(s);
        let (u, w) = (sub(o, a), sub(b, a));
        let c = cross(u, w);
        let norm = (dot(c, c) + eps * eps).sqrt();
        if norm == 0.0 {
            continue; // the paper's sign(0) = 0
        }
        for (i, g) in out.iter_mut().enumerate().take(s.moved_by) {
            let da = pose.column(i, a);
            let db = pose.column(i, b);
            let dc = sub(cross(u, sub(db, da)), cross(da, w));
            *g += dot(c, dc) / norm;
        }
    }
}

/// The null-space vector of eq. (14) in space, summed over the obstacles'
/// centres: `v = (lambda / 4) sum_O sum_k dV_k/dtheta` into `v` (`n`
/// entries). No allocation.
pub fn null_space_vector_into(
    chain: &Chain,
    pose: &SpacePose,
    centres: impl IntoIterator<Item = Vec3>,
    lambda: f64,
    eps: f64,
    v: &mut [f64],
) {
    v.iter_mut().for_each(|x| *x = 0.0);
    for o in centres {
        area_gradient_add(chain, pose, o, eps, v);
    }
    let k = lambda / 4.0;
    v.iter_mut().for_each(|x| *x *= k);
}
