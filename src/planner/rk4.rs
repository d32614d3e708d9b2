//! The classical RK4 step of the paper's section V (step e) over the joint
//! angles, for every arm: the planner (`integrate.rs`) hands over how a
//! stage's joint rates are computed (its pose, its rule, its task
//! velocity); the stages' angles and the combination are written once, in
//! one order of operations, and self-motion's small steps are its own.

use super::methods::Note;
use crate::error::{Error, Result};

/// Where a stage reads its joint rates.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Stage<'a> {
    /// The first stage: the current angles at the step's start `t`, whose
    /// kinematics the planner already holds (computed when the previous
    /// step ended).
    Start {
        /// The step's start time.
        t: f64,
    },
    /// A later stage: `theta` at time `t`; `last` for the fourth.
    At {
        /// The stage's angles.
        theta: &'a [f64],
        /// The stage's time.
        t: f64,
        /// Whether this is the fourth stage (a polyline's corner takes the
        /// segment before it there).
        last: bool,
    },
}

/// An RK4 step's scratch space for an `n`-joint arm: the stage rates
/// `k1..k4`, a stage's angles and the state after the step.
#[derive(Debug, Clone)]
pub(crate) struct Rk4 {
    k: [Vec<f64>; 4],
    theta_stage: Vec<f64>,
    next: Vec<f64>,
}

impl Rk4 {
    /// Room for `n` joints.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            k: [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            theta_stage: vec![0.0; n],
            next: vec![0.0; n],
        }
    }

    /// One step of size `h` from `theta` at time `t`: `rates(stage, out)`
    /// writes a stage's joint rates into `out` and says what happened (a
    /// relaxed program, the exact `Phi` standing in). Returns the angles
    /// after the step and the stages' notes merged; refuses a step to an
    /// angle beyond [`crate::arm::MAX_ANGLE`] or not finite
    /// ([`Error::Diverged`]). Allocation-free.
    pub(crate) fn step(
        &mut self,
        theta: &[f64],
        t: f64,
        h: f64,
        mut rates: impl FnMut(Stage<'_>, &mut [f64]) -> Result<Note>,
    ) -> Result<(&[f64], Note)> {
        let Self {
            k,
            theta_stage,
            next,
        } = self;
        let [k1, k2, k3, k4] = k;
        let mut note = rates(Stage::Start { t }, k1)?;
        for (stage, (c, tt)) in [(0.5 * h, t + 0.5 * h), (0.5 * h, t + 0.5 * h), (h, t + h)]
            .into_iter()
            .enumerate()
        {
            let (prev, out): (&[f64], &mut [f64]) = match stage {
                0 => (&k1[..], &mut k2[..]),
                1 => (&k2[..], &mut k3[..]),
                _ => (&k3[..], &mut k4[..]),
            };
            for ((s, th), k) in theta_stage.iter_mut().zip(theta).zip(prev) {
                *s = th + c * k;
            }
            let at = Stage::At {
                theta: &theta_stage[..],
                t: tt,
                last: stage == 2,
            };
            let stage_note = rates(at, out)?;
            note.handover |= stage_note.handover;
            note.relaxed |= stage_note.relaxed;
        }
        let w = h / 6.0;
        let mut finite = true;
        for (i, nx) in next.iter_mut().enumerate() {
            *nx = theta[i] + w * (((k1[i] + 2.0 * k2[i]) + 2.0 * k3[i]) + k4[i]);
            // Also false for NaN: a runaway angle is refused like a non-finite one.
            finite &= nx.abs() <= crate::arm::MAX_ANGLE;
        }
        if !finite {
            return Err(Error::Diverged { t });
        }
        Ok((next, note))
    }
}
