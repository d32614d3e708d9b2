//! Where a hit is unavoidable whatever the method: the disc on the arm at
//! `t = 0` (or on the post), or on the path the hand must follow (the
//! straight line, a circle or a polyline: [`crate::scene::Path`]).

use super::Class;
use crate::error::Result;
use crate::geometry::segment_distance_squared;
use crate::kinematics::Pose;
use crate::scene::{Path, Scene};

/// Whether a link must hit `obstacle` in `scene` whatever the method:
/// [`Class::StartOverlap`] when the disc touches the arm at `t = 0` (or the
/// post), [`Class::PathBlocked`] when it covers a point of the path the
/// hand must follow (its exact distance to the segments or the circle); `None` when avoidance is possible. What the
/// atlas decides for each cell, for the page's comparison of the methods.
pub fn unavoidable(scene: &Scene, obstacle: &crate::obstacle::Obstacle) -> Option<Class> {
    PlaneGeometry::new(scene, obstacle.radius)
        .ok()
        .and_then(|g| g.classify(obstacle.centre))
}

/// The start pose and the path, which decide `start_overlap` and
/// `path_blocked` for every method at once.
#[derive(Debug, Clone)]
pub struct PlaneGeometry {
    start: Pose,
    post_top: [f64; 2],
    path: Path,
    ends: [[f64; 2]; 2],
    pub(super) radius: f64,
}

impl PlaneGeometry {
    pub(super) fn new(scene: &Scene, radius: f64) -> Result<Self> {
        let start = Pose::new(&scene.arm, &scene.theta0)?;
        let ends = [start.end_effector(), scene.target];
        Ok(Self {
            post_top: [0.0, scene.arm.post()],
            start,
            path: scene.path.clone(),
            ends,
            radius,
        })
    }

    /// `start_overlap`, `path_blocked` or neither (`None`) for a centre.
    /// "Touches" and "covers" use the planner's collision test, distance
    /// below the radius; the post as [`crate::Obstacle::validate`] does.
    pub(super) fn classify(&self, o: [f64; 2]) -> Option<Class> {
        let r2 = self.radius * self.radius;
        let post = segment_distance_squared(o, [0.0, 0.0], self.post_top);
        if post <= r2 || self.start.clearance(o) < self.radius {
            Some(Class::StartOverlap)
        } else if self.blocks(o, r2) {
            Some(Class::PathBlocked)
        } else {
            None
        }
    }

    /// Whether a disc at `o` covers a point of the path (the line by its
    /// squared distance, as the published atlases were classified).
    fn blocks(&self, o: [f64; 2], r2: f64) -> bool {
        let [a, b] = self.ends;
        match self.path {
            Path::Line => segment_distance_squared(o, a, b) < r2,
            _ => self.path.distance_to(o, a, b) < self.radius,
        }
    }
}
