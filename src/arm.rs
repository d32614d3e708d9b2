//! The planar redundant arm: a fixed vertical base post and `n` revolute links.
//!
//! Conventions (`docs/conventions.md`, "The arm and its coordinates"): the absolute angle of link `i`
//! is `phi_i = theta_1 + ... + theta_i`, measured from the vertical axis towards
//! `+X1`, so joint `k` sits at `P(k) = P(k-1) + L_k (sin phi_k, cos phi_k)` with
//! `P(0) = (0, L0)` the top of the post. The end effector is `X = P(n)`.

use std::fmt;
use std::str::FromStr;

use nalgebra::{DVector, Vector2};
use serde::{Deserialize, Serialize};

use crate::error::{clip, coordinate, non_negative, positive, Error, Result};

mod limits;
mod preset;

pub use limits::{JointLimits, RateLimits};
pub use preset::{Preset, PresetTask, PRESETS};

/// Fewest links an [`Arm`] may have: two, to position a planar end effector.
pub const MIN_LINKS: usize = 2;

/// Most links an [`Arm`] may have. The page offers 2 to 6; the limit keeps
/// the networks' fixed-size input buffers sufficient and refuses absurd input.
pub const MAX_LINKS: usize = 32;

/// Largest joint angle accepted (rad), about 160 000 turns: far beyond any
/// run (the numerical route turns a joint by a few radians per task), small
/// enough that sums of angles stay exact to a microradian and finite.
/// Without it, `theta = [1e308, 1e308, ...]` passed as finite and its
/// absolute angles overflowed to NaN positions (found by fuzzing).
pub const MAX_ANGLE: f64 = 1.0e6;

/// A planar arm on a vertical base post of length `post`, with revolute links of
/// lengths `links[0..n]` (the paper's `L0` and `L1..L3`).
///
/// It may carry per-joint position and rate limits ([`JointLimits`],
/// [`RateLimits`]); absent, a joint is unlimited (the paper's arm). They are
/// written as `joint_limits` and `rate_limits` only when present, so an
/// unlimited arm's JSON is as before.
///
/// An arm deserialises through [`Arm::new`] and [`Arm::with_limits`], so a
/// scene or a weights file cannot carry an arm that they would refuse.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ArmFields")]
pub struct Arm {
    post: f64,
    links: Vec<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    joint_limits: Option<JointLimits>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rate_limits: Option<RateLimits>,
}

impl Arm {
    /// An arm with the given post height and link lengths (metres).
    ///
    /// The post may be zero (base joint on the ground); every link must be a
    /// positive finite length, and there must be at least two links so that the
    /// end effector can reach a planar neighbourhood. Lengths beyond
    /// [`crate::error::MAX_COORDINATE`] are refused (their joint positions would overflow).
    pub fn new(post: f64, links: Vec<f64>) -> Result<Self> {
        non_negative("post length L0", post)?;
        coordinate("post length L0", post)?;
        if !(MIN_LINKS..=MAX_LINKS).contains(&links.len()) {
            return Err(Error::LinkCount {
                found: links.len(),
                min: MIN_LINKS,
                max: MAX_LINKS,
            });
        }
        for (i, &l) in links.iter().enumerate() {
            let what = format!("link length L{}", i + 1);
            positive(&what, l)?;
            coordinate(&what, l)?;
        }
        Ok(Self {
            post,
            links,
            joint_limits: None,
            rate_limits: None,
        })
    }

    /// This arm with the given position and rate limits (`None`:
    /// unlimited), refused when either has not one entry per link.
    pub fn with_limits(
        mut self,
        joint_limits: Option<JointLimits>,
        rate_limits: Option<RateLimits>,
    ) -> Result<Self> {
        let count = |what: &str, found: usize| match found == self.dof() {
            true => Ok(()),
            false => Err(Error::DimensionMismatch {
                what: what.into(),
                expected: self.dof(),
                found,
            }),
        };
        if let Some(l) = &joint_limits {
            count("joint limits", l.ranges().len())?;
        }
        if let Some(r) = &rate_limits {
            count("rate limits", r.rates().len())?;
        }
        self.joint_limits = joint_limits;
        self.rate_limits = rate_limits;
        Ok(self)
    }

    /// Each joint's position range, if the arm has limits.
    pub fn joint_limits(&self) -> Option<&JointLimits> {
        self.joint_limits.as_ref()
    }

    /// Each joint's largest rate, if the arm has rate limits.
    pub fn rate_limits(&self) -> Option<&RateLimits> {
        self.rate_limits.as_ref()
    }

    /// Checks that the pose `theta` (`what` names it in the message) lies
    /// within the joints' position limits; any pose does when there are none.
    pub fn check_within_limits(&self, what: &str, theta: &[f64]) -> Result<()> {
        self.joint_limits
            .as_ref()
            .map_or(Ok(()), |l| l.check(what, theta))
    }

    /// Whether `other` has the same post and links, whatever the limits of
    /// either: the kinematics are the same, so networks trained for one fit
    /// the other.
    pub fn same_geometry(&self, other: &Arm) -> bool {
        self.post == other.post && self.links == other.links
    }

    /// Checks every field again (what [`Arm::new`] and
    /// [`Arm::with_limits`] checked).
    pub fn validate(&self) -> Result<()> {
        Arm::new(self.post, self.links.clone())?
            .with_limits(self.joint_limits.clone(), self.rate_limits.clone())
            .map(|_| ())
    }

    /// The paper's arm (section VI): `L0 = 0.5`, `L1 = 0.6`, `L2 = 0.85`, `L3 = 0.6` m.
    pub fn paper() -> Self {
        PRESETS[0].arm()
    }

    /// Number of joints `n`.
    pub fn dof(&self) -> usize {
        self.links.len()
    }

    /// Height of the fixed base post, `L0`.
    pub fn post(&self) -> f64 {
        self.post
    }

    /// Link lengths `L1..Ln`.
    pub fn links(&self) -> &[f64] {
        &self.links
    }

    /// Top of the post, `P(0) = (0, L0)`: the first revolute joint.
    pub fn base(&self) -> Vector2<f64> {
        Vector2::new(0.0, self.post)
    }

    /// Largest distance from `P(0)` that the end effector can reach.
    pub fn max_reach(&self) -> f64 {
        self.links.iter().sum()
    }

    /// Smallest distance from `P(0)` that the end effector can reach
    /// (zero unless one link is longer than all others together).
    pub fn min_reach(&self) -> f64 {
        let longest = self.links.iter().cloned().fold(0.0, f64::max);
        (2.0 * longest - self.max_reach()).max(0.0)
    }

    /// Whether the point lies in the reachable annulus around `P(0)`.
    pub fn can_reach(&self, point: &Vector2<f64>) -> bool {
        let r = (point - self.base()).norm();
        r <= self.max_reach() && r >= self.min_reach()
    }

    /// Checks that `theta` has `n` finite entries.
    pub fn check_theta(&self, theta: &DVector<f64>) -> Result<()> {
        self.check_angles(theta.as_slice())
    }

    /// Checks that `theta` has `n` finite entries, none beyond
    /// [`MAX_ANGLE`] ([`check_angles`]).
    pub fn check_angles(&self, theta: &[f64]) -> Result<()> {
        check_angles(theta, self.dof())
    }
}

/// Checks that `theta` has `n` finite entries, none beyond [`MAX_ANGLE`]
/// (the message is only formatted when there is a problem): every arm's
/// angles, the planar arm's and a chain's.
pub fn check_angles(theta: &[f64], n: usize) -> Result<()> {
    if theta.len() != n {
        return Err(Error::DimensionMismatch {
            what: "theta".into(),
            expected: n,
            found: theta.len(),
        });
    }
    match theta.iter().position(|t| t.abs() > MAX_ANGLE || t.is_nan()) {
        Some(i) if theta[i].is_finite() => Err(Error::TooLarge {
            what: format!("theta_{}", i + 1),
            value: theta[i],
            max: MAX_ANGLE,
            unit: "rad",
        }),
        Some(i) => Err(Error::NonFinite {
            what: format!("theta_{}", i + 1),
        }),
        None => Ok(()),
    }
}

/// The fields of an arm as a file or a scene writes them, checked by
/// [`Arm::new`] when they become an [`Arm`].
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ArmFields {
    post: f64,
    links: Vec<f64>,
    #[serde(default)]
    joint_limits: Option<JointLimits>,
    #[serde(default)]
    rate_limits: Option<RateLimits>,
}

impl TryFrom<ArmFields> for Arm {
    type Error = Error;
    fn try_from(f: ArmFields) -> Result<Self> {
        Arm::new(f.post, f.links)?.with_limits(f.joint_limits, f.rate_limits)
    }
}

/// The arm syntax of the command line (`--arm`), the page's address
/// (`arm=`) and its stored weights: `POST:L1,L2,...` in metres, e.g.
/// `0.5:0.6,0.85,0.6` for the paper's arm.
impl FromStr for Arm {
    type Err = Error;
    fn from_str(text: &str) -> Result<Self> {
        let syntax = |expected: String| Error::Syntax {
            what: "arm",
            text: text.to_string(),
            expected,
        };
        let (post, links) = text
            .trim()
            .split_once(':')
            .ok_or_else(|| syntax("expected POST:L1,L2,... (e.g. 0.5:0.6,0.85,0.6)".into()))?;
        let post = number(post).map_err(&syntax)?;
        let links = number_list(links).map_err(&syntax)?;
        Arm::new(post, links).map_err(|e| syntax(e.to_string()))
    }
}

/// `POST:L1,L2,...`, each number as short as it round-trips (what
/// [`Arm::from_str`] reads back to the same arm).
impl fmt::Display for Arm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:", self.post)?;
        for (i, l) in self.links.iter().enumerate() {
            write!(f, "{}{l}", if i == 0 { "" } else { "," })?;
        }
        Ok(())
    }
}

/// One finite number from text, or why not: decimal or scientific
/// notation, an optional sign, digits on either side of the point (`.5`,
/// `5.` and `+5` read as people mean them).
///
/// Read by serde_json's number parser rather than `str::parse`: the page's
/// module carries serde_json's for the weights files anyway, and core's own
/// costs it 13.5 KB gzipped (178.8 -> 165.2 KB, measured with `make web`);
/// through the same JSON tree as the weights files ([`crate::json::Json`]),
/// so that one monomorphisation of the parser serves both.
/// Exact with the feature `exact-floats`; without it (the page's module)
/// exact for decimals of up to 15 significant digits (Clinger's fast path),
/// which is what people type, and within a unit in the last place beyond.
pub(crate) fn number(text: &str) -> std::result::Result<f64, String> {
    let t = text.trim();
    let refused = || format!("'{}' is not a finite number", clip(t));
    let (sign, digits) = match t.strip_prefix('-') {
        Some(rest) => ("-", rest),
        None => ("", t.strip_prefix('+').unwrap_or(t)),
    };
    // A digit before the exponent, at least.
    let mantissa = digits.split(['e', 'E']).next().unwrap_or("");
    if !mantissa.bytes().any(|b| b.is_ascii_digit()) {
        return Err(refused());
    }
    // JSON's grammar: no leading '+', no bare '.', no leading zeros.
    let digits = digits.trim_start_matches('0');
    let lead = if digits.is_empty() || digits.starts_with(['.', 'e', 'E']) {
        "0"
    } else {
        ""
    };
    let body = match digits.split_once('.') {
        Some((int, frac)) if frac.is_empty() || frac.starts_with(['e', 'E']) => {
            format!("{int}.0{frac}")
        }
        _ => digits.to_string(),
    };
    if body.starts_with(['-', '+']) {
        return Err(refused());
    }
    match serde_json::from_str::<crate::json::Json>(&format!("{sign}{lead}{body}")) {
        Ok(json) => match json.number() {
            Some(x) if x.is_finite() => Ok(x),
            _ => Err(refused()),
        },
        _ => Err(refused()),
    }
}

/// A comma-separated list of finite numbers, or why not.
pub(crate) fn number_list(text: &str) -> std::result::Result<Vec<f64>, String> {
    text.split(',').map(number).collect()
}

#[cfg(test)]
mod tests {
    use super::number;

    #[test]
    fn numbers_read_as_people_write_them() {
        for (text, value) in [
            ("0.6", 0.6),
            (" 0.85 ", 0.85),
            ("-1", -1.0),
            ("+2", 2.0),
            (".5", 0.5),
            ("-.5", -0.5),
            ("5.", 5.0),
            ("007", 7.0),
            ("0", 0.0),
            ("-0", 0.0),
            ("1e-3", 1e-3),
            ("2.5E2", 250.0),
            ("5.e1", 50.0),
            ("0.1", 0.1),
            ("1e308", 1e308),
        ] {
            assert_eq!(number(text), Ok(value), "{text}");
        }
        if cfg!(feature = "exact-floats") {
            let x = 0.30000000000000004;
            assert_eq!(number("0.30000000000000004"), Ok(x));
        }
        for text in [
            "", "abc", "1,5", "NaN", "inf", "-", "+", ".", "1e999", "--1", "+-1", "0x10", "1 2",
            "e5",
        ] {
            assert!(number(text).is_err(), "{text} is refused");
        }
    }

    /// What people type (up to 15 significant digits, modest exponents)
    /// reads to the same `f64` as core's exact parser, with and without
    /// `exact-floats` (`make test-native` runs this without it too, as the
    /// page's module is built).
    #[test]
    fn short_decimals_read_exactly_with_or_without_exact_floats() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..20_000 {
            let digits = 1 + next() % 15;
            let mantissa = next() % 10u64.pow(digits as u32);
            let point = next() % (digits + 1);
            let exponent = (next() % 21) as i32 - 10;
            let mut text = mantissa.to_string();
            while text.len() < point as usize + 1 {
                text.insert(0, '0');
            }
            text.insert(text.len() - point as usize, '.');
            let text = format!("{text}e{exponent}");
            let want: f64 = text.parse().unwrap();
            assert_eq!(number(&text), Ok(want), "{text}");
        }
    }
}
