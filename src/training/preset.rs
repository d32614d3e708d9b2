//! The sizes of a training job the page and the workers offer, named: the
//! Training panel's menu reads them from here ([`Preset::ALL`],
//! [`Preset::label`]), so the page copies no size.

use serde::{Deserialize, Serialize};

use super::Recipe;

/// How big a training job is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// 1 000 samples, at most 100 epochs: seconds for the paper's arm.
    Quick,
    /// The paper's 3 000 samples and at most 400 epochs: the shipped files.
    Thorough,
    /// The `reach` recipe ([`Recipe::Reach`]): networks meant to hold over
    /// the whole workspace, at the recipe's sizes (the shipped `reach` set
    /// for the paper's arm).
    Reach,
}

impl Preset {
    /// The recipe it trains by.
    pub fn recipe(self) -> Recipe {
        match self {
            Preset::Quick | Preset::Thorough => Recipe::Paper,
            Preset::Reach => Recipe::Reach,
        }
    }

    /// Samples drawn, where the preset sets them (else the recipe's).
    pub fn samples(self) -> Option<usize> {
        match self {
            Preset::Quick => Some(1000),
            Preset::Thorough => Some(3000),
            Preset::Reach => None,
        }
    }

    /// Most epochs per network, where the preset sets
    /// them (else the recipe's).
    pub fn epochs(self) -> Option<usize> {
        match self {
            Preset::Quick => Some(100),
            Preset::Thorough => Some(400),
            Preset::Reach => None,
        }
    }

    /// Every preset, in the order of the menu (the first is the default).
    pub const ALL: [Preset; 3] = [Preset::Quick, Preset::Thorough, Preset::Reach];

    /// The name in requests and the page (`quick`, `thorough`, `reach`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::Quick => "quick",
            Preset::Thorough => "thorough",
            Preset::Reach => "reach",
        }
    }

    /// What the menu says of it (its sizes; `tests/training.rs` checks
    /// that the text says the sizes [`Preset::samples`] and
    /// [`Preset::epochs`] give). The reach preset's time is the page's
    /// measured one (70 s in headless Chromium, two cores,
    /// `docs/learning.md`).
    pub fn label(self) -> &'static str {
        match self {
            Preset::Quick => "Quick: 1 000 samples, ≤ 100 epochs",
            Preset::Thorough => "Thorough: 3 000 samples, ≤ 400 epochs (the paper's)",
            Preset::Reach => "Whole reach: every pose, about a minute",
        }
    }
}
