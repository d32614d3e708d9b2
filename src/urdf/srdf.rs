//! The pairs an SRDF (MoveIt's semantic robot description) disables for
//! self-collision: its `<disable_collisions link1="..." link2="..."/>`
//! elements, read with the URDF's parser options (no document type
//! declaration, at most [`MAX_NODES`] nodes), and matched to a chain's
//! volumes by their links' names.

use roxmltree::{Document, Node, ParsingOptions};

use super::volume::Volume;
use super::MAX_NODES;
use crate::error::{Error, Result};

fn refuse(what: impl Into<String>) -> Error {
    Error::Urdf(format!("SRDF: {}", what.into()))
}

/// The pairs of link names an SRDF's `<disable_collisions>` name, in the
/// file's order.
pub fn disabled_links(text: &str) -> Result<Vec<(String, String)>> {
    let options = ParsingOptions {
        allow_dtd: false,
        nodes_limit: MAX_NODES,
        ..ParsingOptions::default()
    };
    let doc = Document::parse_with_options(text, options).map_err(|e| match e {
        roxmltree::Error::DtdDetected => {
            refuse("a document type declaration (<!DOCTYPE ...>) is refused: its entities are never expanded")
        }
        other => refuse(format!("not well-formed XML: {other}")),
    })?;
    let robot = doc.root_element();
    if robot.tag_name().name() != "robot" {
        return Err(refuse(format!(
            "the root element is <{}>, not <robot>",
            crate::error::clip(robot.tag_name().name())
        )));
    }
    let mut out = Vec::new();
    for node in robot
        .children()
        .filter(Node::is_element)
        .filter(|n| n.tag_name().name() == "disable_collisions")
    {
        let name = |key: &str| {
            node.attribute(key).map(str::to_string).ok_or_else(|| {
                refuse(format!(
                    "a <disable_collisions> without {key} (line {})",
                    doc.text_pos_at(node.range().start).row
                ))
            })
        };
        out.push((name("link1")?, name("link2")?));
    }
    Ok(out)
}

/// The pairs of `volumes` (indices, the chain's segments of a chain read
/// from URDF) whose links `links` disables, and the names among them no
/// volume belongs to (links outside the chain, or without a volume).
pub fn disabled_pairs(
    volumes: &[Volume],
    links: &[(String, String)],
) -> (Vec<[usize; 2]>, Vec<String>) {
    let mut pairs = Vec::new();
    let mut unknown = Vec::new();
    for (l1, l2) in links {
        for l in [l1, l2] {
            if !volumes.iter().any(|v| &v.link == l) && !unknown.contains(l) {
                unknown.push(l.clone());
            }
        }
        for (i, a) in volumes.iter().enumerate() {
            for (j, b) in volumes.iter().enumerate() {
                if i < j && ((&a.link, &b.link) == (l1, l2) || (&a.link, &b.link) == (l2, l1)) {
                    pairs.push([i, j]);
                }
            }
        }
    }
    (pairs, unknown)
}
