use redundant_ik::*;
fn main() {
    for (task, sc) in [(1, Scene::task1()), (2, Scene::task2())] {
        for mode in [Mode::None, Mode::Numerical] {
            let tr = Planner::run(sc.clone(), mode, None).unwrap();
            let s = &tr.summary;
            println!(
                "task{task} {mode}: min {:?} coll {} final {:e} maxtrack {:e}",
                s.min_distance, s.collided, s.final_error, s.max_tracking_error
            );
        }
    }
}
