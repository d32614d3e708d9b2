//! The shipped networks of the paper's arm, as sets a user chooses between
//! ([`NetworkSet`]): the paper's recipe (`weights/phi-equivariant.json`,
//! `weights/v-plain.json`) and the whole-reach recipe
//! (`weights/phi-reach.json`, `weights/v-reach.json`, `docs/learning.md`).
//! Compiled into the build with the feature `embedded-weights` (the
//! command-line tool); the page fetches the files beside it and hands them
//! to its module and to each worker's ([`provide_builtin`]). Which
//! networks a method runs with, and whether they fit the arm, is decided
//! here, in one place ([`for_method`]).

use std::sync::{Arc, OnceLock};

use serde::{Deserialize, Serialize};

use super::{Networks, Variant};
use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::nn::Precision;
use crate::planner::{Method, Surrogate};

/// Shipped `Phi` networks, paper form: one 3-35-14-6 net over `theta`.
#[cfg(feature = "embedded-weights")]
pub const PHI_PLAIN_JSON: &str = include_str!("../../weights/phi-plain.json");
/// Shipped `Phi` networks, paper form: three 3-35-14-2 nets, one per row of `Phi`.
#[cfg(feature = "embedded-weights")]
pub const PHI_ROWS_JSON: &str = include_str!("../../weights/phi-rows.json");
/// Shipped `Phi` network, rotation-equivariant: 2-35-14-6 over `(theta_2, theta_3)`.
#[cfg(feature = "embedded-weights")]
pub const PHI_EQUIVARIANT_JSON: &str = include_str!("../../weights/phi-equivariant.json");
/// Shipped `v` network, paper form: 5-25-14-3 over `(theta, O)`.
#[cfg(feature = "embedded-weights")]
pub const V_PLAIN_JSON: &str = include_str!("../../weights/v-plain.json");
/// Shipped whole-reach `Phi` network (recipe `reach`): rotation-equivariant
/// over `(sin, cos)` of `theta_2, theta_3`, trained over the whole torus.
#[cfg(feature = "embedded-weights")]
pub const PHI_REACH_JSON: &str = include_str!("../../weights/phi-reach.json");
/// Shipped whole-reach `v` network (recipe `reach`).
#[cfg(feature = "embedded-weights")]
pub const V_REACH_JSON: &str = include_str!("../../weights/v-reach.json");

/// The `Phi` variant of the paper's set.
pub const DEFAULT_PHI_VARIANT: Variant = Variant::Equivariant;
/// The `v` variant of the paper's set.
pub const DEFAULT_V_VARIANT: Variant = Variant::Plain;

/// A set of shipped networks for the paper's arm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NetworkSet {
    /// Trained by the paper's recipe (section V): raw angles, data around
    /// the poses of its two tasks with obstacles in `[0.3, 0.8]^2`.
    #[default]
    Paper,
    /// Trained by the `reach` recipe: angle features, `Phi` over the whole
    /// joint torus, `v` with obstacles anywhere in the reach.
    Reach,
}

impl NetworkSet {
    /// Every set, in the order of the menus.
    pub const ALL: [NetworkSet; 2] = [NetworkSet::Paper, NetworkSet::Reach];

    /// The name on the command line and in the page.
    pub fn name(self) -> &'static str {
        match self {
            NetworkSet::Paper => "paper",
            NetworkSet::Reach => "reach",
        }
    }

    /// Its weights files in `weights/`: `[phi, v]`.
    pub const fn files(self) -> [&'static str; 2] {
        match self {
            NetworkSet::Paper => ["phi-equivariant.json", "v-plain.json"],
            NetworkSet::Reach => ["phi-reach.json", "v-reach.json"],
        }
    }

    /// What a menu says of it.
    pub fn label(self) -> &'static str {
        match self {
            NetworkSet::Paper => "paper's recipe (trained near the tasks)",
            NetworkSet::Reach => "whole reach (angle features, torus)",
        }
    }

    fn index(self) -> usize {
        self as usize
    }

    /// The JSON text of its files, compiled in.
    #[cfg(feature = "embedded-weights")]
    fn embedded_json(self) -> (&'static str, &'static str) {
        match self {
            NetworkSet::Paper => (PHI_EQUIVARIANT_JSON, V_PLAIN_JSON),
            NetworkSet::Reach => (PHI_REACH_JSON, V_REACH_JSON),
        }
    }
}

impl std::str::FromStr for NetworkSet {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        crate::error::by_name("network set", s, &NetworkSet::ALL, NetworkSet::name)
    }
}

/// The files of `weights/` that hold the paper's set ([`NetworkSet::files`]).
pub const BUILTIN_FILES: [&str; 2] = NetworkSet::Paper.files();

/// The shipped `Phi` weights file of a variant (JSON text).
#[cfg(feature = "embedded-weights")]
pub fn embedded_phi_json(variant: Variant) -> &'static str {
    match variant {
        Variant::Plain => PHI_PLAIN_JSON,
        Variant::Rows => PHI_ROWS_JSON,
        Variant::Equivariant => PHI_EQUIVARIANT_JSON,
    }
}

/// Each set's networks, once loaded, or why they are not (a message, not
/// an [`Error`]: cloning the enum on every read cost the page's module
/// 1.3 KB, measured on 3 December).
type Loaded = std::result::Result<Arc<Networks>, String>;
static BUILTIN: [OnceLock<Loaded>; 2] = [OnceLock::new(), OnceLock::new()];

/// The paper's set ([`builtin_set`]).
pub fn builtin() -> Result<Arc<Networks>> {
    builtin_set(NetworkSet::Paper)
}

/// A shipped set, loaded on first use and shared; or why it cannot load.
/// Compiled in with `embedded-weights`; otherwise what [`provide_builtin`]
/// was given.
pub fn builtin_set(set: NetworkSet) -> Result<Arc<Networks>> {
    let cell = &BUILTIN[set.index()];
    #[cfg(feature = "embedded-weights")]
    let loaded = cell.get_or_init(|| {
        let (phi, v) = set.embedded_json();
        Networks::from_json(phi, v).map(Arc::new).map_err(|e| {
            format!(
                "the built-in '{}' weights could not be loaded ({e})",
                set.name()
            )
        })
    });
    #[cfg(not(feature = "embedded-weights"))]
    let loaded = cell.get().ok_or_else(|| {
        Error::NetworksUnavailable(format!(
            "the built-in '{}' networks have not been loaded yet",
            set.name()
        ))
    })?;
    match loaded {
        Ok(n) => Ok(n.clone()),
        Err(why) => Err(Error::NetworksUnavailable(why.clone())),
    }
}

/// Hands a build without `embedded-weights` a shipped set: the JSON text
/// of the files [`NetworkSet::files`] names, or why they could not be
/// fetched. Only the first call per set counts (the shipped networks never
/// change); a corrupt file is kept as the reason [`builtin_set`] gives.
pub fn provide_builtin(
    set: NetworkSet,
    files: std::result::Result<(&str, &str), String>,
) -> Result<()> {
    let (kept, answer) = match files.map(|(phi, v)| Networks::from_json(phi, v)) {
        Ok(Ok(n)) => (Ok(Arc::new(n)), Ok(())),
        Ok(Err(e)) => (Err(e.to_string()), Err(e)),
        Err(why) => (Err(why.clone()), Err(Error::NetworksUnavailable(why))),
    };
    let _ = BUILTIN[set.index()].set(kept);
    answer
}

/// The networks `method` runs with on `arm`, computing in `precision`: none
/// for a method without networks; else the `installed` ones if they were
/// trained for `arm`, else the built-in ones if they were (the paper's
/// arm). The one place that decides which networks a method uses and
/// whether they fit: the session, the page's off-screen runs and its
/// workers ask here.
pub fn for_method(
    method: Method,
    arm: &Arm,
    installed: Option<&Arc<Networks>>,
    precision: Precision,
) -> Result<Option<Arc<dyn Surrogate>>> {
    if !method.uses_networks() {
        return Ok(None);
    }
    Ok(Some(
        available(arm, installed)?.in_precision(precision) as Arc<dyn Surrogate>
    ))
}

/// The networks for `arm`: the `installed` ones if they fit it, else the
/// built-in ones (the paper's set) if they do; else why there are none.
pub fn available(arm: &Arm, installed: Option<&Arc<Networks>>) -> Result<Arc<Networks>> {
    if let Some(n) = installed.filter(|n| n.arm().same_geometry(arm)) {
        return Ok(n.clone());
    }
    if builtin_fits(arm) {
        return builtin();
    }
    Err(Error::NetworksUnavailable(
        "the built-in ones were trained for the paper's arm, not for this one; train networks for this arm (the Training panel, or redundant-ik train) or load weights trained for it".into(),
    ))
}

/// Whether the built-in networks were trained for `arm` (the paper's).
pub fn builtin_fits(arm: &Arm) -> bool {
    arm.same_geometry(&Arm::paper())
}

impl Networks {
    /// The shipped networks: the paper's set.
    #[cfg(feature = "embedded-weights")]
    pub fn embedded() -> Result<Self> {
        Self::embedded_with(DEFAULT_PHI_VARIANT)
    }

    /// The shipped networks with the chosen `Phi` variant (`plain` and `rows`
    /// are the paper's form, `equivariant` the measured improvement) and the
    /// paper's `v` network.
    #[cfg(feature = "embedded-weights")]
    pub fn embedded_with(phi_variant: Variant) -> Result<Self> {
        Self::from_json(embedded_phi_json(phi_variant), V_PLAIN_JSON)
    }

    /// A shipped set, freshly parsed (see [`builtin_set`] for the shared one).
    #[cfg(feature = "embedded-weights")]
    pub fn embedded_set(set: NetworkSet) -> Result<Self> {
        let (phi, v) = set.embedded_json();
        Self::from_json(phi, v)
    }
}
