//! How the methods built on the paper's eq. (5) use the arm's joint limits:
//! not at all (the paper's experiment, whose arm has none), or through the
//! weight matrix `W` of eq. (7), "usually a diagonal matrix to deal with
//! joint limits", as weighted least norm (Chan and Dubey 1995) makes it.
//! The methods' side is `crate::planner::methods::weighting`.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::error::{Error, Result};

/// The scene's switch `--joint-weighting` (address `weighting=`, JSON
/// `joint_weighting`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum JointWeighting {
    /// `W = I`: the rates are the paper's, whatever the limits.
    #[default]
    None,
    /// Weighted least norm: `W = diag(1 + |dH/dtheta_i|)` for the joints
    /// moving toward a limit, 1 for the others (`H` the joint-range
    /// criterion, [`crate::arm::JointLimits::range_criterion`]).
    Wln,
}

impl JointWeighting {
    /// Every choice, in the order of the page's menu.
    pub const ALL: [JointWeighting; 2] = [JointWeighting::None, JointWeighting::Wln];

    /// Its name on the command line, in the address and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            JointWeighting::None => "none",
            JointWeighting::Wln => "wln",
        }
    }

    /// What the page's menu says.
    pub fn label(self) -> &'static str {
        match self {
            JointWeighting::None => "None (W = I, the paper's)",
            JointWeighting::Wln => "Weighted least norm (W from the limits)",
        }
    }

    /// Whether it is the paper's `W = I`.
    pub fn is_none(&self) -> bool {
        *self == JointWeighting::None
    }
}

impl fmt::Display for JointWeighting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for JointWeighting {
    type Err = Error;
    fn from_str(text: &str) -> Result<Self> {
        crate::error::by_name("joint weighting", text.trim(), &Self::ALL, Self::name)
    }
}

impl Serialize for JointWeighting {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for JointWeighting {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}
