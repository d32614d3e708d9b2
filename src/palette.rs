//! The colours the page's drawing and the SVG figures share, written once:
//! the page reads them through `web::style` (its renderer, its stylesheet's
//! custom properties and its legend), the figures through `figure::colour`.
//! The methods' and the atlas classes' colours live with them
//! (`planner::methods`, `atlas`).

/// Text, axes' labels.
pub const INK: &str = "#1f2933";
/// Secondary text: captions, notes.
pub const MUTED: &str = "#5f6b78";
/// The arm, and the first joint's series.
pub const ARM: &str = "#1d4e89";
/// The hand's path, the tracking error, the third joint's series.
pub const ACCENT: &str = "#d9731a";
/// Obstacles and collisions.
pub const DANGER: &str = "#c0392b";
/// The target, the second joint's series.
pub const TEAL: &str = "#2a9d8f";

/// Colours of the joint-angle series `theta_1, theta_2, ...` in turn, one
/// per joint of the longest arm the page draws (six links); a longer arm's
/// joints take them again from the first (θ4 was drawn in θ1's colour when
/// there were three). The page's joint-angle plot shades each joint's
/// limits in its colour.
pub const JOINT_SERIES: [&str; 6] = [ARM, TEAL, ACCENT, "#6b8e23", "#8c564b", "#7f7f7f"];

/// The colour of joint `i`'s series (from 0).
pub fn joint_series(i: usize) -> &'static str {
    JOINT_SERIES[i % JOINT_SERIES.len()]
}

/// `#rrggbb` as its three channels (at compile time: the figures' colours
/// are constants built from these).
pub const fn rgb(hex: &str) -> (u8, u8, u8) {
    const fn nibble(c: u8) -> u8 {
        match c {
            b'0'..=b'9' => c - b'0',
            b'a'..=b'f' => c - b'a' + 10,
            b'A'..=b'F' => c - b'A' + 10,
            _ => 0,
        }
    }
    let b = hex.as_bytes();
    if b.len() != 7 {
        return (0, 0, 0);
    }
    (
        nibble(b[1]) * 16 + nibble(b[2]),
        nibble(b[3]) * 16 + nibble(b[4]),
        nibble(b[5]) * 16 + nibble(b[6]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_read_as_written_and_each_joint_has_its_own() {
        assert_eq!(rgb(ARM), (0x1d, 0x4e, 0x89));
        assert_eq!(rgb("#FFffFF"), (255, 255, 255));
        assert_eq!(rgb("red"), (0, 0, 0));
        for i in 0..6 {
            for j in 0..i {
                assert_ne!(
                    joint_series(i),
                    joint_series(j),
                    "θ{} and θ{}",
                    i + 1,
                    j + 1
                );
            }
        }
        assert_eq!(joint_series(6), joint_series(0));
    }
}
