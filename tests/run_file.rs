//! The one run file, for every arm: one format (`redundant-ik-run/2`)
//! that reads back as it was written and replays to the same samples, the
//! files of the versions before it (the planar `redundant-ik-run/1` and
//! `redundant-ik-space-run/1`) read and replay to the samples they hold,
//! and a corrupt or hostile file is refused with a reason, never a panic.

use redundant_ik::export::{is_space_run, RunFile, SpaceRunFile, RUN_FORMAT};
use redundant_ik::networks::space::SpaceNetworkSet;
use redundant_ik::networks::NetworkSet;
use redundant_ik::nn::Precision;
use redundant_ik::planner::{Networks, Planner, Trajectory};
use redundant_ik::run::{NetworkChoice, Run};
use redundant_ik::scene::{Scene, SpaceScene};
use redundant_ik::space::{Chain, SpacePreset};
use redundant_ik::{Error, Method};

fn data(name: &str) -> String {
    let path = format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A planar run file of `task` in `method` (with the set `reach` for a
/// learned method), `tf` seconds.
fn planar(task: u32, method: Method, tf: f64) -> RunFile {
    let mut scene = Scene::task(task).unwrap();
    scene.tf = tf;
    let run = Run {
        task,
        method,
        scene,
        networks: method
            .uses_networks()
            .then_some(NetworkChoice::Set(NetworkSet::Reach)),
        precision: Precision::F64,
    };
    let nets = run.surrogate_for(method).unwrap();
    let traj = Planner::run(run.scene.clone(), method, nets).unwrap();
    RunFile::new(run, traj)
}

/// The networks a spatial run file names, loaded in its arithmetic.
fn space_networks(f: &SpaceRunFile) -> Option<Networks<Chain, 3>> {
    let nets = f.networks.as_ref()?.load().unwrap();
    Some(nets.in_precision(f.precision) as Networks<Chain, 3>)
}

/// A spatial run file of the preset `key`'s task in `method` along
/// `path`, `tf` seconds.
fn spatial(key: &str, method: Method, path: &str, tf: f64) -> SpaceRunFile {
    let mut scene = SpaceScene::by_key(key).unwrap();
    scene.path = path.parse().unwrap();
    scene.tf = tf;
    let networks = method
        .uses_networks()
        .then_some(NetworkChoice::Set(SpaceNetworkSet::PandaReach));
    let nets = networks
        .as_ref()
        .map(|c| c.load().unwrap() as Networks<Chain, 3>);
    let traj = Planner::new(scene.clone(), method, nets)
        .and_then(Planner::run_to_end)
        .unwrap();
    SpaceRunFile::of(None, scene, traj, networks, Precision::F64)
}

/// The run of a spatial file's scene and method again.
fn replay_space(f: &SpaceRunFile) -> Trajectory<3> {
    Planner::new(f.scene.clone(), f.method, space_networks(f))
        .and_then(Planner::run_to_end)
        .unwrap()
}

/// The run of a planar file's scene and method again.
fn replay_planar(f: &RunFile) -> Trajectory {
    let run = f.run();
    let nets = run.surrogate_for(run.method).unwrap();
    Planner::run(run.scene, run.method, nets).unwrap()
}

#[test]
fn every_arm_writes_one_format_that_reads_back_as_written_and_replays_to_the_same_samples() {
    let head = format!("{{\"format\":\"{RUN_FORMAT}\"");
    for f in [
        planar(1, Method::NUMERICAL, 2.0),
        planar(2, Method::CASE3, 2.0),
    ] {
        let text = f.to_json();
        assert!(text.starts_with(&head), "{}", &text[..60]);
        assert!(!is_space_run(&text));
        let back = <RunFile>::from_json(&text).unwrap();
        assert_eq!(back, f);
        let again = replay_planar(&back);
        assert_eq!(again.steps, f.steps, "{}", f.method);
        assert_eq!(RunFile::new(back.run(), again).to_json(), text);
    }
    for f in [
        spatial("panda", Method::CASE3, "line", 1.0),
        spatial(
            "iiwa14",
            Method::NUMERICAL,
            "circle:0.5,0,0.2,1,0.5,0.2",
            1.0,
        ),
    ] {
        let text = f.to_json();
        assert!(text.starts_with(&head), "{}", &text[..60]);
        assert!(is_space_run(&text));
        // The file carries the chain whole, its limits with it.
        assert!(text.contains("\"rows\":[{\"a\":0.0,"), "{}", &text[..300]);
        let back = SpaceRunFile::from_json(&text).unwrap();
        assert_eq!(back, f);
        assert!(SpacePreset::of(&back.scene.arm).is_some());
        let again = replay_space(&back);
        assert_eq!(again.steps, f.steps, "{}", f.method);
        let rewritten =
            SpaceRunFile::of(None, back.scene, again, back.networks, back.precision).to_json();
        assert_eq!(rewritten, text);
    }
}

#[test]
fn the_run_files_of_the_versions_before_read_and_replay_to_the_samples_they_hold() {
    // Written by the version before this one (`simulate --json`): the
    // planar run/1 of Task 2 in Case 3 with the reach set, and the
    // space-run/1 files of the Panda in qp and in Case 3 (f32) and of the
    // iiwa14 along a circle in distance.
    let old = <RunFile>::from_json(&data("run-1-task2-case3-reach.json")).unwrap();
    assert_eq!(old.format, RUN_FORMAT, "read into this version");
    assert_eq!(old.task, Some(2));
    assert_eq!(old.networks, Some(NetworkChoice::Set(NetworkSet::Reach)));
    assert_eq!(replay_planar(&old).steps, old.steps);
    for (name, method, precision) in [
        (
            "panda-qp",
            redundant_ik::planner::methods::QP,
            Precision::F64,
        ),
        ("panda-case3", Method::CASE3, Precision::F32),
        (
            "iiwa14-circle",
            redundant_ik::planner::methods::DISTANCE,
            Precision::F64,
        ),
    ] {
        let text = data(&format!("space/space-run-1-{name}.json"));
        assert!(is_space_run(&text));
        let old = SpaceRunFile::from_json(&text).unwrap();
        assert_eq!((old.method, old.precision), (method, precision), "{name}");
        assert_eq!(old.format, RUN_FORMAT, "{name}");
        let again = replay_space(&old);
        assert_eq!(again.steps.len(), old.steps.len(), "{name}");
        // What the old file held (angles, hand, reference, errors,
        // clearance) is the replay's to the bit; what it did not hold was
        // computed from the angles, as the replay computes it.
        assert_eq!(again.steps, old.steps, "{name}");
        let (a, b) = (&again.summary, &old.summary);
        assert_eq!(
            (a.steps, a.min_clearance, a.collision_steps, a.final_error),
            (b.steps, b.min_clearance, b.collision_steps, b.final_error),
            "{name}"
        );
        assert_eq!(a.max_tracking_error, b.max_tracking_error, "{name}");
        // Written again, it is this version's file.
        let text = SpaceRunFile::of(None, old.scene, again, old.networks, old.precision).to_json();
        assert!(SpaceRunFile::from_json(&text).is_ok(), "{name}");
    }
}

#[test]
fn a_planar_reader_refuses_a_run_in_space_and_the_other_way_round() {
    let space = spatial("panda", Method::NUMERICAL, "line", 0.5).to_json();
    let plane = planar(1, Method::NUMERICAL, 0.5).to_json();
    let e = <RunFile>::from_json(&space).unwrap_err().to_string();
    assert!(e.contains("an arm in space"), "{e}");
    let e = SpaceRunFile::from_json(&plane).unwrap_err().to_string();
    assert!(e.contains("a planar arm"), "{e}");
    let old = data("space/space-run-1-panda-qp.json");
    let e = <RunFile>::from_json(&old).unwrap_err().to_string();
    assert!(e.contains("an arm in space"), "{e}");
}

/// `text` with its first `from` replaced by `to` (which must be there).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1)
}

#[test]
fn a_corrupt_or_hostile_run_file_is_an_error_for_either_arm() {
    let space = spatial("panda", Method::NUMERICAL, "line", 0.5).to_json();
    let plane = planar(1, Method::NUMERICAL, 0.5).to_json();
    let both = |from: &str, to: &str, says: &str| {
        for text in [&space, &plane] {
            let bad = edit(text, from, to);
            let e = if is_space_run(text) {
                SpaceRunFile::from_json(&bad).map(|_| ())
            } else {
                <RunFile>::from_json(&bad).map(|_| ())
            };
            let e = e.unwrap_err().to_string();
            assert!(e.contains(says), "'{says}' not in: {e}");
        }
    };
    both(RUN_FORMAT, "redundant-ik-run/3", "not supported");
    both(RUN_FORMAT, "something else", "format");
    both("\"method\":\"numerical\"", "\"method\":\"case9\"", "case9");
    both("\"dt\":", "\"dt\":-1,\"x\":", "unknown field");
    both("\"tf\":0.5", "\"tf\":-0.5", "positive");
    both("\"theta0\":[", "\"theta0\":[9,", "entries");
    both(
        "\"steps\":[{\"t\":0.0,\"theta\":[",
        "\"steps\":[{\"t\":0.0,\"theta\":[1,",
        "entries",
    );
    both("\"lambda\":", "\"lambda\":-1,\"nothing\":", "parameter");
    // The chain itself is checked as the reader builds it.
    let chain_says = |from: &str, to: &str, says: &str| {
        let bad = edit(&space, from, to);
        let e = match SpaceRunFile::from_json(&bad) {
            Ok(_) => panic!("read: {}", &bad[..bad.find("theta0").unwrap_or(0)]),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(says), "'{says}' not in: {e}");
    };
    chain_says("\"radius\":0.06,", "\"radius\":-1,", "radius");
    chain_says(
        "\"rows\":[",
        "\"rows\":[{\"a\":1e300,\"alpha\":0,\"d\":0,\"offset\":0},",
        "a of joint 1",
    );
    chain_says(
        "\"rows\":[{\"a\":0.0,",
        "\"rows\":[{\"a\":0.0,\"b\":1,",
        "unknown field",
    );
    chain_says("\"joint_limits\":[", "\"joint_limits\":[[1,0],", "joint");
    // Not a run file at all, cut short, or too large.
    for text in [&space, &plane] {
        for bad in [
            text[..text.len() / 2].to_string(),
            "[1, 2]".to_string(),
            "{}".to_string(),
            " ".repeat(redundant_ik::export::MAX_RUN_FILE_BYTES + 1),
        ] {
            let e = if is_space_run(text) {
                SpaceRunFile::from_json(&bad).map(|_| ())
            } else {
                <RunFile>::from_json(&bad).map(|_| ())
            };
            assert!(matches!(e, Err(Error::Syntax { .. })), "{e:?}");
        }
    }
}
