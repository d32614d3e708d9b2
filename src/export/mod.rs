//! What leaves the program as files, one place for each format, shared by
//! the command-line tool and the page's workers so that both write the
//! same bytes: a run as JSON (what `redundant-ik simulate --json` prints,
//! the page's "Download run" saves and `simulate --from` reads back) and
//! as CSV, a run of an arm in space as JSON (`simulate --arm panda
//! --json`, which `simulate --from` replays too; feature `space`), and the
//! cells of an atlas as CSV (its JSON is the atlas's own,
//! [`crate::atlas::Atlas`]).

mod csv;
mod run;
mod space_run;

pub use csv::{atlas_csv, run_csv, RUN_CSV_FIXED};
pub use run::{RunFile, MAX_RUN_FILE_BYTES, RUN_FORMAT};
pub use space_run::{is_space_run, SpaceRunFile, SPACE_RUN_FORMAT};
