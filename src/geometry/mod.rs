//! Geometry that the kinematics, the obstacle code and the atlas share:
//! where a point is closest to a segment, and how far; the obstacles
//! themselves, balls of any dimension ([`Ball`]: a disc in the plane, a
//! sphere in space). A leaf of the crate but for its errors.

mod ball;

use nalgebra::Vector2;

pub use ball::{Ball, Placement, MAX_BALLS};

/// The parameter `s` in `[0, 1]` of the point `a + s (b - a)` of the
/// segment `a`-`b` closest to `p` (0 for a segment of zero length).
#[inline]
pub fn closest_parameter(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let ap = [p[0] - a[0], p[1] - a[1]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1];
    if len2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The point of the segment `a`-`b` closest to `p`.
#[inline]
pub fn closest_point(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let s = closest_parameter(p, a, b);
    [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
}

/// Squared distance from `p` to the segment `a`-`b`.
#[inline]
pub fn segment_distance_squared(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let s = closest_parameter(p, a, b);
    let ab = [b[0] - a[0], b[1] - a[1]];
    let d = [p[0] - a[0] - s * ab[0], p[1] - a[1] - s * ab[1]];
    d[0] * d[0] + d[1] * d[1]
}

/// Euclidean distance from point `p` to the segment `a`-`b`.
pub fn point_segment_distance(p: &Vector2<f64>, a: &Vector2<f64>, b: &Vector2<f64>) -> f64 {
    segment_distance_squared([p[0], p[1]], [a[0], a[1]], [b[0], b[1]]).sqrt()
}
