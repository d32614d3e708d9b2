//! Revision numbers of what a session's results depend on, so that the
//! page tells a stale atlas or comparison by a number and not by a list of
//! fields it must keep in step with the core (that list forgot every
//! obstacle after the first). Each counter goes up when what it covers
//! changes, found by comparing with what was seen last (not by each setter
//! remembering to count: a setter added later is covered).

use std::cell::RefCell;

use serde::Serialize;

use crate::planner::Method;
use crate::scene::Scene;

/// The revisions of a state: each changes with everything its results
/// depend on.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Revision {
    /// The run: the task, the method, the scene and the networks.
    pub run: u64,
    /// A comparison of every method: the run's, but for the method.
    pub scene: u64,
    /// An atlas: the comparison's, but for the first obstacle's centre
    /// (which the atlas moves over its grid; choosing a cell moves it).
    pub atlas: u64,
}

#[derive(Clone)]
struct Seen {
    task: u32,
    method: Method,
    scene: Scene,
    networks: u64,
}

/// What was seen last and the counters.
#[derive(Default)]
pub(super) struct Revisions(RefCell<(Option<Seen>, Revision)>);

impl Clone for Revisions {
    fn clone(&self) -> Self {
        Revisions(RefCell::new(self.0.borrow().clone()))
    }
}

/// Whether two scenes differ in anything but the first obstacle's centre.
/// Every field is named, so a field added to [`Scene`] must be placed here.
fn differ_for_atlas(a: &Scene, b: &Scene) -> bool {
    let Scene {
        arm,
        theta0,
        target,
        path,
        obstacles,
        damping,
        dt,
        tf,
        feedback_gain,
        params,
        weighting,
        floor,
    } = a;
    let radii_or_rest = obstacles.len() != b.obstacles.len()
        || obstacles
            .iter()
            .zip(&b.obstacles)
            .enumerate()
            .any(|(k, (p, q))| p.radius != q.radius || (k > 0 && p.centre != q.centre));
    radii_or_rest
        || *arm != b.arm
        || *theta0 != b.theta0
        || *target != b.target
        || *path != b.path
        || *damping != b.damping
        || *dt != b.dt
        || *tf != b.tf
        || *feedback_gain != b.feedback_gain
        || *params != b.params
        || *weighting != b.weighting
        || *floor != b.floor
}

impl Revisions {
    /// The revisions for what is current, counting what changed since the
    /// last call.
    pub(super) fn observe(
        &self,
        task: u32,
        method: Method,
        scene: &Scene,
        networks: u64,
    ) -> Revision {
        let mut cell = self.0.borrow_mut();
        let (seen, rev) = &mut *cell;
        match seen {
            Some(s)
                if s.task == task
                    && s.method == method
                    && s.scene == *scene
                    && s.networks == networks => {}
            Some(s) => {
                rev.run += 1;
                let same_but_method = s.task == task && s.networks == networks;
                if !same_but_method || s.scene != *scene {
                    rev.scene += 1;
                }
                if !same_but_method || differ_for_atlas(&s.scene, scene) {
                    rev.atlas += 1;
                }
                *s = Seen {
                    task,
                    method,
                    scene: scene.clone(),
                    networks,
                };
            }
            None => {
                *seen = Some(Seen {
                    task,
                    method,
                    scene: scene.clone(),
                    networks,
                })
            }
        }
        *rev
    }
}
