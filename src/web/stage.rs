//! The stage: the arm, its ghost, the obstacle, the path, the target and the
//! traces, over a metric grid.

use std::f64::consts::{FRAC_PI_2, PI};

use web_sys::CanvasRenderingContext2d;

use super::layer::Layer;
use super::plots::{fmt_tick, nice_step};
use super::style::*;
use super::surface::{dash, disc, polyline, text, Surface, View};
use crate::kinematics::sin_cos;
use crate::session::{Handle, Session};

/// Draws the session on the stage, over an atlas layer if one is shown;
/// returns which entries of the legend it drew (a bit each, in the
/// legend's order), so that the page's legend lists only those.
pub fn draw(s: &Session, surface: &Surface, view: View, layer: Option<&Layer>, shown: u32) -> u32 {
    let mut drawn = bit::ARM | bit::PATH | bit::REFERENCE;
    let ctx = &surface.ctx;
    surface.begin();
    if let Some(layer) = layer {
        layer.draw(ctx, view);
        drawn |= bit::ATLAS;
    }
    let planner = s.planner();
    // The time and the method; on a narrow stage (at about 7 px a
    // character) the method's short label. Drawn last, on top; the grid
    // keeps its labels clear of it.
    let t = planner.sample().t;
    let m = planner.method();
    let mut caption = format!("t = {t:.1} s   ·   {}", m.title());
    if caption.chars().count() as f64 * 7.0 > surface.width - 24.0 {
        caption = format!("t = {t:.1} s · {}", m.label());
    }
    let size = (surface.width, surface.height);
    grid(ctx, view, size, caption.chars().count() as f64 * 7.0);

    let scene = planner.scene();
    let arm = &scene.arm;
    let base = [0.0, arm.post()];

    // The floor the post stands on, across the stage.
    let (_, fy) = view.to_px([0.0, 0.0]);
    ctx.set_fill_style_str(GROUND);
    ctx.fill_rect(0.0, fy, surface.width, 2.0);

    // Workspace boundary: what the end effector can reach.
    ctx.set_stroke_style_str(AXIS);
    ctx.set_line_width(1.0);
    dash(ctx, &[2.0, 5.0]);
    let (bx, by) = view.to_px(base);
    disc(ctx, bx, by, arm.max_reach() * view.scale);
    ctx.stroke();
    dash(ctx, &[]);

    // Where the v network saw obstacles in training (network v methods).
    if let (true, Some(r)) = (planner.method().networks().v, s.trained_range()) {
        drawn |= bit::REGION;
        let (x0, y0) = view.to_px(r.obstacle_min);
        let (x1, y1) = view.to_px(r.obstacle_max);
        ctx.set_stroke_style_str(REGION);
        ctx.set_line_width(1.0);
        dash(ctx, &[3.0, 4.0]);
        ctx.stroke_rect(x0.min(x1), y0.min(y1), (x1 - x0).abs(), (y1 - y0).abs());
        // No label in the drawing (it sat over the arm's path, issue 27):
        // the legend names the box.
        dash(ctx, &[]);
    }

    // Stroboscopic trace: every few poses, faint (as in Figs. 2-11).
    ctx.set_stroke_style_str(ARM);
    ctx.set_global_alpha(STROBE_ALPHA);
    ctx.set_line_width(1.5);
    if s.strobe().len() > 1 {
        drawn |= bit::STROBE;
    }
    for pose in s.strobe() {
        polyline(ctx, Some(view), pose);
    }
    ctx.set_global_alpha(1.0);

    // The path being tracked (the straight line, a circle, a polyline).
    ctx.set_stroke_style_str(MUTED);
    ctx.set_line_width(1.25);
    dash(ctx, &[6.0, 5.0]);
    polyline(ctx, Some(view), &planner.outline());
    dash(ctx, &[]);

    // End-effector trail.
    if s.trail().len() > 1 {
        drawn |= bit::TRAIL;
    }
    ctx.set_stroke_style_str(ACCENT);
    ctx.set_line_width(2.0);
    polyline(ctx, Some(view), s.trail());

    // The influence distance around each obstacle, and the link-obstacle
    // pairs within it (the dampers of `qp`, the pairs `distance` and
    // `priority` push apart): a segment from the link's closest point to
    // the disc.
    if let Some((influence, pairs)) = s.near_pairs() {
        drawn |= bit::DAMPERS;
        ctx.set_stroke_style_str(DAMPER);
        ctx.set_global_alpha(INFLUENCE_ALPHA);
        ctx.set_line_width(1.0);
        dash(ctx, &[2.0, 4.0]);
        for ob in &scene.obstacles {
            let (ox, oy) = view.to_px(ob.centre);
            disc(ctx, ox, oy, (ob.radius + influence) * view.scale);
            ctx.stroke();
        }
        dash(ctx, &[]);
        ctx.set_global_alpha(1.0);
        ctx.set_line_width(2.0);
        for pair in pairs.as_slice() {
            let r = match pair.against {
                crate::clearance::Against::Disc(k) => scene.obstacles[k].radius,
                _ => 0.0,
            };
            let edge = [
                pair.centre[0] + r * pair.normal[0],
                pair.centre[1] + r * pair.normal[1],
            ];
            polyline(ctx, Some(view), &[pair.point, edge]);
            let (px, py) = view.to_px(pair.point);
            disc(ctx, px, py, 3.0);
            ctx.set_fill_style_str(DAMPER);
            ctx.fill();
        }
    }

    // Obstacle discs, with their points O.
    let hit = planner.sample().collision;
    if !scene.obstacles.is_empty() {
        drawn |= bit::OBSTACLE;
    }
    for (i, ob) in scene.obstacles.iter().enumerate() {
        let (ox, oy) = view.to_px(ob.centre);
        disc(ctx, ox, oy, ob.radius * view.scale);
        let alpha = if hit { HIT_ALPHA } else { OBSTACLE_ALPHA };
        ctx.set_fill_style_str(&rgba(DANGER, alpha));
        ctx.fill();
        ctx.set_stroke_style_str(DANGER);
        let held = s.dragging() == Some(Handle::Obstacle(i));
        ctx.set_line_width(if held { 2.5 } else { 1.5 });
        ctx.stroke();
        disc(ctx, ox, oy, 2.0);
        ctx.set_fill_style_str(DANGER);
        ctx.fill();
    }

    // Base post and ground.
    let (gx, gy) = view.to_px([0.0, 0.0]);
    ctx.set_fill_style_str(GROUND);
    ctx.fill_rect(gx - 18.0, gy, 36.0, 6.0);
    ctx.set_stroke_style_str(POST);
    ctx.set_line_width(8.0);
    ctx.set_line_cap("butt");
    polyline(ctx, Some(view), &[[0.0, 0.0], base]);
    ctx.set_line_cap("round");

    // The arm, over each joint's range where it has limits.
    if let Some(pts) = s.display_joints(false) {
        if let Some(limits) = arm.joint_limits() {
            drawn |= bit::LIMITS;
            let theta = planner.theta().as_slice();
            joint_ranges(ctx, view, &pts, limits.ranges(), arm.links(), theta);
        }
        // The lab's ellipses at the hand (the legend's toggles).
        if let Some(hand) = pts.last() {
            drawn |= super::lab::ellipses(ctx, view, *hand, planner.pose().jjt(), shown);
        }
        ctx.set_stroke_style_str(ARM);
        ctx.set_line_width(7.0);
        polyline(ctx, Some(view), &pts);
        for (i, p) in pts.iter().enumerate() {
            let (x, y) = view.to_px(*p);
            let last = i + 1 == pts.len();
            disc(ctx, x, y, if last { 3.5 } else { 5.0 });
            ctx.set_fill_style_str(if last { ARM } else { PAPER });
            ctx.fill();
            ctx.set_line_width(2.0);
            ctx.stroke();
        }
        // What lies below the floor, in red: a real arm would hit the ground.
        if crate::session::below_floor(&pts) {
            drawn |= bit::FLOOR;
            ctx.set_stroke_style_str(DANGER);
            ctx.set_line_width(7.0);
            for w in pts.windows(2) {
                let (a, b) = (w[0], w[1]);
                // The part of the link a-b with y < 0.
                let cut = |p: [f64; 2], q: [f64; 2]| {
                    let s = p[1] / (p[1] - q[1]);
                    [p[0] + s * (q[0] - p[0]), 0.0]
                };
                let part = match (a[1] < 0.0, b[1] < 0.0) {
                    (true, true) => [a, b],
                    (true, false) => [a, cut(a, b)],
                    (false, true) => [cut(a, b), b],
                    _ => continue,
                };
                polyline(ctx, Some(view), &part);
            }
        }
    }

    // Ghost, on top and thinner, with a white edge so that it shows on the
    // arm where the two agree: where the numerical route would have it.
    if let Some(pts) = s.display_joints(true) {
        drawn |= bit::GHOST;
        dash(ctx, &[7.0, 5.0]);
        for (colour, width) in [(PAPER, 4.5), (GHOST, 2.0)] {
            ctx.set_global_alpha(if colour == GHOST { GHOST_ALPHA } else { 0.9 });
            ctx.set_stroke_style_str(colour);
            ctx.set_line_width(width);
            polyline(ctx, Some(view), &pts);
        }
        dash(ctx, &[]);
        for p in &pts[1..] {
            let (x, y) = view.to_px(*p);
            disc(ctx, x, y, 3.0);
            ctx.stroke();
        }
        ctx.set_global_alpha(1.0);
    }

    // Reference point on the line.
    let (rx, ry) = view.to_px(planner.sample().reference);
    disc(ctx, rx, ry, 3.0);
    ctx.set_fill_style_str(MUTED);
    ctx.fill();

    // The target is the line's: another path hides it (and its legend).
    if scene.path.is_line() {
        drawn |= bit::TARGET;
        target(ctx, view, s);
    }

    let font = format!("600 12px {FONT}");
    text(ctx, &font, INK, ("left", "top"), (12.0, 10.0), &caption);
    drawn
}

/// The target marker (at the pointer while it is dragged): a ring and a cross.
/// Each joint's range `[lo, hi]` as a thin wedge at the joint: joint `k`
/// at `P(k-1)` may turn link `k` to the absolute angles `phi_(k-1) + lo ..
/// phi_(k-1) + hi` (`phi_0 = 0`, the post; angles from the vertical towards
/// `+X1`, which is clockwise on the canvas, so a canvas angle is `phi -
/// pi/2`). The radius is a quarter of the link, kept between 10 and 26 px;
/// a dot on the arc marks the joint's angle `theta_k` now (red past a limit).
fn joint_ranges(
    ctx: &CanvasRenderingContext2d,
    view: View,
    pts: &[[f64; 2]],
    ranges: &[[f64; 2]],
    links: &[f64],
    theta: &[f64],
) {
    ctx.set_stroke_style_str(LIMIT);
    ctx.set_line_width(1.5);
    let mut phi = 0.0;
    for (i, (&[lo, hi], &length)) in ranges.iter().zip(links).enumerate() {
        let (Some(p), Some(q)) = (pts.get(i), pts.get(i + 1)) else {
            break;
        };
        let (x, y) = view.to_px(*p);
        let r = (0.25 * length * view.scale).clamp(10.0, 26.0);
        let (a, b) = (phi + lo - FRAC_PI_2, phi + hi - FRAC_PI_2);
        ctx.begin_path();
        let ((sa, ca), (sb, cb)) = (sin_cos(a), sin_cos(b));
        ctx.move_to(x + r * ca, y + r * sa);
        let _ = ctx.arc(x, y, r, a, b);
        if hi - lo < 2.0 * PI {
            ctx.move_to(x + 0.6 * r * ca, y + 0.6 * r * sa);
            ctx.line_to(x + r * ca, y + r * sa);
            ctx.move_to(x + 0.6 * r * cb, y + 0.6 * r * sb);
            ctx.line_to(x + r * cb, y + r * sb);
        }
        ctx.stroke();
        let angle = (q[0] - p[0]).atan2(q[1] - p[1]);
        // The joint's angle now: a dot on its arc, red past a limit.
        let now = theta.get(i).copied().unwrap_or(lo);
        let (sn, cn) = sin_cos(angle - FRAC_PI_2);
        disc(ctx, x + r * cn, y + r * sn, 2.5);
        ctx.set_fill_style_str(if now < lo || now > hi { DANGER } else { LIMIT });
        ctx.fill();
        phi = angle;
    }
}

fn target(ctx: &CanvasRenderingContext2d, view: View, s: &Session) {
    let (tx, ty) = view.to_px(s.target_marker());
    ctx.set_stroke_style_str(ACCENT);
    let held = s.dragging() == Some(Handle::Target);
    ctx.set_line_width(if held { 2.5 } else { 2.0 });
    disc(ctx, tx, ty, 9.0);
    ctx.stroke();
    ctx.begin_path();
    for (dx, dy) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
        ctx.move_to(tx + 4.0 * dx, ty + 4.0 * dy);
        ctx.line_to(tx + 14.0 * dx, ty + 14.0 * dy);
    }
    ctx.stroke();
}

/// Width (CSS px) of a tick label or axis name at 11 px: about 6.5 px a
/// character, a little more than system fonts' digits take (no
/// `measureText` binding in the page's module).
fn text_width(label: &str) -> f64 {
    6.5 * label.chars().count() as f64
}

/// A metric grid with labelled axes through the origin. Every label lies
/// inside the canvas with a 2 px edge: a tick label that would not is left
/// out, and so is one in the caption's place (`caption` px wide at the top
/// left); tick labels stay on the canvas when their axis leaves it, the
/// axes' names (beside their axis, away from its labels) go with it.
fn grid(ctx: &CanvasRenderingContext2d, view: View, (w, h): (f64, f64), caption: f64) {
    let lo = view.to_world(0.0, h);
    let hi = view.to_world(w, 0.0);
    let step = nice_step((hi[0] - lo[0]).min(hi[1] - lo[1]), 6.0);
    let font = format!("11px {FONT}");
    ctx.set_line_width(1.0);
    let (ax, ay) = view.to_px([0.0, 0.0]);
    let lines = |lo: f64, hi: f64| {
        let first = (lo / step).ceil() as i64;
        let last = (hi / step).floor() as i64;
        (first..=last).map(move |k| k as f64 * step)
    };
    let label = |at: (f64, f64), align: (&str, &str), s: &str| {
        text(ctx, &font, MUTED, align, at, s);
    };
    // Under the X1 axis, below the caption's row when the axis is above.
    let top = (ay + 8.0).min(h - 14.0).max(28.0);
    for x in lines(lo[0], hi[0]) {
        let (px, _) = view.to_px([x, 0.0]);
        ctx.set_stroke_style_str(if x.abs() < 1e-9 { AXIS } else { GRID });
        let px = px.round() + 0.5;
        polyline(ctx, None, &[[px, 0.0], [px, h]]);
        let tick = fmt_tick(x, step);
        let half = 0.5 * text_width(&tick);
        if x.abs() > 1e-9 && px - half >= 2.0 && px + half <= w - 2.0 {
            label((px, top), ("center", "top"), &tick);
        }
    }
    for y in lines(lo[1], hi[1]) {
        let (_, py) = view.to_px([0.0, y]);
        ctx.set_stroke_style_str(if y.abs() < 1e-9 { AXIS } else { GRID });
        let py = py.round() + 0.5;
        polyline(ctx, None, &[[0.0, py], [w, py]]);
        let tick = fmt_tick(y, step);
        let tw = text_width(&tick);
        let right = (ax - 6.0).min(w - 2.0).max(tw + 2.0);
        let on_caption = py < 30.0 && right - tw < 16.0 + caption;
        if y.abs() > 1e-9 && py >= 8.0 && py <= h - 8.0 && !on_caption {
            label((right, py), ("right", "middle"), &tick);
        }
    }
    if ay >= 20.0 && ay <= h {
        label((w - 8.0, ay - 4.0), ("right", "bottom"), "X₁ (m)");
    }
    if ax >= 0.0 && ax + 60.0 <= w {
        label((ax + 6.0, 30.0), ("left", "top"), "X₂ (m)");
    }
}
