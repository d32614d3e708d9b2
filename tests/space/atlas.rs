//! The slice atlas of an arm in space: each cell is the run it says, the
//! plane is read as written, a plane that misses the arm is refused.

use redundant_ik::atlas::space::{default_region, slice, Plane};
use redundant_ik::atlas::{Class, Grid};
use redundant_ik::planner::{Networks, Planner};
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::Sphere;
use redundant_ik::{Error, Method};

#[test]
fn every_cell_is_the_run_of_its_sphere() {
    let scene = SpaceScene::by_key("panda").unwrap();
    let plane = Plane::through_line(&scene);
    let grid = Grid::new(default_region(&scene, plane), 7).unwrap();
    let methods = [Method::NO_AVOIDANCE, Method::NUMERICAL, Method::CASE3];
    let nets = redundant_ik::networks::space::SpaceNetworkSet::PandaReach
        .load()
        .unwrap();
    let a = slice(&scene, plane, grid, &methods, Some(&nets)).unwrap();
    assert_eq!(a.cells.len(), 49);
    let mut run = 0;
    for c in &a.cells {
        for (k, m) in methods.iter().enumerate() {
            let o = &a
                .cells
                .iter()
                .find(|d| d.centre == c.centre)
                .unwrap()
                .outcomes[k];
            if o.class == Class::StartOverlap {
                continue;
            }
            let mut s = scene.clone();
            s.obstacles = vec![Sphere::new(c.centre, a.radius)];
            let direct = Planner::new(s, *m, Some(nets.clone() as Networks<_, 3>))
                .and_then(Planner::run_to_end)
                .unwrap();
            assert_eq!(o.min_clearance, direct.summary.min_clearance);
            assert_eq!(o.final_error, Some(direct.summary.final_error));
            let hit = direct.summary.collision_steps > 0;
            assert!(
                o.class == Class::PathBlocked || (o.class == Class::Collision) == hit,
                "{:?} {m}: {:?}",
                c.centre,
                o.class
            );
            run += 1;
        }
    }
    assert!(run > 60, "most cells run");
    // The task's own sphere lies near the slice's cells that collide without avoidance.
    assert!(a.count(0, Class::Collision) > 0 && a.count(0, Class::StartOverlap) > 0);
}

#[test]
fn a_slice_is_read_as_written_and_one_that_misses_the_arm_is_refused() {
    assert_eq!("xz:0.1".parse::<Plane>().unwrap(), Plane::Xz(0.1));
    assert_eq!(" yz : -0.2".parse::<Plane>().unwrap(), Plane::Yz(-0.2));
    assert_eq!(Plane::Xy(0.25).to_string(), "xy:0.25");
    for bad in ["xz", "ab:0.1", "xz:x", "xz:nan", "xz:1e9"] {
        assert!(bad.parse::<Plane>().is_err(), "{bad}");
    }
    let scene = SpaceScene::by_key("iiwa14").unwrap();
    let far = Plane::Yz(5.0);
    let grid = Grid::new(default_region(&scene, far), 5).unwrap();
    let e = slice(&scene, far, grid, &[Method::NUMERICAL], None).unwrap_err();
    assert!(matches!(e, Error::SliceMissesReach { .. }), "{e}");
    let near = Plane::Xz(0.0);
    let grid = Grid::new(default_region(&scene, near), 5).unwrap();
    assert!(matches!(
        slice(&scene, near, grid, &[Method::CASE3], None),
        Err(Error::NetworksUnavailable(_))
    ));
}

/// The maps of a slice atlas (`atlas --out` for an arm in space): one panel
/// per method whose caption is the atlas's own count, the slice's axes, and
/// a legend of the classes this arm can have.
#[test]
fn the_maps_of_a_slice_say_what_its_cells_hold() {
    let scene = SpaceScene::by_key("panda").unwrap();
    let plane = Plane::Xz(0.1);
    let grid = Grid::new(default_region(&scene, plane), 5).unwrap();
    let methods = [
        Method::NO_AVOIDANCE,
        Method::NUMERICAL,
        "qp".parse().unwrap(),
    ];
    let a = slice(&scene, plane, grid, &methods, None).unwrap();
    let svg = redundant_ik::figure::slice_svg(&a, &scene, "Franka Panda", false).unwrap();
    assert!(svg.starts_with("<svg"), "{:.80}", svg);
    assert!(
        svg.contains("Franka Panda: where the arm stays clear, sphere (r = 0.06 m) centred on each of 5 x 5 cells of the slice xz:0.1"),
        "the title: {:.400}",
        svg
    );
    assert!(
        svg.contains("\nsphere x (m)\n") && svg.contains("\nz (m)\n"),
        "the slice's axes"
    );
    let avoidable = a.avoidable();
    for (k, m) in methods.iter().enumerate() {
        let won = a.count(k, Class::Success);
        let caption = format!(
            "{}: {:.0}% clear and reached ({won}/{avoidable})",
            m.label(),
            100.0 * won as f64 / avoidable as f64
        );
        assert!(svg.contains(&caption), "{caption} in the figure");
    }
    // The Panda has joint limits: the legend lists that class; it checks no
    // self-collision, and the legend leaves that one out.
    assert!(svg.contains(Class::Limit.label()));
    assert!(!svg.contains(Class::SelfCollision.label()));
    assert!(svg.contains("own sphere, seen square to the slice"));
    // Every class a cell has is drawn in its colour.
    for c in &a.cells {
        for o in &c.outcomes {
            assert!(
                svg.to_lowercase()
                    .contains(&o.class.colour().to_lowercase()),
                "{:?} drawn",
                o.class
            );
        }
    }

    // An atlas of the hand's pose says so.
    let svg = redundant_ik::figure::slice_svg(&a, &scene, "Franka Panda", true).unwrap();
    assert!(svg.contains("Franka Panda, the hand&apos;s pose: where"));

    // With self-collision checked, the legend lists it.
    let mut checked = scene.clone();
    checked.arm = checked
        .arm
        .clone()
        .with_self_collision(&[], &[&scene.theta0])
        .unwrap();
    let b = slice(&checked, plane, grid, &methods[..1], None).unwrap();
    let svg = redundant_ik::figure::slice_svg(&b, &checked, "Franka Panda", false).unwrap();
    assert!(svg.contains(Class::SelfCollision.label()));
}

/// A slice atlas reads back from its JSON (the page's workers draw its maps
/// from it); a file whose cells do not fit its grid, plane or methods is
/// refused with the reason.
#[test]
fn a_slice_atlas_reads_back_and_a_broken_one_is_refused() {
    use redundant_ik::atlas::space::SliceAtlas;
    let scene = SpaceScene::by_key("iiwa14").unwrap();
    let plane = Plane::through_line(&scene);
    let grid = Grid::new(default_region(&scene, plane), 3).unwrap();
    let mut a = slice(&scene, plane, grid, &[Method::NUMERICAL], None).unwrap();
    a.arm = Some("iiwa14");
    let text = serde_json::to_string(&a).unwrap();
    let back: SliceAtlas = serde_json::from_str(&text).unwrap();
    assert_eq!(back, a);
    let refused = |edit: &dyn Fn(&mut serde_json::Value), why: &str| {
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        edit(&mut v);
        let e = serde_json::from_str::<SliceAtlas>(&v.to_string()).unwrap_err();
        assert!(e.to_string().contains(why), "{e}");
    };
    refused(
        &|v| v["cells"].as_array_mut().unwrap().truncate(8),
        "an atlas of 3 x 3 cells lists 8",
    );
    refused(
        &|v| v["cells"][4]["centre"][2] = 9.0.into(),
        "cell 4 is not at its grid point",
    );
    refused(
        &|v| v["cells"][2]["outcomes"] = serde_json::json!([]),
        "cell 2 has 0 outcomes for 1 methods",
    );
    refused(&|v| v["arm"] = "ur99".into(), "unknown arm in space 'ur99'");
    refused(&|v| v["methods"] = serde_json::json!([]), "names no method");
    refused(&|v| v["grid"]["n"] = 1.into(), "");
}
