//! The pointer and the keys: a path drawn (or typed), grabbing, dragging
//! and dropping the target (a new line from the hand) and the obstacles
//! (moved at once), and the arrow keys.

use super::Session;
use crate::error::{finite, positive, Result};
use crate::planner::Planner;

/// Speed (m/s) of the straight line planned when the user drops the target.
pub const DRAG_LINE_SPEED: f64 = 0.25;
/// Shortest line planned after a drag (s).
pub const MIN_LINE_DURATION: f64 = 1.0;
/// How far one arrow key moves the selected item (m; `keys.rs`).
pub const NUDGE: f64 = 0.05;

/// `point` rounded to the millimetre (a non-finite coordinate stays so, for
/// the checks that refuse it).
fn to_mm(point: [f64; 2]) -> [f64; 2] {
    point.map(|v| (v * 1000.0).round() / 1000.0)
}

/// What the pointer holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Handle {
    /// The target of the straight line.
    Target,
    /// Obstacle `i`.
    Obstacle(usize),
    /// The elbow `P(k)` (`1 <= k < n`): dragging it moves the arm in the
    /// null space, the hand holding still (`super::self_motion`).
    Joint(usize),
}

impl Handle {
    /// `"target"`, `"obstacle"` or `"joint"`.
    pub fn name(self) -> &'static str {
        match self {
            Handle::Target => "target",
            Handle::Obstacle(_) => "obstacle",
            Handle::Joint(_) => "joint",
        }
    }
}

impl Session {
    /// Plans a new run: a straight line from the current end effector to
    /// `target` (the path becomes the line), lasting `duration` seconds (default: at
    /// [`DRAG_LINE_SPEED`], at least [`MIN_LINE_DURATION`]; rounded up to
    /// whole steps). The run's scene starts from the pose the arm has now
    /// at `t = 0` and ends with the line (`tf`), so it is a scene like any
    /// other: [`Session::reset`] goes back to where the line began, and
    /// `redundant-ik simulate` replays it from the page's file. Paused at
    /// `t = 0`, histories and readouts cleared; refused, changing nothing,
    /// on a bad target or duration.
    pub fn set_target(&mut self, target: [f64; 2], duration: Option<f64>) -> Result<()> {
        let p = self.planner();
        let duration = match duration {
            Some(d) => d,
            None => {
                let ee = p.sample().ee;
                let dist = (target[0] - ee[0]).hypot(target[1] - ee[1]);
                (dist / DRAG_LINE_SPEED).max(MIN_LINE_DURATION)
            }
        };
        positive("line duration", duration)?;
        let mut scene = p.scene().clone();
        scene.theta0 = p.theta().as_slice().to_vec();
        scene.target = target;
        // A new target is a new line, whatever the path was.
        scene.path = crate::scene::Path::Line;
        scene.tf = (duration / scene.dt - 1e-9).ceil().max(1.0) * scene.dt;
        let planner = Planner::new(scene, p.method(), p.networks().cloned())?;
        self.twin.replace(planner);
        self.own_start = true;
        self.restart();
        Ok(())
    }

    /// Starts the run from the pose `theta0` and ends it at `tf` (the
    /// page's address of a run whose line was dropped from another pose),
    /// paused at `t = 0`; refused, changing nothing, on a bad pose or time.
    pub fn set_start(&mut self, theta0: Vec<f64>, tf: f64) -> Result<()> {
        let p = self.planner();
        let mut scene = p.scene().clone();
        scene.theta0 = theta0;
        scene.tf = tf;
        let planner = Planner::new(scene, p.method(), p.networks().cloned())?;
        self.twin.replace(planner);
        self.own_start = true;
        self.restart();
        Ok(())
    }

    /// Makes `path` the one the hand follows (a line, a circle, a polyline
    /// drawn on the stage or typed: [`crate::scene::Path`]), from the run's
    /// start over its `tf`, and runs it from `t = 0` to the end; refused,
    /// changing nothing, when the scene refuses it (a circle centred on the
    /// hand's start).
    pub fn set_path(&mut self, path: crate::scene::Path) -> Result<()> {
        let p = self.planner();
        let mut scene = p.scene().clone();
        scene.path = path;
        let planner = Planner::new(scene, p.method(), p.networks().cloned())?;
        self.twin.replace(planner);
        self.restart();
        self.run_to_end();
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
    /// the post), an elbow toward it in the null space (the arm's new
    /// start), the target only as a marker until [`Session::drag_end`].
    ///
    /// The target and the obstacles land on the millimetre (a pixel of the
    /// drawing is 2 to 10 mm): the page's links and messages then quote
    /// `0.8`, not `0.7999998728434248`, and reproduce the scene exactly.
    pub fn drag_to(&mut self, point: [f64; 2]) -> Result<()> {
        match self.drag {
            Some(Handle::Target) => {
                finite("pointer x", point[0])?;
                finite("pointer y", point[1])?;
                self.drag_point = Some(to_mm(point));
                Ok(())
            }
            Some(Handle::Obstacle(i)) => self.place_obstacle(i, to_mm(point)),
            Some(Handle::Joint(k)) => self.drag_joint(k, point),
            None => Ok(()),
        }
    }

    /// Ends a drag at `point`. Releasing the target plans a new run (a
    /// straight line from the current end effector) and starts the clock;
    /// releasing an obstacle in a run that has ended replays the run.
    pub fn drag_end(&mut self, point: [f64; 2]) -> Result<()> {
        let moved = self.drag_to(point);
        let handle = self.drag.take();
        let point = self.drag_point.take();
        moved?;
        match (handle, point) {
            (Some(Handle::Target), Some(p)) => {
                self.set_target(p, None)?;
                self.set_running(true);
            }
            (Some(Handle::Obstacle(_) | Handle::Joint(_)), _) => self.after_change(),
            _ => {}
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
            Handle::Joint(_) => return Ok(()),
        };
        let to = [at[0] + dx * NUDGE, at[1] + dy * NUDGE];
        match handle {
            Handle::Target => {
                self.set_target(to, None)?;
                self.set_running(true);
                Ok(())
            }
            Handle::Obstacle(i) => self.move_obstacle(i, to),
            Handle::Joint(_) => Ok(()),
        }
    }
}
