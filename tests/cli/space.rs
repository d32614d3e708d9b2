//! `simulate` for the arms in space: the presets' tasks, the JSON and CSV,
//! and the refusals of what belongs to the other kind of arm.

use super::{ok, refused, scratch};
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
    assert_eq!(json["arm"], "panda");
    assert_eq!(json["method"], "numerical");
    let samples = json["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 41, "2 s at 0.05 s, and t = 0");
    let last = &samples[40];
    assert_eq!(last["hand"].as_array().unwrap().len(), 3);
    for (got, want) in last["hand"]
        .as_array()
        .unwrap()
        .iter()
        .zip([0.45, 0.25, 0.5])
    {
        assert!((got.as_f64().unwrap() - want).abs() < 1e-6);
    }
    assert_eq!(json["spheres"][0]["radius"], 0.05);
    assert!(json["summary"]["min_clearance"].as_f64().is_some());
    let csv = ok(&["simulate", "--arm", "iiwa14", "--csv"]);
    let head = csv.lines().next().unwrap();
    assert_eq!(head, "t,theta1,theta2,theta3,theta4,theta5,theta6,theta7,x,y,z,x_ref,y_ref,z_ref,tracking_error,clearance,past_limits");
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
        "straight line",
    );
    refused(
        &[
            "figure",
            "--arm",
            "panda",
            "--compare",
            "--out",
            "/dev/null",
        ],
        "not built",
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
fn atlas_maps_a_slice_of_each_arm_in_space() {
    let json: Value = serde_json::from_str(&ok(&[
        "atlas", "--arm", "panda", "--grid", "9", "--slice", "xz:0.1", "--json",
    ]))
    .unwrap();
    assert_eq!(json["arm"], "panda");
    assert_eq!(json["cells"].as_array().unwrap().len(), 81);
    assert_eq!(
        json["methods"].as_array().unwrap().len(),
        json["cells"][0]["outcomes"].as_array().unwrap().len()
    );
    assert_eq!(
        json["cells"][0]["centre"][1], 0.1,
        "every centre on y = 0.1"
    );
    let table = ok(&["atlas", "--arm", "iiwa14", "--grid", "7"]);
    assert!(
        table.contains("slice yz:0.498"),
        "the default plane through the line: {table}"
    );
    assert!(table.contains("Numerical"));
    let csv = ok(&[
        "atlas",
        "--arm",
        "iiwa14",
        "--grid",
        "5",
        "--csv",
        "--methods",
        "numerical",
    ]);
    assert_eq!(
        csv.lines().next().unwrap(),
        "x,y,z,numerical,numerical_clearance,numerical_final_error"
    );
    assert_eq!(csv.lines().count(), 26);
    refused(&["atlas", "--arm", "panda", "--slice", "yz:9"], "reach");
    refused(&["atlas", "--arm", "panda", "--slice", "ab:0"], "slice");
    refused(
        &["atlas", "--arm", "iiwa14", "--methods", "case3"],
        "no networks are shipped for iiwa14",
    );
    refused(&["atlas", "--slice", "xz:0"], "arm in space");
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
fn the_learned_methods_train_evaluate_and_run_for_the_panda() {
    // Case 3 with the shipped panda-reach set (its default for the Panda),
    // refined and closed-loop, reaches the target.
    let text = ok(&[
        "simulate",
        "--arm",
        "panda",
        "--method",
        "case3",
        "--refine",
        "2",
        "--feedback",
        "1",
    ]);
    let err: f64 = text
        .lines()
        .find(|l| l.starts_with("final hand error"))
        .and_then(|l| l.split_whitespace().nth(3))
        .and_then(|x| x.parse().ok())
        .unwrap();
    assert!(err < 1e-3, "{text}");
    let text = ok(&["eval", "--arm", "panda", "--samples", "50"]);
    assert!(
        text.contains("Phi [12, 96, 96, 21]") && text.contains("Case 3"),
        "{text}"
    );
    // A short training writes a file the planner takes back.
    let (phi, v) = (scratch("space-phi.json"), scratch("space-v.json"));
    for (net, out) in [("phi", &phi), ("v", &v)] {
        ok(&[
            "train",
            "--arm",
            "panda",
            "--net",
            net,
            "--samples",
            "200",
            "--epochs",
            "2",
            "--hidden",
            "8",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
    }
    ok(&[
        "simulate",
        "--arm",
        "panda",
        "--method",
        "case2",
        "--phi-weights",
        phi.to_str().unwrap(),
        "--v-weights",
        v.to_str().unwrap(),
    ]);
    refused(
        &[
            "train",
            "--arm",
            "panda",
            "--net",
            "phi",
            "--recipe",
            "paper",
            "--out",
            "/dev/null",
        ],
        "whole-reach recipe in space",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "iiwa14",
            "--method",
            "case2",
            "--phi-weights",
            phi.to_str().unwrap(),
            "--v-weights",
            v.to_str().unwrap(),
        ],
        "trained for the arm 'panda'",
    );
}
