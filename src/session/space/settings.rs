//! The scene of a spatial session, changed by the page's controls: the
//! methods' parameters, the joint weighting, the damping, the floor, the
//! feedback gain, the path, the target and the spheres. Each change is
//! refused, changing nothing, where the scene does not validate, and runs
//! the scene again otherwise.

use super::{SpaceHandle, SpaceSession};
use crate::error::{within, Error, Result};
use crate::ik::DampingSchedule;
use crate::planner::params::by_name;
use crate::scene::{JointWeighting, SpacePath};
use crate::space::{Sphere, Vec3};

impl SpaceSession {
    /// Sets parameter `name` (as the address and the command line name
    /// it); refused, changing nothing, when unknown or out of its range.
    pub fn set_param(&mut self, name: &str, value: f64) -> Result<()> {
        let p = by_name(name)?;
        let mut scene = self.scene.clone();
        scene.params.set(p, value)?;
        self.apply(scene)
    }

    /// How the methods of eq. (5) use the joint limits.
    pub fn set_weighting(&mut self, weighting: JointWeighting) -> Result<()> {
        let mut scene = self.scene.clone();
        scene.weighting = weighting;
        self.apply(scene)
    }

    /// Whether the damping schedule near singular poses is on (the
    /// planar page's switch: the schedule's defaults, or none).
    pub fn set_damping(&mut self, on: bool) -> Result<()> {
        let mut scene = self.scene.clone();
        scene.damping = on.then(DampingSchedule::default);
        self.apply(scene)
    }

    /// Makes `path` the one the hand follows (the line to the target, a
    /// circle, a polyline typed or drawn: [`SpacePath`]); refused,
    /// changing nothing, when the scene refuses it (a circle with no
    /// plane through the hand's start, say).
    pub fn set_path(&mut self, path: SpacePath) -> Result<()> {
        let mut scene = self.scene.clone();
        scene.path = path;
        self.apply(scene)
    }

    /// The run's start pose (rad; the address's `theta0`, what self-motion
    /// leaves); refused, changing nothing, when it does not fit the chain
    /// or lies past a joint's limit.
    pub fn set_start(&mut self, theta0: &[f64]) -> Result<()> {
        let mut scene = self.scene.clone();
        scene.theta0 = theta0.to_vec();
        self.apply(scene)?;
        self.index = 0;
        self.show(0);
        Ok(())
    }

    /// Whether the floor `z = 0` is an obstacle.
    pub fn set_floor(&mut self, floor: bool) -> Result<()> {
        let mut scene = self.scene.clone();
        scene.floor = floor;
        self.apply(scene)
    }

    /// The closed-loop gain `K` (1/s; 0: the paper's open loop).
    pub fn set_feedback(&mut self, gain: f64) -> Result<()> {
        within("feedback gain", gain, 0.0, 100.0)?;
        let mut scene = self.scene.clone();
        scene.feedback_gain = gain;
        self.apply(scene)
    }

    /// The end of the hand's line (m); refused, changing nothing, where
    /// the scene does not validate.
    pub fn set_target(&mut self, target: Vec3) -> Result<()> {
        let mut scene = self.scene.clone();
        scene.target = target;
        self.apply(scene)
    }

    /// Moves sphere `i` to `centre`, its radius kept.
    pub fn move_sphere(&mut self, i: usize, centre: Vec3) -> Result<()> {
        let mut scene = self.scene.clone();
        let n = scene.obstacles.len();
        let s = scene.obstacles.get_mut(i).ok_or_else(|| no_sphere(i, n))?;
        s.centre = centre;
        self.apply(scene)
    }

    /// Replaces the spheres by `flat` (`[x, y, z, r, ...]`, m).
    pub fn set_spheres(&mut self, flat: &[f64]) -> Result<()> {
        let mut scene = self.scene.clone();
        scene.obstacles = Sphere::from_flat(flat)?;
        self.apply(scene)
    }

    /// Adds a sphere of radius `r` at `centre`; returns its index.
    pub fn add_sphere(&mut self, centre: Vec3, r: f64) -> Result<usize> {
        let mut flat: Vec<f64> = self.flat_spheres();
        flat.extend_from_slice(&[centre[0], centre[1], centre[2], r]);
        self.set_spheres(&flat)?;
        let i = self.scene.obstacles.len() - 1;
        self.selected = SpaceHandle::Sphere(i);
        Ok(i)
    }

    /// Removes sphere `i`.
    pub fn remove_sphere(&mut self, i: usize) -> Result<()> {
        if i >= self.scene.obstacles.len() {
            return Err(no_sphere(i, self.scene.obstacles.len()));
        }
        let mut scene = self.scene.clone();
        scene.obstacles.remove(i);
        self.apply(scene)?;
        self.selected = SpaceHandle::Target;
        Ok(())
    }

    /// The spheres as `[x, y, z, r, ...]`.
    pub fn flat_spheres(&self) -> Vec<f64> {
        self.scene
            .obstacles
            .iter()
            .flat_map(|s| [s.centre[0], s.centre[1], s.centre[2], s.radius])
            .collect()
    }
}

/// Sphere `i` (from 0) asked of a scene of `n`.
fn no_sphere(i: usize, n: usize) -> Error {
    Error::OutOfRange {
        what: "sphere number".into(),
        value: (i + 1) as f64,
        min: 1.0,
        max: n as f64,
    }
}
