//! What leaves the program as files, one place for each format, shared by
//! the command-line tool and the page's workers so that both write the
//! same bytes: a run of any arm as JSON (what `redundant-ik simulate
//! --json` prints, the page's "Download run" saves and `simulate --from`
//! reads back; the older versions' files read too) and as CSV, and the
//! cells of an atlas as CSV (its JSON is the atlas's own,
//! [`crate::atlas::Atlas`]).

mod csv;
mod run;
mod space_run;

pub use csv::{atlas_csv, run_csv, slice_atlas_csv, RUN_CSV_FIXED};
pub use run::{
    is_pose_run, is_space_run, PoseRunFile, Recorded, RunFile, RunKind, SpaceRunFile,
    MAX_RUN_FILE_BYTES, PLANAR_RUN_FORMAT_1, RUN_FORMAT, SPACE_RUN_FORMAT_1,
};
