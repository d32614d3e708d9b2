//! Property tests over random arms and poses (native only: proptest needs the OS).
#![cfg(not(target_family = "wasm"))]

use proptest::prelude::*;
use redundant_ik::ik;
use redundant_ik::nalgebra::{DVector, Vector2};
use redundant_ik::obstacle;
use redundant_ik::Arm;

fn arm_and_theta() -> impl Strategy<Value = (Arm, DVector<f64>)> {
    (2usize..6).prop_flat_map(|n| {
        (
            0.0f64..1.0,
            prop::collection::vec(0.1f64..1.0, n),
            prop::collection::vec(-3.2f64..3.2, n),
        )
            .prop_map(|(post, links, th)| (Arm::new(post, links).unwrap(), DVector::from_vec(th)))
    })
}

proptest! {
    #[test]
    fn joint_rates_track_the_task_velocity_exactly_when_undamped(
        (arm, th) in arm_and_theta(),
        xd in (-1.0f64..1.0, -1.0f64..1.0),
        lambda in 0.0f64..8.0,
        o in (-2.0f64..2.0, 0.6f64..2.5),
    ) {
        let j = arm.jacobian(&th);
        prop_assume!(ik::smallest_singular_value(&j) > 1e-2);
        let xdot = Vector2::new(xd.0, xd.1);
        let ob = obstacle::Obstacle::new(o.0, o.1, 0.05);
        let v = obstacle::null_space_vector(&arm, &th, &[ob], lambda);
        let rates = ik::theta_dot_symmetric(&j, &xdot, &v, 0.0).unwrap();
        // Whatever v is, J theta_dot = Xdot (eq. 4): the null-space term is invisible.
        prop_assert!((j * rates - xdot).amax() < 1e-8 * (1.0 + v.amax()));
    }

    #[test]
    fn damped_rates_are_bounded_everywhere(
        (arm, th) in arm_and_theta(),
        xd in (-1.0f64..1.0, -1.0f64..1.0),
        delta in 1e-4f64..1.0,
    ) {
        let j = arm.jacobian(&th);
        let xdot = Vector2::new(xd.0, xd.1);
        let rates = ik::theta_dot_symmetric(&j, &xdot, &DVector::zeros(arm.dof()), delta).unwrap();
        prop_assert!(rates.norm() <= xdot.norm() / (2.0 * delta.sqrt()) + 1e-9);
    }

    #[test]
    fn damping_schedule_is_continuous_and_bounded(
        (arm, th) in arm_and_theta(),
    ) {
        let s = ik::DampingSchedule::default();
        let d = s.delta(&arm.jacobian(&th));
        prop_assert!((0.0..=s.delta_max).contains(&d));
    }
}
