//! The robot model carries its limits: an arm's optional joint position
//! limits `LO:HI,...` (rad) and rate limits `R,...` (rad/s), one syntax for
//! the command line and the page's address, written in the arm's JSON only
//! when present, checked wherever an arm is made or read, and refused with
//! a message naming what is wrong. Absent, an arm is unlimited: the paper's
//! arm, its files and its numbers are as before.

use redundant_ik::arm::{JointLimits, RateLimits, PRESETS};
use redundant_ik::{Arm, Error, Scene};

const LIMITS: &str = "-2.0944:2.0944,-2.0944:2.0944,-2.0944:2.0944";

fn limits(text: &str) -> JointLimits {
    text.parse().expect("valid joint limits")
}

fn rates(text: &str) -> RateLimits {
    text.parse().expect("valid rate limits")
}

/// The paper's arm with the given limits.
fn limited(joint: Option<&str>, rate: Option<&str>) -> Arm {
    Arm::paper()
        .with_limits(joint.map(limits), rate.map(rates))
        .expect("limits fit the paper's arm")
}

// ---- the syntax ---------------------------------------------------------

#[test]
fn joint_limits_read_as_one_pair_per_joint_and_write_back_the_same_text() {
    let l = limits(LIMITS);
    assert_eq!(l.ranges(), &[[-2.0944, 2.0944]; 3]);
    assert_eq!(l.to_string(), LIMITS);
    for text in ["-1:1,0:3.5,-0.25:1e-3", "0:1,-3.14159:-0.5"] {
        let once = limits(text);
        assert_eq!(limits(&once.to_string()), once, "{text}");
    }
    assert_eq!(
        limits(" -1 : 1 , 0:2 ").ranges(),
        &[[-1.0, 1.0], [0.0, 2.0]]
    );
}

#[test]
fn rate_limits_read_as_one_number_per_joint_and_write_back_the_same_text() {
    let r = rates("1.5,1.5,2");
    assert_eq!(r.rates(), &[1.5, 1.5, 2.0]);
    assert_eq!(r.to_string(), "1.5,1.5,2");
    let odd = rates("0.1,3e-2,12.75");
    assert_eq!(rates(&odd.to_string()), odd);
}

#[test]
fn an_empty_range_is_refused_naming_the_joint() {
    for text in ["-1:1,1:-1,-1:1", "-1:1,0.5:0.5,-1:1"] {
        let e = text.parse::<JointLimits>().unwrap_err();
        assert!(e.to_string().contains("joint 2's limits"), "{e}");
    }
    let e = JointLimits::new(vec![[0.0, 1.0], [2.0, 1.0]]).unwrap_err();
    assert_eq!(
        e,
        Error::EmptyRange {
            joint: 2,
            range: [2.0, 1.0]
        }
    );
}

#[test]
fn non_finite_and_malformed_limits_are_refused() {
    for text in [
        "nan:1,-1:1,-1:1",
        "-1:inf,-1:1,-1:1",
        "-1:1,-1,-1:1",
        "-1:1:2,-1:1,-1:1",
        "",
        "a:b",
    ] {
        let e = text.parse::<JointLimits>().unwrap_err();
        assert!(matches!(e, Error::Syntax { .. }), "{text}: {e}");
    }
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let e = JointLimits::new(vec![[bad, 1.0], [-1.0, 1.0]]).unwrap_err();
        assert!(matches!(e, Error::NonFinite { .. }), "{bad}: {e}");
    }
}

#[test]
fn a_rate_limit_must_be_positive_and_finite() {
    for text in ["1,0,1", "1,-2,1", "1,nan,1", "1,inf,1", "", "1,,1"] {
        let e = text.parse::<RateLimits>().unwrap_err();
        assert!(matches!(e, Error::Syntax { .. }), "{text}: {e}");
    }
    let e = RateLimits::new(vec![1.0, 0.0]).unwrap_err();
    assert!(e.to_string().contains("rate limit of joint 2"), "{e}");
    assert!(matches!(
        RateLimits::new(vec![f64::NAN]),
        Err(Error::NonFinite { .. })
    ));
}

#[test]
fn limits_must_have_one_entry_per_link() {
    let e = Arm::paper()
        .with_limits(Some(limits("-1:1,-1:1")), None)
        .unwrap_err();
    assert_eq!(
        e,
        Error::DimensionMismatch {
            what: "joint limits".into(),
            expected: 3,
            found: 2
        }
    );
    let e = Arm::paper()
        .with_limits(None, Some(rates("1,1,1,1")))
        .unwrap_err();
    assert!(
        e.to_string()
            .contains("rate limits has 4 entries, expected 3"),
        "{e}"
    );
}

// ---- the arm and its scene ----------------------------------------------

#[test]
fn an_arm_without_limits_is_unlimited_and_writes_no_limit_fields() {
    let arm = Arm::paper();
    assert!(arm.joint_limits().is_none() && arm.rate_limits().is_none());
    let json = serde_json::to_string(&arm).unwrap();
    assert_eq!(json, r#"{"post":0.5,"links":[0.6,0.85,0.6]}"#);
    assert!(arm
        .check_within_limits("any pose", &[1e5, -1e5, 3.0])
        .is_ok());
}

#[test]
fn a_limited_arm_is_still_the_same_geometry_for_its_networks() {
    let arm = limited(Some(LIMITS), Some("1,1,1"));
    assert_ne!(arm, Arm::paper());
    assert!(arm.same_geometry(&Arm::paper()));
    assert!(redundant_ik::networks::builtin_fits(&arm));
}

#[test]
fn a_start_pose_outside_the_limits_is_refused_naming_joint_angle_and_limits() {
    let mut scene = Scene::task1(); // theta0 = [pi/12, pi/2, -pi/6]
    scene.arm = limited(Some("-1:1,-1:1,-1:1"), None);
    let e = scene.validate().unwrap_err();
    match &e {
        Error::OutOfRange {
            what,
            value,
            min,
            max,
        } => {
            assert!(
                what.contains("start pose") && what.contains("joint 2"),
                "{e}"
            );
            assert_eq!(
                (*value, *min, *max),
                (std::f64::consts::FRAC_PI_2, -1.0, 1.0)
            );
        }
        other => panic!("expected OutOfRange, got {other:?}"),
    }
    let text = e.to_string();
    assert!(
        text.contains("theta_2") && text.contains("-1 and 1"),
        "{text}"
    );
    // The bounds themselves are inside.
    scene.arm = limited(Some("0:0.25,1:1.5,-0.5:0"), None);
    scene.theta0 = vec![0.25, 1.5, -0.5];
    scene
        .validate()
        .expect("a pose on its bounds is within them");
}

#[test]
fn a_scene_with_limits_round_trips_through_json() {
    let mut scene = Scene::task2();
    scene.arm = limited(Some(LIMITS), Some("1.5,1.5,2"));
    scene.validate().unwrap();
    let json = serde_json::to_string(&scene).unwrap();
    assert!(json.contains(r#""joint_limits":[[-2.0944,2.0944],[-2.0944,2.0944],[-2.0944,2.0944]]"#));
    assert!(json.contains(r#""rate_limits":[1.5,1.5,2.0]"#));
    let back: Scene = serde_json::from_str(&json).unwrap();
    assert_eq!(back, scene);
}

#[test]
fn an_old_scene_without_limits_reads_as_unlimited_and_writes_as_before() {
    let old = serde_json::to_string(&Scene::task1()).unwrap();
    assert!(!old.contains("limits"), "{old}");
    let scene: Scene = serde_json::from_str(&old).unwrap();
    assert!(scene.arm.joint_limits().is_none() && scene.arm.rate_limits().is_none());
    assert_eq!(serde_json::to_string(&scene).unwrap(), old);
}

#[test]
fn bad_limits_in_a_file_are_refused_when_read() {
    let arm = |extra: &str| format!(r#"{{"post":0.5,"links":[0.6,0.85,0.6]{extra}}}"#);
    for (extra, what) in [
        (
            r#","joint_limits":[[1,-1],[-1,1],[-1,1]]"#,
            "joint 1's limits",
        ),
        (
            r#","joint_limits":[[-1,1],[-1,1]]"#,
            "joint limits has 2 entries",
        ),
        (r#","rate_limits":[1,0,1]"#, "rate limit of joint 2"),
        (r#","rate_limits":[1,1]"#, "rate limits has 2 entries"),
    ] {
        let e = serde_json::from_str::<Arm>(&arm(extra)).unwrap_err();
        assert!(e.to_string().contains(what), "{extra}: {e}");
    }
    let ok: Arm = serde_json::from_str(&arm(r#","joint_limits":[[-1,1],[-2,2],[-1,1]]"#)).unwrap();
    assert_eq!(ok.joint_limits().unwrap().to_string(), "-1:1,-2:2,-1:1");
}

#[test]
fn every_preset_is_a_valid_arm_with_the_limits_it_declares() {
    for p in PRESETS {
        let arm = p.arm();
        arm.validate()
            .unwrap_or_else(|e| panic!("preset {}: {e}", p.key));
        assert_eq!(
            arm.joint_limits().map(|l| l.ranges().to_vec()),
            p.joint_limits.map(|l| l.to_vec())
        );
        assert_eq!(
            arm.rate_limits().map(|r| r.rates().to_vec()),
            p.rate_limits.map(|r| r.to_vec())
        );
    }
    assert_eq!(
        PRESETS[0].arm(),
        Arm::paper(),
        "the paper's arm stays unlimited"
    );
}

#[test]
fn the_page_session_sets_limits_keeping_its_scene_or_refuses_changing_nothing() {
    let mut s = redundant_ik::session::Session::new(2).unwrap();
    let before = s.planner().scene().clone();
    s.set_arm_limits(Some(limits(LIMITS)), Some(rates("1,1,1")))
        .unwrap();
    let scene = s.planner().scene();
    assert_eq!(scene.theta0, before.theta0, "Task 2's start pose stays");
    assert_eq!(scene.arm.joint_limits().unwrap().to_string(), LIMITS);
    let e = s
        .set_arm_limits(Some(limits("-1:1,-1:1,-1:1")), None)
        .unwrap_err();
    assert!(e.to_string().contains("joint 2's limits"), "{e}");
    assert_eq!(
        s.planner().scene().arm.rate_limits().unwrap().to_string(),
        "1,1,1"
    );
    // Another task of the paper's arm keeps the arm's limits.
    s.load_task(1).unwrap();
    assert_eq!(
        s.planner().scene().arm.joint_limits().unwrap().to_string(),
        LIMITS
    );
    s.set_arm_limits(None, None).unwrap();
    assert_eq!(s.planner().scene().arm, Arm::paper());
}

// ---- the command line -----------------------------------------------------

#[cfg(not(target_family = "wasm"))]
mod cli {
    use std::process::{Command, Output};

    use serde_json::Value;

    fn cli(args: &[&str]) -> Output {
        Command::new(env!("CARGO_BIN_EXE_redundant-ik"))
            .args(args)
            .output()
            .expect("the binary runs")
    }

    fn ok(args: &[&str]) -> String {
        let out = cli(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?} failed: {err}");
        String::from_utf8_lossy(&out.stdout).into_owned()
    }

    /// A one-line `error:` mentioning `what`, exit status 2, no panic.
    fn refused(args: &[&str], what: &str) {
        let out = cli(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
        let first = err.lines().next().unwrap_or_default();
        assert!(first.starts_with("error:"), "{args:?}: {err}");
        assert!(
            first.contains(what),
            "{args:?}: '{first}' should mention '{what}'"
        );
    }

    const LIMITS: &str = "--joint-limits=-2.0944:2.0944,-2.0944:2.0944,-2.0944:2.0944";

    #[test]
    fn the_flags_set_the_arms_limits_shown_in_the_json() {
        let run: Value = serde_json::from_str(&ok(&[
            "simulate",
            LIMITS,
            "--rate-limits",
            "1.5,1.5,2",
            "--json",
        ]))
        .unwrap();
        let arm = &run["scene"]["arm"];
        assert_eq!(
            arm["joint_limits"],
            serde_json::json!([[-2.0944, 2.0944], [-2.0944, 2.0944], [-2.0944, 2.0944]])
        );
        assert_eq!(arm["rate_limits"], serde_json::json!([1.5, 1.5, 2.0]));
        let plain: Value = serde_json::from_str(&ok(&["simulate", "--json"])).unwrap();
        assert!(plain["scene"]["arm"].get("joint_limits").is_none());
        assert!(plain["scene"]["arm"].get("rate_limits").is_none());
        let text = ok(&["simulate", LIMITS]);
        assert!(text.contains("joint limits -2.0944:2.0944,"), "{text}");
    }

    #[test]
    fn the_paper_networks_still_fit_a_limited_paper_arm() {
        for method in ["case1", "case2", "case3"] {
            let run: Value =
                serde_json::from_str(&ok(&["simulate", "--method", method, LIMITS, "--json"]))
                    .unwrap();
            assert!(run["scene"]["arm"]["joint_limits"].is_array(), "{method}");
        }
    }

    #[test]
    fn figure_and_atlas_take_the_flags_too() {
        for cmd in ["figure", "atlas"] {
            let help = ok(&[cmd, "--help"]);
            assert!(
                help.contains("--joint-limits") && help.contains("--rate-limits"),
                "{cmd}"
            );
        }
        ok(&[
            "atlas",
            "--grid",
            "2",
            "--methods",
            "numerical",
            "--threads",
            "1",
            "--json",
            LIMITS,
        ]);
        refused(
            &[
                "atlas",
                "--grid",
                "2",
                "--methods",
                "numerical",
                "--joint-limits=-1:1,-1:1,-1:1",
            ],
            "joint 2's limits",
        );
    }

    #[test]
    fn bad_limits_on_the_command_line_are_refused_with_what_is_wrong() {
        for (args, what) in [
            (
                vec!["simulate", "--joint-limits=1:-1,-1:1,-1:1"],
                "joint 1's limits",
            ),
            (
                vec!["simulate", "--joint-limits=nan:1,-1:1,-1:1"],
                "not a finite number",
            ),
            (
                vec!["simulate", "--joint-limits=-1:1,-1:1"],
                "joint limits has 2 entries, expected 3",
            ),
            (
                vec!["simulate", "--rate-limits", "1,1"],
                "rate limits has 2 entries, expected 3",
            ),
            (
                vec!["simulate", "--rate-limits", "1,0,1"],
                "rate limit of joint 2 must be positive",
            ),
            (
                vec!["simulate", "--rate-limits", "1,inf,1"],
                "not a finite number",
            ),
            (
                vec!["simulate", "--joint-limits=-1:1,-1:1,-1:1"],
                "start pose theta0: theta_2 (joint 2's limits) must lie between -1 and 1",
            ),
            (
                vec!["simulate", LIMITS, "--theta0=0,3,0"],
                "theta_2 (joint 2's limits) must lie between -2.0944 and 2.0944 (got 3)",
            ),
        ] {
            refused(&args, what);
        }
    }

    #[test]
    fn from_refuses_the_limit_flags_like_every_scene_flag() {
        let dir = std::env::temp_dir().join(format!("redundant-ik-limits-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("run.json");
        std::fs::write(&file, ok(&["simulate", LIMITS, "--json"])).unwrap();
        let from = file.to_str().unwrap();
        // The file keeps its limits.
        let back: Value =
            serde_json::from_str(&ok(&["simulate", "--from", from, "--json"])).unwrap();
        assert_eq!(
            back["scene"]["arm"]["joint_limits"][0],
            serde_json::json!([-2.0944, 2.0944])
        );
        refused(
            &["simulate", "--from", from, LIMITS],
            "--joint-limits cannot change it",
        );
        refused(
            &["simulate", "--from", from, "--rate-limits", "1,1,1"],
            "--rate-limits cannot change it",
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
