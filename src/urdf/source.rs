//! Where a run's robot came from, as its run file records it: a shipped
//! robot by name, or the user's URDF whole (its text, the chain's base and
//! tip, and the text's SHA-256, which the command-line tool writes and
//! checks). The scene's chain is what runs; the text lets a reader open
//! the robot again (its links, names and meshes' names). Its reader
//! checks that the text describes the scene's chain
//! ([`RobotSource::check`], the tool's `--from`); the wasm modules, which
//! read run files too, leave the URDF reader out.

use serde::{Deserialize, Serialize};

use super::{Urdf, UrdfChain, MAX_URDF_BYTES};
use crate::error::{Error, Result};
use crate::space::Chain;

/// A run's robot: its name, and for a user's URDF the file itself.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotSource {
    /// A shipped robot's key (`panda`), or the URDF's robot name.
    pub name: String,
    /// The URDF's text (absent for a shipped robot).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub urdf: Option<String>,
    /// The text's SHA-256, in hexadecimal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sha256: Option<String>,
    /// The chain's base link, where it is not the tree's root.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base: Option<String>,
    /// The chain's tip link, where the tree has several leaves.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tip: Option<String>,
}

impl RobotSource {
    /// The name a run file's robot goes by: its own, else `robot` (a file
    /// that records none, as files written before robots were did).
    pub fn name_of(source: Option<&Self>) -> &str {
        source.map_or("robot", |r| r.name.as_str())
    }

    /// A shipped robot, by name.
    pub fn shipped(name: &str) -> Self {
        Self {
            name: name.into(),
            urdf: None,
            sha256: None,
            base: None,
            tip: None,
        }
    }

    /// Refused unless the URDF it carries (if any) is at most
    /// [`MAX_URDF_BYTES`], reads, and moves as `chain` does: the same
    /// joints, frames and flange (its volumes may have come from meshes
    /// the file does not carry, so they are not compared).
    pub fn check(&self, chain: &Chain) -> Result<()> {
        let Some(text) = &self.urdf else {
            return Ok(());
        };
        if text.len() > MAX_URDF_BYTES {
            return Err(Error::Urdf(format!(
                "the run file's URDF is {} bytes, more than the {MAX_URDF_BYTES} allowed",
                text.len()
            )));
        }
        let differs = |why: String| {
            Error::Urdf(format!(
                "the run file's URDF does not describe the chain its scene runs{why}"
            ))
        };
        let urdf = Urdf::parse(text)?;
        let uc = UrdfChain::new(&urdf, self.base.as_deref(), self.tip.as_deref())?;
        if uc.dof() != chain.dof() {
            return Err(differs(format!(
                " ({} moving joints, the scene's chain {})",
                uc.dof(),
                chain.dof()
            )));
        }
        let ours = uc
            .to_chain(&[], chain.joint_limits().cloned())
            .map_err(|e| differs(format!(": {e}")))?;
        // To a nanometre and a nanoradian: the page reads a URDF with the
        // crate's own sines and cosines, which differ from the native ones
        // in the last bits.
        if !ours.kinematics_within(chain, 1e-9) {
            return Err(differs(String::new()));
        }
        Ok(())
    }
}
