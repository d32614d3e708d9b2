//! The named arms in space (`--arm panda`, `--arm iiwa14`, the address's
//! `arm=panda`), each with its limits, its capsules and a task in the
//! paper's spirit: a straight line of the hand at constant speed from the
//! ready pose, past a sphere near the forearm that the arm without
//! avoidance hits.

use serde::Serialize;

use super::chain::{Chain, Row};
use super::pose::Vec3;
use crate::arm::{JointLimits, Preset, RateLimits};
use crate::error::{Error, Result};

/// A named arm in space.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpacePreset {
    /// Its name (`--arm panda`).
    pub key: &'static str,
    /// What a menu says.
    pub label: &'static str,
    /// Where its numbers come from, and their licence.
    pub source: &'static str,
    /// The modified DH rows `(a_(i-1), alpha_(i-1), d_i, offset_i)`.
    pub rows: &'static [Row],
    /// The flange in the last frame (m).
    pub flange: Vec3,
    /// The capsules' radius (m).
    pub radius: f64,
    /// Each joint's range `[lo, hi]` (rad).
    pub joint_limits: &'static [[f64; 2]],
    /// Each joint's largest rate (rad/s).
    pub rate_limits: &'static [f64],
    /// Its task.
    pub task: SpaceTask,
}

/// A preset's task: the start pose, the end of the hand's line, a sphere.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpaceTask {
    /// Joint angles at `t = 0` (rad), within the limits.
    pub theta0: &'static [f64],
    /// The end of the line (m).
    pub target: Vec3,
    /// The sphere `[x, y, z, r]` (m).
    pub sphere: [f64; 4],
}

impl SpacePreset {
    /// The chain with its limits.
    pub fn chain(&self) -> Chain {
        Chain::new(self.rows.to_vec(), self.flange, self.radius)
            .and_then(|c| {
                c.with_limits(
                    Some(JointLimits::new(self.joint_limits.to_vec())?),
                    Some(RateLimits::new(self.rate_limits.to_vec())?),
                )
            })
            // Display, not Debug: the page's module carries no Debug of
            // the error (2 KB of code) for a message no user sees.
            .unwrap_or_else(|e| panic!("a preset's numbers pass the chain's checks (tested): {e}"))
    }

    /// The preset whose chain `chain` is, whatever its limits, if any (a
    /// run file carries the chain, not the preset's name).
    pub fn of(chain: &Chain) -> Option<&'static SpacePreset> {
        PRESETS.iter().find(|p| p.chain().same_kinematics(chain))
    }

    /// What the outputs (summaries, figures, maps) call the arm whose
    /// chain is `chain`: its preset's label, else `name` (a URDF's robot
    /// name, as a run file records it) with its joints.
    pub fn label_of(chain: &Chain, name: &str) -> String {
        match Self::of(chain) {
            Some(p) => p.label.to_string(),
            None => format!("{name} ({} joints, in space)", chain.dof()),
        }
    }

    /// The preset called `key`, if any.
    pub fn by_key(key: &str) -> Option<&'static SpacePreset> {
        PRESETS.iter().find(|p| p.key == key)
    }

    /// The preset called `key`, or an error that names every arm in space.
    pub fn named(key: &str) -> Result<&'static SpacePreset> {
        Self::by_key(key.trim()).ok_or_else(|| Error::UnknownName {
            kind: "arm in space",
            name: crate::error::clip(key),
            choices: crate::error::choices(&PRESETS.map(|p| p.key)),
        })
    }
}

/// Every named arm, the planar presets ([`crate::arm::PRESETS`]) and the
/// arms in space ([`PRESETS`]): one namespace, which the command line's
/// `--arm` and Python's `Robot.preset` read (the page's address reads the
/// two tables through its module).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Named {
    /// A planar arm.
    Planar(&'static Preset),
    /// An arm in space.
    Space(&'static SpacePreset),
}

impl Named {
    /// The arm called `key` (spaces around it ignored), if any.
    pub fn find(key: &str) -> Option<Named> {
        let key = key.trim();
        SpacePreset::by_key(key)
            .map(Named::Space)
            .or_else(|| Preset::by_key(key).map(Named::Planar))
    }

    /// What a refusal of an unknown name lists: the planar names, then
    /// those in space.
    pub fn choices() -> String {
        let planar = crate::arm::PRESETS.map(|p| p.key).join(", ");
        let space = PRESETS.map(|p| p.key).join(", ");
        format!("the planar {planar} or, in space, {space}")
    }
}

const H: f64 = std::f64::consts::FRAC_PI_2;

/// The named arms in space.
pub const PRESETS: [SpacePreset; 2] = [
    // Franka Emika Panda: Franka's FCI documentation ("Robot and interface
    // specifications", the modified DH table), the same geometry as
    // Robotics Toolbox for Python's `models.DH.Panda` (MIT licence), whose
    // forward kinematics and Jacobian tests/data/space/panda.json records.
    // Limits and rates from the same page; the ready pose `qr` is Robotics
    // Toolbox's. The capsules: radius 0.06 m, Robotics Toolbox's collision
    // spheres' (Franka's own self-collision capsules have radii 0.04-0.06
    // m), on the segments between distinct frame origins.
    SpacePreset {
        key: "panda",
        label: "Franka Panda (7 joints, in space)",
        source: "Franka FCI documentation, modified DH (as Robotics Toolbox's models.DH.Panda, MIT)",
        rows: &[
            Row::new(0.0, 0.0, 0.333),
            Row::new(0.0, -H, 0.0),
            Row::new(0.0, H, 0.316),
            Row::new(0.0825, H, 0.0),
            Row::new(-0.0825, -H, 0.384),
            Row::new(0.0, H, 0.0),
            Row::new(0.088, H, 0.0),
        ],
        flange: [0.0, 0.0, 0.107],
        radius: 0.06,
        joint_limits: &[
            [-2.8973, 2.8973],
            [-1.7628, 1.7628],
            [-2.8973, 2.8973],
            [-3.0718, -0.0698],
            [-2.8973, 2.8973],
            [-0.0175, 3.7525],
            [-2.8973, 2.8973],
        ],
        rate_limits: &[2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61],
        task: SpaceTask {
            theta0: &[0.0, -0.3, 0.0, -2.2, 0.0, 2.0, std::f64::consts::FRAC_PI_4],
            // From qr's hand (0.474, 0, 0.516), 0.3 m sideways; the
            // sphere, 10 cm clear of the arm at the start, sits above and
            // ahead of where the forearm ends without avoidance, which it
            // enters by 2 cm (docs/space.md).
            target: [0.474, 0.3, 0.516],
            sphere: [0.215, 0.21, 0.7, 0.06],
        },
    },
    // KUKA LBR iiwa 14 as Drake describes it: RobotLocomotion/models,
    // iiwa_description/urdf/iiwa14_no_collision.urdf (commit 4723170e;
    // BSD-3-Clause over iiwa_stack's BSD-2-Clause), as modified DH rows of
    // the same kinematics (no joint negated, no offsets; the rows were
    // found from the URDF's axes and checked against it to 1.4e-15 by
    // scripts/space-reference.py, tests/data/space/iiwa14.json): joint 2
    // 0.1575 + 0.2025 = 0.36 m above the base, 4 another 0.2045 + 0.2155 =
    // 0.42 m, 6 another 0.1845 + 0.2155 = 0.40 m, the flange
    // (`iiwa_link_ee`) 0.081 + 0.045 = 0.126 m beyond. Limits and rates
    // are the URDF's (+-170, 120, 170, 120, 170, 120, 175 degrees; 85, 85,
    // 100, 75, 130, 135, 135 degrees/s); the ready pose is Drake's
    // ManipulationStation's `q0`. The capsules: radius 0.07 m, within the
    // radii of Drake's sphere collision model (iiwa14_spheres_collision.urdf,
    // 0.053-0.080 m).
    SpacePreset {
        key: "iiwa14",
        label: "KUKA LBR iiwa 14 (7 joints, in space)",
        source: "Drake's iiwa14_no_collision.urdf (RobotLocomotion/models, BSD-3-Clause), as modified DH rows",
        rows: &[
            Row::new(0.0, 0.0, 0.36),
            Row::new(0.0, -H, 0.0),
            Row::new(0.0, H, 0.42),
            Row::new(0.0, H, 0.0),
            Row::new(0.0, -H, 0.4),
            Row::new(0.0, -H, 0.0),
            Row::new(0.0, H, 0.0),
        ],
        flange: [0.0, 0.0, 0.126],
        radius: 0.07,
        joint_limits: &[
            [-2.96705972839, 2.96705972839],
            [-2.09439510239, 2.09439510239],
            [-2.96705972839, 2.96705972839],
            [-2.09439510239, 2.09439510239],
            [-2.96705972839, 2.96705972839],
            [-2.09439510239, 2.09439510239],
            [-3.05432619099, 3.05432619099],
        ],
        rate_limits: &[
            1.4835298641951802,
            1.4835298641951802,
            1.7453292519943295,
            1.3089969389957472,
            2.2689280275926285,
            2.356194490192345,
            2.356194490192345,
        ],
        task: SpaceTask {
            theta0: &[0.0, 0.6, 0.0, -1.75, 0.0, 1.0, 0.0],
            // From q0's hand (0.496, 0, 0.302), 0.3 m sideways; the
            // sphere, 13 cm clear at the start, sits above and ahead of
            // where the forearm ends without avoidance.
            target: [0.5, 0.3, 0.3],
            sphere: [0.39, 0.26, 0.63, 0.06],
        },
    },
];
