//! A run of an arm in space: a chain, a start pose, the hand's path (the
//! straight line, a circle or a polyline), spheres and the integration
//! settings; the methods' parameters are
//! the planar scene's ([`Params`]), read by the same declarations.

use super::{JointWeighting, Params, Scene, SpacePath};
use crate::error::{coordinate, Error, Result};
use crate::space::{Chain, SpacePose, SpacePreset, Sphere, Vec3, MAX_SPHERES};

/// Everything that defines one run of an arm in space: the one [`Scene`]
/// of a chain, whose hand has three coordinates and follows a
/// [`SpacePath`] past spheres.
pub type SpaceScene = Scene<Chain, SpacePath, 3>;

/// Where a robot's own line ends for a hand at `start`: 0.15 m along `y`.
pub fn own_line_end(start: Vec3) -> Vec3 {
    [start[0], start[1] + 0.15, start[2]]
}

impl SpaceScene {
    /// The preset's own task: its ready pose, line and sphere, `dt = 0.05
    /// s`, `tf = 5 s`, every parameter at its default.
    pub fn preset(p: &SpacePreset) -> Self {
        let [x, y, z, r] = p.task.sphere;
        Self::line(
            p.chain(),
            p.task.theta0.to_vec(),
            p.task.target,
            vec![Sphere::new([x, y, z], r)],
        )
    }

    /// A robot's own line: from `theta0` to `target` past `obstacles`,
    /// `dt = 0.05 s`, `tf = 5 s`, every parameter at its default.
    fn line(arm: Chain, theta0: Vec<f64>, target: Vec3, obstacles: Vec<Sphere>) -> Self {
        Self {
            arm,
            theta0,
            target,
            path: SpacePath::Line,
            obstacles,
            damping: None,
            dt: 0.05,
            tf: 5.0,
            feedback_gain: 0.0,
            params: Params::default(),
            weighting: JointWeighting::None,
            floor: false,
        }
    }

    /// The own task of a robot that has none of its own (a chain read from
    /// URDF, by the command line or in the page): it starts at the middle
    /// of its joints' ranges (each within +-pi; zero without limits), its
    /// hand's line runs 0.15 m along `y` ([`own_line_end`]), no sphere,
    /// `dt = 0.05 s`, `tf = 5 s`, every parameter at its default. Refused
    /// where that start is not a pose of the chain.
    pub fn own(arm: Chain) -> Result<Self> {
        let theta0: Vec<f64> = arm
            .joint_limits()
            .map(|l| {
                l.ranges()
                    .iter()
                    .map(|[lo, hi]| {
                        (0.5 * (lo + hi)).clamp(-std::f64::consts::PI, std::f64::consts::PI)
                    })
                    .collect()
            })
            .unwrap_or_else(|| vec![0.0; arm.dof()]);
        let start = SpacePose::new(&arm, &theta0)?.hand();
        Ok(Self::line(arm, theta0, own_line_end(start), Vec::new()))
    }

    /// The preset called `key`'s task.
    pub fn by_key(key: &str) -> Result<Self> {
        SpacePreset::named(key).map(Self::preset)
    }

    /// The hand at `t = 0` (NaN where `theta0` does not fit the chain).
    pub fn start(&self) -> Vec3 {
        SpacePose::new(&self.arm, &self.theta0).map_or([f64::NAN; 3], |p| p.hand())
    }

    /// Where the path ends: the target for the line, the start for a
    /// circle, the last point.
    pub fn path_end(&self) -> Vec3 {
        self.path.end(self.start(), self.target)
    }

    /// Checks every field; the first problem found is returned.
    pub fn validate(&self) -> Result<()> {
        check_chain_scene(
            &self.arm,
            &self.theta0,
            self.target,
            &self.path,
            &self.obstacles,
        )?;
        self.validate_settings()
    }
}

/// What a scene of a chain in space checks, whatever its task: the start
/// pose (one finite angle per joint, within the limits), the hand's
/// target position, the path from the start, the spheres.
pub(super) fn check_chain_scene(
    arm: &Chain,
    theta0: &[f64],
    target: Vec3,
    path: &SpacePath,
    obstacles: &[Sphere],
) -> Result<()> {
    arm.check_angles(theta0)?;
    if let Some(l) = arm.joint_limits() {
        l.check("start pose theta0", theta0)?;
    }
    for (&c, axis) in target.iter().zip(["x", "y", "z"]) {
        coordinate(&format!("target {axis}"), c)?;
    }
    path.validate(SpacePose::new(arm, theta0)?.hand())?;
    if obstacles.len() > MAX_SPHERES {
        return Err(Error::DimensionMismatch {
            what: "spheres (at most)".into(),
            expected: MAX_SPHERES,
            found: obstacles.len(),
        });
    }
    for s in obstacles {
        s.validate(arm)?;
    }
    Ok(())
}
