//! `atlas`: the table, the JSON, the heat maps, the CSV and the refusals.

use super::*;

#[test]
fn atlas_prints_the_success_table_and_writes_json_and_an_svg() {
    let table = ok(&[
        "atlas",
        "--task",
        "2",
        "--grid",
        "5",
        "--methods",
        "none,numerical",
    ]);
    assert!(table.contains("Atlas of Task 2: 5 x 5"), "{table}");
    assert!(
        table.contains("No avoidance") && table.contains("Numerical"),
        "{table}"
    );
    assert!(!table.contains("Case 1"), "{table}");

    // The JSON: a small grid over the obstacle's neighbourhood, every method.
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
    assert_eq!(v["methods"].as_array().unwrap().len(), methods::PAPER.len());
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
fn atlas_refuses_bad_grids_regions_methods_and_threads() {
    refused(&["atlas", "--grid", "1"], "grid points per side");
    refused(&["atlas", "--grid", "500"], "grid points per side");
    refused(&["atlas", "--region", "0,1,0"], "four numbers");
    refused(&["atlas", "--region", "1,0,0,1"], "empty");
    refused(&["atlas", "--region", "0,1,nan,1"], "finite");
    refused(&["atlas", "--region", "0,x,0,1"], "not a number");
    refused(&["atlas", "--methods", "numerical,fast"], "unknown method");
    refused(&["atlas", "--threads", "0"], "threads");
    refused(&["atlas", "--radius", "-1"], "radius");
}

#[test]
fn atlas_csv_has_a_line_per_cell_and_says_where_avoidance_mattered() {
    let csv = ok(&["atlas", "--grid", "5", "--methods", "numerical", "--csv"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "x,y,avoidance_needed,numerical_class,numerical_clearance,numerical_final_error"
    );
    assert_eq!(lines.len(), 26);
    let v = json(&["atlas", "--grid", "5", "--methods", "numerical", "--json"]);
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

#[test]
fn atlas_and_figure_take_a_circle_and_draw_it() {
    let svg = scratch("atlas-circle.svg");
    let v = json(&[
        "atlas",
        "--path",
        "circle:1.2,0.8",
        "--feedback",
        "1",
        "--grid",
        "11",
        "--methods",
        "numerical",
        "--json",
        "--out",
        svg.to_str().unwrap(),
    ]);
    let text = v.to_string();
    assert!(text.contains("path_blocked"), "{text:.400}");
    let drawn = std::fs::read_to_string(&svg).unwrap();
    assert!(
        drawn.contains("path circle:1.2,0.8"),
        "the legend names the path"
    );
    // The run's figure and the comparison draw it too.
    let fig = scratch("circle.svg");
    ok(&[
        "figure",
        "--path",
        "circle:1.2,0.8",
        "--out",
        fig.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&fig)
        .unwrap()
        .contains("path circle:1.2,0.8"));
    let cmp = scratch("compare.svg");
    ok(&[
        "figure",
        "--compare",
        "--path",
        "points:1.2,0.3;0.6,0.3",
        "--out",
        cmp.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&cmp)
        .unwrap()
        .contains("path points:1.2,0.3;0.6,0.3"));
}
