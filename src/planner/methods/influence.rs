//! The two distances the methods beyond the paper share (`distance`,
//! `priority`, `qp`): link-obstacle pairs closer than the influence
//! distance `d_i` count ([`crate::clearance::Pairs`]), and the stop
//! distance `d_s` is the clearance they keep (NEO's and mink's orders of
//! magnitude, scaled to this arm; `docs/methods.md`).

use crate::scene::{Param, Scale};

/// Influence distance `d_i` (m): pairs closer than this count. At most
/// 100 m, beyond any arm's reach.
pub static INFLUENCE: Param = Param {
    name: "influence",
    flag: "--influence",
    label: "Influence distance dᵢ",
    what: "influence distance d_i",
    #[cfg(feature = "cli")]
    help: "Influence distance d_i of distance, priority and qp: link-obstacle pairs closer than this count",
    unit: "m",
    bounds: (1e-3, 100.0),
    default: 0.3,
    slider: (0.05, 0.8, 0.01),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: Some(&STOP_DISTANCE),
};

/// Stop distance `d_s` (m) of the velocity dampers (`qp`) and of the
/// escape speed (`priority`), and the floor of the clearance in the
/// potential (`distance`): the clearance they keep. Below `d_i`.
pub static STOP_DISTANCE: Param = Param {
    name: "stop_distance",
    flag: "--stop-distance",
    label: "Stop distance dₛ",
    what: "stop distance d_s",
    #[cfg(feature = "cli")]
    help: "Stop distance d_s of the velocity dampers (qp) and of the escape speed (priority); floors the clearance of distance",
    unit: "m",
    bounds: (0.0, 100.0),
    default: 0.02,
    slider: (0.0, 0.2, 0.005),
    scale: Scale::Linear,
    count: false,
    below: Some(&INFLUENCE),
    above: None,
};
