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

#[test]
fn simulate_prints_a_readable_summary_of_the_papers_task_1() {
    let text = ok(&["simulate", "--task", "1", "--mode", "numerical"]);
    assert!(text.contains("Task 1"), "{text}");
    assert!(
        text.contains("0.2345 m"),
        "smallest distance of Fig. 3: {text}"
    );
    assert!(text.contains("no collision"), "{text}");

    let text = ok(&["simulate", "--task", "1", "--mode", "none"]);
    assert!(text.to_lowercase().contains("collision"), "{text}");
    assert!(!text.contains("no collision"), "Fig. 2 collides: {text}");
}

#[test]
fn simulate_json_has_every_step_and_a_consistent_summary() {
    let run = json(&["simulate", "--task", "2", "--mode", "numerical", "--json"]);
    let steps = run["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 101, "t = 0 plus 100 RK4 steps");
    let last = &steps[100];
    assert!((last["t"].as_f64().unwrap() - 10.0).abs() < 1e-9);
    assert_eq!(last["theta"].as_array().unwrap().len(), 3);
    let joints = last["joints"].as_array().unwrap();
    assert_eq!(joints.len(), 4, "P(0) (the top of the post) .. P(3)");
    assert_eq!(joints[0], serde_json::json!([0.0, 0.5]));
    assert_eq!(joints[3], last["ee"], "P(3) is the end effector");
    assert_eq!(last["reference"], serde_json::json!([0.6, 0.2]));

    let min = steps
        .iter()
        .map(|s| s["distance"].as_f64().unwrap())
        .fold(f64::INFINITY, f64::min);
    let summary = &run["summary"];
    assert_eq!(summary["min_distance"].as_f64().unwrap(), min);
    assert!((min - 0.2193).abs() < 1e-3);
    assert_eq!(summary["collided"], false);
    assert!(summary["final_error"].as_f64().unwrap() < 1e-6);
    assert!(summary["max_tracking_error"].as_f64().unwrap() < 1e-6);
}

#[test]
fn the_network_cases_run_from_the_embedded_weights() {
    let learned = methods::ALL.iter().filter(|m| m.uses_networks());
    for mode in learned.map(|m| m.name()) {
        let run = json(&["simulate", "--task", "1", "--mode", mode, "--json"]);
        let s = &run["summary"];
        assert_eq!(s["collided"], false, "{mode}");
        assert!(s["final_error"].as_f64().unwrap() < 5e-3, "{mode}: {s}");
    }
    let closed = json(&["simulate", "--mode", "case3", "--feedback", "1", "--json"]);
    assert!(closed["summary"]["final_error"].as_f64().unwrap() < 1e-4);
}

#[test]
fn an_out_of_reach_target_completes_with_finite_numbers_and_says_so() {
    let run = json(&["simulate", "--target", "5,5", "--json"]);
    let s = &run["summary"];
    assert_eq!(s["reached"], false);
    assert_eq!(s["target_reachable"], false);
    assert_eq!(s["auto_damping"], true);
    for step in run["steps"].as_array().unwrap() {
        for q in step["theta"].as_array().unwrap() {
            assert!(q.as_f64().is_some_and(f64::is_finite), "{step}");
        }
    }
    let text = ok(&["simulate", "--target", "5,5"]);
    assert!(text.contains("not reached"), "{text}");
}

#[test]
fn bad_input_is_one_error_line_and_exit_status_2() {
    let table: &[(&[&str], &str)] = &[
        (&["simulate", "--theta0", "nan,0,0"], "finite"),
        (&["simulate", "--lambda", "inf"], "lambda"),
        (&["simulate", "--dt", "0"], "dt"),
        (&["simulate", "--dt", "-0.1"], "dt"),
        (&["simulate", "--tf", "1.05"], "whole number"),
        (&["simulate", "--obstacle", "1"], "x,y or x,y,r"),
        (&["simulate", "--obstacle", "a,b"], "obstacle"),
        (&["simulate", "--obstacle", "0,0.3"], "post"),
        (&["simulate", "--radius", "-1"], "radius"),
        (&["simulate", "--feedback", "-1"], "feedback"),
        (&["simulate", "--feedback", "100"], "unstable"),
        (&["simulate", "--target", "1e9,0"], "within"),
        (&["simulate", "--task", "3"], "task 3"),
        (&["simulate", "--mode", "case4"], "mode"),
        (&["simulate", "--theta0", "0,1"], "3"),
        (&["figure", "--task", "1"], "required"),
    ];
    for (args, what) in table {
        refused(args, what);
    }
}

/// Hostile input through every subcommand: NaN, infinities, 1e308, huge
/// lists, negative radii, 0 or 100 links, garbage. Each is one `error:`
/// line naming the problem, exit status 2, no panic (docs/reliability.md).
#[test]
fn hostile_input_through_every_subcommand_is_one_readable_error() {
    let hundred_links = format!("0.5:{}", vec!["0.1"; 100].join(","));
    let huge_list = vec!["0.1"; 10_000].join(",");
    let table: &[(&[&str], &str)] = &[
        // NaN and infinities, wherever a number goes.
        (&["simulate", "--lambda", "NaN"], "lambda"),
        (&["simulate", "--lambda", "-inf"], "lambda"),
        (&["simulate", "--delta", "nan"], "delta"),
        (&["simulate", "--target", "NaN,0.2"], "target"),
        (&["simulate", "--target", "0.6,inf"], "target"),
        (&["simulate", "--obstacle", "nan,0.5"], "obstacle"),
        (&["simulate", "--theta0", "0,inf,0"], "theta"),
        (&["simulate", "--tf", "inf"], "tf"),
        (&["simulate", "--dt", "nan"], "dt"),
        (&["atlas", "--region", "0,1,0,inf"], "finite"),
        (&["bench", "--batch-ms", "inf"], "batch"),
        (&["eval", "--feedback", "nan"], "feedback"),
        (
            &["figure", "--lambda", "nan", "--out", "/dev/null"],
            "lambda",
        ),
        // Finite but absurd.
        (&["simulate", "--lambda", "1e308"], "lambda"),
        (&["simulate", "--delta", "1e308"], "delta"),
        (&["simulate", "--target", "1e308,0"], "within"),
        (&["simulate", "--obstacle", "0.5,1e308"], "within"),
        (&["simulate", "--theta0", "1e308,1e308,0"], "rad"),
        (&["simulate", "--tf", "1e308"], "steps"),
        (&["simulate", "--dt", "1e-300"], "steps"),
        (&["simulate", "--feedback", "1e308"], "unstable"),
        (&["simulate", "--arm", "0.5:1e308,1"], "link length l1"),
        (&["simulate", "--arm", "1e308:1,1"], "post"),
        (&["atlas", "--grid", "18446744073709551616"], "grid"),
        (&["atlas", "--region", "-1e308,1e308,0,1"], "within"),
        (
            &[
                "train",
                "--net",
                "phi",
                "--samples",
                "1e9",
                "--out",
                "/dev/null",
            ],
            "samples",
        ),
        (
            &[
                "train",
                "--net",
                "phi",
                "--epochs",
                "0",
                "--out",
                "/dev/null",
            ],
            "epoch",
        ),
        (&["eval", "--samples", "0"], "samples"),
        (&["bench", "--batch-ms", "1e308"], "batch"),
        // Negative radii and lengths.
        (&["simulate", "--radius", "-0.05"], "radius"),
        (&["simulate", "--obstacle", "0.5,0.5,-0.05"], "radius"),
        (&["atlas", "--radius", "-1"], "radius"),
        (
            &["simulate", "--arm", "0.5:0.6,-0.85,0.6"],
            "link length l2",
        ),
        (
            &["train", "--net", "v", "--noise=-1", "--out", "/dev/null"],
            "noise",
        ),
        // 0, 1 or 100 links; huge lists.
        (&["simulate", "--arm", "0.5:"], "not a finite number"),
        (&["simulate", "--arm", "0.5:0.6"], "link"),
        (&["simulate", "--arm", &hundred_links], "link"),
        (
            &[
                "train",
                "--net",
                "phi",
                "--arm",
                &hundred_links,
                "--out",
                "/dev/null",
            ],
            "link",
        ),
        (&["simulate", "--theta0", &huge_list], "10000"),
        (&["simulate", "--target", &huge_list], "x,y"),
        (&["atlas", "--region", &huge_list], "four numbers"),
        (
            &[
                "train",
                "--net",
                "phi",
                "--hidden",
                &huge_list,
                "--out",
                "/dev/null",
            ],
            "hidden",
        ),
        // Garbage.
        (&["simulate", "--lambda", "four"], "lambda"),
        (&["simulate", "--target", "x,y"], "target"),
        (&["simulate", "--mode", "\u{1F4A5}"], "mode"),
        (&["simulate", "--task=-1"], "task"),
        (&["simulate", "--arm", "::"], "arm"),
        (&["atlas", "--modes", ",,,"], "mode"),
        (&["train", "--net", "both", "--out", "/dev/null"], "net"),
        (&["simulate", "--phi-variant", "sideways"], "phi-variant"),
        (&["simulate", "--bogus"], "unexpected argument"),
    ];
    for (args, what) in table {
        refused(args, what);
    }
}

/// Weights files that are huge, truncated, hold NaN or another arm's
/// networks, or are not text: refused with the reason, through every
/// subcommand that reads them.
#[test]
fn hostile_weights_files_are_refused_with_the_reason() {
    let phi = std::fs::read_to_string("weights/phi-equivariant.json").unwrap();
    let v = std::fs::read_to_string("weights/v-plain.json").unwrap();
    let write = |name: &str, bytes: &[u8]| {
        let p = scratch(name);
        std::fs::write(&p, bytes).unwrap();
        p.to_str().unwrap().to_owned()
    };
    let huge = write("huge.json", &vec![b' '; (8 << 20) + 1]);
    let truncated = write("truncated.json", &phi.as_bytes()[..phi.len() / 2]);
    let first_weight = phi.find("\"weights\": [").unwrap() + "\"weights\": [".len();
    let nan = write(
        "nan.json",
        format!("{}NaN,{}", &phi[..first_weight], &phi[first_weight..]).as_bytes(),
    );
    let overflow = write(
        "overflow.json",
        format!("{}1e999,{}", &phi[..first_weight], &phi[first_weight..]).as_bytes(),
    );
    let binary = write("binary.json", &[0xff, 0xfe, 0x00, 0x01, 0x80]);
    let mut other: Value = serde_json::from_str(&v).unwrap();
    other["arm"]["links"] = serde_json::json!([0.6, 0.85, 0.6, 0.4]);
    let other = write("other-arm.json", other.to_string().as_bytes());
    let v = write("v.json", v.as_bytes());
    let cases: &[(&str, &str)] = &[
        (&huge, "at most 8 mb"),
        (&truncated, "not a valid weights file"),
        (&nan, "not a valid weights file"),
        (&overflow, "not a valid weights file"),
        (&binary, "cannot read"),
    ];
    for (file, what) in cases {
        refused(
            &[
                "simulate",
                "--mode",
                "case3",
                "--phi-weights",
                file,
                "--v-weights",
                &v,
            ],
            what,
        );
        refused(&["eval", "--phi", file, "--v", &v], what);
        refused(
            &[
                "atlas",
                "--grid",
                "2",
                "--modes",
                "case1",
                "--phi-weights",
                file,
                "--v-weights",
                &v,
            ],
            what,
        );
    }
    refused(
        &["simulate", "--mode", "case2", "--v-weights", &other],
        "arm",
    );
}

#[test]
fn a_corrupt_or_mismatched_weights_file_is_refused_with_the_reason() {
    let bad = scratch("bad.json");
    std::fs::write(&bad, "{\"format\": 12").unwrap();
    let bad = bad.to_str().unwrap();
    refused(
        &["simulate", "--mode", "case1", "--phi-weights", bad],
        "weights",
    );
    refused(
        &[
            "simulate",
            "--mode",
            "case1",
            "--phi-weights",
            "weights/v-plain.json",
        ],
        "phi",
    );
    refused(
        &[
            "simulate",
            "--mode",
            "case2",
            "--v-weights",
            "no/such/file.json",
        ],
        "cannot read",
    );
}

#[test]
fn figure_writes_an_svg_and_all_writes_every_task_and_mode() {
    let one = scratch("task1.svg");
    ok(&["figure", "--task", "1", "--out", one.to_str().unwrap()]);
    let svg = std::fs::read_to_string(&one).unwrap();
    assert!(svg.starts_with("<svg") || svg.contains("<svg"), "an SVG");
    assert!(
        svg.contains("<circle") || svg.contains("<path"),
        "with shapes"
    );

    let dir = scratch("all");
    ok(&["figure", "--all", "--out", dir.to_str().unwrap()]);
    let count = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "svg"))
        })
        .count();
    assert_eq!(
        count,
        2 * (methods::ALL.len() + 1),
        "2 tasks x every method, and a comparison per task"
    );

    let cmp = scratch("compare.svg");
    ok(&[
        "figure",
        "--compare",
        "--task",
        "2",
        "--out",
        cmp.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&cmp).unwrap();
    // The legends use the methods' labels (Method::label, as the page does).
    for label in methods::ALL.iter().map(|m| m.label()) {
        assert!(
            svg.contains(&format!("\n{label}, min ")),
            "{label} in the legend"
        );
    }
    assert!(svg.contains("min 0.2193 m"), "Task 2's numerical clearance");
}

#[test]
fn train_writes_a_weights_file_that_simulate_accepts() {
    let out = scratch("tiny-phi.json");
    let path = out.to_str().unwrap();
    let text = ok(&[
        "train",
        "--net",
        "phi",
        "--variant",
        "equivariant",
        "--samples",
        "200",
        "--epochs",
        "5",
        "--hidden",
        "8",
        "--quiet",
        "--out",
        path,
    ]);
    assert!(
        text.to_lowercase().contains("test"),
        "reports its test error: {text}"
    );
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(file["net"], "phi");
    // A barely trained net still runs to the end without a panic or NaN; the
    // summary reports what it did.
    let run = json(&[
        "simulate",
        "--mode",
        "case1",
        "--phi-weights",
        path,
        "--json",
    ]);
    assert!(run["summary"]["final_error"]
        .as_f64()
        .is_some_and(f64::is_finite));
}

#[test]
fn eval_reports_accuracy_and_all_five_modes_on_both_tasks() {
    let report = json(&["eval", "--samples", "100", "--json"]);
    let outcomes = report["outcomes"].as_array().unwrap();
    assert_eq!(outcomes.len(), 10, "2 tasks x 5 modes");
    assert!(report["v"]["median"].as_f64().unwrap() < 0.1);
    assert!(
        report["phi"][0]["relative_error"]["median"]
            .as_f64()
            .unwrap()
            < 1e-3
    );
    assert_eq!(report["case3_avoided"], 10);
}

#[test]
fn a_constant_delta_in_a_network_case_damps_the_network_phi() {
    // It used to swap in the exact Phi silently and print the numerical
    // route's numbers.
    let run = |mode: &str| {
        json(&[
            "simulate", "--task", "1", "--mode", mode, "--delta", "0.001", "--json",
        ])["summary"]
            .clone()
    };
    let (numerical, case1) = (run("numerical"), run("case1"));
    assert_ne!(numerical["final_error"], case1["final_error"]);
    assert_ne!(numerical["min_distance"], case1["min_distance"]);
    assert_eq!(case1["handover_steps"], 0);
    // Where the schedule takes over, the text says so.
    let text = ok(&[
        "simulate", "--task", "1", "--mode", "case1", "--target", "2.5,0.8",
    ]);
    assert!(text.contains("exact damped Phi stood in"), "{text}");
}

#[test]
fn bench_reports_every_figure_and_no_allocation_per_step() {
    // Short batches: this checks the report, not the speed.
    let bench = |extra: &[&str]| {
        let mut args = vec![
            "bench",
            "--json",
            "--batch-ms",
            "1",
            "--batches",
            "5",
            "--no-lm",
            "--no-atlas",
        ];
        args.extend_from_slice(extra);
        json(&args)
    };
    let v = bench(&[]);
    // By default the paper's five methods, one key each.
    for key in ["theta_dot_ns", "step_ns", "allocs_per_step"] {
        let mut names: Vec<&str> = v[key]
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        let mut paper: Vec<&str> = methods::PAPER.iter().map(|m| m.name()).collect();
        names.sort();
        paper.sort();
        assert_eq!(names, paper, "{key}");
    }
    for m in methods::PAPER {
        let mode = m.name();
        for key in ["theta_dot_ns", "step_ns"] {
            let x = v[key][mode].as_f64().unwrap_or(f64::NAN);
            assert!(x.is_finite() && x > 0.0, "{key}.{mode} = {}", v[key][mode]);
        }
        assert_eq!(v["allocs_per_step"][mode], 0.0, "{mode} allocates");
    }
    for net in ["phi", "v"] {
        assert!(v["forward_ns"][net].as_f64().is_some_and(|x| x > 0.0));
    }
    assert!(v["lm_epoch_ms"].is_null(), "--no-lm skips the epoch");
    assert!(v["atlas_ms"].is_null(), "--no-atlas skips the atlas");
    let kernels = v["kernels"].as_str().unwrap_or_default().to_string();
    assert!(
        ["avx2+fma", "fma", "portable"].contains(&kernels.as_str()),
        "{kernels}"
    );
    // The run-time choice of AVX2 can be switched off: the baseline build's
    // kernels (FMA only where the compile-time target has it).
    let base = bench(&["--baseline-kernels"]);
    let expected = if cfg!(target_feature = "fma") {
        "fma"
    } else {
        "portable"
    };
    assert_eq!(base["kernels"], expected);
    // --modes all times every method.
    let all = bench(&["--modes", "all"]);
    assert_eq!(
        all["step_ns"].as_object().unwrap().len(),
        methods::ALL.len()
    );
    refused(&["bench", "--batches", "2"], "batches");
    refused(&["bench", "--batch-ms", "nan"], "batch-ms");
}

#[test]
fn atlas_prints_the_success_table_and_writes_json_and_an_svg() {
    let table = ok(&[
        "atlas",
        "--task",
        "2",
        "--grid",
        "5",
        "--modes",
        "none,numerical",
    ]);
    assert!(table.contains("Atlas of Task 2: 5 x 5"), "{table}");
    assert!(
        table.contains("No avoidance") && table.contains("Numerical"),
        "{table}"
    );
    assert!(!table.contains("Case 1"), "{table}");

    // The JSON: a small grid over the obstacle's neighbourhood, every mode.
    let svg = scratch("atlas.svg");
    let v = json(&[
        "atlas",
        "--task",
        "1",
        "--grid",
        "4",
        "--region",
        "0.2,0.8,0.2,0.8",
        "--json",
        "--threads",
        "1",
        "--out",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(v["task"], 1);
    assert_eq!(v["grid"]["n"], 4);
    assert_eq!(v["grid"]["region"], serde_json::json!([0.2, 0.8, 0.2, 0.8]));
    assert_eq!(v["radius"], 0.05);
    assert_eq!(v["lambda"], 4.0);
    assert_eq!(v["modes"].as_array().unwrap().len(), methods::PAPER.len());
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 16);
    assert_eq!(
        (cells[1]["x"].as_f64(), cells[1]["y"].as_f64()),
        (Some(0.4), Some(0.2))
    );
    for m in methods::PAPER.iter().map(|m| m.name()) {
        assert!(cells[5]["outcomes"][m]["class"].is_string(), "{m}");
        assert!(v["summary"][m]["counts"]["success"].is_u64(), "{m}");
    }
    // The same cells on two threads.
    let two = json(&[
        "atlas",
        "--task",
        "1",
        "--grid",
        "4",
        "--region",
        "0.2,0.8,0.2,0.8",
        "--json",
        "--threads",
        "2",
    ]);
    assert_eq!(two["cells"], v["cells"]);

    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg"));
    for label in methods::PAPER
        .iter()
        .map(|m| m.label())
        .chain(["collision"])
    {
        assert!(text.contains(label), "the SVG names {label}");
    }
}

#[test]
fn atlas_refuses_bad_grids_regions_modes_and_threads() {
    refused(&["atlas", "--grid", "1"], "grid points per side");
    refused(&["atlas", "--grid", "500"], "grid points per side");
    refused(&["atlas", "--region", "0,1,0"], "four numbers");
    refused(&["atlas", "--region", "1,0,0,1"], "empty");
    refused(&["atlas", "--region", "0,1,nan,1"], "finite");
    refused(&["atlas", "--region", "0,x,0,1"], "not a number");
    refused(&["atlas", "--modes", "numerical,fast"], "unknown mode");
    refused(&["atlas", "--threads", "0"], "threads");
    refused(&["atlas", "--radius", "-1"], "radius");
}

#[test]
fn train_and_simulate_take_any_arm() {
    let arm = "0.5:0.6,0.85,0.6,0.4";
    let phi = scratch("phi-4.json");
    let v = scratch("v-4.json");
    for (net, variant, out) in [("phi", "equivariant", &phi), ("v", "plain", &v)] {
        ok(&[
            "train",
            "--arm",
            arm,
            "--net",
            net,
            "--variant",
            variant,
            "--samples",
            "200",
            "--epochs",
            "3",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
    }
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&phi).unwrap()).unwrap();
    assert_eq!(file["arm"]["links"].as_array().unwrap().len(), 4);
    assert_eq!(file["training"]["sampling"]["random_tasks"], 60);
    // The numerical route runs on the arm at once, from its start pose, with
    // obstacles of their own radii.
    let s = json(&[
        "simulate",
        "--arm",
        arm,
        "--mode",
        "numerical",
        "--obstacle",
        "0.5,0.5,0.08",
        "--obstacle",
        "-0.4,1.2",
        "--json",
    ]);
    assert_eq!(s["steps"][0]["theta"].as_array().unwrap().len(), 4);
    assert_eq!(s["summary"]["reached"], true);
    // Case 3 with the networks trained for it, and an explicit start pose.
    let s = json(&[
        "simulate",
        "--arm",
        arm,
        "--mode",
        "case3",
        "--theta0",
        "0.2,1.4,-0.5,-0.5",
        "--phi-weights",
        phi.to_str().unwrap(),
        "--v-weights",
        v.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(s["steps"][0]["theta"][1], 1.4);
    // Networks for another arm, a start pose of the wrong length, bad arms.
    refused(&["simulate", "--arm", arm, "--mode", "case3"], "arm");
    refused(
        &["simulate", "--arm", arm, "--theta0", "0.1,0.2,0.3"],
        "theta",
    );
    refused(&["simulate", "--arm", "0.5:0.6"], "link");
    refused(&["simulate", "--arm", "0.5,0.6,0.6"], "post:l1");
    refused(&["simulate", "--arm", "0.5:0.6,x"], "not a finite number");
    refused(&["simulate", "--arm", "-1:0.6,0.6"], "post");
    refused(&["simulate", "--obstacle", "0.5,0.5,-0.1"], "radius");
    refused(&["simulate", "--obstacle", "0.5,0.5,0.1,3"], "x,y,r");
    refused(&["train", "--arm", "0.5:0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6", "--net", "phi", "--out", "/dev/null"], "link");
}

#[test]
fn the_reach_recipe_and_network_set_through_the_command_line() {
    // `train --recipe reach` writes angle features and the smoothed sign.
    let out = scratch("tiny-reach-v.json");
    let path = out.to_str().unwrap();
    let text = ok(&[
        "train",
        "--net",
        "v",
        "--recipe",
        "reach",
        "--samples",
        "200",
        "--epochs",
        "3",
        "--hidden",
        "6",
        "--quiet",
        "--out",
        path,
    ]);
    assert!(
        text.contains("recipe reach") && text.contains("encoding angles"),
        "{text}"
    );
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(file["encoding"], "angles");
    assert_eq!(file["variant"], "equivariant");
    assert_eq!(file["training"]["sampling"]["sign_smoothing"], 0.1);
    // The shipped reach set runs Case 3 with refinement and feedback, and
    // the refinement changes the run (it is applied).
    let run = |refine: &str| {
        json(&[
            "simulate",
            "--mode",
            "case3",
            "--networks",
            "reach",
            "--refine",
            refine,
            "--feedback",
            "1",
            "--json",
        ])
    };
    let (plain, refined) = (run("0"), run("2"));
    assert_eq!(refined["scene"]["params"]["refine"], 2.0);
    assert!(refined["summary"]["final_error"].as_f64().unwrap() < 5e-3);
    assert_ne!(plain["summary"], refined["summary"]);
    // A figure of the refined run says so in its caption.
    let fig = scratch("refined-case3.svg");
    ok(&[
        "figure",
        "--mode",
        "case3",
        "--networks",
        "reach",
        "--refine",
        "2",
        "--out",
        fig.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&fig).unwrap();
    assert!(
        svg.contains("Φ refined by 2 Newton-Schulz steps"),
        "caption of {fig:?}"
    );
    // The exact route is the same with either set (it runs no network).
    let numerical = |set: &str| {
        json(&[
            "simulate",
            "--mode",
            "numerical",
            "--networks",
            set,
            "--json",
        ])["summary"]
            .clone()
    };
    assert_eq!(numerical("paper"), numerical("reach"));
    // `--optimiser adam` trains by Adam and records its options; Adam's
    // settings without it are refused rather than ignored.
    let adam_out = scratch("tiny-adam-phi.json");
    let adam_path = adam_out.to_str().unwrap();
    ok(&[
        "train",
        "--net",
        "phi",
        "--samples",
        "200",
        "--epochs",
        "2",
        "--hidden",
        "6",
        "--optimiser",
        "adam",
        "--batch",
        "32",
        "--learning-rate",
        "0.01",
        "--quiet",
        "--out",
        adam_path,
    ]);
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&adam_out).unwrap()).unwrap();
    assert_eq!(file["training"]["adam"]["batch"], 32);
    assert_eq!(file["training"]["adam"]["max_epochs"], 2);
    assert_eq!(file["nets"][0]["report"]["epochs"].as_u64(), Some(2));
    refused(
        &[
            "train",
            "--net",
            "phi",
            "--batch",
            "32",
            "--out",
            "/dev/null",
        ],
        "--optimiser adam",
    );
    // A network too wide for Levenberg-Marquardt's J^T J is refused with
    // the way out, not an allocation that kills the process.
    let wide = "train --net phi --samples 100 --hidden 96,96 --optimiser lm --out /dev/null";
    refused(&wide.split(' ').collect::<Vec<_>>(), "--optimiser adam");
    refused(&["simulate", "--networks", "nope"], "networks");
    refused(&["simulate", "--refine", "1.5"], "refine");
    refused(&["simulate", "--refine", "9"], "refine");
    refused(&["simulate", "--sign-smoothing", "-1"], "smoothing");
    refused(
        &[
            "simulate",
            "--mode",
            "case1",
            "--networks",
            "reach",
            "--phi-variant",
            "plain",
        ],
        "phi-variant",
    );
    refused(
        &["train", "--net", "v", "--recipe", "both", "--out", path],
        "recipe",
    );
    // eval of the reach set.
    let text = ok(&[
        "eval",
        "--networks",
        "reach",
        "--refine",
        "2",
        "--feedback",
        "1",
        "--samples",
        "200",
    ]);
    assert!(text.contains("feedback K = 1, refine 2"), "{text}");
}

#[test]
fn a_run_file_is_read_back_by_simulate_and_figure_and_csv_has_a_line_per_step() {
    // What `simulate --json` writes (and the page's "Download run") is a
    // scene `--from` replays: the same steps and summary, and the method.
    let file = scratch("run-from.json");
    let text = ok(&[
        "simulate",
        "--task",
        "2",
        "--mode",
        "case3",
        "--feedback",
        "1",
        "--target",
        "0.7,0.3",
        "--json",
    ]);
    std::fs::write(&file, &text).unwrap();
    let path = file.to_str().unwrap();
    let again = ok(&["simulate", "--from", path, "--json"]);
    assert_eq!(again, text, "the same run, byte for byte");
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(
        (v["task"].as_u64(), v["mode"].as_str()),
        (Some(2), Some("case3"))
    );
    // Another method on the same scene.
    let other: Value = json(&["simulate", "--from", path, "--mode", "numerical", "--json"]);
    assert_eq!(other["mode"], "numerical");
    assert_eq!(other["scene"], v["scene"]);
    // The CSV: a header and one line per sample, in the file's numbers.
    let csv = ok(&["simulate", "--from", path, "--csv"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "t,theta1,theta2,theta3,x,y,ref_x,ref_y,tracking_error,clearance,collision"
    );
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(lines.len(), steps.len() + 1);
    let last: Vec<f64> = lines[lines.len() - 1]
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let s = &steps[steps.len() - 1];
    assert_eq!(last[0], s["t"].as_f64().unwrap());
    assert_eq!(last[3], s["theta"][2].as_f64().unwrap());
    assert_eq!(last[4], s["ee"][0].as_f64().unwrap());
    let clearance = s["distance"].as_f64().unwrap() - 0.05;
    assert!(
        (last[9] - clearance).abs() < 1e-12,
        "{} vs {clearance}",
        last[9]
    );
    // The figures of the file's run.
    for (flag, marker) in [(None, "polyline"), (Some("--plots"), "joint angles")] {
        let out = scratch("from.svg");
        let mut args = vec!["figure", "--from", path, "--out", out.to_str().unwrap()];
        args.extend(flag);
        ok(&args);
        let svg = std::fs::read_to_string(&out).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains(marker), "{flag:?}");
        assert!(svg.contains("Case 3 · Task 2 · λ = 4"), "the caption line");
        assert!(svg.contains("closed loop K = 1"), "the caption line");
    }
    // A file is the whole scene, and a bad file is one readable error.
    refused(&["simulate", "--from", path, "--lambda", "3"], "--lambda");
    std::fs::write(&file, "{\"task\": 1}").unwrap();
    refused(&["simulate", "--from", path], "run file");
    refused(
        &["simulate", "--from", "/nonexistent/run.json"],
        "cannot read",
    );
}

#[test]
fn atlas_csv_has_a_line_per_cell_and_says_where_avoidance_mattered() {
    let csv = ok(&["atlas", "--grid", "5", "--modes", "numerical", "--csv"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "x,y,avoidance_needed,numerical_class,numerical_clearance,numerical_final_error"
    );
    assert_eq!(lines.len(), 26);
    let v = json(&["atlas", "--grid", "5", "--modes", "numerical", "--json"]);
    for (line, cell) in lines[1..].iter().zip(v["cells"].as_array().unwrap()) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[0].parse::<f64>().unwrap(), cell["x"].as_f64().unwrap());
        assert_eq!(
            f[3],
            cell["outcomes"]["numerical"]["class"].as_str().unwrap()
        );
        let needed = match cell["avoidance_needed"].as_bool() {
            Some(true) => "1",
            Some(false) => "0",
            None => "",
        };
        assert_eq!(f[2], needed);
    }
    assert!(v["summary"]["numerical"]["mattered"]["cells"].is_u64());
}
