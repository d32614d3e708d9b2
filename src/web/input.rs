//! Pointer and keyboard input on the stage: which handle a pointer would
//! grab, where a drag may go, and what the arrow keys do.

use super::surface::{Surface, View};
use crate::session::{Handle, Session};

/// Radius (CSS px) of the target marker a pointer grabs.
const TARGET_GRAB_PX: f64 = 10.0;
/// Radius (CSS px) around an elbow a pointer grabs.
const JOINT_GRAB_PX: f64 = 8.0;
/// Handles stay this far (CSS px) inside the canvas, so they can always be
/// picked up again.
const EDGE_PX: f64 = 8.0;

/// What a pointer at canvas CSS pixel `(x, y)` would grab, with `slop`
/// extra pixels of tolerance (0 to 64): the target before the obstacle,
/// the obstacle before an elbow (the joints between the first and the
/// hand, which drag the arm in its null space).
pub fn hit(s: &Session, view: View, x: f64, y: f64, slop: f64) -> Option<Handle> {
    if !(x.is_finite() && y.is_finite() && slop.is_finite()) {
        return None;
    }
    let slop = slop.clamp(0.0, 64.0);
    let near = |p: [f64; 2], r: f64| {
        let (px, py) = view.to_px(p);
        (px - x).hypot(py - y) <= r
    };
    // The target is the line's: hidden (and not grabbed) on another path.
    let line = s.planner().scene().path.is_line();
    if line && near(s.target_marker(), TARGET_GRAB_PX + slop) {
        return Some(Handle::Target);
    }
    if let Some(i) = obstacle_at(s, view, x, y, slop) {
        return Some(Handle::Obstacle(i));
    }
    let joints = s.planner().pose().joints();
    (1..joints.len().saturating_sub(1))
        .find(|&k| near(joints[k], JOINT_GRAB_PX + slop))
        .map(Handle::Joint)
}

/// The obstacle under canvas CSS pixel `(x, y)` with `slop` extra pixels of
/// tolerance: the one drawn last (on top) when discs overlap.
pub fn obstacle_at(s: &Session, view: View, x: f64, y: f64, slop: f64) -> Option<usize> {
    if !(x.is_finite() && y.is_finite() && slop.is_finite()) {
        return None;
    }
    let slop = slop.clamp(0.0, 64.0);
    s.obstacles().iter().rposition(|ob| {
        let (px, py) = view.to_px(ob.centre);
        (px - x).hypot(py - y) <= ob.radius * view.scale + slop
    })
}

/// The world point of canvas CSS pixel `(x, y)`, kept inside the canvas.
pub fn drag_point(surface: &Surface, view: View, x: f64, y: f64) -> [f64; 2] {
    let (w, h) = (surface.width, surface.height);
    let clamp = |v: f64, hi: f64| {
        if v.is_finite() {
            v.clamp(EDGE_PX, (hi - EDGE_PX).max(EDGE_PX))
        } else {
            v
        }
    };
    view.to_world(clamp(x, w), clamp(y, h))
}

/// A key on the focused drawing ([`key`]).
pub enum Key {
    /// An arrow: move the selected item by `(dx, dy)` steps, `fine` with Shift.
    Move { dx: f64, dy: f64, fine: bool },
    /// `n` (Shift: back): select the next item.
    Next { forward: bool },
    /// `a`: an obstacle at the middle of the view, selected.
    Add,
    /// Delete or Backspace: the selected obstacle removed.
    Remove,
}

/// What a key does on the drawing, if anything (the keyboard help in the
/// page lists the same keys).
pub fn key(key: &str, shift: bool) -> Option<Key> {
    let arrow = |dx, dy| {
        Some(Key::Move {
            dx,
            dy,
            fine: shift,
        })
    };
    match key {
        "ArrowLeft" => arrow(-1.0, 0.0),
        "ArrowRight" => arrow(1.0, 0.0),
        "ArrowUp" => arrow(0.0, 1.0),
        "ArrowDown" => arrow(0.0, -1.0),
        "n" | "N" => Some(Key::Next { forward: !shift }),
        "a" | "A" => Some(Key::Add),
        "Delete" | "Backspace" => Some(Key::Remove),
        _ => None,
    }
}
