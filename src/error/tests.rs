//! How numbers and positions read in messages.

use super::{Error, Num};

#[test]
fn numbers_in_messages_stay_short() {
    for (x, shown) in [
        (1e308, "1e308"),
        (-1e308, "-1e308"),
        (f64::MAX, "1.79769e308"),
        (5e-324, "4.94066e-324"),
        (1e-300, "1e-300"),
        (9.999999999999999e300, "1e301"),
        (1234567.0, "1.23457e6"),
        (0.5, "0.5"),
        (-3.0, "-3"),
        (0.0, "0"),
        (f64::NAN, "NaN"),
        (f64::INFINITY, "inf"),
    ] {
        assert_eq!(Num(x).to_string(), shown, "{x:e}");
    }
}

/// A dragged obstacle's position is quoted to the millimetre.
#[test]
fn positions_in_messages_are_given_to_the_millimetre() {
    let e = Error::ObstacleOnPost {
        x: -0.00000007629394550197807,
        y: 0.6000000238418579,
        radius: 0.05,
    };
    assert_eq!(
        e.to_string(),
        "obstacle at (0, 0.6) with radius 0.05 overlaps the fixed base post; move it away from the post"
    );
}
