//! A chain of modified-DH rows written as URDF ([`chain_urdf`]): what the
//! arms in space ship as (`robots/*.urdf`, written from the presets, so
//! that their numbers live in one place, `src/space/preset.rs`), and what
//! any chain can be opened as by the tools that read URDF. Joint `i`'s
//! origin is `Rx(alpha) Tx(a) Tz(d) Rz(offset)` (the row's fixed part:
//! `Rz(theta)` commutes with `Tz(d)`), its axis `z`; each capsule is a
//! `<cylinder>` on its segment in the frame of the joint that moves it
//! (the reader makes a cylinder the capsule on its axis with its radius,
//! which is the chain's own capsule); the flange is a fixed joint to the
//! link `flange`.

use std::fmt::Write as _;

use super::Frame;
use crate::space::rotation::matrix_rpy;
use crate::space::{Chain, SpacePose, Vec3};

/// `v` in full (Rust's shortest text that reads back to the same `f64`).
fn num(v: f64) -> String {
    // `+ 0.0` writes `-0` as `0`.
    format!("{:?}", v + 0.0).trim_end_matches(".0").to_string()
}

fn triple(v: Vec3) -> String {
    format!("{} {} {}", num(v[0]), num(v[1]), num(v[2]))
}

/// The origin element of `f`.
fn origin(f: &Frame) -> String {
    format!(
        "<origin xyz=\"{}\" rpy=\"{}\"/>",
        triple(f.translation),
        triple(matrix_rpy(&f.rotation))
    )
}

/// `chain` as the text of a URDF named `name`, with `comment` (its
/// source) at the top. Its links are `base_link`, `link1`..`linkN` and
/// `flange`; its joints `joint1`..`jointN` (with the chain's limits and
/// rate limits, where it has them) and `flange_joint`.
pub fn chain_urdf(name: &str, comment: &str, chain: &Chain) -> String {
    let n = chain.dof();
    let mut out = String::from("<?xml version=\"1.0\"?>\n");
    let _ = writeln!(out, "<!-- {} -->", comment.replace("--", "- -"));
    let _ = writeln!(out, "<robot name=\"{name}\">");
    // The frames at zero, to place each capsule in its joint's frame.
    let pose = SpacePose::new(chain, &vec![0.0; n]).ok();
    let (base_rot, base_origin) = chain.base();
    // The base link's frame is the world's (the chain's base placement
    // goes into the first joint's origin).
    let frame_of = |k: usize| -> Frame {
        match (&pose, k) {
            (_, 0) | (None, _) => Frame::IDENTITY,
            (Some(p), k) => {
                let [x, y, z] = p.frame(k - 1);
                Frame {
                    rotation: [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]],
                    translation: p.joint_origin(k - 1),
                }
            }
        }
    };
    let link_name = |k: usize| {
        if k == 0 {
            "base_link".to_string()
        } else {
            format!("link{k}")
        }
    };
    for k in 0..=n {
        let _ = writeln!(out, "  <link name=\"{}\">", link_name(k));
        if let Some(p) = &pose {
            let f = frame_of(k);
            for s in chain.segments().iter().filter(|s| s.moved_by == k) {
                let (a, b) = p.segment(s);
                let (a, b) = (local(&f, a), local(&f, b));
                let d: Vec3 = std::array::from_fn(|i| b[i] - a[i]);
                let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                if length.is_nan() || length <= 0.0 {
                    continue;
                }
                let mid: Vec3 = std::array::from_fn(|i| 0.5 * (a[i] + b[i]));
                // z onto d: Rz(yaw) Ry(pitch).
                let u = d.map(|x| x / length);
                let pitch = u[2].clamp(-1.0, 1.0).acos();
                let yaw = u[1].atan2(u[0]);
                let _ = writeln!(
                    out,
                    "    <collision><origin xyz=\"{}\" rpy=\"0 {} {}\"/><geometry><cylinder radius=\"{}\" length=\"{}\"/></geometry></collision>",
                    triple(mid),
                    num(pitch),
                    num(yaw),
                    num(chain.radius()),
                    num(length)
                );
            }
        }
        let _ = writeln!(out, "  </link>");
    }
    let _ = writeln!(out, "  <link name=\"flange\"/>");
    let limits = chain.joint_limits().map(|l| l.ranges().to_vec());
    let rates = chain.rate_limits().map(|r| r.rates().to_vec());
    for (i, row) in chain.rows().iter().enumerate() {
        let (sa, ca) = crate::kinematics::sin_cos(row.alpha);
        let (so, co) = crate::kinematics::sin_cos(row.offset);
        // Rx(alpha) Rz(offset), and the translation Rx(alpha) (a, 0, d).
        let fixed = Frame {
            rotation: [
                [co, -so, 0.0],
                [ca * so, ca * co, -sa],
                [sa * so, sa * co, ca],
            ],
            translation: [row.a, -sa * row.d, ca * row.d],
        };
        let mut fixed = fixed;
        if i == 0 {
            fixed = Frame {
                rotation: base_rot,
                translation: base_origin,
            }
            .then(&fixed);
        }
        let limit = match (&limits, &rates) {
            (None, None) => String::new(),
            _ => {
                let [lo, hi] = limits.as_ref().map_or([-1e3, 1e3], |l| l[i]);
                let v = rates
                    .as_ref()
                    .map_or(String::new(), |r| format!(" velocity=\"{}\"", num(r[i])));
                format!(
                    "\n    <limit lower=\"{}\" upper=\"{}\"{v} effort=\"0\"/>",
                    num(lo),
                    num(hi)
                )
            }
        };
        let kind = if limits.is_some() {
            "revolute"
        } else {
            "continuous"
        };
        let _ = writeln!(
            out,
            "  <joint name=\"joint{}\" type=\"{kind}\">\n    <parent link=\"{}\"/>\n    <child link=\"link{}\"/>\n    {}\n    <axis xyz=\"0 0 1\"/>{limit}\n  </joint>",
            i + 1,
            link_name(i),
            i + 1,
            origin(&fixed)
        );
    }
    let _ = writeln!(
        out,
        "  <joint name=\"flange_joint\" type=\"fixed\">\n    <parent link=\"link{n}\"/>\n    <child link=\"flange\"/>\n    {}\n  </joint>",
        origin(&Frame {
            rotation: chain.flange_rotation(),
            translation: chain.flange(),
        })
    );
    out.push_str("</robot>\n");
    out
}

/// The world point `p` in the frame `f` (`f` maps that frame to the world).
fn local(f: &Frame, p: Vec3) -> Vec3 {
    let d: Vec3 = std::array::from_fn(|i| p[i] - f.translation[i]);
    // R^T d.
    std::array::from_fn(|c| (0..3).map(|r| f.rotation[r][c] * d[r]).sum())
}
