//! The named arms the page's designer and the command line offer
//! (`--arm NAME`, the address's `arm=NAME`), each with its limits and,
//! where it has one, its own task.

use serde::Serialize;

use super::{Arm, JointLimits, RateLimits};

/// An arm the page's designer and the command line offer by name.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Preset {
    /// Its name (`--arm four` on the command line).
    pub key: &'static str,
    /// What the designer's menu says.
    pub label: &'static str,
    /// Post height `L0` (m).
    pub post: f64,
    /// Link lengths (m).
    pub links: &'static [f64],
    /// Each joint's position range `[lo, hi]` (rad), if limited.
    pub joint_limits: Option<&'static [[f64; 2]]>,
    /// Each joint's largest rate (rad/s), if limited.
    pub rate_limits: Option<&'static [f64]>,
    /// The arm's own task, in the paper's spirit, if it has one (else the
    /// paper's target and obstacle, from [`crate::session::start_pose`]).
    pub task: Option<PresetTask>,
}

/// A preset's own task: a start pose, the end of its straight line and an
/// obstacle disc the arm without avoidance hits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PresetTask {
    /// Joint angles at `t = 0` (rad), within the preset's limits.
    pub theta0: &'static [f64],
    /// The end of the line (m).
    pub target: [f64; 2],
    /// The obstacle's centre and radius `[x, y, r]` (m).
    pub obstacle: [f64; 3],
}

/// The named arms: the paper's, two longer ones, and a real robot.
pub const PRESETS: [Preset; 4] = [
    Preset {
        key: "paper",
        label: "The paper's arm (3 links)",
        post: 0.5,
        links: &[0.6, 0.85, 0.6],
        joint_limits: None,
        rate_limits: None,
        task: None,
    },
    Preset {
        key: "four",
        label: "4 links",
        post: 0.5,
        links: &[0.6, 0.85, 0.6, 0.4],
        joint_limits: None,
        rate_limits: None,
        task: None,
    },
    Preset {
        key: "five",
        label: "5 links",
        post: 0.5,
        links: &[0.5, 0.6, 0.5, 0.4, 0.3],
        joint_limits: None,
        rate_limits: None,
        task: None,
    },
    // KUKA LBR iiwa 14 in its plane, from `planar_iiwa14_spheres_dense_
    // elbow_collision.urdf` (RobotLocomotion/drake, manipulation/models/
    // iiwa_description/urdf/, now RobotLocomotion/models; Drake's BSD-3-
    // Clause licence over iiwa_stack's BSD-2-Clause): joints 1, 3, 5 and 7
    // welded, joints 2, 4, 6 with parallel axes. Joint 2 sits 0.1575 +
    // 0.2025 = 0.36 m above the base (our post); joint 2 to 4: 0.2045 +
    // 0.2155 = 0.42 m, 4 to 6: 0.1845 + 0.2155 = 0.40 m, 6 to
    // `iiwa_link_ee`: 0.081 + 0.045 = 0.126 m. Joint 4's axis is -y where
    // 2's and 6's are +y, so our theta_2 = -q_4 (the limits are symmetric,
    // the same either way). Limits +-2.09439510239 rad and the URDF's
    // velocity limits (rad/s). Its task: Drake's default pose of the
    // model (q = 0.1, -1.2, 1.6, so theta = 0.1, 1.2, 1.6: the hand points
    // down at (0.458, 0.763)), a line down to (0.6, 0.3), and a disc of
    // 0.05 m grown by the widest collision sphere of the links (0.08 m;
    // our links are segments, docs/lab.md) beside the elbow's sweep.
    Preset {
        key: "iiwa-planar",
        label: "KUKA iiwa14, planar (joints 2, 4, 6)",
        post: 0.36,
        links: &[0.42, 0.40, 0.126],
        joint_limits: Some(&[
            [-2.09439510239, 2.09439510239],
            [-2.09439510239, 2.09439510239],
            [-2.09439510239, 2.09439510239],
        ]),
        rate_limits: Some(&[1.4835298641951802, 1.3089969389957472, 2.356194490192345]),
        task: Some(PresetTask {
            theta0: &[0.1, 1.2, 1.6],
            target: [0.6, 0.3],
            obstacle: [0.75, 0.5, 0.13],
        }),
    },
];

impl Preset {
    /// The planar preset called `key`, if any (every arm's names:
    /// [`crate::space::Named`]).
    pub fn by_key(key: &str) -> Option<&'static Preset> {
        PRESETS.iter().find(|p| p.key == key)
    }

    /// The preset whose post and links `arm` has, if any.
    pub fn of(arm: &Arm) -> Option<&'static Preset> {
        PRESETS
            .iter()
            .find(|p| p.post == arm.post && p.links == arm.links)
    }

    /// The arm, with the preset's limits if it has any (each preset is
    /// checked by a test to pass [`Arm::new`] and [`Arm::with_limits`]).
    pub fn arm(&self) -> Arm {
        Arm {
            post: self.post,
            links: self.links.to_vec(),
            joint_limits: self
                .joint_limits
                .map(|l| JointLimits::from_checked(l.to_vec())),
            rate_limits: self
                .rate_limits
                .map(|r| RateLimits::from_checked(r.to_vec())),
        }
    }
}
