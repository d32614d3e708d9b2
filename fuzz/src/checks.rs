//! What every target checks, and the shipped networks they share.

use std::sync::{Arc, OnceLock};

use redundant_ik::planner::{Method, Planner, Surrogate};
use redundant_ik::{Networks, Scene};

/// The shipped networks, parsed once per process.
pub fn shipped() -> &'static Networks {
    static NETS: OnceLock<Networks> = OnceLock::new();
    NETS.get_or_init(|| Networks::embedded().expect("the shipped networks load"))
}

pub fn shipped_surrogate() -> Arc<dyn Surrogate> {
    static NETS: OnceLock<Arc<Networks>> = OnceLock::new();
    NETS.get_or_init(|| Arc::new(shipped().clone())).clone()
}

pub fn assert_finite(what: &str, xs: &[f64]) {
    assert!(
        xs.iter().all(|x| x.is_finite()),
        "non-finite {what} accepted: {xs:?}"
    );
}

/// What a planner's state is, for checking that a refusal changed nothing
/// and that nothing non-finite got in.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    scene: Scene,
    method: Method,
    time: f64,
    theta: Vec<f64>,
    ee: [f64; 2],
}

impl Snapshot {
    pub fn of(p: &Planner) -> Self {
        Self {
            scene: p.scene().clone(),
            method: p.method(),
            time: p.time(),
            theta: p.theta().as_slice().to_vec(),
            ee: p.sample().ee,
        }
    }

    pub fn assert_finite(&self) {
        assert_finite("joint angle", &self.theta);
        assert_finite("time", &[self.time]);
        assert_finite("end effector", &self.ee);
    }
}

/// Up to `steps` RK4 steps: each one that goes through leaves a finite
/// state, and the first that fails leaves the state as it was.
pub fn step_checked(p: &mut Planner, steps: usize) {
    for _ in 0..steps {
        let before = Snapshot::of(p);
        if p.step().is_err() {
            assert_eq!(Snapshot::of(p), before, "a failed step changed the state");
            return;
        }
        Snapshot::of(p).assert_finite();
    }
}
