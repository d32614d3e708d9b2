//! `--task pose` and `--target X,Y,Z,ROLL,PITCH,YAW`: the hand's full pose
//! as the task of an arm in space, its run file replayed by `--from`, its
//! CSV, its benchmark, and the options it refuses.

use super::{json, ok, refused, scratch};

#[test]
fn a_pose_target_runs_the_pose_task_and_its_file_replays() {
    let args = [
        "simulate",
        "--arm",
        "panda",
        "--target",
        "0.45,0.25,0.5,3.0,0.2,-0.5",
        "--method",
        "qp",
        "--json",
    ];
    let v = json(&args);
    assert_eq!(v["format"], "redundant-ik-run/2");
    assert_eq!(v["scene"]["arm"]["orientation_weight"], 1.0);
    assert_eq!(v["scene"]["target"].as_array().unwrap().len(), 6);
    let s = &v["summary"];
    assert!(s["final_error"].as_f64().unwrap() < 5e-3, "{s}");
    assert!(s["final_orientation_error"].as_f64().unwrap() < 5e-3, "{s}");
    assert_eq!(s["collided"], false, "{s}");
    // Each sample's joints are points in space, its hand a pose.
    let first = &v["steps"][0];
    assert_eq!(first["joints"][0].as_array().unwrap().len(), 3);
    assert_eq!(first["ee"].as_array().unwrap().len(), 6);
    let file = scratch("pose-run.json");
    std::fs::write(&file, serde_json::to_string(&v).unwrap()).unwrap();
    let path = file.to_str().unwrap();
    let again = json(&["simulate", "--from", path, "--json"]);
    assert_eq!(again["steps"], v["steps"]);
    let text = ok(&["simulate", "--from", path]);
    assert!(
        text.contains("the hand's pose") && text.contains("rad"),
        "{text}"
    );
    refused(&["simulate", "--from", path, "--tf", "2"], "--tf");
    // Its figure and plots: the orientation's error beside the position's.
    let svg = scratch("pose-figure.svg");
    ok(&["figure", "--from", path, "--out", svg.to_str().unwrap()]);
    let drawn = std::fs::read_to_string(&svg).unwrap();
    assert!(drawn.contains("the hand&apos;s pose: ") || drawn.contains("the hand's pose: "));
    assert!(
        drawn.contains(" rad\n"),
        "the orientation's final error in the title"
    );
    ok(&[
        "figure",
        "--from",
        path,
        "--plots",
        "--out",
        svg.to_str().unwrap(),
    ]);
    let plots = std::fs::read_to_string(&svg).unwrap();
    assert!(plots.contains("orientation (rad)") && plots.contains("Z = diag(1, 1, 1, "));
}

#[test]
fn figure_compares_the_methods_that_run_the_pose() {
    let svg = scratch("pose-compare.svg");
    let out = ok(&[
        "figure",
        "--arm",
        "iiwa14",
        "--task",
        "pose",
        "--compare",
        "--out",
        svg.to_str().unwrap(),
    ]);
    let drawn = std::fs::read_to_string(&svg).unwrap();
    assert!(
        drawn.contains("QP with dampers") && drawn.contains("Numerical"),
        "{out}"
    );
    // No Phi network is trained for the pose: Cases 1 and 3 are not runs of it.
    assert!(!drawn.contains("Case 1") && !drawn.contains("Case 3"));
}

#[test]
fn a_circle_of_the_pose_task_keeps_the_start_orientation_and_replays() {
    let v = json(&[
        "simulate",
        "--arm",
        "panda",
        "--task",
        "pose",
        "--path",
        "circle:0.4,0,0.55,0,0,1",
        "--method",
        "qp",
        "--feedback",
        "1",
        "--json",
    ]);
    assert_eq!(v["scene"]["path"], "circle:0.4,0,0.55,0,0,1");
    let steps = v["steps"].as_array().unwrap();
    let first = &steps[0]["reference"];
    for x in steps {
        for k in 3..6 {
            assert_eq!(x["reference"][k], first[k]);
        }
    }
    let file = scratch("pose-circle.json");
    std::fs::write(&file, serde_json::to_string(&v).unwrap()).unwrap();
    let again = json(&["simulate", "--from", file.to_str().unwrap(), "--json"]);
    assert_eq!(again["steps"], v["steps"]);
    // The summary names the path where it has no target.
    let text = ok(&["simulate", "--from", file.to_str().unwrap()]);
    assert!(
        text.contains("path circle:0.4,0,0.55,0,0,1 ending at") && !text.contains("target"),
        "{text}"
    );
}

#[test]
fn case_2_runs_the_pose_task_and_its_file_names_its_networks() {
    let v = json(&[
        "simulate", "--arm", "panda", "--task", "pose", "--method", "case2", "--json",
    ]);
    assert_eq!(v["networks"]["set"], "panda-reach", "{}", v["networks"]);
    let file = scratch("pose-case2.json");
    std::fs::write(&file, serde_json::to_string(&v).unwrap()).unwrap();
    let path = file.to_str().unwrap();
    let again = json(&["simulate", "--from", path, "--json"]);
    assert_eq!(again["steps"], v["steps"]);
    refused(
        &["simulate", "--from", path, "--networks", "panda-reach"],
        "--from names the networks",
    );
}

#[test]
fn the_numerical_route_reaches_the_target_pose_with_feedback() {
    let v = json(&[
        "simulate",
        "--arm",
        "iiwa14",
        "--task",
        "pose",
        "--target",
        "0.5,0.1,0.55,3.1,0.3,0.2",
        "--feedback",
        "10",
        "--json",
    ]);
    let s = &v["summary"];
    assert!(s["final_error"].as_f64().unwrap() < 1e-6, "{s}");
    assert!(s["final_orientation_error"].as_f64().unwrap() < 1e-6, "{s}");
    let csv = ok(&["simulate", "--arm", "iiwa14", "--task", "pose", "--csv"]);
    let header = csv.lines().next().unwrap();
    assert!(
        header.contains(",rx,ry,rz,ref_x") && header.contains("tracking_error,orientation_error,"),
        "{header}"
    );
}

#[test]
fn the_pose_task_refuses_what_it_does_not_run() {
    refused(&["simulate", "--task", "pose"], "planar");
    refused(&["simulate", "--task", "seven"], "position or pose");
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--task",
            "position",
            "--target",
            "0.4,0,0.5,0,0,0",
        ],
        "--task pose",
    );
    refused(
        &["simulate", "--arm", "panda", "--orientation-weight", "2"],
        "--orientation-weight",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--task",
            "pose",
            "--orientation-weight",
            "0",
        ],
        "--orientation-weight",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--target",
            "0.4,0,0.5,nan,0,0",
        ],
        "finite",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--target",
            "0.4,0,0.5,3,0,0",
            "--path",
            "circle:0.5,0,0.6,0,0,1",
        ],
        "keeps the hand's start orientation",
    );
    refused(
        &[
            "simulate", "--arm", "panda", "--task", "pose", "--method", "case3",
        ],
        "needs a phi network",
    );
    refused(
        &[
            "simulate", "--arm", "iiwa14", "--task", "pose", "--method", "case2",
        ],
        "no networks are shipped for iiwa14",
    );
}

#[test]
fn bench_times_the_pose_task() {
    let v = json(&[
        "bench",
        "--arm",
        "panda",
        "--task",
        "pose",
        "--methods",
        "numerical,qp",
        "--batches",
        "5",
        "--batch-ms",
        "1",
        "--json",
    ]);
    assert_eq!(v["task"], "pose");
    for m in ["numerical", "qp"] {
        assert_eq!(v["methods"][m]["allocs_per_step"], 0.0, "{v}");
    }
}

#[test]
fn the_pose_task_has_its_slice_atlas() {
    let v = json(&[
        "atlas",
        "--arm",
        "panda",
        "--task",
        "pose",
        "--self-collision",
        "--grid",
        "7",
        "--methods",
        "numerical,qp",
        "--json",
    ]);
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 49);
    // qp neither collides nor self-collides nor passes a limit.
    for c in cells {
        let qp = c["outcomes"][1]["class"].as_str().unwrap();
        assert!(
            !["collision", "self_collision", "limit"].contains(&qp),
            "{c}"
        );
    }
    refused(
        &[
            "atlas",
            "--arm",
            "panda",
            "--task",
            "pose",
            "--methods",
            "case1",
            "--grid",
            "5",
        ],
        "pose",
    );
}

#[test]
fn the_pages_pose_run_file_replays_on_the_command_line() {
    use redundant_ik::export::PoseRunFile;
    use redundant_ik::session::space::SpaceSession;
    // The page's session: the Panda's pose task, the target turned, in qp.
    let mut s = SpaceSession::new("panda", redundant_ik::planner::methods::QP).unwrap();
    s.set_pose_task(true).unwrap();
    s.turn_target(2, 0.4).unwrap();
    s.turn_target(1, -0.2).unwrap();
    let file = PoseRunFile::of(
        None,
        s.pose_scene().unwrap(),
        s.pose_trajectory().unwrap(),
        None,
        s.precision(),
    );
    let path = scratch("page-pose-run.json");
    std::fs::write(&path, file.to_json()).unwrap();
    let again = json(&["simulate", "--from", path.to_str().unwrap(), "--json"]);
    let (ours, theirs) = (&file.steps, again["steps"].as_array().unwrap());
    assert_eq!(ours.len(), theirs.len());
    for (a, b) in ours.iter().zip(theirs) {
        for (x, y) in a.theta.iter().zip(b["theta"].as_array().unwrap()) {
            assert!((x - y.as_f64().unwrap()).abs() <= 1e-9, "{x} {y}");
        }
    }
    let e = again["summary"]["final_orientation_error"]
        .as_f64()
        .unwrap();
    assert!(e < 5e-3, "{e}");
}
