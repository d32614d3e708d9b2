//! The checks of numbers that every setter and parser makes, each naming
//! the number in its error.

use super::{Error, Result};

/// Checks that `value` is finite, naming it in the error.
pub(crate) fn finite(what: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite { what: what.into() })
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
        Err(Error::TooLarge {
            what: what.into(),
            value,
            max: MAX_COORDINATE,
            unit: "m",
        })
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(what: &str, value: f64) -> Result<f64> {
    finite(what, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::NotPositive {
            what: what.into(),
            value,
        })
    }
}

/// Checks that `value` is finite and in `[min, max]`.
pub(crate) fn within(what: &str, value: f64, min: f64, max: f64) -> Result<f64> {
    finite(what, value)?;
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(Error::OutOfRange {
            what: what.into(),
            value,
            min,
            max,
        })
    }
}

/// Checks that `value` is finite and not negative.
pub(crate) fn non_negative(what: &str, value: f64) -> Result<f64> {
    finite(what, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::Negative {
            what: what.into(),
            value,
        })
    }
}

/// Checks that a pose of `n` joints is updated for an arm of `arm` joints
/// with `theta` of `theta` angles: every arm's pose.
pub(crate) fn pose_counts(n: usize, arm: usize, theta: usize) -> Result<()> {
    if theta != n || arm != n {
        return Err(Error::DimensionMismatch {
            what: "theta for this pose".into(),
            expected: n,
            found: if arm != n { arm } else { theta },
        });
    }
    Ok(())
}
