//! The time-series plots under the stage: distance to the obstacle (with
//! its radius), tracking error and joint angles (shaded beyond each joint's
//! limits, where the arm has them), each in a small panel.

use std::f64::consts::PI;

use web_sys::CanvasRenderingContext2d;

use super::style::*;
use super::surface::{dash, polyline, text, Surface};
use crate::palette::joint_series;
use std::collections::VecDeque;

use crate::session::Point;
#[cfg(feature = "page")]
use crate::session::Session;

/// Width of one key of a panel's legend (its swatch and `θ₁`), px.
const KEY_SPACING: f64 = 34.0;
/// The joints' keys as labels alone in their colours, where swatches do
/// not fit beside the title.
const LABEL_SPACING: f64 = 19.0;
/// What the short title "θ (rad)" needs beside the keys (px).
const SHORT_TITLE: f64 = 60.0;

/// How the joints' keys are drawn in the title row.
#[derive(Clone, Copy)]
enum Keys {
    Swatches,
    Labels,
}

/// Tick spacing giving about `target` ticks over `span`.
pub fn nice_step(span: f64, target: f64) -> f64 {
    let raw = (span / target).max(1e-12);
    // powi, not powf: libm's pow costs the page's module 2 KB.
    let mag = 10f64.powi(raw.log10().floor().clamp(-300.0, 300.0) as i32);
    let f = raw / mag;
    let nice = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

/// A tick label with as many decimals as the spacing needs.
pub fn fmt_tick(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).clamp(0.0, 6.0) as usize;
    let v = if v.abs() < step * 1e-6 { 0.0 } else { v };
    format!("{v:.decimals$}")
}

/// Draws the session's time series on `surface`.
#[cfg(feature = "page")]
pub fn draw(s: &Session, surface: &Surface) {
    let limits = s.arm().joint_limits().map_or(&[][..], |l| l.ranges());
    draw_points(s.history(), limits, s.planner().scene().tf, surface);
}

/// Draws a run's time series (`history`, the joints' `limits`) on
/// `surface`: clearance, tracking error, joint angles, over a time axis at
/// least `span` long (the run's `tf`).
pub fn draw_points(history: &VecDeque<Point>, limits: &[[f64; 2]], span: f64, surface: &Surface) {
    surface.begin();
    let ctx = &surface.ctx;
    let span = if span.is_finite() && span > 0.0 {
        span
    } else {
        10.0
    };
    let (t0, t1) = match (history.front(), history.back()) {
        (Some(a), Some(b)) => (a.t, b.t.max(a.t + span)),
        _ => (0.0, span),
    };
    // Three panels: side by side on a wide, short canvas, else stacked.
    let wide = surface.width >= 3.0 * surface.height;
    let (w, h) = if wide {
        (surface.width / 3.0, surface.height)
    } else {
        (surface.width, surface.height / 3.0)
    };
    let at = |k: f64| if wide { (k * w, 0.0) } else { (0.0, k * h) };
    // Clearance to the nearest obstacle's edge, as the readouts, the
    // comparison, the CSV and the atlas give it: 0 is contact, below is a
    // link inside the disc.
    let clearance: Vec<[f64; 2]> = history
        .iter()
        .filter_map(|p| p.clearance.map(|c| [p.t, c]))
        .collect();
    let (lo, hi) = clearance
        .iter()
        .fold((0.0f64, 0.1f64), |(lo, hi), p| (lo.min(p[1]), hi.max(p[1])));
    let pad = 0.05 * (hi - lo);
    let frame = Frame::new(at(0.0), w, h, (t0, t1), (lo - pad, hi + pad));
    frame.axes(ctx, "clearance to obstacle (m)");
    if !clearance.is_empty() {
        ctx.set_stroke_style_str(DANGER);
        ctx.set_line_width(1.0);
        dash(ctx, &[4.0, 3.0]);
        frame.line(ctx, &[[t0, 0.0], [t1, 0.0]]);
        dash(ctx, &[]);
        let (_, y) = frame.px(t1, 0.0);
        let font = format!("11px {FONT}");
        text(
            ctx,
            &font,
            DANGER,
            ("right", "bottom"),
            (frame.right, y - 2.0),
            "contact",
        );
    }
    frame.series(ctx, ARM, 1.75, &clearance);

    let error: Vec<[f64; 2]> = history.iter().map(|p| [p.t, p.error]).collect();
    let emax = error.iter().map(|p| p[1]).fold(1e-3, f64::max);
    let frame = Frame::new(at(1.0), w, h, (t0, t1), (0.0, emax * 1.1));
    frame.axes(ctx, "tracking error (m)");
    frame.series(ctx, ACCENT, 1.75, &error);

    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in history.iter().flat_map(|p| &p.theta) {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        (lo, hi) = (-PI, PI);
    }
    // The joints' limits, in view, each shaded beyond in its joint's colour.
    for r in limits {
        lo = lo.min(r[0]);
        hi = hi.max(r[1]);
    }
    let pad = ((hi - lo) * 0.1).max(0.1);
    let frame = Frame::new(at(2.0), w, h, (t0, t1), (lo - pad, hi + pad));
    let joints = history.front().map_or(0, |p| p.theta.len());
    // The keys share the title row with the title: where the full title
    // leaves them too little room (a narrow panel, many joints), the short
    // one; where even that does not leave room (seven joints), the keys
    // close up as labels in their colours. They never go inside the plot,
    // over the curves, nor over the title.
    let room = frame.right - frame.left - KEY_SPACING * joints as f64 - 10.0;
    let (title, keys) = if room >= 125.0 {
        ("joint angles (rad)", Keys::Swatches)
    } else if room >= SHORT_TITLE {
        ("θ (rad)", Keys::Swatches)
    } else {
        ("θ (rad)", Keys::Labels)
    };
    frame.axes(ctx, title);
    for (i, r) in limits.iter().enumerate() {
        ctx.set_fill_style_str(&rgba(joint_series(i), 0.12));
        let (_, y_hi) = frame.px(t0, r[1]);
        let (_, y_lo) = frame.px(t0, r[0]);
        let width = frame.right - frame.left;
        ctx.fill_rect(frame.left, frame.top, width, y_hi - frame.top);
        ctx.fill_rect(frame.left, y_lo, width, frame.bottom - y_lo);
    }
    for i in 0..joints {
        let colour = joint_series(i);
        frame.key(
            ctx,
            keys,
            i,
            joints,
            &format!("θ{}", subscript(i + 1)),
            colour,
        );
        let series: Vec<[f64; 2]> = history
            .iter()
            .filter_map(|p| p.theta.get(i).map(|v| [p.t, *v]))
            .collect();
        frame.series(ctx, colour, 1.5, &series);
    }
}

/// `n` in Unicode subscript digits.
fn subscript(n: usize) -> String {
    n.to_string()
        .chars()
        .map(|c| char::from_u32(0x2080 + c.to_digit(10).unwrap_or(0)).unwrap_or(c))
        .collect()
}

/// One small time-series panel.
struct Frame {
    left: f64,
    right: f64,
    top: f64,
    bottom: f64,
    tx: (f64, f64),
    vy: (f64, f64),
}

impl Frame {
    fn new((x0, y0): (f64, f64), width: f64, height: f64, tx: (f64, f64), vy: (f64, f64)) -> Self {
        let span = (vy.1 - vy.0).abs().max(1e-12);
        Self {
            left: x0 + 44.0,
            right: x0 + width - 10.0,
            top: y0 + 22.0,
            bottom: y0 + height - 18.0,
            tx,
            vy: (vy.0, vy.0 + span),
        }
    }

    fn px(&self, t: f64, v: f64) -> (f64, f64) {
        let fx = (t - self.tx.0) / (self.tx.1 - self.tx.0).max(1e-12);
        let fy = (v - self.vy.0) / (self.vy.1 - self.vy.0);
        (
            self.left + fx * (self.right - self.left),
            self.bottom - fy.clamp(-0.05, 1.05) * (self.bottom - self.top),
        )
    }

    fn axes(&self, ctx: &CanvasRenderingContext2d, title: &str) {
        let bold = format!("600 11px {FONT}");
        let small = format!("11px {FONT}");
        text(
            ctx,
            &bold,
            INK,
            ("left", "bottom"),
            (self.left, self.top - 6.0),
            title,
        );
        ctx.set_line_width(1.0);
        ctx.set_stroke_style_str(GRID);
        let step = nice_step(self.vy.1 - self.vy.0, 3.0);
        let mut v = (self.vy.0 / step).ceil() * step;
        while v <= self.vy.1 + 1e-12 {
            let (_, y) = self.px(self.tx.0, v);
            let y = y.round() + 0.5;
            polyline(ctx, None, &[[self.left, y], [self.right, y]]);
            let at = (self.left - 5.0, y);
            text(
                ctx,
                &small,
                MUTED,
                ("right", "middle"),
                at,
                &fmt_tick(v, step),
            );
            v += step;
        }
        let step = nice_step(self.tx.1 - self.tx.0, 5.0);
        let mut t = (self.tx.0 / step).ceil() * step;
        while t <= self.tx.1 + 1e-9 {
            let (x, _) = self.px(t, self.vy.0);
            if x < self.right - 34.0 {
                let at = (x, self.bottom + 3.0);
                text(
                    ctx,
                    &small,
                    MUTED,
                    ("center", "top"),
                    at,
                    &fmt_tick(t, step),
                );
            }
            t += step;
        }
        let at = (self.right, self.bottom + 3.0);
        text(ctx, &small, MUTED, ("right", "top"), at, "t (s)");
        ctx.set_stroke_style_str(AXIS);
        let corner = [
            [self.left + 0.5, self.top],
            [self.left + 0.5, self.bottom + 0.5],
            [self.right, self.bottom + 0.5],
        ];
        polyline(ctx, None, &corner);
    }

    fn line(&self, ctx: &CanvasRenderingContext2d, pts: &[[f64; 2]]) {
        let px: Vec<[f64; 2]> = pts
            .iter()
            .map(|p| {
                let (x, y) = self.px(p[0], p[1]);
                [x, y]
            })
            .collect();
        polyline(ctx, None, &px);
    }

    fn series(&self, ctx: &CanvasRenderingContext2d, colour: &str, width: f64, pts: &[[f64; 2]]) {
        ctx.set_stroke_style_str(colour);
        ctx.set_line_width(width);
        self.line(ctx, pts);
    }

    /// Entry `index` of `count` of the panel's legend, right-aligned in the
    /// title row: a swatch and its label [`KEY_SPACING`] apart, or the
    /// label alone in its colour [`LABEL_SPACING`] apart.
    fn key(
        &self,
        ctx: &CanvasRenderingContext2d,
        keys: Keys,
        index: usize,
        count: usize,
        label: &str,
        colour: &str,
    ) {
        let after = (count - 1 - index.min(count - 1)) as f64;
        let y = self.top - 12.0;
        let font = format!("11px {FONT}");
        match keys {
            Keys::Swatches => {
                let x = self.right - KEY_SPACING * after - 18.0;
                ctx.set_stroke_style_str(colour);
                ctx.set_line_width(2.0);
                polyline(ctx, None, &[[x - 16.0, y], [x - 4.0, y]]);
                text(ctx, &font, INK, ("left", "middle"), (x, y), label);
            }
            Keys::Labels => {
                let x = self.right - LABEL_SPACING * after - 18.0;
                text(ctx, &font, colour, ("left", "middle"), (x, y), label);
            }
        }
    }
}
