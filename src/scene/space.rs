//! A run of an arm in space: a chain, a start pose, the hand's path (the
//! straight line, a circle or a polyline), spheres and the integration
//! settings; the methods' parameters are
//! the planar scene's ([`Params`]), read by the same declarations.

use super::{JointWeighting, Params, SpacePath};
use crate::error::{coordinate, Error, Result};
use crate::ik::DampingSchedule;
use crate::space::{Chain, SpacePose, SpacePreset, Sphere, Vec3, MAX_SPHERES};

/// Everything that defines one run of an arm in space.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceScene {
    /// The chain, with its limits.
    pub chain: Chain,
    /// Joint angles at `t = 0` (rad).
    pub theta0: Vec<f64>,
    /// The end of the hand's straight line (m), for [`SpacePath::Line`].
    pub target: Vec3,
    /// What the hand follows at constant speed over `tf`: the straight
    /// line to `target`, a circle or a polyline ([`SpacePath`]).
    pub path: SpacePath,
    /// The spheres; their centres are the points `O` of the criterion.
    pub spheres: Vec<Sphere>,
    /// Optional damping schedule added to `delta` near singular poses.
    pub damping: Option<DampingSchedule>,
    /// Runge-Kutta step (s).
    pub dt: f64,
    /// Final time (s); a whole number of steps.
    pub tf: f64,
    /// Closed-loop gain `K` (0: the paper's open loop).
    pub feedback_gain: f64,
    /// The methods' parameters that differ from their defaults.
    pub params: Params,
    /// How the methods of eq. (5) use the joint limits.
    pub weighting: JointWeighting,
    /// Whether the floor `z = 0` is an obstacle for the methods that keep
    /// a clearance and for the outcome.
    pub floor: bool,
}

impl SpaceScene {
    /// The preset's own task: its ready pose, line and sphere, `dt = 0.05
    /// s`, `tf = 5 s`, every parameter at its default.
    pub fn preset(p: &SpacePreset) -> Self {
        let [x, y, z, r] = p.task.sphere;
        Self {
            chain: p.chain(),
            theta0: p.task.theta0.to_vec(),
            target: p.task.target,
            path: SpacePath::Line,
            spheres: vec![Sphere::new([x, y, z], r)],
            damping: None,
            dt: 0.05,
            tf: 5.0,
            feedback_gain: 0.0,
            params: Params::default(),
            weighting: JointWeighting::None,
            floor: false,
        }
    }

    /// The preset called `key`'s task.
    pub fn by_key(key: &str) -> Result<Self> {
        SpacePreset::by_key(key)
            .map(Self::preset)
            .ok_or_else(|| Error::UnknownName {
                kind: "arm in space",
                name: key.into(),
                choices: crate::error::choices(
                    &crate::space::PRESETS
                        .iter()
                        .map(|p| p.key)
                        .collect::<Vec<_>>(),
                ),
            })
    }

    /// The hand at `t = 0` (NaN where `theta0` does not fit the chain).
    pub fn start(&self) -> Vec3 {
        SpacePose::new(&self.chain, &self.theta0).map_or([f64::NAN; 3], |p| p.hand())
    }

    /// Where the path ends: the target for the line, the start for a
    /// circle, the last point.
    pub fn path_end(&self) -> Vec3 {
        self.path.end(self.start(), self.target)
    }

    /// The value of parameter `p`.
    #[inline]
    pub fn param(&self, p: &'static super::Param) -> f64 {
        self.params.get(p)
    }

    /// Number of RK4 steps, `tf / dt`.
    pub fn steps(&self) -> usize {
        (self.tf / self.dt).round() as usize
    }

    /// Checks every field; the first problem found is returned.
    pub fn validate(&self) -> Result<()> {
        self.chain.check_angles(&self.theta0)?;
        if let Some(l) = self.chain.joint_limits() {
            l.check("start pose theta0", &self.theta0)?;
        }
        for (&c, axis) in self.target.iter().zip(["x", "y", "z"]) {
            coordinate(&format!("target {axis}"), c)?;
        }
        self.path.validate(self.start())?;
        if self.spheres.len() > MAX_SPHERES {
            return Err(Error::DimensionMismatch {
                what: "spheres (at most)".into(),
                expected: MAX_SPHERES,
                found: self.spheres.len(),
            });
        }
        for s in &self.spheres {
            s.validate(&self.chain)?;
        }
        super::validate_settings(
            &self.params,
            self.damping.as_ref(),
            self.dt,
            self.tf,
            self.feedback_gain,
        )
    }
}
