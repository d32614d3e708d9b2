//! The XML of a URDF into a [`Urdf`]: every element this reads, checked
//! as it is read (finite numbers, a unit axis, `lower <= upper`, names
//! given once), each refusal naming the element and, for XML that is not
//! well formed, the line and column.

use roxmltree::{Document, Node, ParsingOptions};

use super::{Collision, Frame, Geometry, Joint, JointType, Limit, Link, Urdf, Vec3, MAX_NODES};
use crate::error::{Error, Result, MAX_COORDINATE};

/// xacro's namespace: a file that uses it is a macro file, not a URDF.
const XACRO: &str = "http://www.ros.org/wiki/xacro";

fn refuse(what: impl Into<String>) -> Error {
    Error::Urdf(what.into())
}

/// The document's `<robot>`, read.
pub(super) fn document(text: &str) -> Result<Urdf> {
    let options = ParsingOptions {
        allow_dtd: false,
        nodes_limit: MAX_NODES,
        ..ParsingOptions::default()
    };
    let doc = Document::parse_with_options(text, options).map_err(|e| match e {
        roxmltree::Error::DtdDetected => refuse(
            "a document type declaration (<!DOCTYPE ...>) is refused: a URDF needs none, and its entities are never expanded",
        ),
        roxmltree::Error::NodesLimitReached => {
            refuse(format!("more than {MAX_NODES} XML nodes"))
        }
        other => refuse(format!("not well-formed XML: {other}")),
    })?;
    let robot = doc.root_element();
    xacro_check(robot)?;
    if robot.tag_name().name() != "robot" {
        return Err(refuse(format!(
            "the root element is <{}>, not <robot>",
            clip(robot.tag_name().name())
        )));
    }
    let mut links: Vec<Link> = Vec::new();
    let mut joints: Vec<Joint> = Vec::new();
    for node in robot.children().filter(Node::is_element) {
        match node.tag_name().name() {
            "link" => {
                let link = link(node)?;
                if links.iter().any(|l| l.name == link.name) {
                    return Err(refuse(format!(
                        "two links are called '{}'",
                        clip(&link.name)
                    )));
                }
                links.push(link);
            }
            "joint" => {
                let joint = joint(node)?;
                if joints.iter().any(|j| j.name == joint.name) {
                    return Err(refuse(format!(
                        "two joints are called '{}'",
                        clip(&joint.name)
                    )));
                }
                joints.push(joint);
            }
            _ => {}
        }
    }
    if links.is_empty() {
        return Err(refuse("the robot has no <link>"));
    }
    Ok(Urdf {
        name: robot.attribute("name").unwrap_or_default().to_string(),
        links,
        joints,
    })
}

/// Refuses a file that uses xacro: an element of its namespace, or a
/// `${...}` expression in an attribute.
fn xacro_check(root: Node) -> Result<()> {
    let macro_file = root.descendants().filter(Node::is_element).any(|n| {
        n.tag_name().namespace() == Some(XACRO) || n.attributes().any(|a| a.value().contains("${"))
    });
    if macro_file {
        return Err(refuse(
            "this is a xacro file (its macros and ${...} expressions are not read): expand it first, `xacro robot.urdf.xacro > robot.urdf`",
        ));
    }
    Ok(())
}

/// A name quoted in a message, cut to 40 characters (a file can be hostile).
fn clip(text: &str) -> String {
    crate::error::clip(text)
}

/// The attribute `name` of `node`, required.
fn required<'a>(node: Node<'a, '_>, name: &str) -> Result<&'a str> {
    node.attribute(name).ok_or_else(|| {
        refuse(format!(
            "<{}{}> has no {name}",
            node.tag_name().name(),
            node.attribute("name")
                .map(|n| format!(" name='{}'", clip(n)))
                .unwrap_or_default()
        ))
    })
}

/// The child element `name` of `node`, if any.
fn child<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

/// `N` numbers separated by white space, each finite and within
/// [`MAX_COORDINATE`]; `what` names them in a refusal.
fn numbers<const N: usize>(text: &str, what: &str) -> Result<[f64; N]> {
    let parts: Vec<&str> = text.split_whitespace().collect();
    if parts.len() != N {
        return Err(refuse(format!(
            "{what} needs {N} numbers, got '{}'",
            clip(text)
        )));
    }
    let mut out = [0.0; N];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = number(p, what)?;
    }
    Ok(out)
}

/// One finite number within [`MAX_COORDINATE`].
fn number(text: &str, what: &str) -> Result<f64> {
    let v: f64 = text
        .trim()
        .parse()
        .map_err(|_| refuse(format!("{what}: '{}' is not a number", clip(text))))?;
    if !v.is_finite() || v.abs() > MAX_COORDINATE {
        return Err(refuse(format!(
            "{what}: {} is not a finite number within {MAX_COORDINATE:e}",
            clip(text)
        )));
    }
    Ok(v)
}

/// An `<origin>` child, or the identity where there is none.
fn origin(node: Node, what: &str) -> Result<Frame> {
    let Some(o) = child(node, "origin") else {
        return Ok(Frame::IDENTITY);
    };
    let xyz = o
        .attribute("xyz")
        .map(|t| numbers::<3>(t, &format!("{what}'s origin xyz")))
        .transpose()?
        .unwrap_or([0.0; 3]);
    let rpy = o
        .attribute("rpy")
        .map(|t| numbers::<3>(t, &format!("{what}'s origin rpy")))
        .transpose()?
        .unwrap_or([0.0; 3]);
    Ok(Frame::from_xyz_rpy(xyz, rpy))
}

fn link(node: Node) -> Result<Link> {
    let name = required(node, "name")?.to_string();
    let what = format!("link '{}'", clip(&name));
    let mut collisions = Vec::new();
    for c in node
        .children()
        .filter(|c| c.is_element() && c.tag_name().name() == "collision")
    {
        let geometry = child(c, "geometry")
            .ok_or_else(|| refuse(format!("a <collision> of {what} has no <geometry>")))?;
        collisions.push(Collision {
            origin: origin(c, &what)?,
            geometry: shape(geometry, &what)?,
        });
    }
    Ok(Link { name, collisions })
}

/// A positive length.
fn length(node: Node, attribute: &str, what: &str) -> Result<f64> {
    let v = number(required(node, attribute)?, &format!("{what}'s {attribute}"))?;
    if v <= 0.0 {
        return Err(refuse(format!(
            "{what}'s {attribute} must be positive (got {v})"
        )));
    }
    Ok(v)
}

fn shape(geometry: Node, what: &str) -> Result<Geometry> {
    let Some(s) = geometry.children().find(Node::is_element) else {
        return Err(refuse(format!("a <geometry> of {what} is empty")));
    };
    let what = format!("the {} of {what}", s.tag_name().name());
    match s.tag_name().name() {
        "sphere" => Ok(Geometry::Sphere {
            radius: length(s, "radius", &what)?,
        }),
        "cylinder" => Ok(Geometry::Cylinder {
            radius: length(s, "radius", &what)?,
            length: length(s, "length", &what)?,
        }),
        "box" => {
            let size = numbers::<3>(required(s, "size")?, &format!("{what}'s size"))?;
            if size.iter().any(|&v| v <= 0.0) {
                return Err(refuse(format!("{what}'s sides must be positive")));
            }
            Ok(Geometry::Box { size })
        }
        "mesh" => Ok(Geometry::Mesh {
            filename: required(s, "filename")?.to_string(),
            scale: s
                .attribute("scale")
                .map(|t| numbers::<3>(t, &format!("{what}'s scale")))
                .transpose()?
                .unwrap_or([1.0; 3]),
        }),
        other => Err(refuse(format!(
            "{what}: <{}> is not a URDF geometry (sphere, cylinder, box or mesh)",
            clip(other)
        ))),
    }
}

fn joint(node: Node) -> Result<Joint> {
    let name = required(node, "name")?.to_string();
    let what = format!("joint '{}'", clip(&name));
    let kind = match required(node, "type")? {
        "revolute" => JointType::Revolute,
        "continuous" => JointType::Continuous,
        "prismatic" => JointType::Prismatic,
        "fixed" => JointType::Fixed,
        "floating" | "planar" => {
            return Err(refuse(format!(
                "{what} is {}: a serial arm's joints turn or slide about one axis (revolute, continuous, prismatic) or are fixed",
                node.attribute("type").unwrap_or_default()
            )))
        }
        other => {
            return Err(refuse(format!(
                "{what}: type '{}' is not a URDF joint type",
                clip(other)
            )))
        }
    };
    if let Some(m) = child(node, "mimic") {
        return Err(refuse(format!(
            "{what} mimics joint '{}': mimic joints are not supported (each joint moves on its own)",
            clip(m.attribute("joint").unwrap_or_default())
        )));
    }
    let link_of = |tag: &str| -> Result<String> {
        let n = child(node, tag).ok_or_else(|| refuse(format!("{what} has no <{tag}>")))?;
        Ok(required(n, "link")?.to_string())
    };
    let (parent, child_link) = (link_of("parent")?, link_of("child")?);
    let axis = match child(node, "axis").and_then(|a| a.attribute("xyz")) {
        // URDF's default axis.
        None => [1.0, 0.0, 0.0],
        Some(t) => unit(numbers::<3>(t, &format!("{what}'s axis"))?, &what)?,
    };
    let limit = child(node, "limit")
        .map(|l| -> Result<Limit> {
            let get = |a: &str| {
                l.attribute(a)
                    .map(|t| number(t, &format!("{what}'s {a} limit")))
                    .transpose()
            };
            let limit = Limit {
                lower: get("lower")?,
                upper: get("upper")?,
                velocity: get("velocity")?,
            };
            if let (Some(lo), Some(hi)) = (limit.lower, limit.upper) {
                if lo > hi {
                    return Err(refuse(format!(
                        "{what}'s lower limit {lo} is above its upper limit {hi}"
                    )));
                }
            }
            if limit.velocity.is_some_and(|v| v < 0.0) {
                return Err(refuse(format!("{what}'s velocity limit is negative")));
            }
            Ok(limit)
        })
        .transpose()?;
    Ok(Joint {
        name,
        kind,
        parent,
        child: child_link,
        origin: origin(node, &what)?,
        axis,
        limit,
    })
}

/// `v` scaled to unit length; a zero axis refused.
fn unit(v: Vec3, what: &str) -> Result<Vec3> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n.is_nan() || n <= 1e-12 {
        return Err(refuse(format!("{what}'s axis is zero")));
    }
    Ok(v.map(|x| x / n))
}
