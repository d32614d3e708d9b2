//! The numbers of a scene that the methods read, each with its bounds: the
//! paper's gain `lambda` and damping `delta`, and the parameters of the
//! methods beyond the paper ([`Avoidance`], `docs/methods.md`). The command
//! line, the page's controls and the checks all read them from [`Param`].

use serde::{Deserialize, Serialize};

use super::Scene;
use crate::error::{finite, non_negative, within, Error, Result};

/// Largest gain `lambda` accepted: 250 times the paper's 4 (the page's
/// slider ends at 12). Far larger gains only make the first RK4 step
/// overflow (`lambda = 1e308` did, found by the hostile-URL test).
pub const MAX_LAMBDA: f64 = 1000.0;

/// Largest constant damping `delta` accepted (m^2): with `J J^T` of order
/// 1 m^2 it already stops the arm; larger values say nothing more.
pub const MAX_DELTA: f64 = 1000.0;

/// Largest influence distance `d_i` accepted (m): beyond any arm's reach.
pub const MAX_INFLUENCE: f64 = 100.0;
/// Largest damper gain `xi` accepted (m/s).
pub const MAX_DAMPER_GAIN: f64 = 100.0;
/// Smallest and largest task-slack weight `w` accepted: below 1 the task
/// hardly counts; above 1e12 `1 / w` drowns in the rounding of `J J^T`.
pub const MIN_SLACK_WEIGHT: f64 = 1.0;
/// See [`MIN_SLACK_WEIGHT`].
pub const MAX_SLACK_WEIGHT: f64 = 1e12;
/// Largest gain `lambda_d` of the clearance potential accepted.
pub const MAX_DISTANCE_GAIN: f64 = 1000.0;
/// Largest joint-rate limit accepted (rad/s).
pub const MAX_RATE_LIMIT: f64 = 1000.0;

/// Largest smoothing `eps` of the sign in eq. (15) accepted (m^2): the
/// paper's arm's triangles have `|D| < 4 m^2`, so beyond this the
/// criterion is flat everywhere.
pub const MAX_SIGN_SMOOTHING: f64 = 100.0;

/// Most Newton-Schulz steps on a learned `Phi`: each squares the error
/// `J Phi - I`, so after 8 steps any error below 0.9 is below 1e-5 and
/// further steps change nothing a run can see.
pub const MAX_REFINE: u32 = 8;

/// Largest `K dt` accepted for the closed-loop gain. The tracking error then
/// obeys `e' = -K e`, which classical RK4 integrates stably only for
/// `K dt < 2.785`; 2.5 leaves a margin for the arm's nonlinearity.
pub const MAX_GAIN_STEP: f64 = 2.5;

pub(crate) fn validate_lambda(lambda: f64) -> Result<()> {
    non_negative("lambda", lambda)?;
    within("lambda", lambda, 0.0, MAX_LAMBDA).map(|_| ())
}

pub(crate) fn validate_delta(delta: f64) -> Result<()> {
    non_negative("damping factor delta", delta)?;
    within("damping factor delta", delta, 0.0, MAX_DELTA).map(|_| ())
}

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

/// The parameters of the methods beyond the paper (`docs/methods.md`).
/// Link-obstacle pairs with a clearance of at least `influence` are
/// ignored by all three.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Avoidance {
    /// Influence distance `d_i` (m): pairs closer than this count.
    pub influence: f64,
    /// Stop distance `d_s` (m) of the velocity dampers (`qp`) and of the
    /// escape speed (`priority`): the clearance they keep.
    pub stop_distance: f64,
    /// Damper gain `xi` (m/s): how fast a link may approach at the
    /// influence distance (`qp`).
    pub damper_gain: f64,
    /// Weight `w` of the task slack (`qp`): with no damper active the rates
    /// are eq. (5) with damped least squares, `delta = 1 / w`.
    pub slack_weight: f64,
    /// Gain `lambda_d` of the clearance potential (`distance`).
    pub distance_gain: f64,
    /// The escape speed (m/s) of task priority's obstacle-avoidance point
    /// at the stop distance (`priority`); absent in older scenes.
    #[serde(default = "default_escape_speed")]
    pub escape_speed: f64,
    /// The joints' rate limit (rad/s) of the quadratic program (`qp`), as
    /// NEO bounds a robot's joint velocities: without it, where a damper
    /// and the task pull apart the program buys the task with unbounded
    /// rates. Absent in scenes written before it, hence the default.
    #[serde(default = "default_rate_limit")]
    pub rate_limit: f64,
}

fn default_rate_limit() -> f64 {
    Avoidance::default().rate_limit
}

fn default_escape_speed() -> f64 {
    Avoidance::default().escape_speed
}

impl Default for Avoidance {
    /// `d_i = 0.3 m`, `d_s = 0.02 m`, `xi = 1 m/s`, `w = 1e6` (NEO's and
    /// mink's orders of magnitude, scaled to this arm), joint rates within
    /// 1.5 rad/s (the paper's tasks need 0.54), `lambda_d = 1e-3` and an
    /// escape speed of 0.1 m/s, chosen on the atlas (`docs/methods.md`).
    fn default() -> Self {
        Self {
            influence: 0.3,
            stop_distance: 0.02,
            damper_gain: 1.0,
            slack_weight: 1e6,
            distance_gain: 1e-3,
            escape_speed: 0.1,
            rate_limit: 1.5,
        }
    }
}

impl Avoidance {
    /// Checks every number and that `d_s < d_i`.
    pub fn validate(&self) -> Result<()> {
        for p in [
            Param::Influence,
            Param::StopDistance,
            Param::DamperGain,
            Param::SlackWeight,
            Param::DistanceGain,
            Param::EscapeSpeed,
            Param::RateLimit,
        ] {
            let (lo, hi) = p.bounds();
            within(p.what(), p.read(self), lo, hi)?;
        }
        if self.stop_distance >= self.influence {
            return Err(Error::OutOfRange {
                what: "stop distance d_s (below the influence distance)".into(),
                value: self.stop_distance,
                min: 0.0,
                max: self.influence,
            });
        }
        Ok(())
    }
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
    /// Influence distance `d_i` ([`Avoidance::influence`]).
    Influence,
    /// Stop distance `d_s` ([`Avoidance::stop_distance`]).
    StopDistance,
    /// Damper gain `xi` ([`Avoidance::damper_gain`]).
    DamperGain,
    /// Task-slack weight `w` ([`Avoidance::slack_weight`]).
    SlackWeight,
    /// Gain `lambda_d` of the clearance potential ([`Avoidance::distance_gain`]).
    DistanceGain,
    /// The escape speed of task priority ([`Avoidance::escape_speed`]).
    EscapeSpeed,
    /// The joints' rate limit ([`Avoidance::rate_limit`]).
    RateLimit,
    /// The smoothing of the sign in eq. (15) ([`Scene::sign_smoothing`]).
    SignSmoothing,
    /// Newton-Schulz steps on a learned `Phi` ([`Scene::refine`]).
    Refine,
}

/// What the page and the command line show of a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ParamInfo {
    /// The name in URLs and JSON (`lambda`, `influence`, ...).
    pub name: &'static str,
    /// The command line's flag (`--lambda`, `--influence`, ...).
    pub flag: &'static str,
    /// What a control is labelled.
    pub label: &'static str,
    /// Its unit, if any.
    pub unit: &'static str,
    /// Smallest and largest value accepted.
    pub bounds: (f64, f64),
    /// The span and step of a slider for it: `(min, max, step)`; in powers
    /// of ten (`log10` of the value) when `log_slider`.
    pub slider: (f64, f64, f64),
    /// Whether its slider moves in powers of ten (a weight that spans
    /// orders of magnitude).
    pub log_slider: bool,
    /// Its value in the paper's tasks.
    pub default: f64,
}

impl Param {
    /// Every parameter.
    pub const ALL: [Param; 11] = [
        Param::Lambda,
        Param::Delta,
        Param::Influence,
        Param::StopDistance,
        Param::DamperGain,
        Param::SlackWeight,
        Param::DistanceGain,
        Param::EscapeSpeed,
        Param::RateLimit,
        Param::SignSmoothing,
        Param::Refine,
    ];

    /// What the page and the command line show of it.
    pub fn info(self) -> ParamInfo {
        let d = Avoidance::default();
        let (name, flag, label, unit, slider, default) = match self {
            Param::Lambda => (
                "lambda",
                "--lambda",
                "Obstacle gain λ",
                "",
                (0.0, 12.0, 0.5),
                4.0,
            ),
            Param::Delta => (
                "delta",
                "--delta",
                "Damping δ",
                "m²",
                (0.0, 0.05, 0.001),
                0.0,
            ),
            Param::Influence => (
                "influence",
                "--influence",
                "Influence distance dᵢ",
                "m",
                (0.05, 0.8, 0.01),
                d.influence,
            ),
            Param::StopDistance => (
                "stop_distance",
                "--stop-distance",
                "Stop distance dₛ",
                "m",
                (0.0, 0.2, 0.005),
                d.stop_distance,
            ),
            Param::DamperGain => (
                "damper_gain",
                "--damper-gain",
                "Damper gain ξ",
                "m/s",
                (0.1, 5.0, 0.1),
                d.damper_gain,
            ),
            Param::SlackWeight => (
                "slack_weight",
                "--slack-weight",
                "Slack weight w",
                "",
                (2.0, 8.0, 0.5),
                d.slack_weight,
            ),
            Param::DistanceGain => (
                "distance_gain",
                "--distance-gain",
                "Distance gain λd",
                "",
                (0.0, 0.01, 1e-4),
                d.distance_gain,
            ),
            Param::EscapeSpeed => (
                "escape_speed",
                "--escape-speed",
                "Escape speed",
                "m/s",
                (0.0, 1.0, 0.01),
                d.escape_speed,
            ),
            Param::RateLimit => (
                "rate_limit",
                "--rate-limit",
                "Joint rate limit",
                "rad/s",
                (0.2, 10.0, 0.1),
                d.rate_limit,
            ),
            Param::SignSmoothing => (
                "sign_smoothing",
                "--sign-smoothing",
                "Sign smoothing ε",
                "m²",
                (0.0, 0.3, 0.01),
                0.0,
            ),
            Param::Refine => (
                "refine",
                "--refine",
                "Refinement steps",
                "",
                (0.0, 4.0, 1.0),
                0.0,
            ),
        };
        ParamInfo {
            name,
            flag,
            label,
            unit,
            bounds: self.bounds(),
            slider,
            log_slider: self == Param::SlackWeight,
            default,
        }
    }

    /// The name on the command line (`--lambda`) and in the page.
    pub fn name(self) -> &'static str {
        self.info().name
    }

    /// What a message calls it.
    fn what(self) -> &'static str {
        match self {
            Param::Lambda => "lambda",
            Param::Delta => "damping factor delta",
            Param::Influence => "influence distance d_i",
            Param::StopDistance => "stop distance d_s",
            Param::DamperGain => "damper gain xi",
            Param::SlackWeight => "slack weight w",
            Param::DistanceGain => "distance gain lambda_d",
            Param::EscapeSpeed => "escape speed",
            Param::RateLimit => "joint rate limit",
            Param::SignSmoothing => "sign smoothing eps",
            Param::Refine => "refinement steps",
        }
    }

    /// Smallest and largest value accepted.
    pub fn bounds(self) -> (f64, f64) {
        match self {
            Param::Lambda => (0.0, MAX_LAMBDA),
            Param::Delta => (0.0, MAX_DELTA),
            Param::Influence => (1e-3, MAX_INFLUENCE),
            Param::StopDistance => (0.0, MAX_INFLUENCE),
            Param::DamperGain => (1e-3, MAX_DAMPER_GAIN),
            Param::SlackWeight => (MIN_SLACK_WEIGHT, MAX_SLACK_WEIGHT),
            Param::DistanceGain => (0.0, MAX_DISTANCE_GAIN),
            Param::EscapeSpeed => (0.0, MAX_DAMPER_GAIN),
            Param::RateLimit => (1e-3, MAX_RATE_LIMIT),
            Param::SignSmoothing => (0.0, MAX_SIGN_SMOOTHING),
            Param::Refine => (0.0, f64::from(MAX_REFINE)),
        }
    }

    /// Checks a value against the bounds (and, for a count, that it is
    /// whole), changing nothing.
    pub(crate) fn check(self, value: f64) -> Result<()> {
        finite(self.what(), value)?;
        let (lo, hi) = self.bounds();
        within(self.what(), value, lo, hi)?;
        if self.is_count() && value.fract() != 0.0 {
            return Err(Error::OutOfRange {
                what: format!("{} (a whole number)", self.what()),
                value,
                min: lo,
                max: hi,
            });
        }
        Ok(())
    }

    /// Whether it counts something (a whole number).
    pub fn is_count(self) -> bool {
        self == Param::Refine
    }

    fn read(self, a: &Avoidance) -> f64 {
        match self {
            Param::Influence => a.influence,
            Param::StopDistance => a.stop_distance,
            Param::DamperGain => a.damper_gain,
            Param::SlackWeight => a.slack_weight,
            Param::DistanceGain => a.distance_gain,
            Param::EscapeSpeed => a.escape_speed,
            Param::RateLimit => a.rate_limit,
            Param::Lambda | Param::Delta | Param::SignSmoothing | Param::Refine => f64::NAN,
        }
    }

    /// Its value in `scene`.
    pub fn get(self, scene: &Scene) -> f64 {
        match self {
            Param::Lambda => scene.lambda,
            Param::Delta => scene.delta,
            Param::SignSmoothing => scene.sign_smoothing,
            Param::Refine => f64::from(scene.refine),
            other => other.read(&scene.avoidance),
        }
    }

    /// Sets it in `scene`; refused, changing nothing, when out of its
    /// bounds (or, for the stop distance, not below the influence distance).
    pub fn set(self, scene: &mut Scene, value: f64) -> Result<()> {
        finite(self.what(), value)?;
        match self {
            Param::Lambda => {
                validate_lambda(value)?;
                scene.lambda = value;
            }
            Param::Delta => {
                validate_delta(value)?;
                scene.delta = value;
            }
            Param::SignSmoothing => {
                self.check(value)?;
                scene.sign_smoothing = value;
            }
            Param::Refine => {
                self.check(value)?;
                scene.refine = value as u32;
            }
            other => {
                let mut a = scene.avoidance;
                match other {
                    Param::Influence => a.influence = value,
                    Param::StopDistance => a.stop_distance = value,
                    Param::DamperGain => a.damper_gain = value,
                    Param::SlackWeight => a.slack_weight = value,
                    Param::RateLimit => a.rate_limit = value,
                    Param::EscapeSpeed => a.escape_speed = value,
                    _ => a.distance_gain = value,
                }
                a.validate()?;
                scene.avoidance = a;
            }
        }
        Ok(())
    }
}

impl std::str::FromStr for Param {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        Param::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| Error::UnknownName {
                kind: "parameter",
                name: s.into(),
                choices: Param::ALL.map(Param::name).join(", "),
            })
    }
}
