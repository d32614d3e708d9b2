//! The keyboard's hold on the drawing: one item selected at a time (the
//! target, an obstacle, an elbow), cycled through by a key and moved by the
//! arrows in steps of [`NUDGE`] or, finer, [`FINE_NUDGE`] metres; so every
//! handle a pointer can drag, a keyboard can move (issue 27: Shift+arrows
//! moved only the first obstacle).

use super::{Handle, Session, NUDGE};
use crate::error::Result;

/// How far one arrow key with Shift moves the selected item (m).
pub const FINE_NUDGE: f64 = 0.005;
/// How far one arrow key moves the arm along a selected elbow's
/// self-motion (rad of joint-space arc), and with Shift.
const SELF_MOTION: f64 = 0.1;
const FINE_SELF_MOTION: f64 = 0.01;

impl Session {
    /// What the keys move: the target, an obstacle, or an elbow `P(k)`
    /// (`1 <= k < n`). A selection that no longer exists (its obstacle
    /// removed, the arm changed) falls back to the target.
    pub fn selected(&self) -> Handle {
        let exists = match self.selected {
            Handle::Target => true,
            Handle::Obstacle(i) => i < self.planner().scene().obstacles.len(),
            Handle::Joint(k) => k >= 1 && k < self.planner().scene().arm.dof(),
        };
        if exists {
            self.selected
        } else {
            Handle::Target
        }
    }

    /// Selects the next item (`forward`) or the one before, in the order
    /// target, obstacles, elbows, and round again; returns it.
    pub fn select_next(&mut self, forward: bool) -> Handle {
        let scene = self.planner().scene();
        let items: Vec<Handle> = std::iter::once(Handle::Target)
            .chain((0..scene.obstacles.len()).map(Handle::Obstacle))
            .chain((1..scene.arm.dof()).map(Handle::Joint))
            .collect();
        let now = self.selected();
        let at = items.iter().position(|h| *h == now).unwrap_or(0);
        let n = items.len();
        let next = if forward {
            (at + 1) % n
        } else {
            (at + n - 1) % n
        };
        self.selected = items[next];
        self.selected
    }

    /// Selects `handle` (an obstacle just added, say).
    pub fn select(&mut self, handle: Handle) {
        self.selected = handle;
    }

    /// Moves the selected item by `(dx, dy)` steps of [`NUDGE`] metres, or
    /// of [`FINE_NUDGE`] when `fine`: the target plans a new line (and
    /// runs it), an obstacle moves at once; an elbow moves the arm along
    /// its self-motion by 0.1 rad (0.01 when `fine`), the hand held. Refused, changing nothing, as a drag
    /// there would be.
    pub fn nudge_selected(&mut self, dx: f64, dy: f64, fine: bool) -> Result<()> {
        let step = if fine { FINE_NUDGE } else { NUDGE };
        match self.selected() {
            // An elbow goes along its self-motion, as the slider moves it:
            // right or up one way, left or down the other.
            Handle::Joint(k) => {
                let arc = if fine { FINE_SELF_MOTION } else { SELF_MOTION };
                self.self_motion(k, (dx + dy).signum() * arc)?;
                self.after_change();
                Ok(())
            }
            handle => self.nudge(handle, dx * step / NUDGE, dy * step / NUDGE),
        }
    }
}
