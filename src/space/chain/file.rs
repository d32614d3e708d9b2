//! The JSON form of a [`Chain`]: what a run file's `scene.arm` holds,
//! read and checked as the constructors check a chain.

use serde::Deserialize;

use super::{Chain, JointFrame, LinkVolume, Row};
use crate::arm::{JointLimits, RateLimits};
use crate::error::{Error, Result};

/// The JSON form of a [`Chain`], as it is written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainFile {
    base: ([[f64; 3]; 3], [f64; 3]),
    #[serde(default)]
    rows: Vec<Row>,
    #[serde(default)]
    joints: Vec<JointFrame>,
    flange: [f64; 3],
    radius: f64,
    #[serde(default)]
    volumes: Vec<LinkVolume>,
    #[serde(default)]
    joint_limits: Option<JointLimits>,
    #[serde(default)]
    rate_limits: Option<RateLimits>,
    #[serde(default)]
    flange_rotation: Option<[[f64; 3]; 3]>,
    #[serde(default)]
    self_pairs: Vec<[usize; 2]>,
}

impl TryFrom<ChainFile> for Chain {
    type Error = Error;
    fn try_from(f: ChainFile) -> Result<Self> {
        let (rotation, origin) = f.base;
        let chain = if f.joints.is_empty() {
            if !f.volumes.is_empty() {
                return Err(Error::Syntax {
                    what: "chain",
                    text: "volumes".into(),
                    expected: "a chain of modified-DH rows has no volumes of its own".into(),
                });
            }
            Chain::placed(rotation, origin, f.rows, f.flange, f.radius)?
        } else if f.rows.is_empty() {
            Chain::of_joints(rotation, origin, f.joints, f.flange, f.volumes)?
        } else {
            return Err(Error::Syntax {
                what: "chain",
                text: "rows and joints".into(),
                expected: "either modified-DH rows or joint frames".into(),
            });
        };
        let mut chain = chain.with_limits(f.joint_limits, f.rate_limits)?;
        if let Some(r) = f.flange_rotation {
            chain = chain.with_flange_rotation(r)?;
        }
        chain.set_self_pairs(f.self_pairs)?;
        Ok(chain)
    }
}
