//! The articulated kind: seed 003's 5-axis arm — waist θ1 about the
//! vertical, shoulder θ2, elbow θ3 and pitch θ4 about parallel horizontal
//! axes, and the tilt θ5 that turns the spray gun about its own axis.
//!
//! Geometry (003 §2.3's steps): the shoulder sits `shoulder_height_m` over
//! the road and `shoulder_offset_m` (003's |AB|) across the arm's plane;
//! upper arm l2, forearm l3 to the pitch axis (the wrist P), then the gun
//! l4 to the nozzle tip along the spray axis t, at angle φ = θ2 + θ3 + θ4
//! from the horizontal in the arm's plane. The fan's long axis is
//! f = cos θ5·e⊥ + sin θ5·n (e⊥ across the arm's plane, n in it, normal
//! to t): with the gun pointing down, ψ = θ1 + π/2 − θ5.
//!
//! IK as 003: θ1 from the wrist's plan position and the offset (two
//! solutions, the second "θ1 = θ_AC − ∠BAC − 90" reaching back, its
//! p_wx < 0), θ2, θ3 as a planar two-link arm (elbow up and down), θ4 and
//! θ5 from the gun's frame. A tilted fan (β ≠ 0) needs the gun to lean in
//! the arm's plane, so the fan must point along it; other tilted poses are
//! out of reach.

use std::f64::consts::FRAC_PI_2;

use serde::{Deserialize, Serialize};

use super::kind::{
    check_pose_finite, electric_problems, expand_turns, keep_closest, servo_counts, sort_dedup,
    ArmKind, Kind, ServoJoint, Q,
};
use super::kinematics::wrap_pi;
use super::{Control, JointLimit, NozzlePose, Paint, Unreachable};

/// An articulated 5-axis robot description (`kind = "articulated"`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Articulated {
    pub name: String,
    pub kind: Kind,
    pub arm: ArticulatedArm,
    pub joints: ArticulatedJoints,
    pub paint: Paint,
    pub control: Control,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArticulatedArm {
    pub shoulder_height_m: f64,
    /// 003's |AB|: the shoulder's offset across the arm's plane.
    pub shoulder_offset_m: f64,
    pub upper_arm_m: f64,
    pub forearm_m: f64,
    /// Pitch axis to the nozzle tip.
    pub gun_m: f64,
    pub tip_height_min_m: f64,
    pub tip_height_max_m: f64,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArticulatedJoints {
    pub waist_rad: ServoJoint,
    pub shoulder_rad: ServoJoint,
    pub elbow_rad: ServoJoint,
    pub pitch_rad: ServoJoint,
    /// 003's "tilt": the gun's turn about its own axis, which turns the fan.
    pub gun_tilt_rad: ServoJoint,
}

impl ArticulatedJoints {
    pub fn all(&self) -> [&ServoJoint; 5] {
        [
            &self.waist_rad,
            &self.shoulder_rad,
            &self.elbow_rad,
            &self.pitch_rad,
            &self.gun_tilt_rad,
        ]
    }
}

pub const JOINT_NAMES: [&str; 5] = [
    "waist_rad",
    "shoulder_rad",
    "elbow_rad",
    "pitch_rad",
    "gun_tilt_rad",
];

/// The gun's frame: tip, spray axis t and fan axis f (003's "arm matrix").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GunFrame {
    pub tip: [f64; 3],
    pub spray: [f64; 3],
    pub fan: [f64; 3],
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn axpy(a: f64, x: [f64; 3], y: [f64; 3]) -> [f64; 3] {
    [a * x[0] + y[0], a * x[1] + y[1], a * x[2] + y[2]]
}

/// Radial and across directions of the arm's plane at waist θ1.
fn plane(theta1: f64) -> ([f64; 3], [f64; 3]) {
    let (s, c) = theta1.sin_cos();
    ([c, s, 0.0], [-s, c, 0.0])
}

impl Articulated {
    /// Forward kinematics to the gun's frame.
    pub fn frame(&self, q: &Q) -> GunFrame {
        let a = &self.arm;
        let (er, ep) = plane(q[0]);
        let dir = |ang: f64| axpy(ang.cos(), er, [0.0, 0.0, ang.sin()]);
        let s = axpy(a.shoulder_offset_m, ep, [0.0, 0.0, a.shoulder_height_m]);
        let e = axpy(a.upper_arm_m, dir(q[1]), s);
        let p = axpy(a.forearm_m, dir(q[1] + q[2]), e);
        let phi = q[1] + q[2] + q[3];
        let t = dir(phi);
        let n = axpy(-phi.sin(), er, [0.0, 0.0, phi.cos()]);
        GunFrame {
            tip: axpy(a.gun_m, t, p),
            spray: t,
            fan: axpy(
                q[4].cos(),
                ep,
                [q[4].sin() * n[0], q[4].sin() * n[1], q[4].sin() * n[2]],
            ),
        }
    }

    /// Every joint set (before turns and limits) giving the gun frame, and
    /// why candidates failed. Up to four: two waist solutions (003) × elbow
    /// up and down.
    pub fn frame_ik(&self, g: &GunFrame) -> (Vec<Q>, Option<Unreachable>) {
        let a = &self.arm;
        let w = axpy(-a.gun_m, g.spray, g.tip);
        let rho = w[0].hypot(w[1]);
        let ang = w[1].atan2(w[0]);
        let mut out = Vec::new();
        let mut closest = None;
        let reach = |v: f64| Unreachable {
            joint: "reach_m".into(),
            value: v,
            min: (a.upper_arm_m - a.forearm_m).abs(),
            max: a.upper_arm_m + a.forearm_m,
            excess: JointLimit {
                min: (a.upper_arm_m - a.forearm_m).abs(),
                max: a.upper_arm_m + a.forearm_m,
                max_vel: 1.0,
                max_acc: 1.0,
            }
            .excess(v),
            flipped: false,
        };
        if rho < a.shoulder_offset_m.abs() {
            keep_closest(&mut closest, reach(0.0));
            return (out, closest);
        }
        let off = (a.shoulder_offset_m / rho).asin();
        // 003 step 2: θ1 = ∠BAC + θ_AC − 90° and, reaching back, θ_AC − ∠BAC − 90°.
        for theta1 in [ang - off, ang - std::f64::consts::PI + off] {
            let (er, ep) = plane(theta1);
            let across = dot(g.spray, ep);
            if across.abs() > 1e-9 {
                keep_closest(
                    &mut closest,
                    Unreachable {
                        joint: "lean_across_arm_rad".into(),
                        value: across.asin(),
                        min: 0.0,
                        max: 0.0,
                        excess: across.asin().abs(),
                        flipped: false,
                    },
                );
                continue;
            }
            let x = dot(w, er);
            let z = w[2] - a.shoulder_height_m;
            let (l2, l3) = (a.upper_arm_m, a.forearm_m);
            let cos3 = (x * x + z * z - l2 * l2 - l3 * l3) / (2.0 * l2 * l3);
            if !(-1.0..=1.0).contains(&cos3) {
                keep_closest(&mut closest, reach(x.hypot(z)));
                continue;
            }
            let phi = g.spray[2].atan2(dot(g.spray, er));
            let n = axpy(-phi.sin(), er, [0.0, 0.0, phi.cos()]);
            let theta5 = dot(g.fan, n).atan2(dot(g.fan, ep));
            // 003 step 3: a planar two-axis arm, elbow both ways.
            for theta3 in [cos3.acos(), -cos3.acos()] {
                let theta2 = z.atan2(x) - (l3 * theta3.sin()).atan2(l2 + l3 * theta3.cos());
                let theta4 = phi - theta2 - theta3;
                out.push([
                    wrap_pi(theta1),
                    wrap_pi(theta2),
                    wrap_pi(theta3),
                    wrap_pi(theta4),
                    wrap_pi(theta5),
                ]);
            }
        }
        (out, closest)
    }

    pub fn problems(&self) -> Vec<(String, String)> {
        let a = &self.arm;
        let mut out = electric_problems(
            &self.paint,
            &self.control,
            [a.tip_height_min_m, a.tip_height_max_m],
            &JOINT_NAMES,
            self.joints.all(),
            4,
        );
        if self.kind != Kind::Articulated {
            out.push(("kind".into(), "must be \"articulated\" here".into()));
        }
        out.extend(super::ranges::outside(super::ranges::rows(
            "arm",
            a,
            super::ranges::ARTICULATED_ARM,
        )));
        out
    }
}

impl ArmKind for Articulated {
    fn name(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> Kind {
        Kind::Articulated
    }
    fn joint_names(&self) -> [&'static str; 5] {
        JOINT_NAMES
    }
    fn limits(&self) -> [JointLimit; 5] {
        self.joints.all().map(ServoJoint::limit)
    }

    fn fk(&self, q: &Q) -> NozzlePose {
        let g = self.frame(q);
        let yaw = g.fan[1].atan2(g.fan[0]);
        let lean = g.spray[0] * yaw.cos() + g.spray[1] * yaw.sin();
        NozzlePose {
            x_m: g.tip[0],
            y_m: g.tip[1],
            z_m: g.tip[2],
            yaw_rad: wrap_pi(yaw),
            tilt_rad: lean.clamp(-1.0, 1.0).asin(),
        }
    }

    fn ik(&self, pose: &NozzlePose) -> Result<Vec<Q>, Unreachable> {
        check_pose_finite(pose)?;
        let limits = self.limits();
        let mut found = Vec::new();
        let mut closest = None;
        let spray = super::telescopic::spray_axis(pose.yaw_rad, pose.tilt_rad);
        let (sb, cb) = pose.tilt_rad.sin_cos();
        let (sp, cp) = pose.yaw_rad.sin_cos();
        // The fan axis normal to the spray axis, along ψ; its opposite (the
        // fan flipped, ψ + π with −β) paints the same.
        for sign in [1.0, -1.0] {
            let g = GunFrame {
                tip: [pose.x_m, pose.y_m, pose.z_m],
                spray,
                fan: [sign * cb * cp, sign * cb * sp, sign * sb],
            };
            let (cands, why) = self.frame_ik(&g);
            if let Some(u) = why {
                keep_closest(&mut closest, u);
            }
            for q in cands {
                expand_turns(
                    q,
                    &JOINT_NAMES,
                    &limits,
                    &[true; 5],
                    &mut found,
                    &mut closest,
                );
            }
        }
        if found.is_empty() {
            return Err(closest.unwrap_or_else(|| Unreachable::not_finite("reach_m", f64::NAN)));
        }
        sort_dedup(&mut found);
        Ok(found)
    }

    fn encoders(&self, q: &Q) -> [i64; 5] {
        servo_counts(self.joints.all(), q)
    }
    fn joints_from_encoders(&self, counts: &[i64; 5]) -> Result<Q, Unreachable> {
        Ok(crate::kind::servo_joints(self.joints.all(), counts))
    }
    fn tip_heights_m(&self) -> [f64; 2] {
        [self.arm.tip_height_min_m, self.arm.tip_height_max_m]
    }
    fn reference_point(&self, q: &Q) -> [f64; 3] {
        let g = self.frame(q);
        axpy(-self.arm.gun_m, g.spray, g.tip)
    }
    fn section_joints(&self) -> [usize; 2] {
        [1, 2]
    }
    fn problems(&self) -> Vec<(String, String)> {
        Articulated::problems(self)
    }
}

/// Gun pointing straight down: φ = −π/2.
pub const DOWN: f64 = -FRAC_PI_2;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kind::ARTICULATED_TOML;
    use crate::AnyRobot;
    use proptest::prelude::*;

    fn shipped() -> Articulated {
        match AnyRobot::from_toml_str(ARTICULATED_TOML, "shipped").unwrap() {
            AnyRobot::Articulated(t) => t,
            _ => unreachable!(),
        }
    }

    fn close(a: &GunFrame, b: &GunFrame, tol: f64) -> bool {
        (0..3).all(|k| {
            (a.tip[k] - b.tip[k]).abs() < tol
                && (a.spray[k] - b.spray[k]).abs() < tol
                && (a.fan[k] - b.fan[k]).abs() < tol
        })
    }

    /// 003 §2.3: [−170 50 −45 20 −30]° and [−170 20.7 45 −40.7 −30]° give
    /// the same arm matrix. The seed gives no link lengths; the flip keeps
    /// θ2 + θ3 + θ4 and moves θ2 by 2·atan2(l3 sin θ3, l2 + l3 cos θ3),
    /// which is 29.3° (50 → 20.7) for l3/l2 = 0.5: the shipped arm's
    /// 3.2 m and 1.6 m.
    #[test]
    fn seed_003_example_both_solutions_shorter_chosen() {
        let mut r = shipped();
        assert_eq!(r.arm.forearm_m / r.arm.upper_arm_m, 0.5);
        // 003's arm turns its joints fully (its 360° joints).
        for j in [
            &mut r.joints.waist_rad,
            &mut r.joints.shoulder_rad,
            &mut r.joints.elbow_rad,
            &mut r.joints.pitch_rad,
            &mut r.joints.gun_tilt_rad,
        ] {
            j.min = -std::f64::consts::PI;
            j.max = std::f64::consts::PI;
        }
        let q = [-170.0f64, 50.0, -45.0, 20.0, -30.0].map(f64::to_radians);
        let g = r.frame(&q);
        let (sols, _) = r.frame_ik(&g);
        let deg = |s: &Q| s.map(f64::to_degrees);
        let has = |target: [f64; 5], tol: f64| {
            sols.iter()
                .any(|s| deg(s).iter().zip(target).all(|(a, b)| (a - b).abs() < tol))
        };
        assert!(
            has([-170.0, 50.0, -45.0, 20.0, -30.0], 1e-9),
            "{:?}",
            sols.iter().map(deg).collect::<Vec<_>>()
        );
        // The seed prints one decimal.
        assert!(has([-170.0, 20.7, 45.0, -40.7, -30.0], 0.05));
        for s in &sols {
            assert!(close(&r.frame(s), &g, 1e-9));
        }
        // Of the seed's two, the second travels less from the rest
        // position (all joints at 0; every joint 1 rad/s): 170° either way
        // at the waist, then 306.4° against 315° in all.
        let pair: Vec<Q> = sols
            .iter()
            .copied()
            .filter(|s| (s[0] - q[0]).abs() < 1e-9)
            .collect();
        assert_eq!(pair.len(), 2);
        let limits = r.limits().map(|l| JointLimit { max_vel: 1.0, ..l });
        let i = crate::kind::shortest_travel(&pair, &[0.0; 5], &limits).unwrap();
        assert!((pair[i][1].to_degrees() - 20.7).abs() < 0.05);
    }

    proptest! {
        /// FK∘IK = identity for every solution, over the painting poses:
        /// gun down (any fan direction) or leaned along the arm.
        #[test]
        fn fk_of_every_ik_solution_is_the_pose(u in proptest::array::uniform5(0.0f64..1.0), lean in -0.2f64..0.2, tilted in any::<bool>()) {
            let r = shipped();
            let lim = r.limits();
            let mut q: Q = std::array::from_fn(|k| lim[k].min + u[k] * (lim[k].max - lim[k].min));
            // Pitch from the other joints so the gun points down (or leans
            // in the arm's plane with the fan along it).
            q[3] = DOWN + if tilted { lean } else { 0.0 } - q[1] - q[2];
            if tilted {
                q[4] = FRAC_PI_2;
            }
            prop_assume!(lim[3].contains(q[3]));
            let pose = r.fk(&q);
            let all = r.ik(&pose).unwrap();
            prop_assert!(all.iter().any(|s| s.iter().zip(&q).all(|(a, b)| (wrap_pi(a - b)).abs() < 1e-6)),
                "{q:?} not among {all:?}");
            for s in &all {
                let p = r.fk(s);
                prop_assert!(p.same_spray(&pose, 1e-7), "{p:?} vs {pose:?}");
            }
        }
    }

    #[test]
    fn tilt_across_the_arm_is_refused_with_its_reason() {
        let r = shipped();
        let q = [FRAC_PI_2, 0.3, -1.0, DOWN + 0.7, 0.0];
        let mut pose = r.fk(&q);
        pose.tilt_rad = 0.2;
        // Fan along the arm's plane? ψ = θ1 + π/2 − θ5 = π: across the arm.
        let e = r.ik(&pose).unwrap_err();
        assert_eq!(e.joint, "lean_across_arm_rad", "{e}");
    }
}
