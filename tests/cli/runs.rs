//! What a run is, through the command line: every declared parameter is a
//! flag that reaches the run's JSON; `--from` refuses every scene flag
//! beside it; a run names its networks and replays with them, in the
//! arithmetic it ran in; a run file
//! written before parameters were declared by their methods still loads
//! and replays as it ran.

use super::*;
use redundant_ik::export::RunFile;
use redundant_ik::planner::params;

/// A value of `p` inside its bounds and other than its default.
fn other_value(p: &redundant_ik::scene::Param) -> f64 {
    let (lo, hi, step) = p.slider;
    let (lo, hi, step) = if p.scale == redundant_ik::scene::Scale::Log {
        (10f64.powf(lo), 10f64.powf(hi), 10f64.powf(step))
    } else {
        (lo, hi, step)
    };
    let mid = lo + ((hi - lo) / 2.0 / step).round() * step;
    let v = if mid == p.default { mid + step } else { mid };
    if p.count {
        v.round()
    } else {
        v
    }
}

#[test]
fn every_declared_parameter_is_a_flag_that_reaches_the_run() {
    let all = params::all();
    assert!(
        all.len() >= 11,
        "the methods declare {} parameters",
        all.len()
    );
    for &p in all {
        // The stop distance stays below the influence distance (0.3 m).
        let v = if p.name == "stop_distance" {
            0.1
        } else {
            other_value(p)
        };
        let run = json(&["simulate", "--tf", "0.2", p.flag, &v.to_string(), "--json"]);
        assert_eq!(run["scene"]["params"][p.name], v, "{}", p.flag);
        // The help names it with its default.
        let help = ok(&["simulate", "--help"]);
        assert!(help.contains(p.flag), "{} missing from --help", p.flag);
        // Out of bounds, it is refused by name.
        let too_big = (p.bounds.1 * 2.0 + 1.0).to_string();
        let out = cli(&["simulate", p.flag, &too_big]);
        assert_eq!(out.status.code(), Some(2), "{} {too_big}", p.flag);
        assert!(
            stderr(&out).contains(p.what),
            "{}: {}",
            p.flag,
            stderr(&out)
        );
    }
}

/// The long flags of `simulate --help`: (flag, takes a value).
fn simulate_flags() -> Vec<(String, bool)> {
    let help = ok(&["simulate", "--help"]);
    help.lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let l = l.strip_prefix("-h, ").unwrap_or(l);
            let flag = l.strip_prefix("--")?.split_whitespace().next()?;
            Some((format!("--{flag}"), l.contains('<')))
        })
        .collect()
}

#[test]
fn from_refuses_every_scene_flag_beside_it_and_applies_the_rest() {
    let file = scratch("guard.json");
    std::fs::write(&file, ok(&["simulate", "--tf", "0.3", "--json"])).unwrap();
    let path = file.to_str().unwrap();
    // Values that parse, for the flags that are not parameters.
    let value = |flag: &str| match flag {
        "--task" => Some("2"),
        "--arm" => Some("paper"),
        "--obstacle" | "--target" => Some("0.5,0.5"),
        "--radius" | "--orientation-weight" => Some("0.05"),
        "--dt" => Some("0.1"),
        "--tf" => Some("1"),
        "--theta0" => Some("0.1,0.2,0.3"),
        "--feedback" => Some("1"),
        "--joint-limits" => Some("-2:2,-2:2,-2:2"),
        "--rate-limits" => Some("1,1,1"),
        "--joint-weighting" => Some("wln"),
        "--path" => Some("circle:1.2,0.8"),
        "--urdf" => Some("robots/ur5e.urdf"),
        "--base" | "--tip" => Some("base_link"),
        "--package-dir" => Some("robots"),
        "--srdf" => Some("robots/ur5e.urdf"),
        _ => None,
    };
    // What goes with --from: the method, the output and the networks
    // (which a file of a method without networks does not name).
    let beside = [
        "--from",
        "--method",
        "--json",
        "--csv",
        "--help",
        "--networks",
        "--phi-variant",
        "--phi-weights",
        "--v-weights",
        "--precision",
    ];
    let mut checked = 0;
    for (flag, takes) in simulate_flags() {
        if beside.contains(&flag.as_str()) {
            continue;
        }
        let param = params::by_flag(&flag).map(|p| p.default.to_string());
        let v = match (takes, param.as_deref(), value(&flag)) {
            (false, _, _) => None,
            (true, Some(v), _) | (true, None, Some(v)) => Some(v.to_string()),
            (true, None, None) => panic!("no value known for {flag}: add one here"),
        };
        let mut args = vec!["simulate", "--from", path, flag.as_str()];
        if let Some(v) = &v {
            args.push(v);
        }
        refused(&args, &flag);
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} scene flags checked");
    // The method and the output go with it.
    let other: Value = json(&["simulate", "--from", path, "--method", "qp", "--json"]);
    assert_eq!(other["method"], "qp");
}

#[test]
fn a_run_names_its_networks_and_replays_with_them() {
    let text = ok(&[
        "simulate",
        "--method",
        "case3",
        "--networks",
        "reach",
        "--refine",
        "2",
        "--feedback",
        "1",
        "--json",
    ]);
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["networks"], serde_json::json!({"set": "reach"}));
    let file = scratch("reach-run.json");
    std::fs::write(&file, &text).unwrap();
    let path = file.to_str().unwrap();
    assert_eq!(
        ok(&["simulate", "--from", path, "--json"]),
        text,
        "replayed as it ran"
    );
    // The paper's set would be another run: not silently.
    refused(
        &["simulate", "--from", path, "--networks", "paper"],
        "--networks",
    );
    let paper: Value = json(&[
        "simulate",
        "--method",
        "case3",
        "--refine",
        "2",
        "--feedback",
        "1",
        "--json",
    ]);
    assert_ne!(paper["summary"], v["summary"]);
    // A method without networks names none.
    let numerical: Value = json(&["simulate", "--networks", "reach", "--json"]);
    assert!(numerical.get("networks").is_none());
    // The user's files go into the run, so it replays without them.
    let phi = scratch("own-phi.json");
    std::fs::write(&phi, redundant_ik::networks::PHI_REACH_JSON).unwrap();
    let own = ok(&[
        "simulate",
        "--method",
        "case1",
        "--phi-weights",
        phi.to_str().unwrap(),
        "--networks",
        "reach",
        "--tf",
        "1",
        "--json",
    ]);
    let o: Value = serde_json::from_str(&own).unwrap();
    assert!(o["networks"]["phi"]
        .as_str()
        .unwrap()
        .contains("\"encoding\""));
    let file = scratch("own-run.json");
    std::fs::write(&file, &own).unwrap();
    std::fs::remove_file(&phi).unwrap();
    assert_eq!(
        ok(&["simulate", "--from", file.to_str().unwrap(), "--json"]),
        own
    );
}

#[test]
fn a_run_in_f32_says_so_and_replays_in_f32() {
    let args = |precision: &'static str| {
        [
            "simulate",
            "--method",
            "case3",
            "--precision",
            precision,
            "--tf",
            "2",
            "--json",
        ]
    };
    let f32_text = ok(&args("f32"));
    let (single, double): (Value, Value) =
        (serde_json::from_str(&f32_text).unwrap(), json(&args("f64")));
    assert_eq!(single["precision"], "f32");
    assert!(
        double.get("precision").is_none(),
        "f64, the default, is left out"
    );
    let (e32, e64) = (
        single["summary"]["final_error"].as_f64().unwrap(),
        double["summary"]["final_error"].as_f64().unwrap(),
    );
    assert_ne!(e32, e64, "the f32 run is its own");
    assert!((e32 - e64).abs() < 1e-5, "{e32} vs {e64}");
    let file = scratch("f32-run.json");
    std::fs::write(&file, &f32_text).unwrap();
    let path = file.to_str().unwrap();
    assert_eq!(
        ok(&["simulate", "--from", path, "--json"]),
        f32_text,
        "replayed in f32"
    );
    refused(
        &["simulate", "--from", path, "--precision", "f64"],
        "--precision",
    );
    // A method without networks has no precision to keep.
    let numerical: Value = json(&["simulate", "--precision", "f32", "--tf", "1", "--json"]);
    assert!(numerical.get("precision").is_none());
    refused(&["simulate", "--precision", "f16"], "precision");
}

#[test]
fn a_run_file_written_before_the_parameters_moved_loads_and_replays_as_it_ran() {
    // tests/data/run-0.1.json: simulate --json of the version before, with
    // lambda, delta, avoidance, sign_smoothing and refine in its scene.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/run-0.1.json");
    let old: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let read = <RunFile>::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    let scene = &read.scene;
    for (name, v) in [
        ("lambda", 5.0),
        ("delta", 0.001),
        ("influence", 0.25),
        ("sign_smoothing", 0.05),
        ("refine", 2.0),
    ] {
        assert_eq!(scene.param(params::by_name(name).unwrap()), v, "{name}");
    }
    assert!(read.summary.success == (!read.summary.collided && read.summary.reached));
    let again: Value = json(&["simulate", "--from", path, "--json"]);
    // The same steps, but not bit for bit: the file's Case 1 run refines
    // Phi twice, and the refinement has since projected Phi onto the range
    // of J^T (ik::refine_phi), which moves its angles by up to 1.03e-5 rad
    // in these four steps (measured). Flags and every other field agree.
    assert_close(&again["steps"], &old["steps"], 1e-4, "steps");
    // It names its method `mode` (in the summary too), as files did before
    // "method"; the replay writes `method`.
    assert_eq!(read.method.name(), "case1");
    assert_eq!(read.summary.method, read.method);
    assert_eq!(again["method"], old["mode"]);
    assert_eq!(again["summary"]["method"], old["summary"]["mode"]);
    assert!(again.get("mode").is_none() && again["summary"].get("mode").is_none());
}

/// `a` and `b` agree field by field, numbers to within `tol`.
fn assert_close(a: &Value, b: &Value, tol: f64, at: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!((x - y).abs() <= tol, "{at}: {x} vs {y}");
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}");
            for (i, (x, y)) in x.iter().zip(y).enumerate() {
                assert_close(x, y, tol, &format!("{at}[{i}]"));
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(
                x.keys().collect::<Vec<_>>(),
                y.keys().collect::<Vec<_>>(),
                "{at}"
            );
            for (k, x) in x {
                assert_close(x, &y[k], tol, &format!("{at}.{k}"));
            }
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

/// Every run file names its format and version first; a planar file of
/// the version before (`redundant-ik-run/1`, the same layout) and one of
/// 0.2 without a format (the unversioned files) replay to the same bytes,
/// this version's format written; another version, or another format, is
/// refused by name.
#[test]
fn every_run_file_names_its_format_and_an_unversioned_one_replays_to_the_same_bytes() {
    let text = ok(&[
        "simulate", "--task", "1", "--method", "qp", "--tf", "1", "--json",
    ]);
    assert!(
        text.starts_with(r#"{"format":"redundant-ik-run/2","task":1,"#),
        "{}",
        &text[..60]
    );
    let file = super::scratch("unversioned.json");
    let path = file.to_str().unwrap();
    for older in ["", r#""format":"redundant-ik-run/1","#] {
        std::fs::write(
            &file,
            text.replacen(r#""format":"redundant-ik-run/2","#, older, 1),
        )
        .unwrap();
        assert_eq!(ok(&["simulate", "--from", path, "--json"]), text);
    }
    for (format, what) in [
        ("redundant-ik-run/3", "redundant-ik-run/3 is not supported"),
        ("hello", "not hello"),
    ] {
        std::fs::write(&file, text.replacen("redundant-ik-run/2", format, 1)).unwrap();
        refused(&["simulate", "--from", path], what);
    }
}
