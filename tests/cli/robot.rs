//! `redundant-ik robot`: what the core makes of a URDF, as text and JSON;
//! the arms in space written as URDF are the shipped files; a file the
//! reader refuses is one readable error.

use super::{json, ok, refused, scratch};

const SLIDER: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/urdf/slider_arm.urdf"
);

#[test]
fn robot_describes_the_chain_its_limits_and_how_each_volume_was_made() {
    // Without --tip the tree's two leaves are named.
    refused(&["robot", SLIDER], "--tip");
    let text = ok(&["robot", SLIDER, "--tip", "tool"]);
    assert!(
        text.starts_with("robot 'slider_arm': 4 moving joints from 'world' to 'tool'"),
        "{text}"
    );
    assert!(
        text.contains("lift")
            && text.contains("prismatic")
            && text.contains("0 to 0.4 m, at most 0.25 m/s"),
        "{text}"
    );
    assert!(
        text.contains("wrist") && text.contains("no limits"),
        "{text}"
    );
    // The mesh is found beside the URDF (package://slider_arm/meshes/...).
    assert!(
        text.contains("capsule around the mesh package://slider_arm/meshes/forearm.stl"),
        "{text}"
    );
    assert!(
        text.contains("warning: link 'hand': its mesh 'meshes/missing.stl' cannot be read"),
        "{text}"
    );
    let v = json(&["robot", SLIDER, "--tip", "tool", "--json"]);
    assert_eq!(v["chain"]["joints"].as_array().unwrap().len(), 4);
    assert_eq!(v["chain"]["joints"][0]["kind"], "prismatic");
    assert_eq!(v["volumes"].as_array().unwrap().len(), 7);
    assert_eq!(v["warnings"].as_array().unwrap().len(), 3);
    // Another base: three joints.
    let v = json(&[
        "robot", SLIDER, "--base", "carriage", "--tip", "tool", "--json",
    ]);
    assert_eq!(v["chain"]["joints"].as_array().unwrap().len(), 3);
}

#[test]
fn the_arms_in_space_print_as_the_shipped_urdf_files() {
    for key in ["panda", "iiwa14"] {
        let text = ok(&["robot", "--urdf-of", key]);
        let path = format!("{}/robots/{key}.urdf", env!("CARGO_MANIFEST_DIR"));
        assert_eq!(text, std::fs::read_to_string(&path).unwrap(), "{key}");
        let described = ok(&["robot", &path]);
        assert!(
            described.contains("7 moving joints from 'base_link' to 'flange'"),
            "{described}"
        );
        assert!(!described.contains("warning"), "{described}");
    }
    refused(&["robot", "--urdf-of", "ur5"], "panda");
    // Another maker's arm, written by hand from its published DH table.
    let ur = ok(&[
        "robot",
        concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5e.urdf"),
    ]);
    assert!(
        ur.starts_with("robot 'ur5e': 6 moving joints from 'base_link' to 'flange'"),
        "{ur}"
    );
    assert!(!ur.contains("warning"), "{ur}");
}

#[test]
fn a_file_the_reader_refuses_is_one_readable_error() {
    let file = scratch("bad.urdf");
    let path = file.to_str().unwrap();
    for (text, says) in [
        ("<robot><link name='a'>", "not well-formed"),
        ("<robot xmlns:xacro='http://www.ros.org/wiki/xacro'><xacro:include filename='x'/><link name='a'/></robot>", "xacro"),
        ("<robot><link name='a'/><link name='b'/><joint name='j' type='floating'><parent link='a'/><child link='b'/></joint></robot>", "floating"),
    ] {
        std::fs::write(&file, text).unwrap();
        refused(&["robot", path], says);
    }
    refused(&["robot", "/no/such/file.urdf"], "cannot read");
    refused(&["robot"], "required");
}

const UR5E: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5e.urdf");

#[test]
fn simulate_figure_and_atlas_run_a_robot_from_its_urdf() {
    let start = ["--urdf", UR5E, "--theta0", "0,-1.2,1.4,-1.8,-1.5,0"];
    let text = ok(&[&["simulate"][..], &start].concat());
    assert!(
        text.starts_with("ur5e (6 joints, in space) | method numerical"),
        "{text}"
    );
    // The line runs 0.15 m along y from where --theta0 puts the hand.
    let raw = ok(&[
        &["simulate"][..],
        &start,
        &[
            "--method",
            "qp",
            "--obstacle",
            "-0.74,-0.02,0.48,0.05",
            "--json",
        ],
    ]
    .concat());
    let v: serde_json::Value = serde_json::from_str(&raw).unwrap();
    // Replayed, the run file's robot keeps its name.
    let file = super::scratch("ur5e-run.json");
    std::fs::write(&file, &raw).unwrap();
    let replay = ok(&["simulate", "--from", file.to_str().unwrap()]);
    assert!(
        replay.starts_with("ur5e (6 joints, in space) | method qp"),
        "{replay}"
    );
    let (first, last) = (&v["steps"][0]["ee"], &v["steps"][100]["ee"]);
    assert!(
        (last[1].as_f64().unwrap() - first[1].as_f64().unwrap() - 0.15).abs() < 1e-4,
        "{last}"
    );
    assert!(v["summary"]["final_error"].as_f64().unwrap() < 1e-4);
    assert_eq!(
        v["summary"]["collision_steps"],
        serde_json::Value::Null,
        "the QP keeps the sphere off"
    );
    assert!(
        v["scene"]["arm"]["joints"].as_array().unwrap().len() == 6,
        "the file carries the chain"
    );
    // The run file replays anywhere, the URDF not needed.
    let file = scratch("ur5e-run.json");
    std::fs::write(&file, &raw).unwrap();
    let again = ok(&["simulate", "--from", file.to_str().unwrap(), "--json"]);
    assert!(again == raw, "the replay differs");
    // A figure and an atlas of its slice.
    let svg = scratch("ur5e.svg");
    ok(&[
        &["figure"][..],
        &start,
        &["--method", "qp", "--out", svg.to_str().unwrap()],
    ]
    .concat());
    assert!(std::fs::read_to_string(&svg).unwrap().contains("ur5e"));
    let atlas = json(
        &[
            &["atlas"][..],
            &start,
            &["--grid", "4", "--methods", "none,qp", "--json"],
        ]
        .concat(),
    );
    assert_eq!(atlas["cells"].as_array().unwrap().len(), 16);
    assert_eq!(atlas["arm"], serde_json::Value::Null, "no preset");
}

#[test]
fn what_a_robot_from_urdf_cannot_run_is_refused_with_its_reason() {
    refused(
        &["simulate", "--urdf", UR5E, "--method", "case3"],
        "no networks are shipped",
    );
    refused(
        &["simulate", "--urdf", UR5E, "--arm", "panda"],
        "cannot be used with",
    );
    // The test arm's pose task: four joints cannot hold six coordinates.
    // The Panda cut at its fourth link cannot hold a pose's six coordinates.
    let panda = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/panda.urdf");
    refused(
        &[
            "simulate", "--urdf", panda, "--tip", "link4", "--task", "pose",
        ],
        "at least 6",
    );
    refused(&["simulate", "--urdf", UR5E, "--theta0", "0,0,0"], "theta");
    refused(&["simulate", "--tip", "tool"], "--tip goes with --urdf");
}

#[test]
fn a_run_file_records_its_robot_and_refuses_a_changed_urdf() {
    // A shipped robot by name.
    let v = json(&["simulate", "--arm", "panda", "--json"]);
    assert_eq!(v["robot"], serde_json::json!({ "name": "panda" }));
    // A user's URDF whole, with its SHA-256.
    let v = json(&["simulate", "--urdf", UR5E, "--method", "qp", "--json"]);
    let robot = &v["robot"];
    assert_eq!(robot["name"], "ur5e");
    let text = std::fs::read_to_string(UR5E).unwrap();
    assert_eq!(robot["urdf"], text.as_str());
    let hash = robot["sha256"].as_str().unwrap();
    assert_eq!(hash.len(), 64);
    assert!(hash.bytes().all(|b| b.is_ascii_hexdigit()));
    // It replays anywhere (the file is the robot), and says the same.
    let file = scratch("ur5e-robot-run.json");
    std::fs::write(&file, serde_json::to_string(&v).unwrap()).unwrap();
    let path = file.to_str().unwrap();
    let again = json(&["simulate", "--from", path, "--json"]);
    assert_eq!(again["steps"], v["steps"]);
    assert_eq!(again["robot"], v["robot"]);
    // A text changed after the hash was taken is refused.
    let mut changed = v.clone();
    changed["robot"]["urdf"] = text.replace("ur5e", "ur5f").into();
    std::fs::write(&file, serde_json::to_string(&changed).unwrap()).unwrap();
    refused(&["simulate", "--from", path], "sha-256");
    // The scene's chain against its URDF: to within rounding (the page
    // reads the file with the crate's own sines and cosines), not a
    // millimetre off.
    let nudged = |by: f64| {
        let mut w = v.clone();
        let x = w["scene"]["arm"]["joints"][2]["translation"][0]
            .as_f64()
            .unwrap();
        w["scene"]["arm"]["joints"][2]["translation"][0] = (x + by).into();
        std::fs::write(&file, serde_json::to_string(&w).unwrap()).unwrap();
    };
    nudged(1e-15);
    ok(&["simulate", "--from", path]);
    nudged(1e-3);
    refused(&["simulate", "--from", path], "does not describe");
    // A URDF of another robot than the scene's chain is refused.
    let mut other = v;
    let slider = std::fs::read_to_string(SLIDER).unwrap();
    other["robot"]["urdf"] = serde_json::Value::String(slider);
    other["robot"]["tip"] = "tool".into();
    other["robot"]["sha256"] = serde_json::Value::Null;
    std::fs::write(&file, serde_json::to_string(&other).unwrap()).unwrap();
    refused(&["simulate", "--from", path], "does not describe");
}
