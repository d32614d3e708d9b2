//! Scenes: an arm, a start pose, a straight-line task, obstacles and the
//! integration settings. The paper's two tasks (section VI) are presets.

use nalgebra::{DVector, Vector2};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

mod file;
mod params;
mod path;
mod pose;
mod space;
mod space_path;
mod weighting;

use crate::arm::Arm;
use crate::error::{coordinate, positive, Error, Result};
use crate::geometry::Ball;
use crate::ik::DampingSchedule;
use crate::obstacle::Obstacle;

pub use file::{ParamMap, SceneFile};
pub(crate) use params::validate_gain;
pub use params::{Param, Params, Scale, MAX_GAIN_STEP};
pub use path::{Path, DRAWN_SPACING, MAX_LAPS, MAX_POINTS, MIN_RADIUS};
pub use pose::{PoseScene, ORIENTATION_WEIGHT};
pub use space::{own_line_end, SpaceScene};
pub(crate) use space_path::circle_plane;
pub use space_path::{SpacePath, MIN_NORMAL_SINE};
pub use weighting::JointWeighting;

/// The paper's final end-effector position for both tasks, `Xf = (0.60, 0.20)`.
pub const PAPER_TARGET: [f64; 2] = [0.60, 0.20];
/// Obstacle radius (our choice, `docs/conventions.md`: the paper gives none).
pub const PAPER_RADIUS: f64 = 0.05;
/// Everything that defines one planning run, for an arm `A` whose hand has
/// `M` coordinates and follows a path `P`: the planar arm's by default
/// (`Scene`), a chain in space's as [`SpaceScene`].
///
/// A scene is written and read as a [`SceneFile`]: its parameters by
/// name, every declared one written (the planner's list,
/// `crate::planner::params`), and the fields of older files (`lambda`,
/// `delta`, `avoidance`, `sign_smoothing`, `refine`) read into them.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene<A = Arm, P = Path, const M: usize = 2, const D: usize = M> {
    /// The manipulator, with its limits.
    pub arm: A,
    /// Joint angles at `t = 0` (radians).
    pub theta0: Vec<f64>,
    /// End of the straight line, `X(tf)` (for the path `line`).
    pub target: [f64; M],
    /// What the hand follows at constant speed over `tf`: the straight
    /// line to `target` (the paper's), a circle or a polyline ([`Path`],
    /// [`SpacePath`]).
    pub path: P,
    /// The obstacles (discs in the plane, spheres in space); their centres
    /// are the points `O` of eq. (16).
    pub obstacles: Vec<Ball<D>>,
    /// Optional damping schedule added to `delta` near singular poses.
    pub damping: Option<DampingSchedule>,
    /// Runge-Kutta step (s).
    pub dt: f64,
    /// Final time `tf` (s); must be a whole number of steps.
    pub tf: f64,
    /// Closed-loop gain `K` in `Xdot + K (X_ref - X)`; 0 is the paper's open loop.
    pub feedback_gain: f64,
    /// The values of the methods' parameters (the paper's gain `lambda`
    /// and damping `delta` among them) that differ from their defaults.
    pub params: Params,
    /// How the methods of eq. (5) use the arm's joint limits: the paper's
    /// `W = I`, or weighted least norm.
    pub weighting: JointWeighting,
    /// Whether the floor (`y = 0` in the plane, `z = 0` in space) is an
    /// obstacle for the methods that keep a clearance (`distance`,
    /// `priority`, `qp`), and in the plane the post too, also for the
    /// outcome (a link below the floor or across the post collides); off
    /// in the paper's tasks.
    pub floor: bool,
}

impl<A, P, const M: usize, const D: usize> Scene<A, P, M, D> {
    /// The value of parameter `p` in this scene.
    #[inline]
    pub fn param(&self, p: &'static Param) -> f64 {
        self.params.get(p)
    }

    /// Sets parameter `p`; refused, changing nothing, when out of its
    /// bounds.
    pub fn set_param(&mut self, p: &'static Param, value: f64) -> Result<()> {
        self.params.set(p, value)
    }

    /// Number of RK4 steps, `tf / dt`.
    pub fn steps(&self) -> usize {
        (self.tf / self.dt).round() as usize
    }

    /// Checks what every scene has: the parameters, the damping schedule,
    /// `dt`, the feedback gain and `tf`.
    pub(crate) fn validate_settings(&self) -> Result<()> {
        validate_settings(
            &self.params,
            self.damping.as_ref(),
            self.dt,
            self.tf,
            self.feedback_gain,
        )
    }
}

/// A scene is written as its [`SceneFile`] (either kind of arm).
impl<A, P, const M: usize, const D: usize> Serialize for Scene<A, P, M, D>
where
    A: Serialize + Clone,
    P: Serialize + Default + PartialEq + Clone,
    [f64; M]: Serialize,
    [f64; D]: Serialize,
{
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        SceneFile::from(self.clone()).serialize(s)
    }
}

/// A scene is read from a [`SceneFile`], its parameters checked as it
/// becomes one (the whole scene is checked where a file is read).
impl<'de, A, P, const M: usize, const D: usize> Deserialize<'de> for Scene<A, P, M, D>
where
    A: Deserialize<'de>,
    P: Deserialize<'de> + Default,
    [f64; M]: Deserialize<'de>,
    [f64; D]: Deserialize<'de>,
{
    fn deserialize<De: serde::Deserializer<'de>>(d: De) -> std::result::Result<Self, De::Error> {
        let file = SceneFile::<A, P, M, D>::deserialize(d)?;
        Scene::try_from(file).map_err(serde::de::Error::custom)
    }
}

impl Scene {
    /// Task 1 of section VI: `theta0 = [pi/12, pi/2, -pi/6]` (start
    /// `(1.555883, 1.014850)`), straight line to `(0.60, 0.20)` in 10 s, RK4 with
    /// `dt = 0.1`, every parameter at its default (the paper's `delta = 0`,
    /// `lambda = 4`), obstacle disc at `(0.5, 0.5)` with
    /// radius 0.05 (our choice: the paper gives neither).
    pub fn task1() -> Self {
        Self::paper_task(vec![PI / 12.0, PI / 2.0, -PI / 6.0], [0.5, 0.5])
    }

    /// Task 2 of section VI. The paper prints `theta0 = [pi/12, pi/2, pi/6]`, but
    /// that pose puts the end effector at `(1.400592, 0.435295)`, not at the
    /// printed start `(1.495943, 0.559559)`; `[pi/12, pi/2, pi/12]` gives the
    /// printed start to 1e-6, so we use it. Obstacle at `(0.6, 0.6)` (our choice).
    pub fn task2() -> Self {
        Self::paper_task(vec![PI / 12.0, PI / 2.0, PI / 12.0], [0.6, 0.6])
    }

    /// Task 1 or 2 by number.
    pub fn task(number: u32) -> Result<Self> {
        match number {
            1 => Ok(Self::task1()),
            2 => Ok(Self::task2()),
            task => Err(Error::UnknownTask { task }),
        }
    }

    fn paper_task(theta0: Vec<f64>, obstacle: [f64; 2]) -> Self {
        Self {
            arm: Arm::paper(),
            theta0,
            target: PAPER_TARGET,
            path: Path::Line,
            obstacles: vec![Obstacle::new(obstacle[0], obstacle[1], PAPER_RADIUS)],
            damping: None,
            dt: 0.1,
            tf: 10.0,
            feedback_gain: 0.0,
            params: Params::default(),
            weighting: JointWeighting::None,
            floor: false,
        }
    }

    /// `theta0` as a vector.
    pub fn theta0_vector(&self) -> DVector<f64> {
        DVector::from_column_slice(&self.theta0)
    }

    /// The hand's position at `t = 0` (`theta0` must have one entry per
    /// link, as [`Scene::validate`] checks first).
    pub fn start(&self) -> [f64; 2] {
        crate::kinematics::Pose::new(&self.arm, &self.theta0)
            .map_or([f64::NAN; 2], |p| p.end_effector())
    }

    /// Where the path ends: the target for a line, the start for a
    /// circle, the last point of a polyline ([`Path::end`]).
    pub fn path_end(&self) -> [f64; 2] {
        match self.path {
            Path::Line => self.target,
            _ => self.path.end(self.start(), self.target),
        }
    }

    /// The target as a vector.
    pub fn target_vector(&self) -> Vector2<f64> {
        Vector2::new(self.target[0], self.target[1])
    }

    /// The post's height `L0` where the ground counts as an obstacle
    /// ([`Scene::floor`]), for [`crate::clearance::Pairs::add_ground`].
    #[inline]
    pub fn ground(&self) -> Option<f64> {
        self.floor.then(|| self.arm.post())
    }

    /// Takes the start pose, target and obstacle of the arm's own task
    /// when the arm is a preset that has one ([`crate::arm::PresetTask`]);
    /// whether it did.
    pub fn use_preset_task(&mut self) -> bool {
        let Some(task) = crate::arm::Preset::of(&self.arm).and_then(|p| p.task) else {
            return false;
        };
        let [x, y, r] = task.obstacle;
        self.theta0 = task.theta0.to_vec();
        self.target = task.target;
        self.obstacles = vec![Obstacle::new(x, y, r)];
        true
    }

    /// Checks every field; the first problem found is returned.
    pub fn validate(&self) -> Result<()> {
        self.arm.validate()?;
        self.arm.check_theta(&self.theta0_vector())?;
        self.arm
            .check_within_limits("start pose theta0", &self.theta0)?;
        coordinate("target x", self.target[0])?;
        coordinate("target y", self.target[1])?;
        if !self.path.is_line() {
            self.path.validate(self.start())?;
        }
        for ob in &self.obstacles {
            ob.validate(&self.arm)?;
        }
        self.validate_settings()
    }
}

/// Checks what a planar and a spatial scene share: the parameters, the
/// damping schedule, `dt`, the feedback gain and `tf` (a whole number of
/// steps, at most [`MAX_STEPS`]).
pub(crate) fn validate_settings(
    params: &Params,
    damping: Option<&DampingSchedule>,
    dt: f64,
    tf: f64,
    feedback_gain: f64,
) -> Result<()> {
    params.validate()?;
    if let Some(d) = damping {
        d.validate()?;
    }
    positive("time step dt", dt)?;
    validate_gain(feedback_gain, dt)?;
    positive("final time tf", tf)?;
    let ratio = tf / dt;
    if (ratio - ratio.round()).abs() > 1e-9 * ratio.max(1.0) {
        return Err(Error::NotWholeSteps { tf, dt });
    }
    if ratio.round() > MAX_STEPS {
        return Err(Error::TooManySteps {
            steps: ratio,
            max: MAX_STEPS,
        });
    }
    Ok(())
}

/// Most RK4 steps a run may take.
pub const MAX_STEPS: f64 = 1.0e7;
