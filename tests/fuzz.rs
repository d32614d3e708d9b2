//! The fuzz targets' inputs, replayed: every input that ever made a target
//! fail (`fuzz/regressions/<target>/`, kept forever) and the committed
//! corpora (`fuzz/corpus/<target>/`, what `make fuzz` grew) run through the
//! same bodies as the fuzzer (`fuzz/src/lib.rs`), so a fix that regresses
//! fails `cargo test` without cargo-fuzz. docs/reliability.md tells how
//! the targets run and what they found. Native only (as the fuzzer).
#![cfg(not(target_family = "wasm"))]

#[path = "../fuzz/src/lib.rs"]
#[allow(dead_code)]
mod bodies;

use std::path::Path;

/// Runs `body` on every input of `fuzz/<dir>/<target>` (a `README.md`
/// there is a note, not an input), naming the input that fails; returns
/// how many ran.
fn replay(dir: &str, target: &str, body: fn(&[u8])) -> usize {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz")
        .join(dir)
        .join(target);
    let mut files: Vec<_> = std::fs::read_dir(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.is_file() && p.file_name().is_some_and(|n| n != "README.md"))
        .collect();
    files.sort();
    for file in &files {
        let data = std::fs::read(file).expect("a readable input");
        let run = std::panic::catch_unwind(|| body(&data));
        assert!(run.is_ok(), "{} fails again", file.display());
    }
    files.len()
}

macro_rules! target {
    ($name:ident) => {
        mod $name {
            #[test]
            fn every_input_that_once_failed_passes() {
                let n = super::replay("regressions", stringify!($name), super::bodies::$name);
                if n == 0 {
                    // An empty folder must be deliberate and say why.
                    let note = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                        .join("fuzz/regressions")
                        .join(stringify!($name))
                        .join("README.md");
                    let why = std::fs::read_to_string(&note).unwrap_or_default();
                    assert!(
                        why.contains("on purpose"),
                        "fuzz/regressions/{} replays no input and has no note saying why",
                        stringify!($name)
                    );
                }
            }

            #[test]
            fn the_committed_corpus_passes() {
                let n = super::replay("corpus", stringify!($name), super::bodies::$name);
                assert!(n > 0, "the corpus of {} is empty", stringify!($name));
            }
        }
    };
}

target!(weights);
target!(scene);
target!(session);
target!(atlas);
target!(trainer);
target!(urdf);
