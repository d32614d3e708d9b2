//! Scenes: an arm, a start pose, a straight-line task, obstacles and the
//! integration settings. The paper's two tasks (section VI) are presets.

use nalgebra::{DVector, Vector2};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

mod params;

use crate::arm::Arm;
use crate::error::{coordinate, positive, Error, Result};
use crate::ik::DampingSchedule;
use crate::obstacle::Obstacle;

pub(crate) use params::{validate_delta, validate_gain, validate_lambda};
pub use params::{
    Avoidance, Param, MAX_DAMPER_GAIN, MAX_DELTA, MAX_DISTANCE_GAIN, MAX_GAIN_STEP, MAX_INFLUENCE,
    MAX_LAMBDA, MAX_RATE_LIMIT, MAX_REFINE, MAX_SIGN_SMOOTHING, MAX_SLACK_WEIGHT, MIN_SLACK_WEIGHT,
};

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
    /// The parameters of the methods beyond the paper (influence distance,
    /// stop distance, damper gain, slack weight, distance gain); absent in
    /// scenes written before they existed, hence the defaults.
    #[serde(default)]
    pub avoidance: Avoidance,
    /// The smoothing `eps` (m^2) of the sign in eq. (15)
    /// ([`crate::obstacle::smoothed_sign`]); 0, the paper's, leaves the
    /// sign as it is. Absent in scenes written before it, and left out of
    /// written scenes while 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub sign_smoothing: f64,
    /// Newton-Schulz steps that refine a learned `Phi` with the pose's `J`
    /// (Cases 1 and 3, [`crate::ik::refine_phi`]); 0, the paper's, uses the
    /// network's `Phi` as it is. Left out of written scenes while 0.
    #[serde(default, skip_serializing_if = "is_zero_count")]
    pub refine: u32,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn is_zero_count(k: &u32) -> bool {
    *k == 0
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
            avoidance: Avoidance::default(),
            sign_smoothing: 0.0,
            refine: 0,
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
        self.avoidance.validate()?;
        Param::SignSmoothing.check(self.sign_smoothing)?;
        Param::Refine.check(f64::from(self.refine))?;
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
