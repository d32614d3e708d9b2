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
