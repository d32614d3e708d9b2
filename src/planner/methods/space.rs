//! What the methods' rules for an arm in space share: the context a rule
//! reads ([`SpaceContext`]), the rule's interface ([`SpaceRule`]) and eq.
//! (18) with `m = 3`. Each method writes its spatial rule in its own file,
//! under "In space", beside its planar rule: the same registry, parameters
//! and rooms, with rules that read a [`SpacePose`] (the hand's `3 x n`
//! Jacobian, the joints' axes, the capsules) instead of a planar pose. A
//! method that has one names its builder in its
//! [`Entry::space`](super::Entry); [`Method::space_rule`](super::Method)
//! refuses the others with a clear error.

use super::{Method, Note};
use crate::error::{Error, Result};
use crate::planner::SpaceSurrogate;
use crate::scene::SpaceScene;
use crate::space::linalg::{smallest_singular_value3, solve_spd3};
use crate::space::SpacePose;

/// What a spatial rule reads besides the pose.
#[derive(Clone, Copy)]
pub struct SpaceContext<'a> {
    /// The scene, with its current target, spheres and gains.
    pub scene: &'a SpaceScene,
    /// The networks the learned routes (Cases 1-3) run with, if any.
    pub networks: Option<&'a dyn SpaceSurrogate>,
}

impl SpaceContext<'_> {
    /// The networks `method` needs, or a clear error without them.
    pub fn networks_for(&self, method: Method) -> Result<&dyn SpaceSurrogate> {
        self.networks.ok_or_else(|| {
            Error::NetworksUnavailable(format!(
                "method {method} needs networks trained for this arm in space (the Panda's: --networks panda-reach)"
            ))
        })
    }

    /// The damping the schedule adds at `pose` (zero when it is off).
    #[inline]
    pub fn scheduled_delta(&self, pose: &SpacePose) -> f64 {
        self.scene.damping.map_or(0.0, |d| {
            d.delta_at_sigma(smallest_singular_value3(pose.jjt()))
        })
    }
}

/// A method's computation for one spatial planner, with its own scratch
/// space (a step allocates nothing).
pub trait SpaceRule: Send + Sync {
    /// Joint rates at `pose` for the commanded hand velocity `xdot` into
    /// `out` (`n` entries).
    fn theta_dot(
        &mut self,
        cx: &SpaceContext<'_>,
        pose: &SpacePose,
        xdot: [f64; 3],
        out: &mut [f64],
    ) -> Result<Note>;

    /// A copy with its own scratch space.
    fn boxed_clone(&self) -> Box<dyn SpaceRule>;
}

impl Clone for Box<dyn SpaceRule> {
    fn clone(&self) -> Self {
        self.boxed_clone()
    }
}

/// Eq. (18) with `m = 3`: `(J J^T + delta I) varphi = Xdot - J v`,
/// `theta_dot = J^T varphi + v` into `out` (`v` has `n` entries).
pub fn eq18(
    pose: &SpacePose,
    xdot: [f64; 3],
    v: &[f64],
    delta: f64,
    out: &mut [f64],
) -> Result<()> {
    let jac = pose.jacobian();
    let mut a = pose.jjt();
    for (i, row) in a.iter_mut().enumerate() {
        row[i] += delta;
    }
    let mut rhs = xdot;
    for (col, vi) in jac.chunks_exact(3).zip(v) {
        for r in 0..3 {
            rhs[r] -= col[r] * vi;
        }
    }
    let phi = solve_spd3(a, rhs)?;
    for ((o, col), vi) in out.iter_mut().zip(jac.chunks_exact(3)).zip(v) {
        *o = col[0] * phi[0] + col[1] * phi[1] + col[2] * phi[2] + vi;
    }
    Ok(())
}

/// Eq. (18) weighted by a diagonal `W` given as its inverse `winv` (`n`
/// entries), with `m = 3`: `J+ = W^-1 J^T (J W^-1 J^T + delta I)^-1`, the
/// null-space vector in the same metric (as the planar
/// [`crate::ik::theta_dot_weighted_into`]):
/// `(J W^-1 J^T + delta I) varphi = Xdot - J W^-1 v`,
/// `theta_dot = W^-1 (J^T varphi + v)` into `out`.
pub fn eq18_weighted(
    pose: &SpacePose,
    winv: &[f64],
    xdot: [f64; 3],
    v: &[f64],
    delta: f64,
    out: &mut [f64],
) -> Result<()> {
    let jac = pose.jacobian();
    let mut a = [[0.0; 3]; 3];
    let mut rhs = xdot;
    for ((col, vi), w) in jac.chunks_exact(3).zip(v).zip(winv) {
        for r in 0..3 {
            for c in 0..3 {
                a[r][c] += col[r] * (w * col[c]);
            }
            rhs[r] -= col[r] * (w * vi);
        }
    }
    for (i, row) in a.iter_mut().enumerate() {
        row[i] += delta;
    }
    let phi = solve_spd3(a, rhs)?;
    for (((o, col), vi), w) in out.iter_mut().zip(jac.chunks_exact(3)).zip(v).zip(winv) {
        *o = w * ((col[0] * phi[0] + col[1] * phi[1] + col[2] * phi[2]) + vi);
    }
    Ok(())
}
