//! What the lecture draws at the hand: the manipulability (velocity)
//! ellipse `{J theta_dot : |theta_dot| <= 1}` and the force ellipse
//! `{f : |J^T f| <= 1}`, from [`crate::kinematics::velocity_ellipse`],
//! each when its legend toggle is on.

use std::f64::consts::TAU;

use web_sys::CanvasRenderingContext2d;

use super::style::{bit, FORCE, FORCE_SCALE, MAX_FORCE, VELOCITY, VELOCITY_SCALE};
use super::surface::View;
use crate::kinematics::velocity_ellipse;

/// Draws the ellipses `shown` asks for (the bits [`bit::ELLIPSE`],
/// [`bit::FORCE`]) centred at the hand `at`, for `J J^T = jjt`; returns the
/// bits drawn. The velocity ellipse's half-lengths are `sigma_i` (m per
/// rad/s) drawn at [`VELOCITY_SCALE`]; the force ellipse's `1 / sigma_i`
/// (N per N m) at [`FORCE_SCALE`], each at most [`MAX_FORCE`] m (it is
/// unbounded at a singular pose).
pub fn ellipses(
    ctx: &CanvasRenderingContext2d,
    view: View,
    at: [f64; 2],
    jjt: [f64; 3],
    shown: u32,
) -> u32 {
    let (axes, half) = velocity_ellipse(jjt);
    // The canvas's y points down: the angle of the major axis mirrors.
    let rotation = -axes[0][1].atan2(axes[0][0]);
    let (x, y) = view.to_px(at);
    let mut drawn = 0;
    for (b, colour, [a, c]) in [
        (bit::ELLIPSE, VELOCITY, half.map(|h| h * VELOCITY_SCALE)),
        (
            bit::FORCE,
            FORCE,
            half.map(|h| (FORCE_SCALE / h).min(MAX_FORCE)),
        ),
    ] {
        if shown & b == 0 {
            continue;
        }
        drawn |= b;
        ctx.begin_path();
        let _ = ctx.ellipse(
            x,
            y,
            (a * view.scale).max(0.5),
            (c * view.scale).max(0.5),
            rotation,
            0.0,
            TAU,
        );
        ctx.set_stroke_style_str(colour);
        ctx.set_line_width(1.75);
        ctx.stroke();
    }
    drawn
}
