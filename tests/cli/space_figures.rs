//! `figure` and `atlas` for an arm in space as for a planar one: the run's
//! plots (`--plots`), every method over time (`--compare`), the whole set
//! (`--all`), and a spatial run file's scene (`--from`) for both commands.

use super::{ok, refused, scratch};
use serde_json::Value;

fn read(path: &std::path::Path) -> String {
    std::fs::read_to_string(path).expect("the figure was written")
}

#[test]
fn figure_plots_and_compares_the_runs_of_an_arm_in_space() {
    let plots = scratch("panda-plots.svg");
    ok(&[
        "figure",
        "--arm",
        "panda",
        "--method",
        "qp",
        "--plots",
        "--out",
        plots.to_str().unwrap(),
    ]);
    let svg = read(&plots);
    assert!(svg.contains("Franka Panda (7 joints, in space), QP with dampers over time"));
    assert!(svg.contains("clearance to obstacle (m)") && svg.contains("tracking error (m)"));
    assert!(
        svg.contains("θ7") && !svg.contains("θ8"),
        "a curve per joint"
    );
    assert!(
        svg.contains("a sphere of radius 0.06 m"),
        "the caption says the scene"
    );

    // The velocity ellipsoid at the final pose: three rings more in each view.
    let (plain, with) = (scratch("panda-plain.svg"), scratch("panda-ellipsoid.svg"));
    ok(&["figure", "--arm", "panda", "--out", plain.to_str().unwrap()]);
    ok(&[
        "figure",
        "--arm",
        "panda",
        "--ellipse",
        "--out",
        with.to_str().unwrap(),
    ]);
    let (plain, with) = (read(&plain), read(&with));
    assert!(with.contains("manipulability ellipsoid at 1/4 scale"));
    assert!(!plain.contains("ellipsoid"));
    assert_eq!(
        with.matches("<polyline").count(),
        plain.matches("<polyline").count() + 7,
        "three rings in each of the two views, and the legend's swatch"
    );

    // Every method that runs on the iiwa (it has no networks: Cases 1-3
    // are skipped, and the figure says which ran).
    let compare = scratch("iiwa-compare.svg");
    let out = ok(&[
        "figure",
        "--arm",
        "iiwa14",
        "--compare",
        "--out",
        compare.to_str().unwrap(),
    ]);
    assert!(out.contains("wrote"));
    let svg = read(&compare);
    assert!(svg.contains("KUKA LBR iiwa 14 (7 joints, in space): the methods over time"));
    for label in ["Numerical", "QP with dampers", "Task priority"] {
        assert!(svg.contains(&format!("{label}, final ")), "{label}");
    }
    assert!(!svg.contains("Case 3, final"), "no networks for the iiwa");

    // The whole set: each method's two views and the comparison.
    let dir = scratch("iiwa-all");
    ok(&[
        "figure",
        "--arm",
        "iiwa14",
        "--all",
        "--out",
        dir.to_str().unwrap(),
    ]);
    for name in [
        "iiwa14_numerical.svg",
        "iiwa14_qp.svg",
        "iiwa14_compare.svg",
    ] {
        assert!(dir.join(name).exists(), "{name}");
    }
}

/// A spatial run file's scene, method and networks, drawn and mapped as
/// `--arm` with the same options draws and maps them.
#[test]
fn figure_and_atlas_read_a_spatial_run_file() {
    let file = scratch("space-from.json");
    let args = [
        "--arm", "panda", "--method", "qp", "--lambda", "8", "--tf", "2",
    ];
    let mut simulate = vec!["simulate", "--json"];
    simulate.extend(args);
    std::fs::write(&file, ok(&simulate)).unwrap();
    let path = file.to_str().unwrap();
    for extra in [&[][..], &["--plots"][..]] {
        let (a, b) = (scratch("from-a.svg"), scratch("from-b.svg"));
        let mut from = vec!["figure", "--from", path, "--out", a.to_str().unwrap()];
        from.extend(extra);
        ok(&from);
        let mut direct = vec!["figure", "--out", b.to_str().unwrap()];
        direct.extend(args);
        direct.extend(extra);
        ok(&direct);
        assert_eq!(read(&a), read(&b), "figure --from {extra:?}");
    }
    // --method draws another method on the file's scene.
    let other = scratch("from-numerical.svg");
    ok(&[
        "figure",
        "--from",
        path,
        "--method",
        "numerical",
        "--plots",
        "--out",
        other.to_str().unwrap(),
    ]);
    assert!(read(&other).contains("Numerical over time"));

    let atlas = |extra: &[&str]| -> Value {
        let mut a = vec![
            "atlas",
            "--json",
            "--grid",
            "3",
            "--methods",
            "numerical,qp",
        ];
        a.extend(extra);
        serde_json::from_str(&ok(&a)).unwrap()
    };
    let mut direct = vec![];
    direct.extend(args.iter().filter(|a| **a != "--method" && **a != "qp"));
    assert_eq!(atlas(&["--from", path]), atlas(&direct));
    refused(
        &["atlas", "--from", path, "--obstacle", "0.3,0.2,0.7"],
        "--obstacle",
    );
}
