//! The URDF reader as a specification: a hand-written arm with a
//! prismatic joint, fixed joints, non-zero `rpy`, a tilted axis, a
//! continuous joint, every kind of collision geometry and a side branch
//! reads into the chain from its root to its tool, each joint's frame the
//! fixed joints folded in, each link's volume made as the module says; and
//! every hostile file is refused with its reason, never a panic.

use redundant_ik::urdf::volume::{self, capsule_around, Source};
use redundant_ik::urdf::{Frame, JointKind, Urdf, UrdfChain, MAX_CHAIN_JOINTS};

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/urdf");

fn slider() -> Urdf {
    Urdf::parse(&std::fs::read_to_string(format!("{DIR}/slider_arm.urdf")).unwrap()).unwrap()
}

/// The test meshes, by their URDF names.
fn meshes(name: &str) -> Option<Vec<u8>> {
    let rest = name.strip_prefix("package://slider_arm/").unwrap_or(name);
    std::fs::read(format!("{DIR}/{rest}")).ok()
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

#[test]
fn the_chain_runs_from_the_root_to_the_tip_with_the_fixed_joints_folded_in() {
    let urdf = slider();
    assert_eq!(urdf.name, "slider_arm");
    let e = UrdfChain::new(&urdf, None, None).unwrap_err().to_string();
    assert!(
        e.contains("'tool'") && e.contains("'camera'") && e.contains("--tip"),
        "{e}"
    );
    let chain = UrdfChain::new(&urdf, None, Some("tool")).unwrap();
    assert_eq!((chain.base.as_str(), chain.tip.as_str()), ("world", "tool"));
    let names: Vec<&str> = chain.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["lift", "shoulder", "elbow", "wrist"]);
    let kinds: Vec<JointKind> = chain.joints.iter().map(|j| j.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKind::Prismatic,
            JointKind::Revolute,
            JointKind::Revolute,
            JointKind::Revolute
        ]
    );
    // The mount (0.1, -0.2, 0.05), turned 0.5 rad about z, then 0.2 m up.
    let lift = &chain.joints[0];
    let mount = Frame::from_xyz_rpy([0.1, -0.2, 0.05], [0.0, 0.0, 0.5]);
    assert_eq!(
        lift.origin,
        mount.then(&Frame::translation([0.0, 0.0, 0.2]))
    );
    assert!(close(lift.origin.translation, [0.1, -0.2, 0.25], 1e-15));
    // The axis is made a unit one; the limits and rate read.
    assert_eq!(lift.axis, [0.0, 0.0, 1.0]);
    assert_eq!((lift.limits, lift.velocity), (Some([0.0, 0.4]), Some(0.25)));
    // The elbow's frame: the plate's (0.4 m along x, turned 0.3 rad), then
    // 0.05 m along the plate's x.
    let elbow = &chain.joints[2];
    let (s, c) = 0.3f64.sin_cos();
    assert!(close(
        elbow.origin.translation,
        [0.4 + 0.05 * c, 0.05 * s, 0.0],
        1e-15
    ));
    assert!(close(elbow.axis, [0.0, 0.6, 0.8], 1e-15));
    // A continuous joint has no limits; this one no rate either.
    assert_eq!(
        (chain.joints[3].limits, chain.joints[3].velocity),
        (None, None)
    );
    assert_eq!(chain.tip_frame, Frame::translation([0.0, 0.0, 0.12]));
    // The links the chain carries (the camera's branch left out), each
    // with the joint that moves it.
    let links: Vec<(&str, usize)> = chain
        .links
        .iter()
        .map(|l| (l.name.as_str(), l.moved_by))
        .collect();
    assert_eq!(
        links,
        [
            ("world", 0),
            ("base", 0),
            ("carriage", 1),
            ("upper_arm", 2),
            ("elbow_housing", 2),
            ("forearm", 3),
            ("hand", 4),
            ("tool", 4)
        ]
    );
    // From another base: the carriage (the lift is then not in the chain).
    let upper = UrdfChain::new(&urdf, Some("carriage"), Some("tool")).unwrap();
    assert_eq!(upper.dof(), 3);
    let e = UrdfChain::new(&urdf, Some("hand"), Some("base")).unwrap_err();
    assert!(e.to_string().contains("not below"), "{e}");
}

#[test]
fn each_links_volume_is_made_from_its_collision_geometry_and_says_how() {
    let urdf = slider();
    let chain = UrdfChain::new(&urdf, None, Some("tool")).unwrap();
    let (v, warnings) = volume::volumes(&urdf, &chain, &meshes, 0.04);
    let by = |link: &str| v.iter().find(|x| x.link == link).unwrap();
    // The world has no geometry: the segment to the lift, with a warning.
    let world = by("world");
    assert_eq!(world.source, Source::Segment);
    assert_eq!(
        (world.a, world.b, world.radius),
        ([0.0; 3], chain.joints[0].origin.translation, 0.04)
    );
    // The box 0.3 x 0.2 x 0.2: the capsule on its long side (x), of the
    // radius of half the other two sides' diagonal, in the base's frame.
    let base = by("base");
    assert_eq!(base.source, Source::Box);
    assert!((base.radius - 0.5 * 0.2f64.hypot(0.2)).abs() < 1e-15);
    let mount = Frame::from_xyz_rpy([0.1, -0.2, 0.05], [0.0, 0.0, 0.5]);
    assert!(close(base.a, mount.apply([-0.15, 0.0, 0.1]), 1e-15));
    assert!(close(base.b, mount.apply([0.15, 0.0, 0.1]), 1e-15));
    // The sphere; the cylinder turned onto x, 0.4 m long from the shoulder.
    let carriage = by("carriage");
    assert_eq!(
        (
            carriage.source.clone(),
            carriage.a,
            carriage.b,
            carriage.radius
        ),
        (Source::Sphere, [0.0; 3], [0.0; 3], 0.08)
    );
    let upper = by("upper_arm");
    assert_eq!(
        (upper.source.clone(), upper.radius, upper.moved_by),
        (Source::Cylinder, 0.05, 2)
    );
    assert!(close(upper.a, [0.0; 3], 1e-15) && close(upper.b, [0.4, 0.0, 0.0], 1e-15));
    // The forearm's STL box, x in [-0.15, 0.15], y and z in [-0.03, 0.03],
    // placed 0.15 m along x: the capsule on x of radius 0.03 sqrt 2, every
    // corner on its surface.
    let forearm = by("forearm");
    assert_eq!(
        forearm.source,
        Source::Mesh("package://slider_arm/meshes/forearm.stl".into())
    );
    assert!((forearm.radius - 0.03 * 2f64.sqrt()).abs() < 1e-9);
    assert!(close(forearm.a, [0.0; 3], 1e-9) && close(forearm.b, [0.3, 0.0, 0.0], 1e-9));
    // The hand's mesh is missing: a warning names it, and the segment to
    // the tip stands in; the elbow housing has no geometry of its own.
    let hand = by("hand");
    assert_eq!(
        (hand.source.clone(), hand.a, hand.b),
        (Source::Segment, [0.0; 3], [0.0, 0.0, 0.12])
    );
    assert_eq!(by("elbow_housing").source, Source::Segment);
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("'hand'") && w.contains("missing.stl")),
        "{warnings:?}"
    );
    assert!(warnings
        .iter()
        .any(|w| w.contains("'world'") && w.contains("no collision")));
    // The tool's segment would have no length: no volume, no warning.
    assert!(v.iter().all(|x| x.link != "tool"));
    assert!(warnings.iter().all(|w| !w.contains("'tool'")));
}

#[test]
fn a_capsule_fitted_around_points_holds_every_point_and_is_near_the_tightest() {
    // Points on a tilted cylinder of radius 0.1, 1 m long, one turn of a
    // helix: their principal axis is not quite the cylinder's (the turn
    // does not average out), so the fitted radius is a few per cent more
    // than the cylinder's, never less.
    let axis = [0.6, 0.0, 0.8];
    let mut points = Vec::new();
    for k in 0..40 {
        let t = -0.5 + k as f64 / 39.0;
        let a = k as f64 * 0.7;
        let (s, c) = a.sin_cos();
        // Two directions across the axis.
        let u = [0.8 * c, s, -0.6 * c];
        points.push(std::array::from_fn(|i| 0.3 + t * axis[i] + 0.1 * u[i]));
    }
    let (a, b, r) = capsule_around(&points);
    assert!((0.1..0.11).contains(&r), "{r}");
    let dist = |p: &[f64; 3]| {
        let d: [f64; 3] = std::array::from_fn(|i| b[i] - a[i]);
        let len2: f64 = d.iter().map(|x| x * x).sum();
        let t = ((0..3).map(|i| (p[i] - a[i]) * d[i]).sum::<f64>() / len2).clamp(0.0, 1.0);
        (0..3)
            .map(|i| (p[i] - a[i] - t * d[i]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    assert!(points.iter().all(|p| dist(p) <= r + 1e-12));
    let length = (0..3).map(|i| (b[i] - a[i]).powi(2)).sum::<f64>().sqrt();
    assert!(length <= 1.0 + 1e-9 && length > 0.9, "{length}");
}

/// The reader's refusal of `text`.
fn refused(text: &str) -> String {
    match Urdf::parse(text) {
        Err(e) => e.to_string(),
        Ok(urdf) => UrdfChain::new(&urdf, None, None)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_else(|| panic!("read: {text}")),
    }
}

/// A robot of `joints` (their XML) between the links `a` to `e`.
fn robot(joints: &str) -> String {
    format!(
        "<robot name='r'><link name='a'/><link name='b'/><link name='c'/><link name='d'/><link name='e'/>{joints}</robot>"
    )
}

fn joint(name: &str, kind: &str, parent: &str, child: &str, extra: &str) -> String {
    format!("<joint name='{name}' type='{kind}'><parent link='{parent}'/><child link='{child}'/>{extra}</joint>")
}

#[test]
fn hostile_and_broken_files_are_refused_with_their_reason() {
    let chain = [
        joint("j1", "continuous", "a", "b", ""),
        joint("j2", "continuous", "b", "c", ""),
        joint("j3", "continuous", "c", "d", ""),
        joint("j4", "continuous", "d", "e", ""),
    ]
    .concat();
    assert!(Urdf::parse(&robot(&chain)).is_ok());
    let cases: Vec<(String, &str)> = vec![
        ("<robot name='r'><link name='a'></robot>".into(), "not well-formed XML"),
        ("<robot name='r'>\n<link name='a'>\n</robot>".into(), "3:"),
        (
            "<?xml version='1.0'?><!DOCTYPE r [<!ENTITY x 'y'>]><robot name='r'><link name='&x;'/></robot>".into(),
            "document type declaration",
        ),
        (
            "<robot name='r' xmlns:xacro='http://www.ros.org/wiki/xacro'><xacro:property name='l' value='1'/><link name='a'/></robot>".into(),
            "xacro",
        ),
        ("<robot name='r'><link name='${name}'/></robot>".into(), "xacro"),
        ("<rob name='r'><link name='a'/></rob>".into(), "<robot>"),
        ("<robot name='r'/>".into(), "no <link>"),
        ("<robot><link name='a'/><link name='a'/></robot>".into(), "two links"),
        (robot(&[joint("j", "revolute", "a", "b", ""), joint("j", "revolute", "b", "c", "")].concat()), "two joints"),
        (robot(&joint("j", "floating", "a", "b", "")), "floating"),
        (robot(&joint("j", "planar", "a", "b", "")), "planar"),
        (robot(&joint("j", "hinge", "a", "b", "")), "not a URDF joint type"),
        (robot(&joint("j", "revolute", "a", "b", "<mimic joint='k'/>")), "mimic"),
        (robot(&joint("j", "revolute", "a", "b", "<axis xyz='0 0 0'/>")), "axis is zero"),
        (robot(&joint("j", "revolute", "a", "b", "<axis xyz='0 nan 1'/>")), "not a finite number"),
        (robot(&joint("j", "revolute", "a", "b", "<origin xyz='0 0 inf'/>")), "not a finite number"),
        (robot(&joint("j", "revolute", "a", "b", "<origin xyz='0 0'/>")), "3 numbers"),
        (robot(&joint("j", "revolute", "a", "b", "<limit lower='1' upper='-1'/>")), "above its upper"),
        (robot(&joint("j", "revolute", "a", "b", "<limit lower='x' upper='1'/>")), "not a number"),
        (robot(&joint("j", "revolute", "a", "z", "")), "does not have"),
        (robot(&joint("j", "revolute", "a", "a", "")), "to itself"),
        (robot(&[joint("j1", "revolute", "a", "b", ""), joint("j2", "revolute", "c", "b", "")].concat()), "two parents"),
        (
            robot(&[
                joint("j1", "revolute", "a", "b", ""),
                joint("j2", "revolute", "b", "c", ""),
                joint("j3", "revolute", "c", "d", ""),
                joint("j4", "revolute", "d", "e", ""),
                joint("j5", "revolute", "e", "a", ""),
            ].concat()),
            "loop",
        ),
        (robot(&joint("j", "revolute", "a", "b", "")), "have no parent"),
        (robot(&[joint("j1", "fixed", "a", "b", ""), joint("j2", "fixed", "b", "c", ""), joint("j3", "fixed", "c", "d", ""), joint("j4", "fixed", "d", "e", "")].concat()), "no joint moves"),
        (
            "<robot><link name='a'><collision><geometry><sphere radius='-1'/></geometry></collision></link></robot>".into(),
            "must be positive",
        ),
        (
            "<robot><link name='a'><collision><geometry><cone radius='1'/></geometry></collision></link></robot>".into(),
            "not a URDF geometry",
        ),
        (
            "<robot><link name='a'><collision><geometry/></collision></link></robot>".into(),
            "is empty",
        ),
    ];
    for (text, says) in cases {
        let e = refused(&text);
        assert!(e.contains(says), "'{says}' not in: {e}\n{text}");
        assert!(e.starts_with("URDF: "), "{e}");
    }
    // A tip or base that is not there.
    let urdf = Urdf::parse(&robot(&chain)).unwrap();
    assert!(UrdfChain::new(&urdf, None, Some("z"))
        .unwrap_err()
        .to_string()
        .contains("no link 'z'"));
    assert!(UrdfChain::new(&urdf, Some("z"), None)
        .unwrap_err()
        .to_string()
        .contains("--base"));
    // More than the most joints a chain may have.
    let n = MAX_CHAIN_JOINTS + 1;
    let links: String = (0..=n).map(|k| format!("<link name='l{k}'/>")).collect();
    let joints: String = (0..n)
        .map(|k| {
            joint(
                &format!("j{k}"),
                "continuous",
                &format!("l{k}"),
                &format!("l{}", k + 1),
                "",
            )
        })
        .collect();
    let e = refused(&format!("<robot>{links}{joints}</robot>"));
    assert!(e.contains(&format!("more than {MAX_CHAIN_JOINTS}")), "{e}");
    // A file over the size a URDF may have.
    let big = format!(
        "<robot><link name='a'/>{}</robot>",
        " ".repeat(redundant_ik::urdf::MAX_URDF_BYTES)
    );
    assert!(refused(&big).contains("bytes"));
}

/// Random joint values within `chain`'s limits (seeded).
fn within(chain: &redundant_ik::space::Chain, seed: &mut u64) -> Vec<f64> {
    let ranges = chain.joint_limits().unwrap().ranges().to_vec();
    ranges
        .iter()
        .map(|[lo, hi]| {
            *seed ^= *seed << 13;
            *seed ^= *seed >> 7;
            *seed ^= *seed << 17;
            lo + (hi - lo) * ((*seed >> 11) as f64 / (1u64 << 53) as f64)
        })
        .collect()
}

/// The arms in space written as URDF read back to the same chain: every
/// joint's origin and axis, the flange and every capsule at random poses
/// within the limits to 1e-12 m, and the same limits; and the shipped
/// `robots/*.urdf` are what the presets write now.
#[test]
fn the_arms_in_space_written_as_urdf_read_back_to_the_same_chain() {
    use redundant_ik::space::{SpacePose, PRESETS};
    for p in &PRESETS {
        let chain = p.chain();
        let text = redundant_ik::urdf::chain_urdf(p.key, "test", &chain);
        let urdf = Urdf::parse(&text).unwrap();
        let uc = UrdfChain::new(&urdf, None, None).unwrap();
        assert_eq!(
            (uc.base.as_str(), uc.tip.as_str(), uc.dof()),
            ("base_link", "flange", chain.dof())
        );
        let limits: Vec<[f64; 2]> = uc.joints.iter().map(|j| j.limits.unwrap()).collect();
        assert_eq!(limits, chain.joint_limits().unwrap().ranges(), "{}", p.key);
        let rates: Vec<f64> = uc.joints.iter().map(|j| j.velocity.unwrap()).collect();
        assert_eq!(rates, chain.rate_limits().unwrap().rates(), "{}", p.key);
        let (volumes, warnings) = volume::volumes(&urdf, &uc, &|_| None, 0.05);
        assert!(
            volumes.iter().all(|v| v.source == Source::Cylinder),
            "{}",
            p.key
        );
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut worst: f64 = 0.0;
        for _ in 0..50 {
            let q = within(&chain, &mut seed);
            let frames = uc.frames(&q).unwrap();
            let pose = SpacePose::new(&chain, &q).unwrap();
            let mut err = |a: [f64; 3], b: [f64; 3]| {
                worst = worst.max((0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max));
            };
            for (i, f) in frames[..chain.dof()].iter().enumerate() {
                err(f.translation, pose.joint_origin(i));
                err(f.rotate([0.0, 0.0, 1.0]), pose.axis(i));
            }
            err(frames[chain.dof()].translation, pose.hand());
            // The capsules, in the world, against the chain's own segments.
            let world = |v: &volume::Volume, x: [f64; 3]| {
                if v.moved_by == 0 {
                    x
                } else {
                    frames[v.moved_by - 1].apply(x)
                }
            };
            assert_eq!(volumes.len(), chain.segments().len(), "{}", p.key);
            for (v, s) in volumes.iter().zip(chain.segments()) {
                let (a, b) = pose.segment(s);
                err(world(v, v.a), a);
                err(world(v, v.b), b);
                assert_eq!(v.radius, chain.radius());
                assert_eq!(v.moved_by, s.moved_by);
            }
        }
        assert!(worst < 1e-12, "{}: {worst:e}", p.key);
        assert!(warnings.is_empty(), "{}: {warnings:?}", p.key);
        // The shipped file is what the preset writes now.
        let shipped = std::fs::read_to_string(format!(
            "{}/robots/{}.urdf",
            env!("CARGO_MANIFEST_DIR"),
            p.key
        ))
        .unwrap();
        let comment_free = |t: &str| {
            t.lines()
                .filter(|l| !l.starts_with("<!--"))
                .collect::<Vec<_>>()
                .join("\n")
        };
        assert_eq!(
            comment_free(&shipped),
            comment_free(&text),
            "robots/{}.urdf: run redundant-ik robot --urdf-of {} > robots/{}.urdf",
            p.key,
            p.key,
            p.key
        );
    }
}

/// Every shipped URDF (and the hand-written arm, with its prismatic joint,
/// fixed joints, tilted axis and continuous wrist) against an independent
/// implementation: Pinocchio's frames of every moving joint and of the
/// tip at 10 random poses each, recorded by
/// `scripts/check-urdf-pinocchio.py` in `tests/data/urdf/pinocchio.json`,
/// agree with the reader's chain to 1e-9 m and 1e-9.
#[test]
fn every_shipped_urdf_has_pinocchios_frames() {
    let text = std::fs::read_to_string(format!("{DIR}/pinocchio.json")).unwrap();
    let data: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut files = 0;
    let mut worst: f64 = 0.0;
    for f in data["files"].as_array().unwrap() {
        let path = format!(
            "{}/{}",
            env!("CARGO_MANIFEST_DIR"),
            f["file"].as_str().unwrap()
        );
        let urdf = Urdf::parse(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let chain = UrdfChain::new(&urdf, None, f["tip"].as_str()).unwrap();
        for run in f["runs"].as_array().unwrap() {
            let q: Vec<f64> = serde_json::from_value(run["q"].clone()).unwrap();
            let frames = chain.frames(&q).unwrap();
            let theirs = run["joints"]
                .as_array()
                .unwrap()
                .iter()
                .chain(std::iter::once(&run["tip"]));
            for (ours, theirs) in frames.iter().zip(theirs) {
                let t: [f64; 3] = serde_json::from_value(theirs["translation"].clone()).unwrap();
                let r: [[f64; 3]; 3] = serde_json::from_value(theirs["rotation"].clone()).unwrap();
                let ours_all = ours
                    .translation
                    .iter()
                    .chain(ours.rotation.iter().flatten());
                let theirs_all = t.iter().chain(r.iter().flatten());
                for (a, b) in ours_all.zip(theirs_all) {
                    worst = worst.max((a - b).abs());
                }
            }
            assert_eq!(frames.len(), chain.dof() + 1);
        }
        files += 1;
    }
    assert_eq!(
        files, 4,
        "the three shipped robots and the hand-written arm"
    );
    assert!(worst < 1e-9, "{worst:e}");
}
