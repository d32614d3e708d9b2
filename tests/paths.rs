//! The paths beyond the line (issue 25, item 4): the syntax, the timed
//! reference of each kind, tracking a circle with every method, the line
//! unchanged, and the atlas's `path_blocked` for a circle.

use std::sync::Arc;

use redundant_ik::atlas::{unavoidable, Class};
use redundant_ik::networks::Networks;
use redundant_ik::planner::{methods, Planner, Surrogate, Track};
use redundant_ik::scene::{Path, Scene, SceneFile, DRAWN_SPACING, MAX_LAPS, MAX_POINTS};
use redundant_ik::Obstacle;

const CIRCLE: &str = "circle:1.2,0.8";

fn circle_scene(feedback: f64) -> Scene {
    let mut s = Scene::task1();
    s.path = CIRCLE.parse().unwrap();
    s.feedback_gain = feedback;
    s
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn vec2(x: [f64; 2]) -> nalgebra::Vector2<f64> {
    nalgebra::Vector2::new(x[0], x[1])
}

#[test]
fn the_syntax_round_trips() {
    for text in [
        "line",
        "circle:1.2,0.8",
        "circle:-0.5,0.001,3",
        "points:1,0.5",
        "points:1,0.5;0.8,0.2;-0.25,1.75",
    ] {
        let p: Path = text.parse().unwrap();
        assert_eq!(p.to_string(), text);
        assert_eq!(p.to_string().parse::<Path>().unwrap(), p);
    }
    // Spaces and a trailing ';' are read as people mean them; LAPS 1 is
    // the default and is not written.
    let p: Path = " points: 1, 0.5 ; 0.8,0.2; ".parse().unwrap();
    assert_eq!(p, Path::Points(vec![[1.0, 0.5], [0.8, 0.2]]));
    let c: Path = "circle:1,2,1".parse().unwrap();
    assert_eq!(c.to_string(), "circle:1,2");
    assert_eq!(Path::default(), Path::Line);
}

#[test]
fn bad_paths_are_refused_with_a_message() {
    let too_many = format!("points:{}", vec!["1,1"; MAX_POINTS + 1].join(";"));
    for (text, says) in [
        ("", "expected line"),
        ("spiral:1,2", "expected line"),
        ("circle:1", "circle:CX,CY"),
        ("circle:1,2,3,4", "circle:CX,CY"),
        ("circle:NaN,0.8", "not a finite number"),
        ("circle:1,inf", "not a finite number"),
        ("circle:1,2,0", "LAPS"),
        ("circle:1,2,-1", "LAPS"),
        ("circle:1,2,1.5", "LAPS"),
        ("circle:1,2,1001", "from 1 to 1000"),
        ("points:", "expected 1 to 64 points"),
        ("points:;;", "expected 1 to 64 points"),
        ("points:1,2,3", "expected X,Y"),
        ("points:1,x", "not a finite number"),
        (too_many.as_str(), "expected 1 to 64 points"),
    ] {
        let e = text.parse::<Path>().unwrap_err().to_string();
        assert!(e.contains(says), "{text:?}: {e}");
    }
    // The messages' numbers are the limits'.
    assert_eq!((MAX_POINTS, MAX_LAPS), (64, 1000));
    // The centre at the hand's start: radius 0.
    let mut s = Scene::task1();
    let start = s.start();
    s.path = Path::Circle {
        centre: start,
        laps: 1,
    };
    let e = s.validate().unwrap_err().to_string();
    assert!(e.contains("radius 0"), "{e}");
    assert!(Planner::new(s, methods::NUMERICAL, None).is_err());
    // A point out of reach is allowed: the run misses it.
    let mut s = Scene::task1();
    s.path = "points:5,5".parse().unwrap();
    let sum = Planner::run_summary(s, methods::NUMERICAL, None).unwrap();
    assert!(!sum.reached && !sum.target_reachable);
}

#[test]
fn a_circle_closes_on_itself_at_constant_speed_through_the_start() {
    let start = Scene::task1().start();
    for laps in [1, 3] {
        let path = Path::Circle {
            centre: [1.2, 0.8],
            laps,
        };
        let track = Track::new(&path, start, [0.6, 0.2], 0.0, 10.0);
        let r = dist(start, [1.2, 0.8]);
        assert!((r - 0.416).abs() < 1e-3, "radius {r}");
        assert_eq!(track.end(), start);
        assert_eq!(track.reference(10.0), start);
        assert!(dist(track.reference(0.0), start) < 1e-15);
        let speed = 2.0 * std::f64::consts::PI * r * laps as f64 / 10.0;
        for k in 0..=1000 {
            let t = 10.0 * k as f64 / 1000.0;
            let x = track.reference(t);
            assert!(
                (dist(x, [1.2, 0.8]) - r).abs() < 1e-12,
                "off the circle at {t}"
            );
            let v = vec2(track.velocity(5.0, t, true));
            assert!((v.norm() - speed).abs() < 1e-12, "speed at {t}");
            // The velocity is the reference's derivative (central difference).
            let e = 1e-6;
            let d = (vec2(track.reference(t + e)) - vec2(track.reference(t - e))) / (2.0 * e);
            if k > 0 && k < 1000 {
                assert!((d - v).norm() < 1e-6 * speed, "derivative at {t}");
            }
            // Counter-clockwise: (x - c) x v > 0.
            let (dx, dy) = (x[0] - 1.2, x[1] - 0.8);
            assert!(dx * v[1] - dy * v[0] > 0.0);
        }
        // Half a lap (laps = 1): diametrically opposite the start.
        if laps == 1 {
            let half = track.reference(5.0);
            assert!((dist(half, start) - 2.0 * r).abs() < 1e-12);
        }
    }
}

#[test]
fn a_polyline_runs_from_the_hand_to_its_last_point_at_constant_speed() {
    let start = Scene::task1().start();
    let path: Path = "points:1.2,0.3;0.6,0.3;0.6,0.3;0.6,1.0".parse().unwrap();
    let track = Track::new(&path, start, [0.6, 0.2], 0.0, 10.0);
    assert_eq!(track.reference(0.0), start);
    assert_eq!(track.reference(10.0), [0.6, 1.0]);
    assert_eq!(track.end(), [0.6, 1.0]);
    let total = dist(start, [1.2, 0.3]) + 0.6 + 0.7;
    let n = 2000;
    let mut walked = 0.0;
    for k in 1..=n {
        let (a, b) = (10.0 * (k - 1) as f64 / n as f64, 10.0 * k as f64 / n as f64);
        let step = dist(track.reference(a), track.reference(b));
        walked += step;
        // Constant speed: equal times, equal arc lengths (a corner inside
        // a step shortens its chord a little).
        assert!(step <= total / n as f64 + 1e-12);
        let v = vec2(track.velocity(0.5 * (a + b), 0.5 * (a + b), true));
        assert!((v.norm() - total / 10.0).abs() < 1e-12);
    }
    assert!((walked - total).abs() < 1e-3, "{walked} vs {total}");
    // At a corner the side decides: before it the first segment's
    // direction, after it the second's (a square's corner at t = 1 s).
    let square: Path = "points:1,0;1,1".parse().unwrap();
    let square = Track::new(&square, [0.0, 0.0], [0.0, 0.0], 0.0, 2.0);
    assert_eq!(square.velocity(0.95, 1.0, false), [1.0, 0.0]);
    assert_eq!(square.velocity(1.05, 1.0, true), [0.0, 1.0]);
    assert_eq!(square.velocity(2.05, 2.0, false), [0.0, 0.0]);
    // The run ends at the last point.
    let mut s = Scene::task1();
    s.path = path;
    s.feedback_gain = 1.0;
    let sum = Planner::run_summary(s, methods::NUMERICAL, None).unwrap();
    assert!(sum.final_error < 5e-3 && sum.reached, "{sum:?}");
}

/// The goal of the item: Task 1's arm and start on the circle about
/// (1.2, 0.8), the numerical route, closed loop K = 1.
#[test]
fn the_numerical_route_tracks_the_circle_to_a_micrometre_and_closes_it() {
    let traj = Planner::run(circle_scene(1.0), methods::NUMERICAL, None).unwrap();
    let start = traj.steps[0].ee;
    let end = traj.steps.last().unwrap().ee;
    println!(
        "numerical, circle, K = 1: max tracking error {:.3e} m, back at the start within {:.3e} m",
        traj.summary.max_tracking_error,
        dist(start, end)
    );
    assert!(traj.summary.max_tracking_error < 1e-6);
    assert!(dist(start, end) < 1e-6);
    assert!(traj.summary.final_error < 1e-6 && traj.summary.reached);
    // The reference is the circle's: every sample's reference on it.
    for s in &traj.steps {
        assert!((dist(s.reference, [1.2, 0.8]) - dist(start, [1.2, 0.8])).abs() < 1e-12);
    }
}

#[test]
fn every_method_runs_the_circle() {
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    for &method in methods::ALL {
        let nets = method.uses_networks().then(|| nets.clone());
        let traj = Planner::run(circle_scene(1.0), method, nets).unwrap();
        let sum = &traj.summary;
        println!(
            "{method}: max tracking error {:.3e} m, final error {:.3e} m",
            sum.max_tracking_error, sum.final_error
        );
        assert_eq!(traj.steps.len(), 101);
        assert!(sum.final_error.is_finite(), "{method}: {sum:?}");
    }
}

#[test]
fn the_line_is_unchanged() {
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    for &method in methods::ALL {
        let nets = method.uses_networks().then(|| nets.clone());
        let absent = Planner::run(Scene::task1(), method, nets.clone()).unwrap();
        let mut explicit = Scene::task1();
        explicit.path = "line".parse().unwrap();
        let explicit = Planner::run(explicit, method, nets).unwrap();
        assert_eq!(absent, explicit, "{method}");
    }
    // The JSON of a line scene has no `path` field; a circle's has its
    // text, and reads back.
    let json = serde_json::to_value(Scene::task1()).unwrap();
    assert!(json.get("path").is_none(), "{json}");
    let json = serde_json::to_string(&circle_scene(0.0)).unwrap();
    assert!(json.contains(r#""path":"circle:1.2,0.8""#), "{json}");
    let back: Scene = serde_json::from_str(&json).unwrap();
    assert_eq!(back, circle_scene(0.0));
    // A hostile path in a file is an error, not a panic.
    let bad = json.replace("circle:1.2,0.8", "circle:1e999,0");
    let e = serde_json::from_str::<SceneFile>(&bad)
        .unwrap_err()
        .to_string();
    assert!(e.contains("path"), "{e}");
}

#[test]
fn path_blocked_tests_the_disc_against_the_whole_circle() {
    let scene = circle_scene(0.0);
    let start = scene.start();
    let r = dist(start, [1.2, 0.8]);
    // On the far side of the circle, away from the straight line to the
    // target: blocked for the circle, not for the line.
    let far = Obstacle::new(1.2, 0.8 - r, 0.05);
    assert_eq!(unavoidable(&scene, &far), Some(Class::PathBlocked));
    assert_eq!(unavoidable(&Scene::task1(), &far), None);
    // At the centre, farther than the radius from every point: free.
    let centre = Obstacle::new(1.2, 0.8, 0.05);
    assert_eq!(unavoidable(&scene, &centre), None);
    // And a polyline's corner is tested too.
    let mut poly = Scene::task1();
    poly.path = "points:1.2,0.3;0.6,1.0".parse().unwrap();
    let corner = Obstacle::new(1.2, 0.3, 0.05);
    assert_eq!(unavoidable(&poly, &corner), Some(Class::PathBlocked));
    assert_eq!(unavoidable(&Scene::task1(), &corner), None);
}

#[test]
fn a_drawn_stroke_is_thinned_to_points_5_cm_apart_ending_where_it_ended() {
    // A stroke of 1 mm steps along x, 0.333 m long.
    let stroke: Vec<[f64; 2]> = (0..=333).map(|k| [1.0 + k as f64 * 1e-3, 0.5]).collect();
    let Path::Points(p) = Path::drawn(&stroke) else {
        panic!("a polyline")
    };
    // To the millimetre.
    assert_eq!(p[0], stroke[0]);
    assert_eq!(*p.last().unwrap(), [1.333, 0.5]);
    for w in p.windows(2).take(p.len() - 2) {
        assert!(dist(w[0], w[1]) >= DRAWN_SPACING - 1e-12, "{w:?}");
    }
    assert_eq!(p.len(), 7, "{p:?}");
    // A long scribble keeps at most MAX_POINTS, its end the stroke's.
    let long: Vec<[f64; 2]> = (0..5000)
        .map(|k| {
            let a = k as f64 * 0.01;
            [1.0 + 0.4 * a.cos(), 1.0 + 0.4 * a.sin()]
        })
        .collect();
    let Path::Points(p) = Path::drawn(&long) else {
        panic!("a polyline")
    };
    assert!(
        p.len() <= MAX_POINTS && p.len() > MAX_POINTS / 2,
        "{}",
        p.len()
    );
    assert!(dist(*p.last().unwrap(), *long.last().unwrap()) < 1e-3);
    // Nothing drawn: no points, which the scene refuses.
    let mut s = Scene::task1();
    s.path = Path::drawn(&[]);
    assert!(s
        .validate()
        .unwrap_err()
        .to_string()
        .contains("1 to 64 points"));
}

#[test]
fn a_hostile_stroke_ends_and_is_refused() {
    let mut s = Scene::task1();
    s.path = Path::drawn(&vec![[f64::INFINITY, 0.0]; 100]);
    assert!(s.validate().is_err());
    s.path = Path::drawn(&vec![[f64::NAN, 1.0]; 100]);
    assert!(s.validate().is_err());
}

#[test]
fn the_session_takes_a_path_and_a_new_target_makes_it_the_line_again() {
    use redundant_ik::session::Session;
    let mut s = Session::new(1).unwrap();
    assert_eq!(s.state().path, None, "the line: no path in the state");
    s.set_path(CIRCLE.parse().unwrap()).unwrap();
    assert_eq!(s.state().path.as_deref(), Some(CIRCLE));
    // Refused, changing nothing: the centre at the hand's start.
    let start = s.planner().scene().start();
    let before = s.planner().scene().clone();
    let refused = Path::Circle {
        centre: start,
        laps: 1,
    };
    assert!(s.set_path(refused).is_err());
    assert_eq!(*s.planner().scene(), before);
    // The stage's outline of the circle: closed, on the circle.
    let outline = s.planner().outline();
    assert_eq!(outline.first(), outline.last());
    let r = dist(start, [1.2, 0.8]);
    assert!(outline
        .iter()
        .all(|&p| (dist(p, [1.2, 0.8]) - r).abs() < 1e-12));
    // A new target: a new line from the hand.
    s.set_target([0.9, 0.3], None).unwrap();
    assert!(s.planner().scene().path.is_line());
    assert_eq!(s.state().path, None);
}
