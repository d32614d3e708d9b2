//! The five methods of the paper's section VI and their names.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// How `Phi` and `v` are computed (paper section VI).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// No provision for obstacle avoidance: `v = 0`, eqs. (17)-(18) (Figs. 2, 7).
    None,
    /// Numerical approach: eqs. (17)-(18) with `v` from eq. (14) (Figs. 3, 8).
    Numerical,
    /// Case 1: `Phi` by a network, `v` numerically, eq. (21) (Figs. 4, 9).
    Case1,
    /// Case 2: `Phi` numerically, `v` by a network (Figs. 5, 10).
    Case2,
    /// Case 3: both `Phi` and `v` by networks, eq. (21) (Figs. 6, 11).
    Case3,
}

impl Mode {
    /// All five modes, in the paper's order.
    pub const ALL: [Mode; 5] = [
        Mode::None,
        Mode::Numerical,
        Mode::Case1,
        Mode::Case2,
        Mode::Case3,
    ];

    /// The name used on the command line, in JSON and in the page.
    pub fn name(self) -> &'static str {
        match self {
            Mode::None => "none",
            Mode::Numerical => "numerical",
            Mode::Case1 => "case1",
            Mode::Case2 => "case2",
            Mode::Case3 => "case3",
        }
    }

    /// The name people read in menus and legends: "No avoidance",
    /// "Numerical", "Case 1", "Case 2", "Case 3" (the paper's terms).
    pub fn label(self) -> &'static str {
        match self {
            Mode::None => "No avoidance",
            Mode::Numerical => "Numerical",
            Mode::Case1 => "Case 1",
            Mode::Case2 => "Case 2",
            Mode::Case3 => "Case 3",
        }
    }

    /// What the mode computes, in one line.
    pub fn description(self) -> &'static str {
        match self {
            Mode::None => "v = 0, no obstacle avoidance",
            Mode::Numerical => "Φ and v computed exactly",
            Mode::Case1 => "Φ by a network, v exact",
            Mode::Case2 => "Φ exact, v by a network",
            Mode::Case3 => "Φ and v by networks",
        }
    }

    /// `label: description`, for titles and captions.
    pub fn title(self) -> String {
        format!("{}: {}", self.label(), self.description())
    }

    /// Whether `Phi` comes from a network (Cases 1 and 3).
    pub fn learned_phi(self) -> bool {
        matches!(self, Mode::Case1 | Mode::Case3)
    }

    /// Whether `v` comes from a network (Cases 2 and 3).
    pub fn learned_v(self) -> bool {
        matches!(self, Mode::Case2 | Mode::Case3)
    }

    /// Whether the mode avoids obstacles at all.
    pub fn avoids(self) -> bool {
        self != Mode::None
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Mode {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        Mode::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| Error::UnknownName {
                kind: "mode",
                name: s.into(),
                choices: "none, numerical, case1, case2 or case3",
            })
    }
}
