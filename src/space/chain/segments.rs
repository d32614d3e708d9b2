//! The capsules of a chain of modified-DH rows: one per link, between
//! consecutive distinct frame origins.

use super::{Row, Segment};

/// The segments between consecutive distinct origins. The pose's points
/// are the base's origin (index 0), the origin of each joint's frame
/// (1..=n) and the flange (n + 1). Frame `i`'s origin follows frame
/// `i - 1`'s by `a_(i-1)` along `x_(i-1)` and `d_i` along `z_i`; both zero,
/// the origins coincide in every pose. The base's origin and frame 1's
/// coincide when row 1 has neither.
pub(super) fn segments(rows: &[Row], flange: [f64; 3], radius: f64) -> Vec<Segment> {
    let n = rows.len();
    let mut out = Vec::new();
    let mut from = 0;
    for (i, r) in rows.iter().enumerate() {
        // Point i + 1 is frame (i + 1)'s origin; it moves with joints 1..=i.
        if r.a != 0.0 || r.d != 0.0 {
            out.push(Segment {
                from,
                to: i + 1,
                moved_by: i,
                radius,
            });
            from = i + 1;
        }
    }
    if flange != [0.0; 3] || from == 0 {
        out.push(Segment {
            from,
            to: n + 1,
            moved_by: n,
            radius,
        });
    }
    out
}
