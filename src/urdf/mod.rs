//! A robot's URDF (plain URDF XML; xacro is not read) into what the one
//! chain model needs: its links with their collision geometry and its
//! joints with their origins, axes and limits ([`Urdf`]); the serial chain
//! from a base link to a tip link, the fixed joints folded into the next
//! moving one ([`UrdfChain`]); and each link's volumes, made from its
//! collision geometry ([`volume`]).
//!
//! The XML is read by `roxmltree` (MIT OR Apache-2.0; 31 KB gzipped alone
//! in a wasm32 module at opt-level z, against 123 KB for `urdf-rs` and its
//! five XML crates, measured on 6 December): it refuses a document type
//! declaration, so no entity is ever expanded, and the reader caps the
//! number of nodes. What the reader takes of the URDF specification
//! (`wiki.ros.org/urdf/XML`): `<robot>`, `<link>` with its `<collision>`
//! elements (`<origin>`, `<geometry>` of `<sphere>`, `<cylinder>`, `<box>`
//! or `<mesh>`), `<joint>` of type `revolute`, `continuous`, `prismatic`
//! or `fixed` with `<parent>`, `<child>`, `<origin>`, `<axis>` and
//! `<limit>`. Everything else (inertia, visuals, transmissions, Gazebo
//! tags) is passed over. A `floating` or `planar` joint and a `<mimic>`
//! are refused by name.

mod chain;
mod frame;
mod model;
mod parse;
mod source;
pub mod srdf;
pub mod stl;
pub mod volume;
mod write;

pub use chain::{ChainJoint, ChainLink, JointKind, UrdfChain};
pub use frame::{Frame, Vec3};
pub use source::RobotSource;
pub use write::chain_urdf;

use crate::error::{Error, Result};

/// Largest URDF read (bytes).
pub const MAX_URDF_BYTES: usize = 8 << 20;
/// Most moving joints a chain may have.
pub const MAX_CHAIN_JOINTS: usize = 32;
/// Most XML nodes a URDF may have (elements, attributes' text, comments).
pub const MAX_NODES: u32 = 500_000;

/// A robot as its URDF describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct Urdf {
    /// The `<robot name>`.
    pub name: String,
    /// Every `<link>`, in the file's order.
    pub links: Vec<Link>,
    /// Every `<joint>`, in the file's order.
    pub joints: Vec<Joint>,
}

/// A `<link>`: its name and its collision geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// The link's name.
    pub name: String,
    /// Its `<collision>` elements.
    pub collisions: Vec<Collision>,
}

/// A `<collision>`: a shape placed in the link's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Collision {
    /// The shape's frame in the link's.
    pub origin: Frame,
    /// The shape.
    pub geometry: Geometry,
}

/// A `<geometry>`.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry {
    /// A sphere about the origin.
    Sphere {
        /// Its radius (m).
        radius: f64,
    },
    /// A cylinder along the origin's `z`, centred on it.
    Cylinder {
        /// Its radius (m).
        radius: f64,
        /// Its length (m).
        length: f64,
    },
    /// A box centred on the origin.
    Box {
        /// Its sides along `x`, `y`, `z` (m).
        size: Vec3,
    },
    /// A mesh file, scaled.
    Mesh {
        /// The file as the URDF names it (`package://...` or a path).
        filename: String,
        /// The scale along `x`, `y`, `z`.
        scale: Vec3,
    },
}

/// A `<joint>`'s type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointType {
    /// Turns about its axis within limits.
    Revolute,
    /// Turns about its axis without limits.
    Continuous,
    /// Slides along its axis within limits.
    Prismatic,
    /// Does not move.
    Fixed,
}

/// A `<joint>`.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// The joint's name.
    pub name: String,
    /// Its type.
    pub kind: JointType,
    /// The parent link's name.
    pub parent: String,
    /// The child link's name.
    pub child: String,
    /// The child link's frame in the parent's at zero motion.
    pub origin: Frame,
    /// The axis in the joint's frame, of unit length.
    pub axis: Vec3,
    /// Its `<limit>`, if it has one.
    pub limit: Option<Limit>,
}

/// A `<limit>`: the position range (rad, or m for a prismatic joint) and
/// the largest rate (rad/s or m/s), each where the file gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    /// `lower`.
    pub lower: Option<f64>,
    /// `upper`.
    pub upper: Option<f64>,
    /// `velocity`.
    pub velocity: Option<f64>,
}

impl Urdf {
    /// Reads a URDF's text; refused with a reason (the line and column of
    /// an XML error) where it is not a URDF this reads.
    pub fn parse(text: &str) -> Result<Self> {
        if text.len() > MAX_URDF_BYTES {
            return Err(Error::Urdf(format!(
                "the file has {} bytes, more than the {MAX_URDF_BYTES} a URDF may have",
                text.len()
            )));
        }
        parse::document(text)
    }

    /// The link called `name`, if any.
    pub fn link(&self, name: &str) -> Option<&Link> {
        self.links.iter().find(|l| l.name == name)
    }
}
