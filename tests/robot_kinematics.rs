//! Property tests of the robot model: FK∘IK round trip over the reachable
//! region, actuator and encoder conversions, refusal of out-of-limit poses.

use basr::robot::{Joints, NozzlePose, Robot};
use proptest::prelude::*;

fn robot() -> Robot {
    Robot::basr()
}

/// Joints anywhere inside the default limits.
fn joints_in_limits() -> impl Strategy<Value = Joints> {
    let r = robot();
    let l = r.limits.clone();
    (
        l.base_rot_rad.min..=l.base_rot_rad.max,
        l.extension_m.min..=l.extension_m.max,
        l.vertical_m.min..=l.vertical_m.max,
        l.ee_yaw_rad.min..=l.ee_yaw_rad.max,
        l.tilt_rad.min..=l.tilt_rad.max,
    )
        .prop_map(|(a, b, c, d, e)| Joints {
            base_rot_rad: a,
            extension_m: b,
            vertical_m: c,
            ee_yaw_rad: d,
            tilt_rad: e,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Every pose the robot reaches inverts to joints that give it back to
    /// 1e-9 m / 1e-9 rad, and the joints it came from are among them.
    #[test]
    fn fk_of_ik_is_identity_over_reachable_region(j in joints_in_limits()) {
        let r = robot();
        let pose = r.fk(&j);
        let all = r.ik(&pose).expect("a pose made from valid joints is reachable");
        prop_assert!(!all.is_empty());
        for s in &all {
            let back = r.fk(s);
            prop_assert!((back.x_m - pose.x_m).abs() < 1e-9);
            prop_assert!((back.y_m - pose.y_m).abs() < 1e-9);
            prop_assert!((back.z_m - pose.z_m).abs() < 1e-9);
            prop_assert!(back.same_spray(&pose, 1e-9), "{back:?} vs {pose:?}");
            prop_assert!(r.check_joints(s).is_ok());
        }
        let found = all.iter().any(|s| {
            s.values().iter().zip(j.values()).all(|(a, b)| (a - b).abs() < 1e-9)
        });
        prop_assert!(found, "{j:?} not among {all:?}");
        // The nearest solution to where we came from is where we came from.
        let near = r.ik_nearest(&pose, &j).unwrap();
        for (a, b) in near.values().iter().zip(j.values()) {
            prop_assert!((a - b).abs() < 1e-9);
        }
    }

    /// A random pose either inverts exactly or is refused naming a limit;
    /// its solutions are never outside the limits (no silent clamping).
    #[test]
    fn random_poses_invert_exactly_or_are_refused(
        x in -6.0f64..6.0, y in -2.0f64..6.0, z in 0.0f64..0.45,
        yaw in -7.0f64..7.0, tilt in -0.4f64..0.4,
    ) {
        let r = robot();
        let pose = NozzlePose { x_m: x, y_m: y, z_m: z, yaw_rad: yaw, tilt_rad: tilt };
        match r.ik(&pose) {
            Ok(all) => {
                for s in &all {
                    prop_assert!(r.check_joints(s).is_ok());
                    prop_assert!(r.fk(s).same_spray(&pose, 1e-9));
                }
            }
            Err(e) => {
                prop_assert!(r.limits.get(&e.joint).is_some(), "{e}");
                prop_assert!(e.excess > 0.0, "{e}");
                prop_assert!(e.value < e.min || e.value > e.max, "{e}");
            }
        }
    }

    #[test]
    fn actuators_round_trip(j in joints_in_limits()) {
        let r = robot();
        let a = r.actuators(&j);
        let back = r.joints_from_actuators(&a).unwrap();
        for (p, q) in back.values().iter().zip(j.values()) {
            prop_assert!((p - q).abs() < 1e-12, "{back:?} vs {j:?}");
        }
        // Cylinder inside its stroke, nut and motor consistent (SPEC §4).
        prop_assert!(a.cylinder_m >= -1e-12 && a.cylinder_m <= 0.457 + 1e-12);
        let per_rad = 2.0 * std::f64::consts::PI * 1.1 / 0.003175;
        prop_assert!((a.tilt_motor_rad - a.tilt_nut_m * per_rad).abs() < 1e-9);
        prop_assert!((a.yaw_motor_rad - 10.0 * j.ee_yaw_rad).abs() < 1e-12);
    }

    #[test]
    fn encoders_round_trip(j in joints_in_limits()) {
        let r = robot();
        let e = r.encoders(&j);
        let back = r.joints_from_encoders(&e).unwrap();
        // Counts → joints → counts is exact.
        prop_assert_eq!(r.encoders(&back), e);
        // Joints → counts → joints is within half a count of each axis.
        let s = r.encoder_scales();
        prop_assert!((back.base_rot_rad - j.base_rot_rad).abs() <= 0.5 * s[0] + 1e-12);
        prop_assert!((back.extension_m - j.extension_m).abs() <= 0.5 * s[1] + 1e-12);
        prop_assert!((back.ee_yaw_rad - j.ee_yaw_rad).abs() <= 0.5 * s[2] + 1e-12);
        prop_assert!((back.vertical_m - j.vertical_m).abs() <= 0.5 * s[4] + 1e-12);
        let nut = |t| r.actuators(&Joints { tilt_rad: t, ..j }).tilt_nut_m;
        prop_assert!((nut(back.tilt_rad) - nut(j.tilt_rad)).abs() <= 0.5 * s[3] + 1e-12);
    }
}

#[test]
fn every_limit_is_refused_by_name() {
    let r = robot();
    let ok = NozzlePose {
        x_m: 0.3,
        y_m: 3.0,
        z_m: 0.2,
        yaw_rad: 0.4,
        tilt_rad: 0.1,
    };
    assert!(r.ik(&ok).is_ok());
    let cases = [
        (NozzlePose { y_m: 1.0, ..ok }, "extension_m"),
        (NozzlePose { y_m: 5.6, ..ok }, "extension_m"),
        (
            NozzlePose {
                x_m: 3.0,
                y_m: 0.3,
                ..ok
            },
            "base_rot_rad",
        ),
        (
            NozzlePose {
                x_m: -3.0,
                y_m: 0.3,
                ..ok
            },
            "base_rot_rad",
        ),
        (NozzlePose { z_m: 0.40, ..ok }, "vertical_m"),
        (NozzlePose { z_m: 0.05, ..ok }, "vertical_m"),
        (
            NozzlePose {
                tilt_rad: 0.3,
                ..ok
            },
            "tilt_rad",
        ),
    ];
    for (pose, joint) in cases {
        let e = r.ik(&pose).unwrap_err();
        assert_eq!(e.joint, joint, "{pose:?}: {e}");
        assert!(e.excess > 0.0);
        assert!(e.to_string().contains(joint));
    }
    // Exceeding by a known amount: 5.6 m straight back.
    let e = r
        .ik(&NozzlePose {
            x_m: 0.0,
            y_m: 5.6,
            tilt_rad: 0.0,
            ..ok
        })
        .unwrap_err();
    let need = (5.6f64 * 5.6 - 1e-4).sqrt();
    // The planned reach: the cylinder's less the stroke margin.
    assert!((e.excess - (need - 5.305416666666667)).abs() < 1e-9, "{e}");
}

#[test]
fn joints_beyond_limits_are_reported_not_clamped() {
    let r = robot();
    let j = Joints {
        base_rot_rad: 2.5,
        extension_m: 3.0,
        vertical_m: 0.1,
        ee_yaw_rad: 0.0,
        tilt_rad: 0.0,
    };
    let e = r.check_joints(&j).unwrap_err();
    assert_eq!(e.joint, "base_rot_rad");
    assert!((e.excess - (2.5 - 2.3562)).abs() < 1e-12);
    // FK still reports where those joints put the tip.
    assert!((r.fk(&j).x_m - r.yaw_axis(2.5, 3.0)[0]).abs() < 1e-15);
}
