//! One planner for every arm, as a specification that holds for the planar
//! arm and for a chain in space alike: each check below is written once,
//! generic over the arm model, and run on the paper's tasks, the planar
//! presets with a task of their own, the Panda and the iiwa14.

use redundant_ik::arm::PRESETS as PLANAR_PRESETS;
use redundant_ik::planner::{methods, Planned, Planner, SceneOf};
use redundant_ik::scene::{Scene, SpaceScene};
use redundant_ik::space::PRESETS as SPACE_PRESETS;
use redundant_ik::{Error, Method};

/// The scenes of the planar arm: the paper's two tasks and every preset
/// that has a task of its own.
fn planar_scenes() -> Vec<(String, Scene)> {
    let mut out = vec![
        ("task 1".to_string(), Scene::task1()),
        ("task 2".to_string(), Scene::task2()),
    ];
    for p in PLANAR_PRESETS.iter() {
        let mut s = Scene::task1();
        s.arm = p.arm();
        if s.use_preset_task() {
            out.push((p.key.to_string(), s));
        }
    }
    out
}

/// The scenes of the chains in space: each preset's own task.
fn space_scenes() -> Vec<(String, SpaceScene)> {
    SPACE_PRESETS
        .iter()
        .map(|p| (p.key.to_string(), SpaceScene::preset(p)))
        .collect()
}

/// Every method that needs no networks.
fn exact_methods() -> impl Iterator<Item = Method> {
    methods::ALL.iter().copied().filter(|m| !m.uses_networks())
}

/// A run to the end records a sample per step from the start, and its
/// summary is the one a run that keeps only the summary gives, to the bit.
fn runs_to_its_end<S, A, const M: usize>(label: &str, scene: &S)
where
    S: SceneOf<A, M> + redundant_ik::model::Scene<A> + Clone,
    A: Planned<M, Scene = S>,
{
    for m in exact_methods() {
        let run = Planner::run(scene.clone(), m, None).unwrap();
        let steps = scene.steps();
        assert_eq!(run.steps.len(), steps + 1, "{label} {m}");
        assert_eq!(run.summary.steps, steps, "{label} {m}");
        assert_eq!(run.steps[0].t, 0.0, "{label} {m}");
        let summary = Planner::run_summary(scene.clone(), m, None).unwrap();
        assert_eq!(summary, run.summary, "{label} {m}");
        assert!(run.summary.final_error.is_finite(), "{label} {m}");
        // The summary counts what the samples say.
        let collisions = run.steps.iter().filter(|s| s.collision).count();
        assert_eq!(run.summary.collision_steps, collisions, "{label} {m}");
        assert_eq!(run.summary.collided, collisions > 0, "{label} {m}");
        let limits = run
            .steps
            .iter()
            .filter(|s| !s.past_limits.is_empty())
            .count();
        assert_eq!(run.summary.limit_steps, limits, "{label} {m}");
    }
}

/// A planner reset to `t = 0` runs again exactly as a new one.
fn reset_is_new<S, A, const M: usize>(label: &str, scene: &S)
where
    S: SceneOf<A, M> + redundant_ik::model::Scene<A> + Clone,
    A: Planned<M, Scene = S>,
{
    let mut p = Planner::new(scene.clone(), Method::NUMERICAL, None).unwrap();
    let first = p.summary_to_end().unwrap();
    p.reset();
    assert_eq!(p.time(), 0.0, "{label}");
    let again = p.clone().run_to_end().unwrap();
    let fresh = Planner::run(scene.clone(), Method::NUMERICAL, None).unwrap();
    assert_eq!(again, fresh, "{label}");
    assert_eq!(p.summary_to_end().unwrap(), first, "{label}");
}

/// The sample of a pose says one thing in one vocabulary: the hand is the
/// last of the joints, the tracking error its distance to the reference,
/// the joints past their limits are those outside their ranges.
fn one_vocabulary<S, A, const M: usize>(label: &str, scene: &S)
where
    S: SceneOf<A, M> + redundant_ik::model::Scene<A> + Clone,
    A: Planned<M, Scene = S>,
{
    let mut p = Planner::new(scene.clone(), Method::NO_AVOIDANCE, None).unwrap();
    for _ in 0..scene.steps().min(20) {
        let s = p.step().unwrap().clone();
        let n = s.theta.len();
        assert_eq!(s.joints.len(), n + 1, "{label}");
        // The hand's point is the task's first coordinates (all of them
        // for the position task, the position of the pose task's).
        let d = s.joints[n].as_ref().len();
        assert_eq!(s.joints[n].as_ref(), &s.ee[..d], "{label}");
        assert_eq!(s.ee, A::hand(p.pose()), "{label}");
        let error = (0..M)
            .map(|k| (s.ee[k] - s.reference[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!((error - s.tracking_error).abs() < 1e-15, "{label}");
        // These scenes have no floor: a collision is a link inside an
        // obstacle, a negative clearance.
        assert_eq!(s.collision, s.clearance.is_some_and(|c| c < 0.0), "{label}");
        let limits = scene.arm().joint_limits();
        let past: Vec<usize> = limits.map_or(Vec::new(), |l| {
            l.ranges()
                .iter()
                .zip(&s.theta)
                .enumerate()
                .filter(|(_, (r, &t))| t < r[0] || t > r[1])
                .map(|(k, _)| k + 1)
                .collect()
        });
        assert_eq!(s.past_limits, past, "{label}");
        assert!(
            s.manipulability >= 0.0 && s.manipulability.is_finite(),
            "{label}"
        );
    }
}

/// A learned method without networks is refused when the planner is made,
/// with a reason that names the flag that gives them.
fn learned_needs_networks<S, A, const M: usize>(label: &str, scene: &S)
where
    S: SceneOf<A, M> + redundant_ik::model::Scene<A> + Clone,
    A: Planned<M, Scene = S>,
{
    for m in methods::ALL.iter().filter(|m| m.uses_networks()) {
        let e = Planner::new(scene.clone(), *m, None).err().unwrap();
        assert!(
            matches!(e, Error::NetworksUnavailable(_)),
            "{label} {m}: {e}"
        );
        assert!(e.to_string().contains("--networks"), "{label} {m}: {e}");
    }
}

#[test]
fn the_checks_cover_both_kinds_of_arm() {
    let planar: Vec<String> = planar_scenes().into_iter().map(|(l, _)| l).collect();
    assert_eq!(planar, ["task 1", "task 2", "iiwa-planar"]);
    let space: Vec<String> = space_scenes().into_iter().map(|(l, _)| l).collect();
    assert_eq!(space, ["panda", "iiwa14"]);
    assert!(exact_methods().count() >= 7);
}

/// Every check, on every scene of both kinds of arm.
macro_rules! on_every_arm {
    ($($check:ident),+ $(,)?) => {
        $(
            #[test]
            fn $check() {
                for (label, scene) in planar_scenes() {
                    super::$check(&label, &scene);
                }
                for (label, scene) in space_scenes() {
                    super::$check(&label, &scene);
                }
            }
        )+
    };
}

mod on_every_arm {
    use super::{planar_scenes, space_scenes};
    on_every_arm!(
        runs_to_its_end,
        reset_is_new,
        one_vocabulary,
        learned_needs_networks
    );
}
