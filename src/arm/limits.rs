//! The limits an arm carries: each joint's position range `[lo, hi]`
//! (rad) and each joint's largest rate (rad/s), as robot models state them
//! (URDF's `<limit lower upper velocity>`; Siciliano et al., *Robotics:
//! Modelling, Planning and Control*, 2009, sec. 3.8: `theta_min <= theta
//! <= theta_max`, `|theta_dot| <= theta_dot_max`). Absent on an [`Arm`]
//! means unlimited, as the paper's arm is.
//!
//! One syntax, shared by the command line (`--joint-limits`,
//! `--rate-limits`) and the page's address (`limits=`, `rates=`):
//! `LO:HI,LO:HI,...` and `R,R,...`, one entry per link, read by
//! [`FromStr`] and written back by [`fmt::Display`].
//!
//! [`Arm`]: super::Arm

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::{number, number_list};
use crate::error::{finite, positive, Error, Result};

/// Each joint's position range `[lo, hi]` (rad), `lo < hi`, both finite:
/// joint `k` may turn `theta_k` only within its range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<[f64; 2]>", into = "Vec<[f64; 2]>")]
pub struct JointLimits(Vec<[f64; 2]>);

impl JointLimits {
    /// The ranges, one per joint; refused when a bound is not finite or a
    /// range is empty (`lo >= hi`).
    pub fn new(ranges: Vec<[f64; 2]>) -> Result<Self> {
        for (i, &[lo, hi]) in ranges.iter().enumerate() {
            finite(&format!("lower limit of joint {}", i + 1), lo)?;
            finite(&format!("upper limit of joint {}", i + 1), hi)?;
            if lo >= hi {
                return Err(Error::EmptyRange {
                    joint: i + 1,
                    range: [lo, hi],
                });
            }
        }
        Ok(Self(ranges))
    }

    /// Ranges known to pass [`JointLimits::new`] (a preset's).
    pub(super) fn from_checked(ranges: Vec<[f64; 2]>) -> Self {
        Self(ranges)
    }

    /// The ranges `[lo, hi]`, joint 1 first.
    pub fn ranges(&self) -> &[[f64; 2]] {
        &self.0
    }

    /// Checks that every angle of `theta` lies in its joint's range (the
    /// bounds included); `what` says which pose the message is about.
    pub fn check(&self, what: &str, theta: &[f64]) -> Result<()> {
        for (i, (&angle, &[lo, hi])) in theta.iter().zip(&self.0).enumerate() {
            if !(lo..=hi).contains(&angle) {
                return Err(Error::OutOfRange {
                    what: format!("{what}: theta_{} (joint {}'s limits)", i + 1, i + 1),
                    value: angle,
                    min: lo,
                    max: hi,
                });
            }
        }
        Ok(())
    }
}

/// How close to a limit (as a share of the joint's range) the joint-range
/// criterion is evaluated at most: at and beyond a limit `H` is unbounded
/// (its product changes sign), so the distances to the limits are floored
/// here, which keeps `H` and its gradient finite (about `1e11 / range` at
/// the floor) and pointing back into the range.
const RANGE_FLOOR: f64 = 1e-6;

impl JointLimits {
    /// The distances `(hi - theta, theta - lo)` of joint `i` at `theta`,
    /// each floored at [`RANGE_FLOOR`] times the range.
    #[inline]
    fn margins(&self, i: usize, theta: f64) -> (f64, f64, f64) {
        let [lo, hi] = self.0[i];
        let floor = RANGE_FLOOR * (hi - lo);
        ((hi - theta).max(floor), (theta - lo).max(floor), hi - lo)
    }

    /// The joint-range criterion of Chan and Dubey (1995, eq. 6),
    /// `H(theta) = sum_i (hi_i - lo_i)^2 / (4 (hi_i - theta_i)(theta_i - lo_i))`:
    /// 1 per joint at the middle of its range, growing without bound toward
    /// either limit (the distances floored at a millionth of the range).
    pub fn range_criterion(&self, theta: &[f64]) -> f64 {
        theta
            .iter()
            .enumerate()
            .take(self.0.len())
            .map(|(i, &t)| {
                let (up, down, range) = self.margins(i, t);
                range * range / (4.0 * up * down)
            })
            .sum()
    }

    /// The gradient of [`JointLimits::range_criterion`] into `out` (one
    /// entry per joint):
    /// `dH/dtheta_i = (hi_i - lo_i)^2 (2 theta_i - hi_i - lo_i) / (4 (hi_i - theta_i)^2 (theta_i - lo_i)^2)`,
    /// zero at the middle, positive above it, negative below.
    pub fn range_gradient_into(&self, theta: &[f64], out: &mut [f64]) {
        for (i, (o, &t)) in out.iter_mut().zip(theta).enumerate().take(self.0.len()) {
            let (up, down, range) = self.margins(i, t);
            // 2 theta - hi - lo = (theta - lo) - (hi - theta), from the
            // floored distances so the sign holds beyond a limit.
            *o = range * range * (down - up) / (4.0 * up * up * down * down);
        }
    }
}

impl TryFrom<Vec<[f64; 2]>> for JointLimits {
    type Error = Error;
    fn try_from(ranges: Vec<[f64; 2]>) -> Result<Self> {
        Self::new(ranges)
    }
}

impl From<JointLimits> for Vec<[f64; 2]> {
    fn from(limits: JointLimits) -> Self {
        limits.0
    }
}

/// `LO:HI,LO:HI,...` in radians, e.g. `-2.0944:2.0944,-2.0944:2.0944,-2.0944:2.0944`.
impl FromStr for JointLimits {
    type Err = Error;
    fn from_str(text: &str) -> Result<Self> {
        let syntax = |expected: String| Error::Syntax {
            what: "joint limits",
            text: text.to_string(),
            expected,
        };
        let ranges = text
            .split(',')
            .map(|pair| {
                let (lo, hi) = pair.split_once(':').ok_or_else(|| {
                    format!(
                        "expected LO:HI for each joint (e.g. -2.0944:2.0944), got '{}'",
                        pair.trim()
                    )
                })?;
                Ok([number(lo)?, number(hi)?])
            })
            .collect::<std::result::Result<Vec<_>, String>>()
            .map_err(&syntax)?;
        Self::new(ranges).map_err(|e| syntax(e.to_string()))
    }
}

/// `LO:HI,LO:HI,...`, each number as short as it round-trips.
impl fmt::Display for JointLimits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, [lo, hi]) in self.0.iter().enumerate() {
            write!(f, "{}{lo}:{hi}", if i == 0 { "" } else { "," })?;
        }
        Ok(())
    }
}

/// Each joint's largest rate `|theta_dot_k| <= R_k` (rad/s), positive and
/// finite.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<f64>", into = "Vec<f64>")]
pub struct RateLimits(Vec<f64>);

impl RateLimits {
    /// The rate limits, one per joint; refused when one is not positive
    /// and finite.
    pub fn new(rates: Vec<f64>) -> Result<Self> {
        for (i, &r) in rates.iter().enumerate() {
            positive(&format!("rate limit of joint {}", i + 1), r)?;
        }
        Ok(Self(rates))
    }

    /// Rates known to pass [`RateLimits::new`] (a preset's).
    pub(super) fn from_checked(rates: Vec<f64>) -> Self {
        Self(rates)
    }

    /// The rate limits (rad/s), joint 1 first.
    pub fn rates(&self) -> &[f64] {
        &self.0
    }
}

impl TryFrom<Vec<f64>> for RateLimits {
    type Error = Error;
    fn try_from(rates: Vec<f64>) -> Result<Self> {
        Self::new(rates)
    }
}

impl From<RateLimits> for Vec<f64> {
    fn from(limits: RateLimits) -> Self {
        limits.0
    }
}

/// `R,R,...` in rad/s, e.g. `1.5,1.5,2`.
impl FromStr for RateLimits {
    type Err = Error;
    fn from_str(text: &str) -> Result<Self> {
        let syntax = |expected: String| Error::Syntax {
            what: "rate limits",
            text: text.to_string(),
            expected,
        };
        let rates = number_list(text).map_err(&syntax)?;
        Self::new(rates).map_err(|e| syntax(e.to_string()))
    }
}

/// `R,R,...`, each number as short as it round-trips.
impl fmt::Display for RateLimits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, r) in self.0.iter().enumerate() {
            write!(f, "{}{r}", if i == 0 { "" } else { "," })?;
        }
        Ok(())
    }
}
