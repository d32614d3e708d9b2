//! The command-line tool as a user meets it: `simulate`, `figure`, `train`
//! and `eval`, their outputs, and one-line errors with exit status 2 for bad
//! input. Native only (the binary is not built for wasm32).
#![cfg(not(target_family = "wasm"))]

use std::path::PathBuf;
use std::process::{Command, Output};

use redundant_ik::planner::methods;
use serde_json::Value;

fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_redundant-ik"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs and expects success; returns stdout.
fn ok(args: &[&str]) -> String {
    let out = cli(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        stderr(&out).trim()
    );
    stdout(&out)
}

/// Runs and expects a one-line `error:` naming `what`, exit status 2 and no
/// panic.
fn refused(args: &[&str], what: &str) {
    let out = cli(args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    let first = err.lines().next().unwrap_or_default();
    assert!(first.starts_with("error:"), "{args:?}: {err}");
    assert!(
        first.to_lowercase().contains(what),
        "{args:?}: '{first}' should mention '{what}'"
    );
}

fn json(args: &[&str]) -> Value {
    serde_json::from_str(&ok(args)).expect("valid JSON")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("redundant-ik-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

mod aliases;
mod atlas;
mod outputs;
mod pose;
mod refusals;
mod robot;
mod runs;
mod simulate;
mod slice_atlas;
mod space;
mod space_figures;
mod space_networks;
mod training;
