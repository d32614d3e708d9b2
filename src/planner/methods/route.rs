//! The paper's two routes from `v` to joint rates: eq. (18), the
//! symmetric 2x2 solve with the exact `J`, and eq. (21), with `Phi` from
//! the `Phi` network.

use super::{Context, Method, Note};
use crate::error::Result;
use crate::ik;
use crate::kinematics::Pose;

/// Eq. (18): `(J J^T + delta I) varphi = Xdot - J v`,
/// `theta_dot = J^T varphi + v`, with the scene's constant `delta` plus the
/// damping schedule's share.
#[inline]
pub(super) fn exact(
    cx: &Context<'_>,
    pose: &Pose,
    xdot: [f64; 2],
    v: &[f64],
    out: &mut [f64],
) -> Result<Note> {
    let delta = cx.scene.delta + cx.scheduled_delta(pose);
    ik::theta_dot_symmetric_into(pose.jacobian(), xdot, v, delta, out)?;
    Ok(Note::default())
}

/// Eq. (21): `theta_dot = Phi (Xdot - J v) + v` with `Phi` from the `Phi`
/// network, damped by a constant `delta` through [`ik::damp_phi`]. Where
/// the damping schedule is active (a near-singular pose, where `Phi` is
/// unbounded and no network fits it), the exact damped `Phi` of eq. (20)
/// stands in, and the note says so.
#[inline]
pub(super) fn learned(
    method: Method,
    cx: &Context<'_>,
    pose: &Pose,
    xdot: [f64; 2],
    v: &[f64],
    phi: &mut [f64],
    out: &mut [f64],
) -> Result<Note> {
    let scheduled = cx.scheduled_delta(pose);
    let jac = pose.jacobian();
    let handover = scheduled > 0.0;
    if handover {
        ik::phi_into(jac, cx.scene.delta + scheduled, phi)?;
    } else {
        cx.networks_for(method)?.phi(pose, phi)?;
        ik::damp_phi(phi, cx.scene.delta)?;
    }
    ik::theta_dot_network_into(phi, jac, xdot, v, out)?;
    Ok(Note { handover })
}
