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

use super::file::{WeightsFile, MAX_FILE_BYTES};
use crate::error::{Error, Result};

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

impl WeightsFile {
    /// Parses and validates a weights file (at most [`MAX_FILE_BYTES`]).
    pub fn from_json(json: &str) -> Result<Self> {
        if json.len() > MAX_FILE_BYTES {
            return Err(Error::Weights(format!(
                "the file has {:.1} MB; weights files are at most {} MB",
                json.len() as f64 / 1048576.0,
                MAX_FILE_BYTES >> 20
            )));
        }
        #[cfg(any(feature = "worker", feature = "cli", feature = "eval"))]
        let file = serde_json::from_str::<WeightsFile>(json).map_err(|e| e.to_string());
        #[cfg(not(any(feature = "worker", feature = "cli", feature = "eval")))]
        let file = by_hand::read(json);
        let file = file.map_err(|e| Error::Weights(format!("not a valid weights file: {e}")))?;
        file.validate()?;
        Ok(file)
    }
}

impl crate::networks::space::SpaceWeightsFile {
    /// A file from its JSON text, checked ([`crate::networks::space::SpaceWeightsFile::validate`]).
    pub fn from_json(text: &str) -> Result<Self> {
        if text.len() > MAX_FILE_BYTES {
            return Err(Error::Weights(format!(
                "the file has {} bytes, more than the {} a weights file may have",
                text.len(),
                MAX_FILE_BYTES
            )));
        }
        // The page's and the workers' modules read it by hand (`networks::reader::space`).
        #[cfg(feature = "cli")]
        let file = serde_json::from_str::<Self>(text).map_err(|e| e.to_string());
        #[cfg(not(feature = "cli"))]
        let file = space::read(text);
        let file = file.map_err(|e| Error::Weights(format!("not a spatial weights file: {e}")))?;
        file.validate()?;
        Ok(file)
    }
}
