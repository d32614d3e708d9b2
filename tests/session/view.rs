//! The stage's view (`redundant_ik::view`): the world box it holds, the fit
//! of that box on a canvas, and the user's zoom.

use super::*;
use redundant_ik::view::{bounds, Camera, View, ZOOM};
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// Canvas sizes (CSS px) of the page: a phone, a 1024 and a 1366 laptop,
/// a 1920 screen, 150% zoom on the laptop, and a tall narrow one.
const SIZES: [(f64, f64); 6] = [
    (368.0, 289.0),
    (656.0, 461.0),
    (998.0, 461.0),
    (1552.0, 648.0),
    (542.0, 307.0),
    (300.0, 900.0),
];

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn a_fit_holds_the_box_inside_a_margin_centred_at_one_scale() {
    for bounds in [
        [-2.05, 2.05, 0.0, 2.55],
        [-0.3, 4.0, -0.5, 0.7],
        [0.0, 1.0, 0.0, 3.0],
    ] {
        let [x0, x1, y0, y1] = bounds;
        for (w, h) in SIZES {
            let v = View::fit(w, h, bounds);
            let (l, t) = v.to_px([x0, y1]);
            let (r, b) = v.to_px([x1, y0]);
            // Inside, with the margin (12 px at least), the caption's room
            // (14 px more above) and the floor's labels' (16 px more below).
            assert!(
                l >= 12.0 - 1e-9 && r <= w - 12.0 + 1e-9,
                "{bounds:?} on {w}x{h}: x {l}..{r}"
            );
            assert!(
                t >= 26.0 - 1e-9 && b <= h - 28.0 + 1e-9,
                "{bounds:?} on {w}x{h}: y {t}..{b}"
            );
            // Centred: the box's middle at the middle of the room.
            assert!(close(0.5 * (l + r), 0.5 * w, 1e-9), "centred across");
            assert!(
                close(0.5 * (t + b), 0.5 * (h - 16.0 + 14.0), 1e-9),
                "centred down"
            );
            // One scale: the box keeps its aspect; it fills one way.
            assert!(
                close((r - l) / (b - t), (x1 - x0) / (y1 - y0), 1e-9),
                "aspect kept"
            );
            // It fills the room one way: the margins across or down are the least.
            let m = (0.05 * w.min(h)).clamp(12.0, 32.0);
            let fills = close(l, m, 1e-6) || close(t, m + 14.0, 1e-6);
            assert!(
                fills,
                "{bounds:?} on {w}x{h}: fills the room across or down"
            );
            // The inverse map.
            let p = v.to_world(l, t);
            assert!(close(p[0], x0, 1e-9) && close(p[1], y1, 1e-9));
        }
    }
}

#[test]
fn the_box_holds_the_whole_reach_the_floor_the_obstacles_the_target_and_the_path() {
    let mut s = Session::new(1).unwrap();
    let arm = s.planner().scene().arm.clone();
    let r = arm.max_reach();
    let [x0, x1, y0, y1] = bounds(&s);
    assert_eq!(
        [x0, x1, y0, y1],
        [-r, r, 0.0, arm.post() + r],
        "the paper's arm: its reach above the floor"
    );
    // The tester's target above the old view (y = 1.95) is inside.
    s.set_target([0.6, 2.2], None).unwrap();
    let b = bounds(&s);
    assert!(b[3] >= 2.2 && b[0] <= -2.0, "{b:?}");
    // A target out of reach, and an obstacle far away, grow it.
    s.set_target([2.6, 0.4], None).unwrap();
    s.add_obstacle(Obstacle::new(-2.5, 3.0, 0.1)).unwrap();
    let b = bounds(&s);
    assert!(b[1] >= 2.6 && b[0] <= -2.6 && b[3] >= 3.1, "{b:?}");
}

#[test]
fn a_zoom_keeps_the_point_under_the_pointer_within_its_bounds_and_fit_restores() {
    let s = Session::new(1).unwrap();
    let size = (998.0, 461.0);
    let camera = Camera::default();
    let fitted = camera.view(&s, size);
    assert_eq!(fitted, View::fit(size.0, size.1, bounds(&s)));
    let at = (300.0, 120.0);
    let p = fitted.to_world(at.0, at.1);
    assert!(close(camera.move_view(&s, size, (at, at), 2.0), 2.0, 1e-12));
    let zoomed = camera.view(&s, size);
    let (x, y) = zoomed.to_px(p);
    assert!(
        close(x, at.0, 1e-9) && close(y, at.1, 1e-9),
        "the point stays under the pointer"
    );
    assert!(close(zoomed.scale, 2.0 * fitted.scale, 1e-9));
    // Held within ZOOM of the fit; a bad factor changes nothing.
    assert_eq!(camera.move_view(&s, size, (at, at), 1e6), ZOOM[1]);
    assert_eq!(camera.move_view(&s, size, (at, at), 1e-6), ZOOM[0]);
    assert_eq!(camera.move_view(&s, size, (at, at), f64::NAN), ZOOM[0]);
    assert_eq!(camera.move_view(&s, size, (at, at), -2.0), ZOOM[0]);
    let nowhere = (f64::INFINITY, 0.0);
    assert_eq!(camera.move_view(&s, size, (nowhere, at), 2.0), ZOOM[0]);
    // A pan: factor 1 moves everything by the pointer's pixels.
    let (x, y) = camera.view(&s, size).to_px([0.0, 0.0]);
    camera.move_view(&s, size, ((5.0, 5.0), (15.0, 0.0)), 1.0);
    let (x2, y2) = camera.view(&s, size).to_px([0.0, 0.0]);
    assert!(
        close(x2 - x, 10.0, 1e-9) && close(y2 - y, -5.0, 1e-9),
        "a pan moves by its pixels"
    );
    camera.fit();
    assert_eq!(camera.view(&s, size), fitted);
}

#[test]
fn the_fit_follows_the_scene_unless_the_user_zoomed_and_holds_during_a_drag() {
    let mut s = Session::new(1).unwrap();
    let size = (656.0, 461.0);
    let camera = Camera::default();
    let first = camera.view(&s, size);
    // A target out of reach: the fit makes room for it.
    s.set_target([3.0, 0.5], None).unwrap();
    let grown = camera.view(&s, size);
    assert!(grown.scale < first.scale, "re-fitted to the new target");
    assert_eq!(grown, View::fit(size.0, size.1, bounds(&s)));
    // While the obstacle is dragged the view holds; after the drop it fits.
    s.drag_start(Some(Handle::Obstacle(0)));
    s.drag_to([-2.8, 1.0]).unwrap();
    assert_eq!(
        camera.view(&s, size),
        grown,
        "nothing moves under the pointer"
    );
    s.drag_end([-2.8, 1.0]).unwrap();
    assert_eq!(camera.view(&s, size), View::fit(size.0, size.1, bounds(&s)));
    // Zoomed, the view stays when the scene changes.
    camera.move_view(&s, size, ((100.0, 100.0), (100.0, 100.0)), 3.0);
    let zoomed = camera.view(&s, size);
    s.set_target([0.9, 0.3], None).unwrap();
    assert_eq!(camera.view(&s, size), zoomed, "the user's view is kept");
    // A new canvas size fits again.
    let wide = (900.0, 461.0);
    assert_eq!(camera.view(&s, wide), View::fit(wide.0, wide.1, bounds(&s)));
}
