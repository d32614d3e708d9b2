//! A planner and its numerical twin.
//!
//! In the network cases the demo draws a dashed "ghost" arm: what the exact
//! numerical route would do with the same scene and the same changes. A
//! [`Twin`] owns both planners and applies every change to both, so that
//! mirroring lives in one place.

use std::sync::Arc;

use crate::error::Result;
use crate::planner::{Method, Planner, Surrogate};

/// A planner and, while its method uses networks, a copy of it solved
/// numerically (the ghost).
#[derive(Debug, Clone)]
pub struct Twin {
    main: Planner,
    ghost: Option<Planner>,
}

impl Twin {
    /// The twin of `main` (with a ghost if its method uses networks).
    pub fn new(main: Planner) -> Self {
        let mut twin = Self { main, ghost: None };
        twin.sync_ghost(true);
        twin
    }

    /// The planner.
    pub fn main(&self) -> &Planner {
        &self.main
    }

    /// The numerical ghost, in the network cases.
    pub fn ghost(&self) -> Option<&Planner> {
        self.ghost.as_ref()
    }

    /// Applies a change to the planner and then to the ghost. If the planner
    /// refuses it nothing changes; the ghost follows the same rules, so it
    /// accepts what the planner accepted (should it not, it is dropped: it is
    /// only an illustration).
    pub fn apply(&mut self, change: impl Fn(&mut Planner) -> Result<()>) -> Result<()> {
        change(&mut self.main)?;
        if let Some(g) = &mut self.ghost {
            if change(g).is_err() {
                self.ghost = None;
            }
        }
        Ok(())
    }

    /// Switches the planner's method; the ghost appears in the network cases
    /// (a copy of the planner from now on) and goes in the others.
    pub fn set_method(&mut self, method: Method) -> Result<()> {
        self.main.set_method(method)?;
        self.sync_ghost(false);
        Ok(())
    }

    /// Installs networks in both planners.
    pub fn set_networks(&mut self, networks: Option<Arc<dyn Surrogate>>) -> Result<()> {
        self.apply(|p| p.set_networks(networks.clone()))
    }

    /// Replaces the planner (a new scene); the ghost starts afresh.
    pub fn replace(&mut self, main: Planner) {
        self.main = main;
        self.sync_ghost(true);
    }

    /// Both back to the scene's start; the ghost starts afresh.
    pub fn reset(&mut self) {
        self.main.reset();
        self.sync_ghost(true);
    }

    /// One RK4 step of the planner, then of the ghost (a ghost that fails
    /// where the networks did not bows out). On error nothing changed.
    pub fn step(&mut self) -> Result<()> {
        self.main.step()?;
        if let Some(g) = &mut self.ghost {
            if g.step().is_err() {
                self.ghost = None;
            }
        }
        Ok(())
    }

    /// Keeps the ghost in step with the method: present in the network cases,
    /// absent otherwise; `fresh` rebuilds it from the planner.
    fn sync_ghost(&mut self, fresh: bool) {
        let method = self.main.method();
        if !method.uses_networks() {
            self.ghost = None;
        } else if self.ghost.is_none() || fresh {
            let mut ghost = self.main.clone();
            self.ghost = ghost.set_method(Method::NUMERICAL).is_ok().then_some(ghost);
        }
    }
}
