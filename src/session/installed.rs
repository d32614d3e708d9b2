//! The networks a session's methods run: installed from training or a
//! file, or a shipped set ([`NetworkSet`]), with what they were trained on.

use std::sync::Arc;

use super::Session;
use crate::error::{Error, Result};
use crate::networks::{self, NetworkSet, Networks, TrainedRange};
use crate::nn::Precision;
use crate::planner::{Method, Surrogate};
use crate::run::NetworkChoice;

/// Networks installed in a session, with what they were trained on and
/// what they are: a shipped set, or the user's files (their text, so that
/// a run says which networks made it; the page keeps no copy).
#[derive(Clone)]
pub(super) struct Installed {
    pub(super) surrogate: Arc<dyn Surrogate>,
    pub(super) range: TrainedRange,
    pub(super) networks: Arc<Networks>,
    pub(super) choice: NetworkChoice,
}

impl Session {
    /// What the installed networks were trained on.
    pub fn trained_range(&self) -> Option<&TrainedRange> {
        self.networks.as_ref().map(|n| &n.range)
    }

    /// The networks installed, with their weights files.
    pub fn installed(&self) -> Option<&Arc<Networks>> {
        self.networks.as_ref().map(|n| &n.networks)
    }

    /// The networks installed, if any.
    pub fn networks(&self) -> Option<&Arc<dyn Surrogate>> {
        self.networks.as_ref().map(|n| &n.surrogate)
    }

    /// Whether the methods that use networks can run with this arm: networks
    /// installed for it, or built-in ones trained for it.
    pub fn networks_fit(&self) -> bool {
        networks::available(self.arm(), self.installed()).is_ok()
    }

    /// Installs trained networks (refused if they are for another arm; the
    /// networks in use stay then).
    pub fn set_networks(&mut self, networks: Arc<Networks>) -> Result<()> {
        let choice = NetworkChoice::Files {
            phi: networks.phi_file().to_json()?,
            v: networks.v_file().to_json()?,
        };
        self.install(networks, choice)
    }

    /// Installs the networks of a pair of weights files (JSON text),
    /// refused, the networks in use staying, when they do not load or are
    /// for another arm.
    pub fn load_networks(&mut self, phi_json: &str, v_json: &str) -> Result<()> {
        let networks = Arc::new(Networks::from_json(phi_json, v_json)?);
        let choice = NetworkChoice::Files {
            phi: phi_json.to_string(),
            v: v_json.to_string(),
        };
        self.install(networks, choice)
    }

    /// Installs a shipped network set ([`NetworkSet`]) for the methods that
    /// use networks; refused, the networks in use staying, when the set has
    /// not loaded or was trained for another arm.
    pub fn use_network_set(&mut self, set: NetworkSet) -> Result<()> {
        let nets = networks::builtin_set(set)?;
        if !nets.arm().same_geometry(self.arm()) {
            return Err(Error::NetworksUnavailable(format!(
                "the shipped '{}' networks were trained for the paper's arm, not for this one",
                set.name()
            )));
        }
        self.install(nets, NetworkChoice::Set(set))
    }

    /// The shipped set in use, if the installed networks are one.
    pub fn network_set(&self) -> Option<NetworkSet> {
        self.networks.as_ref().and_then(|n| n.choice.set())
    }

    /// What the installed networks are, if any.
    pub fn network_choice(&self) -> Option<&NetworkChoice> {
        self.networks.as_ref().map(|n| &n.choice)
    }

    /// The arithmetic the networks compute in: `f64` (the default) or
    /// `f32` (a run's `precision`).
    pub fn precision(&self) -> Precision {
        self.precision
    }

    /// Makes the networks compute in `precision` from now on (those
    /// installed are built again in it); a change of what runs, as
    /// installing other networks is.
    pub fn set_precision(&mut self, precision: Precision) -> Result<()> {
        if precision == self.precision {
            return Ok(());
        }
        if let Some(n) = &mut self.networks {
            // The same networks and choice, their kernels built again.
            let networks = n.networks.clone().in_precision(precision);
            let surrogate: Arc<dyn Surrogate> = networks.clone();
            self.twin.set_networks(Some(surrogate.clone()))?;
            n.networks = networks;
            n.surrogate = surrogate;
        }
        self.precision = precision;
        self.networks_installed += 1;
        Ok(())
    }

    /// Installs `networks` in the session's precision.
    pub(super) fn install(&mut self, networks: Arc<Networks>, choice: NetworkChoice) -> Result<()> {
        let networks = networks.in_precision(self.precision);
        let range = networks.trained_range();
        let surrogate: Arc<dyn Surrogate> = networks.clone();
        self.twin.set_networks(Some(surrogate.clone()))?;
        self.networks_installed += 1;
        self.networks = Some(Installed {
            surrogate,
            range,
            networks,
            choice,
        });
        Ok(())
    }

    /// Sets the networks aside (after an arm change, or to use others).
    pub fn clear_networks(&mut self) -> Result<()> {
        if self.planner().method().uses_networks() {
            self.twin.set_method(Method::NUMERICAL)?;
        }
        self.twin.set_networks(None)?;
        self.networks = None;
        self.networks_installed += 1;
        Ok(())
    }
}
