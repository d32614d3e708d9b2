//! Reading a weights file: its text to a checked [`WeightsFile`]. The
//! tool and the workers' module read it with serde's derived readers; the
//! page's module (feature `page` without `worker`, `cli` or `eval`) with
//! its own ([`by_hand`]): serde_json's parser builds a plain JSON tree and
//! the fields are taken from it by hand, with the derived readers' checks.
//!
//! Why by hand: serde's derived readers are monomorphised per struct for
//! serde_json's deserializer, about 55 KB of the page's module raw and
//! 15.7 KB gzipped (153.1 -> 137.4 KB with the weights files not read at
//! all, `make web`'s baseline page module); with this reader it is 148.5 KB
//! (docs/web.md). The tool and the workers'
//! module keep the derived readers, which also read what the page skips:
//! the trainer's options and reports, which take placeholders here (the
//! page uses a file's networks, input ranges and sampling, never how they
//! were trained, and keeps the file's text for the workers). A test reads
//! every shipped file with both readers and compares them, so the two
//! cannot drift apart unseen.

use super::file::{Learned, WeightsFile, MAX_FILE_BYTES};
use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::space::Chain;

#[cfg(any(
    test,
    not(any(feature = "worker", feature = "cli", feature = "eval")),
    not(feature = "cli")
))]
// In the workers' build with the arms in space only its helpers are used
// (by `space`): the planar files go through the derived reader there.
#[cfg_attr(any(feature = "worker", feature = "eval"), allow(dead_code))]
mod by_hand;
// The spatial files by hand in the page's and the workers' modules (the
// workers' with the arms in space read the Panda's networks for the atlas
// and the benchmark), with serde's derived reader in the tool.
#[cfg(any(test, not(feature = "cli")))]
pub(crate) mod space;
#[cfg(test)]
mod tests;

/// How a weights file of an arm is read: by serde's derived readers in
/// the tool, by hand in the page's module (the planar files also in the
/// workers', which read the spatial ones by hand too).
pub trait Readable: Learned {
    /// The file's fields from its text (not yet validated), or why not.
    fn read(text: &str) -> std::result::Result<WeightsFile<Self>, String>;
}

impl Readable for Arm {
    fn read(text: &str) -> std::result::Result<WeightsFile, String> {
        #[cfg(any(feature = "worker", feature = "cli", feature = "eval"))]
        return serde_json::from_str::<WeightsFile>(text).map_err(|e| e.to_string());
        #[cfg(not(any(feature = "worker", feature = "cli", feature = "eval")))]
        return by_hand::read(text);
    }
}

impl Readable for Chain {
    /// This version's layout, or version 1's
    /// ([`crate::networks::space::SPACE_FORMAT_1`], turned into this
    /// version's).
    fn read(text: &str) -> std::result::Result<WeightsFile<Chain>, String> {
        #[cfg(feature = "cli")]
        return derived(text);
        #[cfg(not(feature = "cli"))]
        return space::read(text);
    }
}

impl<A: Readable> WeightsFile<A> {
    /// Parses and validates a weights file of an arm `A` (at most
    /// [`MAX_FILE_BYTES`]).
    pub fn from_json(json: &str) -> Result<Self> {
        if json.len() > MAX_FILE_BYTES {
            return Err(Error::Weights(format!(
                "the file has {:.1} MB; weights files are at most {} MB",
                json.len() as f64 / 1048576.0,
                MAX_FILE_BYTES >> 20
            )));
        }
        let file =
            A::read(json).map_err(|e| Error::Weights(format!("not a valid weights file: {e}")))?;
        file.validate()?;
        Ok(file)
    }
}

/// A spatial file by serde's derived readers: version 1's layout where
/// its `format` says so, else this version's.
#[cfg(feature = "cli")]
fn derived(text: &str) -> std::result::Result<WeightsFile<Chain>, String> {
    use crate::networks::space::{SpaceWeightsFile1, SPACE_FORMAT_1};
    #[derive(serde::Deserialize)]
    struct Probe {
        format: Option<String>,
    }
    let probe: Probe = serde_json::from_str(text).map_err(|e| e.to_string())?;
    if probe.format.as_deref() == Some(SPACE_FORMAT_1) {
        serde_json::from_str::<SpaceWeightsFile1>(text)
            .map_err(|e| e.to_string())
            .and_then(|f| f.into_current().map_err(|e| e.to_string()))
    } else {
        serde_json::from_str(text).map_err(|e| e.to_string())
    }
}
