//! Scenes: an arm, a start pose, a straight-line task, obstacles and the
//! integration settings. The paper's two tasks (section VI) are presets.

use nalgebra::{DVector, Vector2};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::arm::Arm;
use crate::error::{coordinate, non_negative, positive, within, Error, Result};
use crate::ik::DampingSchedule;
use crate::obstacle::Obstacle;

/// The paper's final end-effector position for both tasks, `Xf = (0.60, 0.20)`.
pub const PAPER_TARGET: [f64; 2] = [0.60, 0.20];
/// Obstacle radius (our choice, `docs/conventions.md`: the paper gives none).
pub const PAPER_RADIUS: f64 = 0.05;
/// Gain of the obstacle vector in the paper's runs, `lambda = 4.0`.
pub const PAPER_LAMBDA: f64 = 4.0;

/// Everything that defines one planning run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Scene {
    /// The manipulator.
    pub arm: Arm,
    /// Joint angles at `t = 0` (radians).
    pub theta0: Vec<f64>,
    /// End of the straight line, `X(tf)`.
    pub target: [f64; 2],
    /// Obstacle discs; their centres are the points `O` of eq. (16).
    pub obstacles: Vec<Obstacle>,
    /// Gain `lambda` of the null-space vector, eq. (14) (`v` is scaled by `lambda / 4`).
    pub lambda: f64,
    /// Constant damping factor `delta` of eqs. (6), (17), (20); the paper uses 0.
    pub delta: f64,
    /// Optional damping schedule added to `delta` near singular poses.
    pub damping: Option<DampingSchedule>,
    /// Runge-Kutta step (s).
    pub dt: f64,
    /// Final time `tf` (s); must be a whole number of steps.
    pub tf: f64,
    /// Closed-loop gain `K` in `Xdot + K (X_ref - X)`; 0 is the paper's open loop.
    pub feedback_gain: f64,
}

impl Scene {
    /// Task 1 of section VI: `theta0 = [pi/12, pi/2, -pi/6]` (start
    /// `(1.555883, 1.014850)`), straight line to `(0.60, 0.20)` in 10 s, RK4 with
    /// `dt = 0.1`, `delta = 0`, `lambda = 4`, obstacle disc at `(0.5, 0.5)` with
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
            obstacles: vec![Obstacle::new(obstacle[0], obstacle[1], PAPER_RADIUS)],
            lambda: PAPER_LAMBDA,
            delta: 0.0,
            damping: None,
            dt: 0.1,
            tf: 10.0,
            feedback_gain: 0.0,
        }
    }

    /// `theta0` as a vector.
    pub fn theta0_vector(&self) -> DVector<f64> {
        DVector::from_column_slice(&self.theta0)
    }

    /// The target as a vector.
    pub fn target_vector(&self) -> Vector2<f64> {
        Vector2::new(self.target[0], self.target[1])
    }

    /// Number of RK4 steps, `tf / dt`.
    pub fn steps(&self) -> usize {
        (self.tf / self.dt).round() as usize
    }

    /// Checks every field; the first problem found is returned.
    pub fn validate(&self) -> Result<()> {
        // Re-check the arm: a deserialised scene bypasses `Arm::new`.
        Arm::new(self.arm.post(), self.arm.links().to_vec())?;
        self.arm.check_theta(&self.theta0_vector())?;
        coordinate("target x", self.target[0])?;
        coordinate("target y", self.target[1])?;
        for ob in &self.obstacles {
            ob.validate(&self.arm)?;
        }
        validate_lambda(self.lambda)?;
        validate_delta(self.delta)?;
        if let Some(d) = &self.damping {
            d.validate()?;
        }
        positive("time step dt", self.dt)?;
        validate_gain(self.feedback_gain, self.dt)?;
        positive("final time tf", self.tf)?;
        let ratio = self.tf / self.dt;
        if (ratio - ratio.round()).abs() > 1e-9 * ratio.max(1.0) {
            return Err(Error::NotWholeSteps {
                tf: self.tf,
                dt: self.dt,
            });
        }
        if ratio.round() > MAX_STEPS {
            return Err(Error::TooManySteps {
                steps: ratio,
                max: MAX_STEPS,
            });
        }
        Ok(())
    }
}

/// Most RK4 steps a run may take.
pub const MAX_STEPS: f64 = 1.0e7;

/// Largest gain `lambda` accepted: 250 times the paper's 4 (the page's
/// slider ends at 12). Far larger gains only make the first RK4 step
/// overflow (`lambda = 1e308` did, found by the hostile-URL test).
pub const MAX_LAMBDA: f64 = 1000.0;

/// Largest constant damping `delta` accepted (m^2): with `J J^T` of order
/// 1 m^2 it already stops the arm; larger values say nothing more.
pub const MAX_DELTA: f64 = 1000.0;

pub(crate) fn validate_lambda(lambda: f64) -> Result<()> {
    non_negative("lambda", lambda)?;
    within("lambda", lambda, 0.0, MAX_LAMBDA).map(|_| ())
}

pub(crate) fn validate_delta(delta: f64) -> Result<()> {
    non_negative("damping factor delta", delta)?;
    within("damping factor delta", delta, 0.0, MAX_DELTA).map(|_| ())
}

/// A number of the scene that a method reads ([`crate::planner::MethodInfo::params`]):
/// its name on the command line and in the page, its bounds, and how to
/// read and set it with the scene's checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Param {
    /// Gain `lambda` of the obstacle vector, eq. (14).
    Lambda,
    /// Constant damping `delta` of eqs. (6), (17), (20).
    Delta,
}

impl Param {
    /// The name on the command line (`--lambda`) and in the page.
    pub fn name(self) -> &'static str {
        match self {
            Param::Lambda => "lambda",
            Param::Delta => "delta",
        }
    }

    /// Smallest and largest value accepted.
    pub fn bounds(self) -> (f64, f64) {
        match self {
            Param::Lambda => (0.0, MAX_LAMBDA),
            Param::Delta => (0.0, MAX_DELTA),
        }
    }

    /// Its value in `scene`.
    pub fn get(self, scene: &Scene) -> f64 {
        match self {
            Param::Lambda => scene.lambda,
            Param::Delta => scene.delta,
        }
    }

    /// Sets it in `scene`; refused, changing nothing, when out of bounds.
    pub fn set(self, scene: &mut Scene, value: f64) -> Result<()> {
        match self {
            Param::Lambda => {
                validate_lambda(value)?;
                scene.lambda = value;
            }
            Param::Delta => {
                validate_delta(value)?;
                scene.delta = value;
            }
        }
        Ok(())
    }
}

/// Largest `K dt` accepted for the closed-loop gain. The tracking error then
/// obeys `e' = -K e`, which classical RK4 integrates stably only for
/// `K dt < 2.785`; 2.5 leaves a margin for the arm's nonlinearity.
pub const MAX_GAIN_STEP: f64 = 2.5;

pub(crate) fn validate_gain(gain: f64, dt: f64) -> Result<()> {
    non_negative("feedback gain", gain)?;
    if gain * dt > MAX_GAIN_STEP {
        return Err(Error::UnstableGain {
            gain,
            dt,
            max_gain: MAX_GAIN_STEP / dt,
            max_step: MAX_GAIN_STEP,
        });
    }
    Ok(())
}
