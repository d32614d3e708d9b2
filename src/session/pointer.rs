//! The pointer and the keys: grabbing, dragging and dropping the target
//! (a new line from the hand) and the obstacles (moved at once), and the
//! arrow keys.

use super::Session;
use crate::error::{finite, Result};

/// Speed (m/s) of the straight line planned when the user drops the target.
pub const DRAG_LINE_SPEED: f64 = 0.25;
/// Shortest line planned after a drag (s).
pub const MIN_LINE_DURATION: f64 = 1.0;
/// How far one arrow key moves the target or the obstacle (m).
pub const NUDGE: f64 = 0.05;

/// What the pointer holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Handle {
    /// The target of the straight line.
    Target,
    /// Obstacle `i`.
    Obstacle(usize),
}

impl Handle {
    /// `"target"` or `"obstacle"`.
    pub fn name(self) -> &'static str {
        match self {
            Handle::Target => "target",
            Handle::Obstacle(_) => "obstacle",
        }
    }
}

impl Session {
    /// Plans a new straight line from the current end effector to `target`,
    /// lasting `duration` seconds (default: at [`DRAG_LINE_SPEED`], at least
    /// [`MIN_LINE_DURATION`]).
    pub fn set_target(&mut self, target: [f64; 2], duration: Option<f64>) -> Result<()> {
        let duration = match duration {
            Some(d) => d,
            None => {
                let ee = self.planner().sample().ee;
                let dist = (target[0] - ee[0]).hypot(target[1] - ee[1]);
                (dist / DRAG_LINE_SPEED).max(MIN_LINE_DURATION)
            }
        };
        self.twin.apply(|p| p.set_target(target, duration))?;
        self.histories.clear_strobe();
        Ok(())
    }

    /// What the pointer holds.
    pub fn dragging(&self) -> Option<Handle> {
        self.drag
    }

    /// Where the target marker is: at the pointer while it is dragged.
    pub fn target_marker(&self) -> [f64; 2] {
        match (self.drag, self.drag_point) {
            (Some(Handle::Target), Some(p)) => p,
            _ => self.planner().scene().target,
        }
    }

    /// Grabs a handle (or nothing).
    pub fn drag_start(&mut self, handle: Option<Handle>) {
        self.drag = handle;
        self.drag_point = None;
    }

    /// Moves the held handle to `point`: the obstacle at once (refused on
    /// the post), the target only as a marker until [`Session::drag_end`].
    pub fn drag_to(&mut self, point: [f64; 2]) -> Result<()> {
        match self.drag {
            Some(Handle::Target) => {
                finite("pointer x", point[0])?;
                finite("pointer y", point[1])?;
                self.drag_point = Some(point);
                Ok(())
            }
            Some(Handle::Obstacle(i)) => self.move_obstacle(i, point),
            None => Ok(()),
        }
    }

    /// Ends a drag at `point`. Releasing the target plans a new straight line
    /// from the current end effector and starts the clock.
    pub fn drag_end(&mut self, point: [f64; 2]) -> Result<()> {
        let moved = self.drag_to(point);
        let handle = self.drag.take();
        let point = self.drag_point.take();
        moved?;
        if let (Some(Handle::Target), Some(p)) = (handle, point) {
            self.set_target(p, None)?;
            self.stop_at = None;
            self.set_running(true);
        }
        Ok(())
    }

    /// Abandons a drag: the target stays where it was.
    pub fn drag_cancel(&mut self) {
        self.drag = None;
        self.drag_point = None;
    }

    /// Moves the target (planning a new line and starting the clock) or the
    /// obstacle by `(dx, dy)` steps of [`NUDGE`] metres: the arrow keys.
    pub fn nudge(&mut self, handle: Handle, dx: f64, dy: f64) -> Result<()> {
        let scene = self.planner().scene();
        let at = match handle {
            Handle::Target => scene.target,
            Handle::Obstacle(i) => match scene.obstacles.get(i) {
                Some(o) => o.centre,
                None => return Ok(()),
            },
        };
        let to = [at[0] + dx * NUDGE, at[1] + dy * NUDGE];
        match handle {
            Handle::Target => {
                self.set_target(to, None)?;
                self.set_running(true);
                Ok(())
            }
            Handle::Obstacle(i) => self.move_obstacle(i, to),
        }
    }
}
