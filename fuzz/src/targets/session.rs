//! The `session` target.

use std::sync::Arc;

use arbitrary::Unstructured;
use redundant_ik::session::{Handle, Session};
use redundant_ik::{Arm, Obstacle};

use super::checks::{shipped, Snapshot};
use super::gen::{arm, method, num, num_in, point, small};

/// A session (the page's simulation) driven by up to 32 operations: steps,
/// ticks, targets, obstacles (add, move, remove, replace), every method,
/// every parameter of the methods, `lambda`,
/// damping, feedback, speed, arms, networks, tasks, drags and nudges, with
/// arbitrary numbers. After every operation no angle, time or position is
/// non-finite; an operation refused (other than a step, whose refusal
/// keeps the last good step) leaves the planner as it was; the state the
/// page reads serialises.
pub fn session(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let task = if u.ratio(1u8, 2u8).unwrap_or(true) {
        1
    } else {
        2
    };
    let Ok(mut s) = Session::new(task) else {
        panic!("the paper's task {task} makes a session");
    };
    if u.ratio(3u8, 4u8).unwrap_or(false) {
        s.set_networks(Arc::new(shipped().clone()))
            .expect("the shipped networks fit the paper's arm");
    }
    for _ in 0..32 {
        if u.is_empty() {
            break;
        }
        let before = Snapshot::of(s.planner());
        let op = u.int_in_range(0u8..=25).unwrap_or(0);
        // Operations that step may fail part-way and keep the last good step.
        let steps = matches!(op, 0..=2 | 19 | 20);
        let result = match op {
            0 => s.step(),
            1 => {
                // Bounded, so that one input cannot ask for 100 000 steps.
                let t = num(&mut u);
                let t = if t.is_finite() {
                    s.planner().time() + t.abs().min(0.5)
                } else {
                    t
                };
                s.run_until(t)
            }
            2 => {
                s.set_running(true);
                s.tick(num(&mut u) * 100.0)
            }
            3 => {
                s.set_running(u.arbitrary().unwrap_or(false));
                Ok(())
            }
            4 => {
                let d = u.ratio(1u8, 2u8).unwrap_or(false).then(|| num(&mut u));
                s.set_target(point(&mut u), d)
            }
            5 => s.set_obstacle(point(&mut u)),
            6 => s.move_obstacle(small(&mut u, 9), point(&mut u)),
            7 => s
                .add_obstacle(Obstacle::new(num(&mut u), num(&mut u), num(&mut u)))
                .map(|_| ()),
            8 => s.remove_obstacle(small(&mut u, 9)),
            9 => {
                let obstacles = (0..small(&mut u, 10))
                    .map(|_| Obstacle::new(num(&mut u), num(&mut u), num_in(&mut u, 0.0, 0.3)))
                    .collect();
                s.set_obstacles(obstacles)
            }
            10 => s.set_method(method(&mut u)),
            11 => s.set_lambda(num(&mut u)),
            12 => s.set_damping(u.arbitrary().unwrap_or(false)),
            13 => s.set_feedback(num(&mut u)),
            14 => s.set_speed(num(&mut u)),
            15 => {
                let (post, links) = arm(&mut u);
                match Arm::new(post, links) {
                    Ok(a) => s.set_arm(a),
                    Err(e) => Err(e),
                }
            }
            16 => s.clear_networks(),
            17 => s.set_networks(Arc::new(shipped().clone())),
            18 => s.load_task(u.int_in_range(0u32..=3).unwrap_or(1)),
            19 => {
                s.run_task();
                // A whole task is 100 steps: take a few of them.
                s.tick(100.0)
            }
            20 => {
                s.reset();
                Ok(())
            }
            21 => {
                let handle = match small(&mut u, 3) {
                    0 => None,
                    1 => Some(Handle::Target),
                    _ => Some(Handle::Obstacle(small(&mut u, 9))),
                };
                s.drag_start(handle);
                s.drag_to(point(&mut u))
            }
            22 => s.drag_end(point(&mut u)),
            23 => {
                s.drag_cancel();
                Ok(())
            }
            25 => {
                // Any parameter of any method, to any number.
                let all = redundant_ik::planner::params::all();
                let param = *u.choose(all).unwrap_or(&all[0]);
                s.set_param(param, num(&mut u))
            }
            _ => {
                let handle = if u.arbitrary().unwrap_or(false) {
                    Handle::Target
                } else {
                    Handle::Obstacle(small(&mut u, 9))
                };
                s.nudge(handle, num(&mut u), num(&mut u))
            }
        };
        let after = Snapshot::of(s.planner());
        after.assert_finite();
        if let Some(g) = s.ghost() {
            Snapshot::of(g).assert_finite();
        }
        if result.is_err() && !steps {
            assert_eq!(after, before, "refused operation {op} changed the planner");
        }
        serde_json::to_string(&s.state()).expect("the state serialises");
    }
}
