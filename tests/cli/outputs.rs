//! `figure`, `eval` and `bench`: what each writes or prints.

use super::*;

#[test]
fn figure_writes_an_svg_and_all_writes_every_task_and_method() {
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
    assert!(
        svg.contains("min 0.1693 m"),
        "Task 2's numerical clearance to the edge"
    );
    legends_clear_of_the_curves(&svg, "the comparison");

    let plots = scratch("plots.svg");
    ok(&[
        "figure",
        "--task",
        "1",
        "--plots",
        "--out",
        plots.to_str().unwrap(),
    ]);
    legends_clear_of_the_curves(&std::fs::read_to_string(&plots).unwrap(), "a run's plots");
}

/// Every legend box (plotters' white rectangle at opacity 0.9) lies right
/// of every curve (a polyline of more than two points): issue 27 found the
/// legends drawn over the θ3 curve and over most of the comparison's later
/// half.
fn legends_clear_of_the_curves(svg: &str, what: &str) {
    let attr = |tag: &str, name: &str| -> Option<String> {
        let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        Some(tag[at..].split('"').next()?.to_string())
    };
    let tags = |name: &str| -> Vec<String> {
        svg.split(&format!("<{name} "))
            .skip(1)
            .map(|t| format!(" {}", t.split('>').next().unwrap_or("")))
            .collect()
    };
    let boxes: Vec<f64> = tags("rect")
        .iter()
        .filter(|t| attr(t, "opacity").as_deref() == Some("0.9"))
        .filter_map(|t| attr(t, "x")?.parse().ok())
        .collect();
    assert!(!boxes.is_empty(), "{what}: legends found");
    let right_of_curves = tags("polyline")
        .iter()
        .filter_map(|t| attr(t, "points"))
        .filter(|p| p.split_whitespace().count() > 2)
        .flat_map(|p| {
            p.split_whitespace()
                .filter_map(|xy| xy.split(',').next()?.parse::<f64>().ok())
                .collect::<Vec<_>>()
        })
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(right_of_curves.is_finite(), "{what}: curves found");
    for x in boxes {
        assert!(
            x > right_of_curves,
            "{what}: a legend at x = {x} over the curves (they reach {right_of_curves})"
        );
    }
}

/// The caption names each obstacle's radius where they differ (issue 27:
/// radii 0.05 and 0.12 m were captioned "2 obstacles, radius 0.05 m").
#[test]
fn figure_caption_gives_every_radius_where_they_differ() {
    let caption = |obstacles: &[&str]| {
        let out = scratch("radii.svg");
        let mut args = vec!["figure", "--task", "1", "--out", out.to_str().unwrap()];
        for o in obstacles {
            args.extend(["--obstacle", o]);
        }
        ok(&args);
        std::fs::read_to_string(&out).unwrap()
    };
    let mixed = caption(&["0.6,0.5,0.05", "1.0,1.3,0.12"]);
    assert!(
        mixed.contains("2 obstacles, radii 0.05, 0.12 m"),
        "both radii"
    );
    let same = caption(&["0.6,0.5,0.05", "1.0,1.3,0.05"]);
    assert!(
        same.contains("2 obstacles, radius 0.05 m"),
        "one radius once"
    );
}

/// A figure of the iiwa's planar model: its limits in short decimals, the
/// caption wrapped into lines that fit, and the method's description under
/// the title instead of in one line clipped at both ends (issue 27).
#[test]
fn figure_text_fits_with_short_decimals() {
    let out = scratch("iiwa.svg");
    ok(&[
        "figure",
        "--arm",
        "iiwa-planar",
        "--method",
        "manipulability",
        "--out",
        out.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("joint limits -2.094:2.094,"), "short decimals");
    assert!(svg.contains("rate limits 1.484,1.309,2.356 rad/s"));
    assert!(!svg.contains("2.09439510239"), "no radians to 12 digits");
    let lines: Vec<&str> = svg
        .split("<text x=\"12\"")
        .skip(1)
        .filter_map(|t| t.split('>').nth(1)?.split('<').next())
        .map(str::trim)
        .collect();
    assert!(lines.len() >= 2, "the caption wraps: {lines:?}");
    assert!(lines.iter().all(|l| l.chars().count() <= 120), "{lines:?}");
    assert!(svg.contains("Task 1, Manipulability: "), "the title's head");
    assert!(svg.contains("climbs Yoshikawa"), "the description under it");
}

#[test]
fn figure_ellipse_draws_the_manipulability_ellipse_at_the_final_pose() {
    let plain = scratch("plain.svg");
    ok(&["figure", "--task", "1", "--out", plain.to_str().unwrap()]);
    let with = scratch("ellipse.svg");
    ok(&[
        "figure",
        "--task",
        "1",
        "--ellipse",
        "--out",
        with.to_str().unwrap(),
    ]);
    let (plain, with) = (
        std::fs::read_to_string(&plain).unwrap(),
        std::fs::read_to_string(&with).unwrap(),
    );
    assert!(!plain.contains("manipulability ellipse"), "only when asked");
    assert!(with.contains("manipulability ellipse at 1/4 scale"));
    assert!(
        with.contains("#2E7D32") || with.contains("#2e7d32"),
        "drawn"
    );
}

#[test]
fn eval_reports_accuracy_and_all_five_methods_on_both_tasks() {
    let report = json(&["eval", "--samples", "100", "--json"]);
    let outcomes = report["outcomes"].as_array().unwrap();
    assert_eq!(outcomes.len(), 10, "2 tasks x 5 methods");
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
        let method = m.name();
        for key in ["theta_dot_ns", "step_ns"] {
            let x = v[key][method].as_f64().unwrap_or(f64::NAN);
            assert!(
                x.is_finite() && x > 0.0,
                "{key}.{method} = {}",
                v[key][method]
            );
        }
        assert_eq!(v["allocs_per_step"][method], 0.0, "{method} allocates");
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
    // --methods all times every method.
    let all = bench(&["--methods", "all"]);
    assert_eq!(
        all["step_ns"].as_object().unwrap().len(),
        methods::ALL.len()
    );
    refused(&["bench", "--batches", "2"], "batches");
    refused(&["bench", "--batch-ms", "nan"], "batch-ms");
}

/// The heading names the paper's figure only for the paper's own scene: a
/// moved obstacle is another run (the page saved one as "Task 1, Case 3
/// (paper Fig. 6)").
#[test]
fn a_figure_claims_the_papers_figure_only_for_the_papers_scene() {
    let draw = |extra: &[&str]| {
        let out = scratch(&format!("fig-{}.svg", extra.len()));
        let mut args = vec!["figure", "--task", "1", "--method", "case3", "--out"];
        let path = out.to_string_lossy().into_owned();
        args.push(&path);
        args.extend_from_slice(extra);
        ok(&args);
        std::fs::read_to_string(&out).unwrap()
    };
    assert!(draw(&[]).contains("Task 1, Case 3 (paper Fig. 6)"));
    assert!(
        draw(&["--damping"]).contains("(paper Fig. 6)"),
        "the schedule aside"
    );
    let moved = draw(&["--obstacle", "0.6,0.6"]);
    assert!(moved.contains("Task 1, Case 3") && !moved.contains("paper Fig."));
}
