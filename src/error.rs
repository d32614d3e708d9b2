//! Errors as values. Every message names the problem so that a user can act
//! on it; nothing in the core panics on user input. The variants carry the
//! facts a caller may branch on (which number, its value, the bound it
//! broke), so code and tests match variants, not prose.

use std::fmt;

/// Everything that can go wrong in the core.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// A number that must be finite was NaN or infinite.
    NonFinite {
        /// What was checked, e.g. `"theta_2"`, `"target x"`.
        what: String,
    },
    /// A number that must be positive was zero or negative.
    NotPositive {
        /// What was checked, e.g. `"time step dt"`.
        what: String,
        /// The value given.
        value: f64,
    },
    /// A number that must not be negative was negative.
    Negative {
        /// What was checked, e.g. `"lambda"`.
        what: String,
        /// The value given.
        value: f64,
    },
    /// A number outside the interval it must lie in.
    OutOfRange {
        /// What was checked, e.g. `"speed"`.
        what: String,
        /// The value given.
        value: f64,
        /// Smallest accepted.
        min: f64,
        /// Largest accepted.
        max: f64,
    },
    /// A coordinate or length (m) beyond [`MAX_COORDINATE`], or a joint
    /// angle (rad) beyond [`crate::arm::MAX_ANGLE`].
    TooLarge {
        /// What was checked, e.g. `"target x"`.
        what: String,
        /// The value given.
        value: f64,
        /// The largest accepted magnitude.
        max: f64,
        /// Its unit, `"m"` or `"rad"`.
        unit: &'static str,
    },
    /// A closed-loop gain `K` with `K dt` beyond what RK4 integrates stably.
    UnstableGain {
        /// The gain `K` (1/s).
        gain: f64,
        /// The time step (s).
        dt: f64,
        /// The largest gain accepted with this `dt`.
        max_gain: f64,
        /// The largest `K dt` accepted.
        max_step: f64,
    },
    /// The final time is not a whole number of time steps.
    NotWholeSteps {
        /// Final time (s).
        tf: f64,
        /// Time step (s).
        dt: f64,
    },
    /// More integration steps than a run may take.
    TooManySteps {
        /// `tf / dt`.
        steps: f64,
        /// The limit.
        max: f64,
    },
    /// An arm with too few or too many links.
    LinkCount {
        /// Links given.
        found: usize,
        /// Fewest accepted.
        min: usize,
        /// Most accepted.
        max: usize,
    },
    /// A name that is not one of the choices (a method, a variant, ...).
    UnknownName {
        /// What kind of name, e.g. `"method"`.
        kind: &'static str,
        /// The name given.
        name: String,
        /// The names accepted, for the message.
        choices: String,
    },
    /// Text that does not follow its syntax (an arm `POST:L1,L2,...`, an
    /// obstacle list `x,y,r;x,y,r`).
    Syntax {
        /// What was read, e.g. `"arm"`.
        what: &'static str,
        /// The text given (the message quotes at most 40 characters).
        text: String,
        /// What was wrong, or what was expected.
        expected: String,
    },
    /// The paper has tasks 1 and 2 only.
    UnknownTask {
        /// The task asked for.
        task: u32,
    },
    /// A weight matrix of eqs. (6)-(7) that is not symmetric positive definite.
    NotSpd {
        /// `"W"` or `"Z"`.
        what: String,
        /// `"symmetric"` or `"positive definite"`.
        property: &'static str,
    },
    /// Vector or matrix of the wrong size (e.g. `theta` with 2 entries for a 3-link arm).
    DimensionMismatch {
        /// What was checked.
        what: String,
        /// Entries expected.
        expected: usize,
        /// Entries found.
        found: usize,
    },
    /// A joint's position limits with `lo >= hi`: no angle lies within.
    EmptyRange {
        /// The joint, from 1.
        joint: usize,
        /// Its limits `[lo, hi]` (rad).
        range: [f64; 2],
    },
    /// The obstacle disc overlaps the fixed base post, where the arm cannot avoid it.
    ObstacleOnPost {
        /// Obstacle centre x.
        x: f64,
        /// Obstacle centre y.
        y: f64,
        /// Obstacle radius.
        radius: f64,
    },
    /// A method that has no rule for an arm in space (yet).
    NotInSpace {
        /// The method's name.
        method: &'static str,
        /// The methods that do, for the message.
        choices: String,
    },
    /// An atlas slice whose cells all lie beyond the arm's reach.
    SliceMissesReach {
        /// The plane, as written.
        slice: String,
        /// The reach from the shoulder (m).
        reach: f64,
    },
    /// A sphere that overlaps the fixed base of a chain in space, where the
    /// arm cannot avoid it.
    SphereOnBase {
        /// Its centre.
        centre: [f64; 3],
        /// Its radius.
        radius: f64,
    },
    /// `J J^T + delta I` (eq. 17) cannot be solved: the arm is at a singular pose and no
    /// damping is on.
    Singular(String),
    /// An integration step produced non-finite joint angles; the state was left unchanged.
    Diverged {
        /// Time at the start of the step (s).
        t: f64,
    },
    /// A method whose joint rates have no null-space vector `v` of eq. (5).
    NoNullSpace {
        /// The method's name.
        method: &'static str,
    },
    /// The quadratic program solver ([`crate::qp::solve`]) could not solve a
    /// program for a reason other than infeasibility: a Hessian that is not
    /// positive definite, active constraints that depend on each other, or no
    /// convergence (degenerate constraints).
    QpFailed {
        /// Why, e.g. `"its Hessian H is not positive definite"`.
        reason: &'static str,
    },
    /// A quadratic program whose constraints no point satisfies at once.
    Infeasible {
        /// Constraints of the program.
        constraints: usize,
        /// Of which active when the conflict was found.
        active: usize,
    },
    /// A network method was requested but no trained networks are loaded.
    NetworksUnavailable(String),
    /// The networks were trained for another arm than the planner's.
    NetworksForAnotherArm {
        /// Post and links the networks were trained for.
        trained: (f64, Vec<f64>),
        /// Post and links of the planner's arm.
        arm: (f64, Vec<f64>),
    },
    /// A network weights file is corrupt or does not fit.
    Weights(String),
    /// A scene without obstacles where one is needed (the atlas moves the first).
    NoObstacle,
    /// A region `[x0, x1, y0, y1]` with `x0 >= x1` or `y0 >= y1`.
    EmptyRegion {
        /// The region given.
        region: [f64; 4],
    },
    /// Training options or data that cannot work (too few samples, a split
    /// that leaves nothing to train on, a sampling region that yields no pose).
    Training(String),
    /// A figure that could not be drawn.
    Figure(String),
    /// A URDF that cannot be read into a chain (what is wrong, and where).
    Urdf(String),
}

/// Result alias used throughout the crate.
pub type Result<T> = std::result::Result<T, Error>;

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite { what } => {
                write!(f, "{what} must be a finite number (got NaN or infinity)")
            }
            Error::NotPositive { what, value } => {
                write!(f, "{what} must be positive (got {})", Num(*value))
            }
            Error::Negative { what, value } => {
                write!(f, "{what} must not be negative (got {})", Num(*value))?;
                if what == "lambda" {
                    write!(f, "; a negative gain pulls links towards the obstacle")?;
                }
                Ok(())
            }
            Error::OutOfRange {
                what,
                value,
                min,
                max,
            } => write!(
                f,
                "{what} must lie between {} and {} (got {})",
                Num(*min),
                Num(*max),
                Num(*value)
            ),
            Error::TooLarge {
                what,
                value,
                max,
                unit,
            } => {
                write!(f, "{what} must lie within ±{} {unit} (got {})", Num(*max), Num(*value))
            }
            Error::UnstableGain {
                gain,
                dt,
                max_gain,
                max_step,
            } => write!(
                f,
                "feedback gain K = {} with dt = {} s makes the RK4 step unstable: \
                 K dt must not exceed {max_step} (K <= {max_gain:.4} here)",
                Num(*gain),
                Num(*dt),
            ),
            Error::NotWholeSteps { tf, dt } => write!(
                f,
                "final time tf = {} is not a whole number of steps dt = {}",
                Num(*tf),
                Num(*dt)
            ),
            Error::TooManySteps { steps, max } => {
                write!(f, "tf / dt = {} steps is too many (at most {max})", Num(steps.round()))
            }
            Error::LinkCount { found, min, max } => write!(
                f,
                "an arm needs {min} to {max} links to position a planar end effector (got {found})"
            ),
            Error::UnknownName {
                kind,
                name,
                choices,
            } => write!(f, "unknown {kind} '{name}': use {choices}"),
            Error::Syntax {
                what,
                text,
                expected,
            } => write!(f, "{what} '{}': {expected}", clip(text)),
            Error::UnknownTask { task } => {
                write!(f, "unknown task {task}: the paper has tasks 1 and 2")
            }
            Error::NotSpd { what, property } => write!(f, "{what} must be {property}"),
            Error::DimensionMismatch {
                what,
                expected,
                found,
            } => write!(f, "{what} has {found} entries, expected {expected}"),
            Error::EmptyRange { joint, range } => write!(
                f,
                "joint {joint}'s limits {}:{} are empty: the lower must be below the upper",
                Num(range[0]),
                Num(range[1])
            ),
            Error::ObstacleOnPost { x, y, radius } => write!(
                f,
                "obstacle at ({}, {}) with radius {} overlaps the fixed base post; move it away from the post",
                Short(*x),
                Short(*y),
                Short(*radius)
            ),
            Error::NotInSpace { method, choices } => write!(
                f,
                "method {method} does not run an arm in space; for the Panda and the iiwa choose {choices}"
            ),
            Error::SliceMissesReach { slice, reach } => write!(
                f,
                "no cell of the slice {slice} lies within the arm's reach ({} m of its shoulder): choose a plane through the arm",
                Short(*reach)
            ),
            Error::SphereOnBase { centre, radius } => write!(
                f,
                "sphere at ({}, {}, {}) with radius {} overlaps the arm's fixed base; move it away from the base",
                Short(centre[0]),
                Short(centre[1]),
                Short(centre[2]),
                Short(*radius)
            ),
            Error::Singular(msg) => write!(f, "singular pose: {msg}"),
            Error::Diverged { t } => write!(
                f,
                "integration diverged: non-finite joint angles after the step at t = {t:.3} s; switch damping on"
            ),
            Error::NoNullSpace { method } => {
                write!(f, "method {method} has no null-space vector v")
            }
            Error::QpFailed { reason } => {
                write!(f, "the quadratic program of the joint rates could not be solved: {reason}")
            }
            Error::Infeasible {
                constraints,
                active,
            } => write!(
                f,
                "no joint rates satisfy all {constraints} constraints at once \
                 ({active} of them conflict)"
            ),
            Error::NetworksUnavailable(msg) => write!(f, "networks not available: {msg}"),
            Error::NetworksForAnotherArm { trained, arm } => write!(
                f,
                "the networks were trained for an arm with post {} and links {:?}, not for this one (post {}, links {:?}); train networks for this arm",
                trained.0, trained.1, arm.0, arm.1
            ),
            Error::Weights(msg) => write!(f, "bad network weights: {msg}"),
            Error::Urdf(msg) => write!(f, "URDF: {msg}"),
            Error::NoObstacle => write!(
                f,
                "the scene has no obstacle; the atlas moves the first one over the grid"
            ),
            Error::EmptyRegion { region: [x0, x1, y0, y1] } => write!(
                f,
                "region x {x0}..{x1}, y {y0}..{y1} is empty: it needs x0 < x1 and y0 < y1"
            ),
            Error::Training(msg) => write!(f, "cannot train: {msg}"),
            Error::Figure(msg) => write!(f, "cannot draw the figure: {msg}"),
        }
    }
}

impl std::error::Error for Error {}

/// A number as a message shows it: as written for everyday magnitudes,
/// as `mantissa e exponent` beyond a million or below 1e-4 (`1e308` prints
/// as `1e308`, not as 309 digits). By hand rather than with `{:e}`, which
/// costs the page's module 1.2 KB gzipped; six significant digits.
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if !(x.is_finite() && x != 0.0 && !(1e-4..1e6).contains(&x.abs())) {
            return write!(f, "{x}");
        }
        let mut e = x.abs().log10().floor() as i32;
        // Scaled in two steps, so that neither 10^308 nor 10^-324 overflows.
        let scale = |x: f64, e: i32| x / 10f64.powi(e / 2) / 10f64.powi(e - e / 2);
        let mut m = (scale(x, e) * 1e5).round() / 1e5;
        if m.abs() >= 10.0 {
            e += 1;
            m = (scale(x, e) * 1e5).round() / 1e5;
        }
        write!(f, "{m}e{e}")
    }
}

/// A number with at most three decimals, trailing zeros dropped (a length
/// to the millimetre, an angle to the milliradian): a dragged obstacle's
/// centre is quoted as `0.6`, not `0.6000000238418579` or
/// `-0.00000007629394550197807`, a preset's limit as `2.094` (issue 27).
/// For messages and the figures' captions.
pub(crate) struct Short(pub(crate) f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.0.is_finite() {
            return write!(f, "{}", self.0);
        }
        let text = format!("{:.3}", self.0);
        let text = text.trim_end_matches('0').trim_end_matches('.');
        f.write_str(if text == "-0" { "0" } else { text })
    }
}

/// Text a message quotes, cut to 40 characters (an address can be
/// megabytes long).
pub(crate) fn clip(text: &str) -> String {
    match text.char_indices().nth(40) {
        Some((i, _)) => format!("{}…", &text[..i]),
        None => text.to_string(),
    }
}

/// Names for a message: `"a, b or c"`.
pub(crate) fn choices(names: &[&str]) -> String {
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", join(rest, ", ")),
        _ => join(names, ""),
    }
}

/// `names.join(separator)` by a loop: the standard library's generic join
/// costs the page's module 0.3 KB gzipped.
pub(crate) fn join(names: &[&str], separator: &str) -> String {
    let mut out = String::new();
    for (i, name) in names.iter().enumerate() {
        if i > 0 {
            out.push_str(separator);
        }
        out.push_str(name);
    }
    out
}

/// The one of `all` whose `name` is `text`, or [`Error::UnknownName`] of
/// `kind` listing every name (the `FromStr` of the crate's named choices).
pub(crate) fn by_name<T: Copy>(
    kind: &'static str,
    text: &str,
    all: &[T],
    name: impl Fn(T) -> &'static str,
) -> Result<T> {
    all.iter()
        .copied()
        .find(|&t| name(t) == text)
        .ok_or_else(|| Error::UnknownName {
            kind,
            // Cut to 40 characters: a page's call may pass megabytes.
            name: clip(text),
            choices: choices(&all.iter().map(|&t| name(t)).collect::<Vec<_>>()),
        })
}

mod checks;
pub use checks::MAX_COORDINATE;
pub(crate) use checks::{coordinate, finite, non_negative, pose_counts, positive, within};

#[cfg(test)]
mod tests;
