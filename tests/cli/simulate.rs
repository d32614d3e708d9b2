//! `simulate`: its summary and JSON, the network cases, a run file read
//! back and a run as CSV.

use super::*;

#[test]
fn simulate_prints_a_readable_summary_of_the_papers_task_1() {
    let text = ok(&["simulate", "--task", "1", "--method", "numerical"]);
    assert!(text.contains("Task 1"), "{text}");
    assert!(
        text.contains("0.2345 m"),
        "smallest distance of Fig. 3: {text}"
    );
    assert!(text.contains("no collision"), "{text}");

    let text = ok(&["simulate", "--task", "1", "--method", "none"]);
    assert!(text.to_lowercase().contains("collision"), "{text}");
    assert!(!text.contains("no collision"), "Fig. 2 collides: {text}");
}

#[test]
fn simulate_json_has_every_step_and_a_consistent_summary() {
    let run = json(&["simulate", "--task", "2", "--method", "numerical", "--json"]);
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
    for method in learned.map(|m| m.name()) {
        let run = json(&["simulate", "--task", "1", "--method", method, "--json"]);
        let s = &run["summary"];
        assert_eq!(s["collided"], false, "{method}");
        assert!(s["final_error"].as_f64().unwrap() < 5e-3, "{method}: {s}");
    }
    let closed = json(&["simulate", "--method", "case3", "--feedback", "1", "--json"]);
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
fn a_constant_delta_in_a_network_case_damps_the_network_phi() {
    // It used to swap in the exact Phi silently and print the numerical
    // route's numbers.
    let run = |method: &str| {
        json(&[
            "simulate", "--task", "1", "--method", method, "--delta", "0.001", "--json",
        ])["summary"]
            .clone()
    };
    let (numerical, case1) = (run("numerical"), run("case1"));
    assert_ne!(numerical["final_error"], case1["final_error"]);
    assert_ne!(numerical["min_distance"], case1["min_distance"]);
    assert_eq!(case1["handover_steps"], 0);
    // Where the schedule takes over, the text says so.
    let text = ok(&[
        "simulate", "--task", "1", "--method", "case1", "--target", "2.5,0.8",
    ]);
    assert!(text.contains("exact damped Phi stood in"), "{text}");
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
        "--method",
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
        (v["task"].as_u64(), v["method"].as_str()),
        (Some(2), Some("case3"))
    );
    // Another method on the same scene.
    let other: Value = json(&[
        "simulate",
        "--from",
        path,
        "--method",
        "numerical",
        "--json",
    ]);
    assert_eq!(other["method"], "numerical");
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
fn simulate_follows_a_circle_and_refuses_a_bad_path() {
    let run = json(&[
        "simulate",
        "--path",
        "circle:1.2,0.8",
        "--feedback",
        "1",
        "--json",
    ]);
    assert_eq!(run["scene"]["path"], "circle:1.2,0.8");
    let summary = &run["summary"];
    let err = summary["max_tracking_error"].as_f64().unwrap();
    assert!(err < 1e-6, "{summary}");
    assert!(summary["final_error"].as_f64().unwrap() < 1e-6, "{summary}");
    assert_eq!(summary["reached"], true);
    let steps = run["steps"].as_array().unwrap();
    assert_eq!(steps[0]["ee"], steps[0]["reference"]);
    // The same scene read back replays it.
    let file = scratch("circle.json");
    std::fs::write(&file, serde_json::to_string(&run).unwrap()).unwrap();
    let again = json(&["simulate", "--from", file.to_str().unwrap(), "--json"]);
    assert_eq!(again["summary"], run["summary"]);
    // A polyline ends at its last point; the line's JSON has no path.
    let poly = json(&["simulate", "--path", "points:1.2,0.3;0.6,0.3", "--json"]);
    let last = poly["steps"].as_array().unwrap().last().unwrap().clone();
    let x = last["ee"].as_array().unwrap();
    assert!((x[0].as_f64().unwrap() - 0.6).abs() < 5e-3, "{last}");
    assert!((x[1].as_f64().unwrap() - 0.3).abs() < 5e-3, "{last}");
    let line = json(&["simulate", "--path", "line", "--tf", "0.2", "--json"]);
    assert!(line["scene"].get("path").is_none());
    for bad in ["circle:NaN,1", "points:", "spiral", "circle:1,2,0.5"] {
        refused(&["simulate", "--path", bad], "path");
    }
}

#[test]
fn joint_range_on_an_arm_without_limits_says_it_runs_as_none() {
    let text = ok(&["simulate", "--method", "jointrange"]);
    assert!(text.contains("this arm has no joint limits"), "{text}");
    let text = ok(&["simulate", "--method", "jointrange", "--arm", "iiwa-planar"]);
    assert!(!text.contains("no joint limits"), "{text}");
    let text = ok(&["simulate", "--method", "numerical"]);
    assert!(!text.contains("no joint limits"), "{text}");
}
