//! Errors as values. Every message names the problem so that a user can act
//! on it; nothing in the core panics on user input.

use std::fmt;

/// Everything that can go wrong in the core.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// A number that must be finite was NaN or infinite.
    NonFinite(String),
    /// A value outside its legal range (non-positive length or step, ...).
    InvalidValue(String),
    /// Vector or matrix of the wrong size (e.g. `theta` with 2 entries for a 3-link arm).
    DimensionMismatch {
        /// What was checked.
        what: String,
        /// Entries expected.
        expected: usize,
        /// Entries found.
        found: usize,
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
    /// `J J^T + delta I` (eq. 17) cannot be solved: the arm is at a singular pose and no
    /// damping is on.
    Singular(String),
    /// An integration step produced non-finite joint angles; the state was left unchanged.
    Diverged(String),
    /// A network mode was requested but no trained networks are loaded.
    NetworksUnavailable(String),
    /// A network weights file is corrupt or does not fit.
    Weights(String),
}

/// Result alias used throughout the crate.
pub type Result<T> = std::result::Result<T, Error>;

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite(what) => write!(f, "{what} must be a finite number (got NaN or infinity)"),
            Error::InvalidValue(msg) => write!(f, "{msg}"),
            Error::DimensionMismatch {
                what,
                expected,
                found,
            } => write!(f, "{what} has {found} entries, expected {expected}"),
            Error::ObstacleOnPost { x, y, radius } => write!(
                f,
                "obstacle at ({x}, {y}) with radius {radius} overlaps the fixed base post; move it away from the post"
            ),
            Error::Singular(msg) => write!(f, "singular pose: {msg}"),
            Error::Diverged(msg) => write!(f, "integration diverged: {msg}"),
            Error::NetworksUnavailable(msg) => write!(f, "networks not available: {msg}"),
            Error::Weights(msg) => write!(f, "bad network weights: {msg}"),
        }
    }
}

impl std::error::Error for Error {}

/// Checks that `value` is finite, naming it in the error.
pub(crate) fn finite(what: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite(what.to_string()))
    }
}

/// Largest coordinate (m) accepted for a target or an obstacle: far beyond
/// any arm's reach, small enough that squared distances cannot overflow.
pub const MAX_COORDINATE: f64 = 1.0e4;

/// Checks that a coordinate or length in metres is finite and within
/// [`MAX_COORDINATE`] of zero.
pub(crate) fn coordinate(what: &str, value: f64) -> Result<f64> {
    finite(what, value)?;
    if value.abs() <= MAX_COORDINATE {
        Ok(value)
    } else {
        Err(Error::InvalidValue(format!(
            "{what} must lie within ±{MAX_COORDINATE} m (got {value})"
        )))
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(what: &str, value: f64) -> Result<f64> {
    finite(what, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidValue(format!(
            "{what} must be positive (got {value})"
        )))
    }
}
