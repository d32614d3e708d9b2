//! Constant-speed timing along a path, one piece of maths for the plane
//! and for space (`D = 2` or `3`): the planar [`super::Track`] and the
//! spatial tracks (one [`super::Track`]) read their references and velocities here.
//! With `s = (t - t0) / duration` in `[0, 1]`:
//!
//! - a circle ([`Circle`]): the angle about the centre grows linearly,
//!   `X_ref = c + r (cos a u + sin a w)` with `a = a0 + 2 pi laps s`
//!   (`u`, `w` the plane's orthonormal axes; in the plane the world's `x`
//!   and `y`) and `d/ds X_ref = r 2 pi laps (-sin a u + cos a w)`;
//! - a polyline ([`polyline_at`]): the arc length grows linearly, `X_ref`
//!   the point at arc length `s L` (`L` the whole length), `d/ds X_ref` the
//!   unit direction of its segment times `L`.
//!
//! The callers divide `d/ds` by the duration and evaluate it at each RK4
//! stage's own time (see `planner/path.rs`). Allocation-free.

use crate::kinematics::sin_cos;

/// The fraction of a path's time at `t`, clamped into `[0, 1]`.
#[inline]
pub(crate) fn fraction(t: f64, t0: f64, duration: f64) -> f64 {
    ((t - t0) / duration).clamp(0.0, 1.0)
}

/// Whether a step whose midpoint is `t_mid` lies inside the path's time
/// (outside it the reference holds still: zero velocity).
#[inline]
pub(crate) fn moving(t_mid: f64, t0: f64, duration: f64) -> bool {
    t_mid > t0 && t_mid < t0 + duration
}

/// The length of `v`, by `hypot` (no overflow; in the plane exactly
/// `v[0].hypot(v[1])`).
#[inline]
pub(crate) fn length<const D: usize>(v: [f64; D]) -> f64 {
    v[1..].iter().fold(v[0].abs(), |acc, &x| acc.hypot(x))
}

/// A circle run at constant angular speed: `sweep` radians over the
/// path's time from the angle `phase`, in the plane of the orthonormal
/// `axes` through `centre`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Circle<const D: usize> {
    /// The centre.
    pub centre: [f64; D],
    /// The plane's orthonormal axes `u`, `w`; the angle turns from `u`
    /// toward `w`.
    pub axes: [[f64; D]; 2],
    /// The radius (m).
    pub radius: f64,
    /// The angle at `s = 0` (rad).
    pub phase: f64,
    /// The angle swept over the path, `2 pi laps` (rad).
    pub sweep: f64,
}

impl Circle<2> {
    /// The counter-clockwise planar circle about `centre` through `start`,
    /// `laps` times.
    pub(crate) fn planar(centre: [f64; 2], start: [f64; 2], laps: u32) -> Self {
        let (dx, dy) = (start[0] - centre[0], start[1] - centre[1]);
        Self {
            centre,
            axes: [[1.0, 0.0], [0.0, 1.0]],
            radius: dx.hypot(dy),
            phase: dy.atan2(dx),
            sweep: std::f64::consts::TAU * f64::from(laps),
        }
    }
}

impl<const D: usize> Circle<D> {
    /// The point at fraction `s` and its derivative `d/ds`. (In the plane,
    /// with the world's axes, the products by 1 and the sums with 0 are
    /// exact: the numbers of `c + r (cos a, sin a)` to the bit.)
    #[inline]
    pub(crate) fn at(&self, s: f64) -> ([f64; D], [f64; D]) {
        let (sin, cos) = sin_cos(self.phase + self.sweep * s);
        let (r, v) = (self.radius, self.radius * self.sweep);
        let [u, w] = self.axes;
        (
            std::array::from_fn(|k| self.centre[k] + r * (cos * u[k] + sin * w[k])),
            std::array::from_fn(|k| v * (-sin * u[k] + cos * w[k])),
        )
    }
}

/// The point at fraction `s` of the polyline from `start` through
/// `points` (by arc length) and its derivative `d/ds`; at a corner the
/// segment after it when `after`, else the one before. Zero-length
/// segments are skipped; a polyline of no length stays at `start`.
pub(crate) fn polyline_at<const D: usize>(
    start: [f64; D],
    points: &[[f64; D]],
    s: f64,
    after: bool,
) -> ([f64; D], [f64; D]) {
    let gap = |a: [f64; D], b: [f64; D]| length::<D>(std::array::from_fn(|k| b[k] - a[k]));
    let mut total = 0.0;
    let mut prev = start;
    for &q in points {
        total += gap(prev, q);
        prev = q;
    }
    let arc = s * total;
    let (mut walked, mut prev) = (0.0, start);
    let mut found = ([start, start], 0.0, 0.0);
    for &q in points {
        let len = gap(prev, q);
        if len > 0.0 {
            found = ([prev, q], walked, len);
            let inside = if after {
                arc < walked + len
            } else {
                arc <= walked + len
            };
            if inside {
                break;
            }
        }
        walked += len;
        prev = q;
    }
    let ([a, b], from, len) = found;
    if len == 0.0 {
        return (start, [0.0; D]);
    }
    let u = ((arc - from) / len).clamp(0.0, 1.0);
    let k = total / len;
    (
        std::array::from_fn(|i| a[i] + u * (b[i] - a[i])),
        std::array::from_fn(|i| k * (b[i] - a[i])),
    )
}
