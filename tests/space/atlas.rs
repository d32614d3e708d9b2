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
