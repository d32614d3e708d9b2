//! The playground's core: random tasks and training data for any arm, and
//! training both networks for it with a report (what the page's Training
//! panel runs in a Web Worker).

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use std::sync::Arc;

use redundant_ik::nalgebra::DVector;
use redundant_ik::networks::{Encoding, NetKind, Sampling, Variant};
use redundant_ik::networks::{NetworkSet, Networks};
use redundant_ik::nn::rng::Rng;
use redundant_ik::training::{self, tasks};
use redundant_ik::training_job::{self, Preset, Request, Which};
use redundant_ik::{Arm, Error, Method, Planner, Surrogate};

fn four_links() -> Arm {
    Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap()
}

#[test]
fn random_tasks_start_above_the_ground_and_their_lines_stay_in_reach() {
    for arm in [four_links(), Arm::new(0.3, vec![0.5, 0.5]).unwrap()] {
        let mut rng = Rng::new(3);
        let reach = arm.max_reach();
        for _ in 0..20 {
            let scene = tasks::random_task(&arm, &mut rng).unwrap();
            scene.validate().unwrap();
            let joints = arm.joints(&scene.theta0_vector());
            assert!(joints.iter().all(|p| p[1] >= tasks::GROUND));
            let start = joints[joints.len() - 1];
            let length = (start[0] - scene.target[0]).hypot(start[1] - scene.target[1]);
            assert!(length >= tasks::MIN_LENGTH * reach);
            let run = Planner::run_summary(scene, Method::NO_AVOIDANCE, None).unwrap();
            assert!(run.reached, "the line is reachable: {run:?}");
        }
    }
}

#[test]
fn random_tasks_are_seeded() {
    let arm = four_links();
    let a = tasks::random_task(&arm, &mut Rng::new(9)).unwrap();
    let b = tasks::random_task(&arm, &mut Rng::new(9)).unwrap();
    let c = tasks::random_task(&arm, &mut Rng::new(10)).unwrap();
    assert_eq!(a, b);
    assert_ne!(a, c);
}

#[test]
fn the_check_tasks_need_avoidance_and_the_numerical_route_manages_them() {
    let arm = four_links();
    let scenes = tasks::avoidance_tasks(&arm, 5, tasks::obstacle_region(&arm), 1).unwrap();
    assert_eq!(scenes.len(), 5);
    for scene in &scenes {
        assert_eq!(scene.obstacles.len(), 1);
        let none = Planner::run_summary(scene.clone(), Method::NO_AVOIDANCE, None).unwrap();
        let numerical = Planner::run_summary(scene.clone(), Method::NUMERICAL, None).unwrap();
        assert!(none.collided);
        assert!(tasks::succeeded(&numerical));
    }
    let check = tasks::check(&scenes, Method::NO_AVOIDANCE, None);
    assert_eq!((check.tasks, check.succeeded, check.collided), (5, 0, 5));
    let check = tasks::check(&scenes, Method::NUMERICAL, None);
    assert_eq!(check.succeeded, 5);
}

#[test]
fn the_paper_arm_keeps_the_paper_sampling_and_other_arms_sample_random_tasks() {
    assert_eq!(Sampling::for_arm(&Arm::paper()), Sampling::default());
    let s = Sampling::for_arm(&four_links());
    assert!(s.tasks.is_empty());
    assert!(s.random_tasks > 0);
    s.validate().unwrap();
    // The paper's tasks cannot seed a 4-link arm.
    let err = Sampling::default()
        .visited(&four_links(), &mut Rng::new(1))
        .unwrap_err();
    assert!(matches!(err, Error::Training(m) if m.contains("random tasks")));
}

#[test]
fn training_data_for_a_four_link_arm_has_its_shape_and_respects_the_floor() {
    let arm = four_links();
    let sampling = Sampling::for_arm(&arm);
    let samples = training::draw_samples(&arm, &sampling, 300, 5).unwrap();
    assert_eq!(samples.len(), 300);
    for s in &samples {
        assert_eq!(s.theta.len(), 4);
        let j = arm.jacobian(&DVector::from_column_slice(&s.theta));
        assert!(redundant_ik::ik::smallest_singular_value(&j) >= sampling.sigma_floor);
    }
    assert_eq!(
        samples,
        training::draw_samples(&arm, &sampling, 300, 5).unwrap(),
        "seeded"
    );
    // The equivariant Phi takes theta_2..theta_4 and gives the 4 x 2 Phi.
    let sets = training::phi_datasets(&arm, Variant::Equivariant, Encoding::Raw, &samples).unwrap();
    assert_eq!((sets.len(), sets[0].n_in, sets[0].n_out), (1, 3, 8));
    let v = training::v_dataset(&arm, Variant::Plain, Encoding::Raw, 0.0, &samples).unwrap();
    assert_eq!((v.n_in, v.n_out), (6, 4));
    // With angle features each angle is two inputs.
    let sets =
        training::phi_datasets(&arm, Variant::Equivariant, Encoding::Angles, &samples).unwrap();
    assert_eq!((sets[0].n_in, sets[0].n_out), (6, 8));
    let v =
        training::v_dataset(&arm, Variant::Equivariant, Encoding::Angles, 0.1, &samples).unwrap();
    assert_eq!((v.n_in, v.n_out), (8, 4));
}

fn small(arm: Arm, net: Which) -> Request {
    Request {
        arm,
        net,
        preset: Preset::Quick,
        samples: Some(200),
        epochs: Some(4),
        seed: Some(3),
    }
}

#[test]
fn training_for_a_four_link_arm_gives_networks_the_planner_takes() {
    let arm = four_links();
    let mut epochs = Vec::new();
    let trained = training_job::train(&small(arm.clone(), Which::Both), None, |p| {
        epochs.push((p.net, p.report.epoch));
        assert!(p.report.train_mse.is_finite() && p.report.val_mse.is_finite());
        true
    })
    .unwrap();
    assert!(epochs.first() == Some(&("phi", 1)));
    assert!(epochs.iter().any(|e| e.0 == "v"));
    assert_eq!(trained.phi.arm, arm);
    assert_eq!(trained.phi.net, NetKind::Phi);
    assert_eq!(trained.v.net, NetKind::V);
    // The files round-trip through their JSON text, as the page's download does.
    let nets = Networks::from_json(
        &trained.phi.to_json().unwrap(),
        &trained.v.to_json().unwrap(),
    )
    .unwrap();
    assert_eq!(nets.arm(), &arm);
    let scene = tasks::random_task(&arm, &mut Rng::new(1)).unwrap();
    let surrogate: Arc<dyn Surrogate> = Arc::new(nets);
    Planner::new(scene, Method::CASE3, Some(surrogate)).unwrap();
    let r = &trained.report;
    assert_eq!(r.samples, 200);
    assert!(r.phi.as_ref().unwrap().epochs <= 4);
    assert_eq!(r.phi_error.samples, 500);
    assert!(
        r.paper_tasks.is_empty(),
        "the paper's tasks are for its arm"
    );
    assert_eq!(
        r.random_tasks.len(),
        12,
        "numerical and Cases 1-3, K = 0 and 1; Cases 1 and 3 (the learned Phi) again refined twice"
    );
    let refined: Vec<_> = r
        .random_tasks
        .iter()
        .filter(|row| row.refine == 2)
        .collect();
    assert!(refined
        .iter()
        .all(|row| ["case1", "case3"].contains(&row.check.method)));
    assert_eq!(refined.len(), 4);
    for row in &r.random_tasks {
        assert_eq!(row.check.tasks, training_job::CHECK_TASKS);
        if row.check.method == "numerical" {
            assert_eq!(row.check.succeeded, training_job::CHECK_TASKS);
        }
    }
    // Four epochs are not enough: the networks fail their own check in
    // every loop, and the verdict names each case that fails in the last
    // (drift corrected, refined) and the numbers.
    let case3 = r
        .random_tasks
        .iter()
        .find(|row| row.feedback > 0.0 && row.refine == 2 && row.check.method == "case3")
        .unwrap();
    assert!(case3.check.succeeded < 5, "{}", case3.check.succeeded);
    assert!(!r.verdict.passed);
    assert!(
        r.verdict.checked.contains("10 random tasks"),
        "{}",
        r.verdict.checked
    );
    let line = r
        .verdict
        .failures
        .iter()
        .find(|f| f.starts_with("Case 3"))
        .unwrap();
    assert!(
        line.contains(&format!("succeeds on {} of 10", case3.check.succeeded)),
        "{line}"
    );
    let json = serde_json::to_value(r).unwrap();
    assert_eq!(json["verdict"]["passed"], false);
}

#[test]
fn the_shipped_networks_pass_their_own_check() {
    let r = training_job::assess(&Networks::embedded().unwrap(), 3000).unwrap();
    assert!(r.verdict.passed, "{:?}", r.verdict.failures);
    assert!(
        r.verdict.checked.contains("Tasks 1 and 2"),
        "{}",
        r.verdict.checked
    );
}

#[test]
fn training_one_network_keeps_the_other_and_needs_it_for_this_arm() {
    let embedded = Networks::embedded().unwrap();
    let t = training_job::train(&small(Arm::paper(), Which::V), Some(&embedded), |_| true).unwrap();
    assert_eq!(&t.phi, embedded.phi_file(), "Phi kept");
    assert_ne!(&t.v, embedded.v_file());
    assert!(t.report.phi.is_none() && t.report.v.is_some());
    assert_eq!(
        t.report.paper_tasks.len(),
        20,
        "Cases 1-3 on Tasks 1 and 2, open and closed loop; Cases 1 and 3 refined twice, open and closed"
    );
    assert_eq!(
        t.report
            .paper_tasks
            .iter()
            .filter(|o| o.refine == 2 && o.method == Method::CASE2)
            .count(),
        0,
        "Case 2 has nothing to refine"
    );
    // The built-in networks are for the paper's arm, not this one.
    let err = training_job::train(&small(four_links(), Which::Phi), Some(&embedded), |_| true)
        .unwrap_err();
    assert!(matches!(err, Error::Training(m) if m.contains("train both")));
}

#[test]
fn bad_training_requests_are_refused_with_a_reason() {
    let mut r = small(four_links(), Which::Both);
    r.samples = Some(5);
    assert!(matches!(
        training_job::train(&r, None, |_| true),
        Err(Error::OutOfRange { .. })
    ));
    let mut r = small(four_links(), Which::Both);
    r.epochs = Some(0);
    assert!(matches!(
        r.spec(NetKind::Phi),
        Err(Error::OutOfRange { .. })
    ));
    r.epochs = Some(training_job::MAX_EPOCHS + 1);
    assert!(r.spec(NetKind::V).is_err());
    let json = r#"{"arm": {"post": 0.5, "links": [0.6, 0.6]}, "net": "both", "preset": "quick", "epoch": 3}"#;
    assert!(
        serde_json::from_str::<Request>(json).is_err(),
        "unknown field"
    );
    let json = r#"{"arm": {"post": 0.5, "links": [0.6, 0.6]}, "net": "all", "preset": "quick"}"#;
    assert!(
        serde_json::from_str::<Request>(json).is_err(),
        "unknown network"
    );
    // An arm read from JSON goes through Arm::new: one link is refused there.
    let json = r#"{"arm": {"post": 0.5, "links": [0.6]}, "net": "both", "preset": "quick"}"#;
    let e = serde_json::from_str::<Request>(json).unwrap_err();
    assert!(e.to_string().contains("2 to 32 links"), "{e}");
}

#[test]
fn every_epoch_names_its_optimiser_whose_rate_it_reports() {
    // The page labels `mu` by it: LM's damping, or Adam's learning rate.
    let optimiser = |preset, net| {
        let mut r = small(Arm::paper(), Which::Both);
        r.preset = preset;
        let mut seen = Vec::new();
        training_job::train_net(&r, net, |p| {
            seen.push(p.optimiser);
            false
        })
        .unwrap();
        assert_eq!(seen.len(), 1, "the callback's false stops after one epoch");
        seen[0]
    };
    assert_eq!(optimiser(Preset::Quick, NetKind::Phi), "lm");
    assert_eq!(optimiser(Preset::Quick, NetKind::V), "lm");
    assert_eq!(optimiser(Preset::Reach, NetKind::Phi), "adam");
    assert_eq!(optimiser(Preset::Reach, NetKind::V), "lm");
}

#[test]
fn stopping_early_keeps_what_was_learnt() {
    let mut r = small(four_links(), Which::Both);
    r.epochs = Some(50);
    let mut seen = 0;
    let t = training_job::train(&r, None, |_| {
        seen += 1;
        seen % 3 != 0
    })
    .unwrap();
    assert!(t.report.phi.as_ref().unwrap().epochs <= 3);
    assert!(t.report.v.as_ref().unwrap().epochs <= 3);
}

#[test]
fn an_arm_without_avoidance_tasks_still_gets_its_networks_and_the_report_says_why() {
    // Two links: no redundancy, so no task in which the obstacle changes the
    // route. The check is empty and says so; the trained networks are kept
    // (the soak found the job failing as a whole here).
    let arm = Arm::new(0.3, vec![0.8, 0.7]).unwrap();
    let mut request = small(arm.clone(), Which::Both);
    request.samples = Some(40);
    request.epochs = Some(1);
    let trained = training_job::train(&request, None, |_| true).unwrap();
    assert_eq!(trained.phi.arm, arm);
    assert!(trained.report.random_tasks.is_empty());
    let note = trained.report.random_tasks_note.as_deref().unwrap();
    assert!(note.contains("where the obstacle matters"), "{note}");
    let json = serde_json::to_value(&trained.report).unwrap();
    assert_eq!(json["random_tasks_note"], note);
    assert!(trained.report.verdict.passed, "nothing to fail");
    assert!(trained.report.verdict.checked.starts_with("nothing"));
}

/// The page's training job natively (`docs/speed.md`, "Training in the
/// page"): both networks for the paper's arm, seed 1, the preset of
/// `JOB_PRESET` (quick by default; thorough, reach), as
/// `window.demo.train({net: 'both', preset, seed: 1})` runs it: wall times
/// of each network (`training_job::train_net`) and of the check
/// (`conclude`), one after the other, and what two cores would take (the
/// networks at once, as the page does with two workers).
/// `cargo test --release --test training -- --ignored --nocapture`.
#[cfg(not(target_arch = "wasm32"))]
#[test]
#[ignore = "a timing, not a check: run with --release -- --ignored --nocapture"]
#[allow(clippy::disallowed_methods)] // a native timing
fn the_page_training_job_natively() {
    use std::time::Instant;
    let preset = match std::env::var("JOB_PRESET").as_deref() {
        Ok("thorough") => Preset::Thorough,
        Ok("reach") => Preset::Reach,
        _ => Preset::Quick,
    };
    let request = Request {
        arm: Arm::paper(),
        net: Which::Both,
        preset,
        samples: None,
        epochs: None,
        seed: Some(1),
    };
    let timed = |net| {
        let start = Instant::now();
        let file = training_job::train_net(&request, net, |_| true).unwrap();
        (file, start.elapsed().as_secs_f64())
    };
    let (phi, t_phi) = timed(NetKind::Phi);
    let (v, t_v) = timed(NetKind::V);
    let start = Instant::now();
    let trained = training_job::conclude(&request, phi, v).unwrap();
    let t_check = start.elapsed().as_secs_f64();
    println!(
        "{preset:?}: Phi {t_phi:.2} s, v {t_v:.2} s, check {t_check:.2} s; one core {:.2} s, two {:.2} s; Phi median {:.3e}",
        t_phi + t_v + t_check,
        t_phi.max(t_v) + t_check,
        trained.report.phi_error.median
    );
}

#[test]
fn the_job_in_pieces_gives_the_same_networks_and_report() {
    // The page trains both networks at once in two workers, then checks
    // them in a third: the same files and report as the one-piece job.
    let request = small(Arm::paper(), Which::Both);
    let whole = training_job::train(&request, None, |_| true).unwrap();
    let phi = training_job::train_net(&request, NetKind::Phi, |_| true).unwrap();
    let v = training_job::train_net(&request, NetKind::V, |_| true).unwrap();
    let pieces = training_job::conclude(&request, phi, v).unwrap();
    assert_eq!(pieces, whole);
    // Files of another arm than the request's are refused.
    let other = small(four_links(), Which::Both);
    let err = training_job::conclude(&other, whole.phi.clone(), whole.v.clone()).unwrap_err();
    assert!(err.to_string().contains("another arm"), "{err}");
}

#[test]
fn the_shipped_reach_set_passes_its_own_check() {
    let nets = Networks::embedded_set(NetworkSet::Reach).unwrap();
    let r = training_job::assess(&nets, 20_000).unwrap();
    assert!(r.verdict.passed, "{:?}", r.verdict.failures);
    // Over the whole torus its Phi is within 1% (median) of the exact one.
    assert!(r.phi_error.median < 1e-2, "{}", r.phi_error.median);
}

#[test]
fn each_training_preset_says_the_sizes_it_trains_with() {
    use redundant_ik::training::Preset;
    for p in Preset::ALL {
        let label = p.label();
        let thousands = |n: usize| match n / 1000 {
            0 => n.to_string(),
            k => format!("{k} {:03}", n % 1000),
        };
        if let Some(s) = p.samples() {
            assert!(
                label.contains(&format!("{} samples", thousands(s))),
                "{label}"
            );
        }
        if let Some(e) = p.epochs() {
            assert!(label.contains(&format!("≤ {e} epochs")), "{label}");
        }
        assert_eq!(
            serde_json::to_value(p).unwrap(),
            p.name(),
            "the request's name"
        );
    }
}
