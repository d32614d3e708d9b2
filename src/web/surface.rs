//! A canvas with its 2-D context and the few drawing helpers the renderers
//! share (the stage's world-to-pixel [`View`] is the core's, `crate::view`).

use std::f64::consts::PI;

use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{CanvasRenderingContext2d, HtmlCanvasElement};

use super::style::PAPER;
use crate::error::{positive, within};
pub use crate::view::View;

/// Largest canvas side accepted from the page (device pixels).
const MAX_CANVAS_PX: f64 = 8192.0;

/// A canvas and its 2-D context, with its size in CSS pixels.
pub struct Surface {
    canvas: HtmlCanvasElement,
    pub ctx: CanvasRenderingContext2d,
    pub width: f64,
    pub height: f64,
    dpr: f64,
}

impl Surface {
    pub fn new(canvas: HtmlCanvasElement) -> Result<Self, JsError> {
        let ctx = canvas
            .get_context("2d")
            .ok()
            .flatten()
            .and_then(|c| c.dyn_into::<CanvasRenderingContext2d>().ok())
            .ok_or_else(|| JsError::new("this browser gives no 2-D canvas context"))?;
        let width = f64::from(canvas.client_width().max(1));
        let height = f64::from(canvas.client_height().max(1));
        let mut s = Self {
            canvas,
            ctx,
            width,
            height,
            dpr: 1.0,
        };
        s.resize(width, height, 1.0)?;
        Ok(s)
    }

    /// Sets the size in CSS pixels and the device-pixel ratio; the backing store
    /// gets `size * dpr` pixels, so lines stay sharp on high-DPI screens.
    pub fn resize(&mut self, width: f64, height: f64, dpr: f64) -> Result<(), JsError> {
        let err = |e: crate::Error| JsError::new(&format!("canvas {e}"));
        positive("width", width).map_err(err)?;
        positive("height", height).map_err(err)?;
        within("device pixel ratio", dpr, 1e-3, 1e3).map_err(err)?;
        let dpr = dpr.min(4.0);
        let w = (width * dpr).round().clamp(1.0, MAX_CANVAS_PX);
        let h = (height * dpr).round().clamp(1.0, MAX_CANVAS_PX);
        self.canvas.set_width(w as u32);
        self.canvas.set_height(h as u32);
        self.width = w / dpr;
        self.height = h / dpr;
        self.dpr = dpr;
        Ok(())
    }

    /// This surface with `k` CSS pixels to its unit (`k > 1`: projector
    /// mode): what is drawn in pixels (lines, text, markers) comes out `k`
    /// times larger, and a view [`View::magnified`] by `k` keeps the world
    /// where it was.
    #[cfg(feature = "page")]
    pub fn magnified(&self, k: f64) -> Surface {
        Surface {
            canvas: self.canvas.clone(),
            ctx: self.ctx.clone(),
            width: self.width / k,
            height: self.height / k,
            dpr: self.dpr * k,
        }
    }

    /// Clears to white and sets the CSS-pixel transform.
    pub fn begin(&self) {
        let c = &self.ctx;
        let _ = c.set_transform(self.dpr, 0.0, 0.0, self.dpr, 0.0, 0.0);
        c.set_global_alpha(1.0);
        c.set_fill_style_str(PAPER);
        c.fill_rect(0.0, 0.0, self.width, self.height);
        c.set_line_cap("round");
        c.set_line_join("round");
    }

    /// Clears to transparent (an overlay over another drawing) and sets
    /// the CSS-pixel transform.
    pub fn begin_clear(&self) {
        let c = &self.ctx;
        let _ = c.set_transform(self.dpr, 0.0, 0.0, self.dpr, 0.0, 0.0);
        c.set_global_alpha(1.0);
        c.clear_rect(0.0, 0.0, self.width, self.height);
        c.set_line_cap("round");
        c.set_line_join("round");
    }
}

pub fn dash(ctx: &CanvasRenderingContext2d, pattern: &[f64]) {
    let arr = js_sys::Array::new();
    for v in pattern {
        arr.push(&JsValue::from_f64(*v));
    }
    let _ = ctx.set_line_dash(&arr);
}

/// Strokes a polyline through points given in world (`view`) or pixel
/// (`None`) coordinates.
pub fn polyline<'a>(
    ctx: &CanvasRenderingContext2d,
    view: Option<View>,
    pts: impl IntoIterator<Item = &'a [f64; 2]>,
) {
    ctx.begin_path();
    for (i, p) in pts.into_iter().enumerate() {
        let (x, y) = view.map_or((p[0], p[1]), |v| v.to_px(*p));
        if i == 0 {
            ctx.move_to(x, y);
        } else {
            ctx.line_to(x, y);
        }
    }
    ctx.stroke();
}

pub fn disc(ctx: &CanvasRenderingContext2d, x: f64, y: f64, r: f64) {
    ctx.begin_path();
    let _ = ctx.arc(x, y, r.max(0.0), 0.0, 2.0 * PI);
}

/// Writes `text` at `(x, y)` with a font, colour and alignment.
pub fn text(
    ctx: &CanvasRenderingContext2d,
    font: &str,
    colour: &str,
    align: (&str, &str),
    at: (f64, f64),
    text: &str,
) {
    ctx.set_font(font);
    ctx.set_fill_style_str(colour);
    ctx.set_text_align(align.0);
    ctx.set_text_baseline(align.1);
    let _ = ctx.fill_text(text, at.0, at.1);
}
