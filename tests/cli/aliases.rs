//! The flags' older names: `--mode` and `--modes` (before the tool said
//! "method" everywhere) are still accepted, by every command that has them,
//! and do the same as `--method` and `--methods`; the help names the new ones.

use super::*;

#[test]
fn simulate_takes_mode_as_method_and_its_help_says_method() {
    let args = |flag| ["simulate", "--task", "2", flag, "case3", "--json"];
    assert_eq!(ok(&args("--mode")), ok(&args("--method")));
    let help = ok(&["simulate", "--help"]);
    assert!(help.contains("--method <METHOD>"), "{help}");
    assert!(!help.contains("--mode"), "{help}");
    refused(&["simulate", "--mode", "case9"], "method");
}

#[test]
fn figure_takes_mode_as_method() {
    let svg = |flag, name| {
        let out = scratch(name);
        ok(&[
            "figure",
            "--task",
            "1",
            flag,
            "none",
            "--out",
            out.to_str().unwrap(),
        ]);
        std::fs::read_to_string(out).unwrap()
    };
    assert_eq!(svg("--mode", "mode.svg"), svg("--method", "method.svg"));
}

#[test]
fn atlas_takes_modes_as_methods_and_its_help_says_methods() {
    let args = |flag| {
        [
            "atlas",
            "--grid",
            "3",
            flag,
            "none,numerical",
            "--json",
            "--threads",
            "1",
        ]
    };
    let (old, new) = (json(&args("--modes")), json(&args("--methods")));
    assert_eq!(old["methods"], serde_json::json!(["none", "numerical"]));
    assert_eq!(old["cells"], new["cells"]);
    assert_eq!(old["summary"], new["summary"]);
    let help = ok(&["atlas", "--help"]);
    assert!(help.contains("--methods <METHODS>"), "{help}");
    assert!(!help.contains("--modes"), "{help}");
}

#[test]
fn bench_takes_modes_as_methods() {
    let keys = |flag| {
        let v = json(&[
            "bench",
            "--json",
            "--batch-ms",
            "1",
            "--batches",
            "5",
            "--no-lm",
            "--no-atlas",
            flag,
            "none,qp",
        ]);
        let mut k: Vec<String> = v["step_ns"].as_object().unwrap().keys().cloned().collect();
        k.sort();
        k
    };
    assert_eq!(keys("--modes"), ["none", "qp"]);
    assert_eq!(keys("--modes"), keys("--methods"));
    assert!(ok(&["bench", "--help"]).contains("--methods <METHODS>"));
}
