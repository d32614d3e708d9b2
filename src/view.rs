//! What the page's stage shows: the world box that holds the arm's whole
//! reach with the floor, the obstacles, the target and the path
//! ([`bounds`]), the world-to-pixel map that fits it on a canvas
//! ([`View::fit`]), and the user's zoom and pan ([`Camera`]). Plain
//! geometry, tested natively; the page's module draws, hit-tests and
//! answers `worldToCanvas` through the one [`View`] a [`Camera`] gives.

use std::cell::Cell;

use crate::session::Session;

/// The zoom the user may choose, as multiples of the fitted scale.
pub const ZOOM: [f64; 2] = [0.5, 8.0];
/// Extra room (CSS px) below the box, for the floor's tick labels, and
/// above it, for the caption.
const BELOW_PX: f64 = 16.0;
const ABOVE_PX: f64 = 14.0;

/// A world-to-canvas map (CSS pixels, y up in the world, down on the
/// canvas), one scale for both axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Pixels per metre.
    pub scale: f64,
    ox: f64,
    oy: f64,
}

impl View {
    /// The same map on a surface of `k` CSS pixels to its unit
    /// (`web::surface::Surface::magnified`): the world lands on the same
    /// pixels.
    pub fn magnified(self, k: f64) -> View {
        View {
            scale: self.scale / k,
            ox: self.ox / k,
            oy: self.oy / k,
        }
    }

    /// The view that shows the world box `[x0, x1, y0, y1]` (metres) whole
    /// on a `width` x `height` canvas, centred, at one scale for both axes,
    /// inside a margin: a twentieth of the smaller side (12 to 32 px) all
    /// round, 16 px more below for the floor's tick labels and 14 px more
    /// above for the caption.
    pub fn fit(width: f64, height: f64, bounds: [f64; 4]) -> Self {
        let [x0, x1, y0, y1] = bounds;
        let m = (0.05 * width.min(height)).clamp(12.0, 32.0);
        let room = |side: f64, margin: f64| (side - margin).max(1.0);
        let scale = (room(width, 2.0 * m) / (x1 - x0).max(1e-3))
            .min(room(height, 2.0 * m + BELOW_PX + ABOVE_PX) / (y1 - y0).max(1e-3));
        let centre = [0.5 * (x0 + x1), 0.5 * (y0 + y1)];
        let middle = 0.5 * (height - BELOW_PX + ABOVE_PX);
        Self::at(scale, centre, (0.5 * width, middle))
    }

    /// The view at `scale` (px per metre) that puts the world point `p` at
    /// canvas pixel `at`.
    pub fn at(scale: f64, p: [f64; 2], at: (f64, f64)) -> Self {
        Self {
            scale,
            ox: at.0 - scale * p[0],
            oy: at.1 + scale * p[1],
        }
    }

    /// The canvas pixel of the world point `p`.
    pub fn to_px(self, p: [f64; 2]) -> (f64, f64) {
        (self.ox + self.scale * p[0], self.oy - self.scale * p[1])
    }

    /// The world point of canvas pixel `(x, y)`.
    pub fn to_world(self, x: f64, y: f64) -> [f64; 2] {
        [(x - self.ox) / self.scale, (self.oy - y) / self.scale]
    }
}

/// The world box `[x0, x1, y0, y1]` (metres) the stage shows whole: the
/// disc the hand can reach about the post's top, cut at the floor `y = 0`
/// (the post and the floor below it), grown to hold every obstacle and the
/// path (the line's ends: the target).
pub fn bounds(s: &Session) -> [f64; 4] {
    let scene = s.planner().scene();
    let (post, r) = (scene.arm.post(), scene.arm.max_reach());
    let mut b = [-r, r, 0.0, post + r];
    let mut hold = |p: [f64; 2], pad: f64| {
        b = [
            b[0].min(p[0] - pad),
            b[1].max(p[0] + pad),
            b[2].min(p[1] - pad),
            b[3].max(p[1] + pad),
        ];
    };
    for ob in &scene.obstacles {
        hold(ob.centre, ob.radius);
    }
    for p in s.planner().outline() {
        hold(p, 0.0);
    }
    b
}

#[derive(Clone, Copy)]
struct Shown {
    view: View,
    /// The fitted view's scale (px per metre).
    fit: f64,
    /// What the fit was made for: the scene's revision and the canvas size.
    key: (u64, f64, f64),
    zoomed: bool,
}

/// The stage's view: fitted to [`bounds`] until the user zooms or pans
/// ([`Camera::move_view`]), then the user's until [`Camera::fit`]. The fit
/// is made again when the canvas size or the scene (its revision) changes,
/// except while a handle is dragged (nothing under the pointer moves); a
/// zoomed view keeps its place when the scene changes, not when the
/// canvas is resized.
#[derive(Default)]
pub struct Camera(Cell<Option<Shown>>);

impl Camera {
    /// The view of session `s` on a canvas of `size` CSS pixels.
    pub fn view(&self, s: &Session, size: (f64, f64)) -> View {
        self.shown(s, size).view
    }

    fn shown(&self, s: &Session, (w, h): (f64, f64)) -> Shown {
        let key = (s.revision().scene, w, h);
        let old = self.0.get();
        // The same size: the user's view stays, and so does the fit
        // while a handle is dragged.
        let kept = old.filter(|c| (c.key.1, c.key.2) == (w, h));
        if let Some(c) = kept.filter(|c| c.key == key || s.dragging().is_some()) {
            return c;
        }
        let fitted = View::fit(w, h, bounds(s));
        let zoomed = kept.filter(|c| c.zoomed);
        let shown = Shown {
            view: zoomed.map_or(fitted, |c| c.view),
            fit: fitted.scale,
            key,
            zoomed: zoomed.is_some(),
        };
        self.0.set(Some(shown));
        shown
    }

    /// Moves the view so that the world point at canvas pixel `from` comes
    /// to pixel `to`, zoomed by `factor` (kept within [`ZOOM`] of the
    /// fitted scale): the wheel's zoom about the pointer (`from == to`), a
    /// drag's pan (`factor == 1`), two fingers' both. Returns the zoom
    /// now; numbers that are not finite change nothing. The view is the
    /// user's from then on.
    pub fn move_view(
        &self,
        s: &Session,
        size: (f64, f64),
        (from, to): ((f64, f64), (f64, f64)),
        factor: f64,
    ) -> f64 {
        let c = self.shown(s, size);
        let zoom = (c.view.scale * factor / c.fit).clamp(ZOOM[0], ZOOM[1]);
        let view = View::at(zoom * c.fit, c.view.to_world(from.0, from.1), to);
        if !(view.ox + view.oy + view.scale).is_finite() {
            return c.view.scale / c.fit;
        }
        self.0.set(Some(Shown {
            view,
            zoomed: true,
            ..c
        }));
        zoom
    }

    /// Back to the fitted view (the "Fit" button, the `0` key).
    pub fn fit(&self) {
        self.0.set(None);
    }
}
