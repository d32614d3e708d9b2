//! The bodies of the fuzz targets (`fuzz/fuzz_targets/*.rs` call them;
//! `tests/fuzz.rs` at the top level replays the committed corpora and the
//! regression inputs through them).
//!
//! Each body turns the fuzzer's bytes into calls of the public API, the
//! way the page, the CLI and the workers call it, and asserts what must
//! hold for every input:
//! - nothing panics (a panic is what the fuzzer reports);
//! - no state the core accepts holds a non-finite joint angle, time or
//!   end-effector position;
//! - an operation that is refused leaves the state as it was;
//! - what loads also saves and loads back to the same thing.
//!
//! Numbers are drawn by [`num`]: mostly ordinary values in `[-3, 3]` (the
//! paper's arm reaches 2.05 m), often the special values people and URLs
//! produce (NaN, infinities, 1e308, -0, subnormals), sometimes raw bits.
//! Sizes are kept small so that a million executions take minutes: what is
//! checked is the handling of bad values, not the planner's endurance
//! (the soak and the atlas benchmarks cover that).
//!
//! One file per concern: the generators of arbitrary values (`gen.rs`), the
//! checks every target makes (`checks.rs`) and one file per target
//! (`targets/`).

#[path = "targets/atlas.rs"]
mod atlas;
#[path = "checks.rs"]
mod checks;
#[path = "gen.rs"]
mod gen;
#[path = "targets/scene.rs"]
mod scene;
#[path = "targets/session.rs"]
mod session;
#[path = "targets/trainer.rs"]
mod trainer;
#[path = "targets/urdf.rs"]
mod urdf;
#[path = "targets/weights.rs"]
mod weights;

pub use atlas::atlas;
pub use scene::scene;
pub use session::session;
pub use trainer::trainer;
pub use urdf::urdf;
pub use weights::weights;
