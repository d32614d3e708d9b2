//! `atlas` for the arms in space: the slice atlas as JSON, a table, CSV
//! and its maps, and its refusals.

use super::{ok, refused};
use serde_json::Value;

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
    // The maps: one panel per method, on the slice's axes, beside the JSON.
    let svg = super::scratch("slice.svg");
    let json: Value = serde_json::from_str(&ok(&[
        "atlas",
        "--arm",
        "iiwa14",
        "--grid",
        "5",
        "--methods",
        "none,distance",
        "--json",
        "--out",
        svg.to_str().unwrap(),
    ]))
    .unwrap();
    assert_eq!(json["cells"].as_array().unwrap().len(), 25);
    let drawn = std::fs::read_to_string(&svg).unwrap();
    assert!(
        drawn.contains("cells of the slice yz:0.498"),
        "{drawn:.300}"
    );
    assert!(drawn.contains("No avoidance: ") && drawn.contains("Distance gradient: "));
    assert!(drawn.contains("\nsphere y (m)\n"), "the slice's axes");
    refused(&["atlas", "--arm", "panda", "--slice", "yz:9"], "reach");
    refused(&["atlas", "--arm", "panda", "--slice", "ab:0"], "slice");
    refused(
        &["atlas", "--arm", "iiwa14", "--methods", "case3"],
        "no networks are shipped for iiwa14",
    );
    refused(&["atlas", "--slice", "xz:0"], "arm in space");
}
