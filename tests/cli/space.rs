//! `simulate` for the arms in space: the presets' tasks, the JSON and CSV,
//! and the refusals of what belongs to the other kind of arm.

use super::{ok, refused};
use serde_json::Value;

#[test]
fn simulate_runs_each_arm_in_space_and_says_what_happened() {
    let text = ok(&["simulate", "--arm", "panda"]);
    assert!(text.starts_with("Franka Panda"), "{text}");
    assert!(
        text.contains("COLLISION"),
        "the paper's gain 4 does not clear the Panda's forearm: {text}"
    );
    let text = ok(&["simulate", "--arm", "iiwa14", "--method", "none"]);
    assert!(text.contains("COLLISION"), "{text}");
    let text = ok(&["simulate", "--arm", "iiwa14", "--lambda", "16"]);
    assert!(text.contains("no collision"), "{text}");
}

#[test]
fn simulate_says_a_target_in_space_is_out_of_reach_and_damps_the_run() {
    for arm in ["panda", "iiwa14"] {
        let text = ok(&["simulate", "--arm", arm, "--target", "2,0,0.5"]);
        assert!(
            text.contains("target is out of the arm's reach")
                && text.contains("damping schedule switched on automatically"),
            "{text}"
        );
        assert!(!text.contains("past its limit"), "{text}");
        let text = ok(&["simulate", "--arm", arm]);
        assert!(!text.contains("out of the arm's reach"), "{text}");
    }
}

#[test]
fn simulate_json_and_csv_carry_the_run_in_three_dimensions() {
    let json: Value = serde_json::from_str(&ok(&[
        "simulate",
        "--arm",
        "panda",
        "--target",
        "0.45,0.25,0.5",
        "--obstacle",
        "0.2,0.1,0.75,0.05",
        "--tf",
        "2",
        "--json",
    ]))
    .unwrap();
    assert_eq!(json["format"], "redundant-ik-run/2");
    assert_eq!(json["scene"]["arm"]["rows"].as_array().unwrap().len(), 7);
    assert_eq!(json["method"], "numerical");
    let samples = json["steps"].as_array().unwrap();
    assert_eq!(samples.len(), 41, "2 s at 0.05 s, and t = 0");
    let last = &samples[40];
    assert_eq!(last["ee"].as_array().unwrap().len(), 3);
    assert_eq!(
        last["joints"].as_array().unwrap()[0]
            .as_array()
            .unwrap()
            .len(),
        3
    );
    for (got, want) in last["ee"].as_array().unwrap().iter().zip([0.45, 0.25, 0.5]) {
        assert!((got.as_f64().unwrap() - want).abs() < 1e-6);
    }
    assert_eq!(json["scene"]["obstacles"][0]["radius"], 0.05);
    assert!(json["summary"]["min_clearance"].as_f64().is_some());
    let csv = ok(&["simulate", "--arm", "iiwa14", "--csv"]);
    let head = csv.lines().next().unwrap();
    assert_eq!(head, "t,theta1,theta2,theta3,theta4,theta5,theta6,theta7,x,y,z,ref_x,ref_y,ref_z,tracking_error,clearance,collision");
    assert_eq!(csv.lines().count(), 102);
}

#[test]
fn the_other_kinds_obstacles_and_targets_are_refused_with_a_reason() {
    refused(
        &["simulate", "--arm", "panda", "--obstacle", "0.4,0.1"],
        "disc, for a planar arm",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "paper",
            "--obstacle",
            "0.4,0.1,0.2,0.05",
        ],
        "sphere, for an arm in space",
    );
    refused(
        &["simulate", "--obstacle", "0.4,0.1,0.2,0.05"],
        "sphere, for an arm in space",
    );
    refused(
        &["simulate", "--arm", "panda", "--target", "0.4,0.2"],
        "x,y,z",
    );
    refused(&["simulate", "--target", "0.4,0.2,0.3"], "x,y");
    refused(
        &["simulate", "--arm", "panda", "--theta0", "0,0,0,0.5,0,1,0"],
        "joint 4's limits",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--joint-limits",
            "-1:1,-1:1,-1:1,-1:1,-1:1,-1:1,-1:1",
        ],
        "theta0",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--obstacle",
            "0.02,0,0.1,0.05",
        ],
        "fixed base",
    );
    // The learned methods need networks trained for the arm.
    refused(
        &["simulate", "--arm", "iiwa14", "--method", "case3"],
        "no networks are shipped for iiwa14",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--method",
            "case1",
            "--networks",
            "reach",
        ],
        "not for panda",
    );
    refused(
        &["simulate", "--method", "case3", "--networks", "panda-reach"],
        "not a planar arm",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--path",
            "points:0.4,0.1;0.4,0.2",
        ],
        "a planar path",
    );
    refused(
        &[
            "figure",
            "--arm",
            "panda",
            "--ellipse",
            "--plots",
            "--out",
            "/dev/null",
        ],
        "--plots",
    );
}

#[test]
fn bench_times_the_arms_in_space_and_no_step_allocates() {
    for arm in ["panda", "iiwa14"] {
        let json: Value = serde_json::from_str(&ok(&[
            "bench",
            "--arm",
            arm,
            "--json",
            "--batches",
            "5",
            "--batch-ms",
            "1",
        ]))
        .unwrap();
        let methods = json["methods"].as_object().unwrap();
        assert!(methods.contains_key("numerical"), "{json}");
        for (m, v) in methods {
            assert_eq!(
                v["allocs_per_step"].as_f64(),
                Some(0.0),
                "{arm} {m} allocates"
            );
            assert!(v["step_ns"].as_f64().unwrap() > 0.0);
        }
    }
    super::refused(&["bench", "--arm", "paper"], "arm in space");
}

#[test]
fn figure_draws_a_run_of_an_arm_in_space_in_two_views() {
    let out = super::scratch("panda.svg");
    ok(&[
        "figure",
        "--arm",
        "panda",
        "--lambda",
        "64",
        "--out",
        out.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("Franka Panda (7 joints, in space), Numerical: min clearance 0.1005 m, past a joint limit in 6 steps"), "the title's verdict");
    assert!(svg.contains("oblique view") && svg.contains("from above"));
    assert!(svg.matches("<polyline").count() > 40, "the poses are drawn");
}

#[test]
fn simulate_follows_a_circle_and_a_polyline_in_space() {
    let run = super::json(&[
        "simulate",
        "--arm",
        "panda",
        "--path",
        "circle:0.47,0,0.42,1,0,0",
        "--feedback",
        "1",
        "--json",
    ]);
    assert_eq!(run["scene"]["path"], "circle:0.47,0,0.42,1,0,0");
    assert!(
        run["summary"]["max_tracking_error"].as_f64().unwrap() < 1e-7,
        "{}",
        run["summary"]
    );
    let samples = run["steps"].as_array().unwrap();
    let point = |v: &Value| -> [f64; 3] { [0, 1, 2].map(|k| v[k].as_f64().unwrap()) };
    let (c, n) = ([0.47, 0.0, 0.42], [1.0, 0.0, 0.0]);
    let u = point(&samples[0]["ee"]);
    let u = [u[0] - c[0], u[1] - c[1], u[2] - c[2]];
    let r = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    // N made perpendicular to start - C.
    let along = (n[0] * u[0] + n[1] * u[1] + n[2] * u[2]) / (r * r);
    let m = [0, 1, 2].map(|k| n[k] - along * u[k]);
    for s in samples {
        let q = point(&s["reference"]);
        let d = [0, 1, 2].map(|k| q[k] - c[k]);
        let dist = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        assert!((dist - r).abs() < 1e-12, "on the circle: {dist} vs {r}");
        let h = d[0] * m[0] + d[1] * m[1] + d[2] * m[2];
        assert!(h.abs() < 1e-12, "in its plane: {h}");
    }
    let text = ok(&[
        "simulate",
        "--arm",
        "iiwa14",
        "--path",
        "points:0.55,0.1,0.35;0.5,0.15,0.45;0.45,0,0.4",
        "--feedback",
        "1",
    ]);
    assert!(
        text.contains(
            "path points:0.55,0.1,0.35;0.5,0.15,0.45;0.45,0,0.4 ending at (0.4500, 0.0000, 0.4000)"
        ),
        "{text}"
    );
}

#[test]
fn malformed_paths_and_the_other_kinds_paths_are_refused_with_a_reason() {
    let panda =
        |path: &str, what: &str| refused(&["simulate", "--arm", "panda", "--path", path], what);
    panda("circle:0.4,0.1", "a planar path");
    panda("circle:0.4,0.1,2", "a planar path");
    panda(
        "circle:0.4,0,0.5,1",
        "for an arm in space: expected circle:cx,cy,cz,nx,ny,nz",
    );
    panda("circle:0.4,0,0.5,0,0,0", "normal n is zero");
    panda(
        "circle:0.4,0,0.5,0.0737240401117622,0,0.0155132061520507",
        "parallel",
    );
    panda(
        "circle:0.4737240401117622,0,0.5155132061520507,0,0,1",
        "radius 0",
    );
    panda("circle:0.4,0,0.5,0,0,1,0.5", "whole number");
    panda("circle:nan,0,0.5,0,0,1", "path");
    panda("points:0.4,0.1,0.5;0.4,0.2", "x,y,z for each point");
    panda(
        &format!("points:{}", vec!["0.4,0.1,0.5"; 65].join(";")),
        "1 to 64 points x,y,z",
    );
    refused(
        &["simulate", "--path", "circle:0.4,0,0.5,0,0,1"],
        "a path in space",
    );
    refused(
        &["simulate", "--path", "points:0.4,0.1,0.5"],
        "a path in space",
    );
    refused(
        &[
            "figure",
            "--path",
            "points:0.4,0.1,0.5",
            "--out",
            "/dev/null",
        ],
        "a path in space",
    );
}

#[test]
fn simulate_from_replays_a_spatial_run_to_the_same_json() {
    for args in [
        &["--arm", "panda", "--tf", "2"][..],
        &[
            "--arm",
            "iiwa14",
            "--path",
            "circle:0.5,0,0.2,1,0.5,0.2,2",
            "--feedback",
            "1",
            "--damping",
            "--joint-weighting",
            "wln",
            "--lambda",
            "8",
            "--floor",
            "--method",
            "distance",
        ][..],
        &[
            "--arm",
            "panda",
            "--path",
            "points:0.5,0.1,0.5;0.45,0.15,0.6",
            "--joint-limits",
            "-2.8:2.8,-1.7:1.7,-2.8:2.8,-3:-0.07,-2.8:2.8,-0.01:3.7,-2.8:2.8",
            "--rate-limits",
            "2,2,2,2,2.5,2.5,2.5",
            "--obstacle",
            "0.3,0.2,0.7,0.05",
            "--method",
            "qp",
        ][..],
    ] {
        let mut all = vec!["simulate"];
        all.extend_from_slice(args);
        all.push("--json");
        let first = ok(&all);
        let file = super::scratch("space-run.json");
        std::fs::write(&file, &first).unwrap();
        let path = file.to_str().unwrap();
        let again = ok(&["simulate", "--from", path, "--json"]);
        assert_eq!(again, first, "{args:?}");
        // The file's method unless another is asked for.
        let none: Value = serde_json::from_str(&ok(&[
            "simulate", "--from", path, "--method", "none", "--json",
        ]))
        .unwrap();
        assert_eq!(none["method"], "none");
    }
}

#[test]
fn a_learned_run_in_space_keeps_its_arithmetic_and_replays_in_it() {
    let first = ok(&[
        "simulate",
        "--arm",
        "panda",
        "--method",
        "case3",
        "--precision",
        "f32",
        "--tf",
        "1",
        "--json",
    ]);
    let v: Value = serde_json::from_str(&first).unwrap();
    assert_eq!(v["precision"], "f32");
    assert_eq!(v["networks"], serde_json::json!({"set": "panda-reach"}));
    let double: Value = serde_json::from_str(&ok(&[
        "simulate", "--arm", "panda", "--method", "case3", "--tf", "1", "--json",
    ]))
    .unwrap();
    assert!(double.get("precision").is_none());
    assert_ne!(v["summary"], double["summary"], "the f32 run is its own");
    let file = super::scratch("space-f32-run.json");
    std::fs::write(&file, &first).unwrap();
    let path = file.to_str().unwrap();
    assert_eq!(ok(&["simulate", "--from", path, "--json"]), first);
    refused(
        &["simulate", "--from", path, "--precision", "f64"],
        "--precision",
    );
}

#[test]
fn from_refuses_flags_beside_a_spatial_run_and_a_bad_file() {
    let file = super::scratch("space-guard.json");
    std::fs::write(
        &file,
        ok(&["simulate", "--arm", "panda", "--tf", "0.5", "--json"]),
    )
    .unwrap();
    let path = file.to_str().unwrap();
    for (flag, value) in [
        ("--lambda", "3"),
        ("--arm", "panda"),
        ("--path", "circle:0.4,0,0.5,0,0,1"),
        ("--tf", "1"),
        ("--obstacle", "0.3,0.2,0.7"),
        ("--feedback", "1"),
    ] {
        refused(&["simulate", "--from", path, flag, value], flag);
    }
    refused(&["simulate", "--from", path, "--floor"], "--floor");
    // As figure and atlas do.
    refused(
        &[
            "figure",
            "--from",
            path,
            "--lambda",
            "3",
            "--out",
            "/dev/null",
        ],
        "--lambda",
    );
    refused(&["atlas", "--from", path, "--tf", "1"], "--tf");
    let text = std::fs::read_to_string(&file).unwrap();
    for (bad, what) in [
        (text[..text.len() / 3].to_string(), "not json"),
        (
            text.replacen("redundant-ik-run/2", "redundant-ik-run/7", 1),
            "not supported",
        ),
        (text.replacen("\"tf\":0.5", "\"tf\":1e300", 1), "tf"),
        (
            text.replacen("\"method\":\"numerical\"", "\"method\":\"case9\"", 1),
            "case9",
        ),
    ] {
        std::fs::write(&file, bad).unwrap();
        refused(&["simulate", "--from", path], what);
    }
}
