//! What a run is: a scene (from a paper task), a method, and the networks
//! the method uses (a shipped set by name, or the user's own weights
//! files). The session produces it ([`crate::session::Session::run`]); the
//! page's workers (atlas, files to take away, training check) and the run
//! file take it, so a run made with the whole-reach networks is saved,
//! mapped and replayed with them (`simulate --from`).

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::networks::space::{SpaceNetworkSet, SpaceNetworks};
use crate::networks::{self, NetworkSet, Networks};
use crate::nn::Precision;
use crate::planner::{Method, Surrogate};
use crate::scene::Scene;

/// The networks of a run: a shipped set `S` (the planar arm's
/// [`NetworkSet`], an arm in space's [`SpaceNetworkSet`]), or a pair of
/// weights files. Written `{"set": "reach"}` or `{"phi": "<weights
/// file>", "v": "<weights file>"}` (the files' JSON text, so a run file
/// replays without them).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(
    try_from = "ChoiceFields<S>",
    into = "ChoiceFields<S>",
    bound(
        serialize = "S: Serialize + Clone",
        deserialize = "S: Deserialize<'de>"
    )
)]
pub enum NetworkChoice<S = NetworkSet> {
    /// A shipped set ([`networks::builtin_set`], [`SpaceNetworkSet::load`]).
    Set(S),
    /// The user's weights files (trained in the page or by `train`, or
    /// loaded), as JSON text.
    Files {
        /// The `Phi` network's file.
        phi: String,
        /// The `v` network's file.
        v: String,
    },
}

/// The JSON form of a [`NetworkChoice`]: one flat object (serde's enum
/// machinery costs the page's module kilobytes).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ChoiceFields<S> {
    #[serde(default = "none", skip_serializing_if = "Option::is_none")]
    set: Option<S>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    phi: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    v: Option<String>,
}

fn none<S>() -> Option<S> {
    None
}

impl<S> TryFrom<ChoiceFields<S>> for NetworkChoice<S> {
    type Error = Error;
    fn try_from(f: ChoiceFields<S>) -> Result<Self> {
        match f {
            ChoiceFields {
                set: Some(set),
                phi: None,
                v: None,
            } => Ok(NetworkChoice::Set(set)),
            ChoiceFields {
                set: None,
                phi: Some(phi),
                v: Some(v),
            } => Ok(NetworkChoice::Files { phi, v }),
            _ => Err(Error::Syntax {
                what: "networks of a run",
                text: String::new(),
                expected: "either a shipped set ({\"set\": \"reach\"}) or both weights files ({\"phi\": ..., \"v\": ...})".into(),
            }),
        }
    }
}

impl<S> From<NetworkChoice<S>> for ChoiceFields<S> {
    fn from(c: NetworkChoice<S>) -> Self {
        match c {
            NetworkChoice::Set(set) => ChoiceFields {
                set: Some(set),
                phi: None,
                v: None,
            },
            NetworkChoice::Files { phi, v } => ChoiceFields {
                set: None,
                phi: Some(phi),
                v: Some(v),
            },
        }
    }
}

impl NetworkChoice {
    /// The networks chosen, loaded (a shipped set is loaded once and
    /// shared); or why they cannot be.
    pub fn load(&self) -> Result<Arc<Networks>> {
        match self {
            NetworkChoice::Set(set) => networks::builtin_set(*set),
            NetworkChoice::Files { phi, v } => Ok(Arc::new(Networks::from_json(phi, v)?)),
        }
    }
}

impl<S: Copy> NetworkChoice<S> {
    /// The shipped set, if the choice is one.
    pub fn set(&self) -> Option<S> {
        match self {
            NetworkChoice::Set(set) => Some(*set),
            NetworkChoice::Files { .. } => None,
        }
    }
}

impl NetworkChoice<SpaceNetworkSet> {
    /// The networks chosen for an arm in space, loaded (a shipped set
    /// once per process, where the module carries the files); or why
    /// they cannot be.
    pub fn load(&self) -> Result<Arc<SpaceNetworks>> {
        match self {
            #[cfg(feature = "embedded-weights")]
            NetworkChoice::Set(set) => set.load(),
            #[cfg(not(feature = "embedded-weights"))]
            NetworkChoice::Set(set) => Err(Error::NetworksUnavailable(format!(
                "this module carries no weights: the set {} is weights/{} and weights/{}",
                set.name(),
                set.file_names()[0],
                set.file_names()[1]
            ))),
            NetworkChoice::Files { phi, v } => Ok(Arc::new(SpaceNetworks::read(phi, v)?)),
        }
    }
}

/// One run: everything a result depends on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Run {
    /// The paper task the scene came from (its start pose, target and
    /// obstacles may have been changed since: the scene says what runs).
    pub task: u32,
    /// The method (`mode` in files written before this name).
    #[serde(alias = "mode")]
    pub method: Method,
    /// Everything that defines the motion.
    pub scene: Scene,
    /// The networks of the methods that use them; absent: the paper's set
    /// (what runs written before this field used).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub networks: Option<NetworkChoice>,
    /// The arithmetic the networks computed in; absent: `f64` (what runs
    /// written before this field used, and the command line's default).
    #[serde(default, skip_serializing_if = "Precision::is_f64")]
    pub precision: Precision,
}

impl Run {
    /// The networks the run's methods use, loaded and checked against the
    /// arm: the chosen ones, or the paper's set where none is chosen, in
    /// the run's precision; an error where they were trained for another
    /// arm.
    pub fn load_networks(&self) -> Result<Arc<Networks>> {
        let chosen = self
            .networks
            .as_ref()
            .map(NetworkChoice::<NetworkSet>::load)
            .transpose()?;
        if let Some(n) = &chosen {
            if !n.arm().same_geometry(&self.scene.arm) {
                return Err(Error::NetworksUnavailable(format!(
                    "the networks of this run were trained for the arm {}, not for {}",
                    n.arm(),
                    self.scene.arm
                )));
            }
        }
        let nets = networks::available(&self.scene.arm, chosen.as_ref())?;
        Ok(nets.in_precision(self.precision))
    }

    /// The networks `method` runs with: none for a method without networks,
    /// else [`Run::load_networks`].
    pub fn surrogate_for(&self, method: Method) -> Result<Option<Arc<dyn Surrogate>>> {
        if !method.uses_networks() {
            return Ok(None);
        }
        Ok(Some(self.load_networks()? as Arc<dyn Surrogate>))
    }

    /// Checks the scene (a run is user input where it comes from a file or
    /// the page).
    pub fn validate(&self) -> Result<()> {
        self.scene.validate()
    }
}
