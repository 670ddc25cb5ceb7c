//! The telescopic kind: seed 002's 2R+P arm (base rotation θ1, a revolute
//! boom joint θ2, a telescopic stroke d) carrying a levelled painting head
//! with a yaw and a tilt servo. FK is the DH chain of `envelope::Dh`; IK
//! solves eq. 1 (a quartic in d) for every stroke whose torus passes through
//! the wrist point H, then θ2 from eq. 1's cos φ and eq. 4's sin φ, θ1 from
//! the azimuth.
//!
//! The head: its yaw axis stays vertical through H (a levelling link, as on
//! fire-ladder baskets: 002 §1 names firemen's stairs among telescopic
//! arms); the nozzle pivots at H and its tip is `nozzle_m` from H along the
//! spray axis, leaned by the tilt β towards the fan direction ψ.

use serde::{Deserialize, Serialize};

use super::envelope::{real_roots, Dh};
use super::kind::{
    check_pose_finite, electric_problems, expand_turns, keep_closest, servo_counts, sort_dedup,
    ArmKind, Kind, ServoJoint, Q,
};
use super::kinematics::wrap_pi;
use super::{Control, JointLimit, NozzlePose, Paint, Unreachable};

/// A telescopic (2R+P) robot description (`kind = "telescopic"`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Telescopic {
    pub name: String,
    pub kind: Kind,
    pub arm: TelescopicArm,
    pub joints: TelescopicJoints,
    pub paint: Paint,
    pub control: Control,
}

/// DH parameters of 002 §2 and the head.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TelescopicArm {
    /// h1: height of the first frame's origin (on the base axis) over the road.
    pub base_height_m: f64,
    pub a1_m: f64,
    pub alpha1_rad: f64,
    pub h2_m: f64,
    pub a2_m: f64,
    pub alpha2_rad: f64,
    /// H to the nozzle tip along the spray axis.
    pub nozzle_m: f64,
    /// Tip heights over the road the head paints at.
    pub tip_height_min_m: f64,
    pub tip_height_max_m: f64,
}

/// The five joints, named as their setpoint columns.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TelescopicJoints {
    /// θ1 about the vertical base axis.
    pub base_rot_rad: ServoJoint,
    /// θ2, the DH joint angle of the boom about the second axis.
    pub boom_rad: ServoJoint,
    /// d, the telescopic stroke along the boom.
    pub stroke_m: ServoJoint,
    /// Head yaw: ψ − θ1.
    pub ee_yaw_rad: ServoJoint,
    /// β.
    pub tilt_rad: ServoJoint,
}

impl TelescopicJoints {
    pub fn all(&self) -> [&ServoJoint; 5] {
        [
            &self.base_rot_rad,
            &self.boom_rad,
            &self.stroke_m,
            &self.ee_yaw_rad,
            &self.tilt_rad,
        ]
    }
}

pub const JOINT_NAMES: [&str; 5] = [
    "base_rot_rad",
    "boom_rad",
    "stroke_m",
    "ee_yaw_rad",
    "tilt_rad",
];
const REVOLUTE: [bool; 5] = [true, true, false, true, false];

/// Spray axis leaned by β towards ψ: (sin β·cos ψ, sin β·sin ψ, −cos β).
pub(crate) fn spray_axis(yaw: f64, tilt: f64) -> [f64; 3] {
    let (sb, cb) = tilt.sin_cos();
    let (sp, cp) = yaw.sin_cos();
    [sb * cp, sb * sp, -cb]
}

impl Telescopic {
    pub fn dh(&self) -> Dh {
        let a = &self.arm;
        Dh {
            a1: a.a1_m,
            alpha1: a.alpha1_rad,
            h2: a.h2_m,
            a2: a.a2_m,
            alpha2: a.alpha2_rad,
        }
    }

    /// H in the base frame (road level at the origin).
    pub fn wrist(&self, theta1: f64, theta2: f64, d: f64) -> [f64; 3] {
        let p = self.dh().point(theta1, theta2, d);
        [p[0], p[1], p[2] + self.arm.base_height_m]
    }

    /// Every (θ1, θ2, d) that puts H at `h` with d in range (θ turns not
    /// yet chosen); the nearest stroke outside the range when none.
    pub fn wrist_ik(&self, h: [f64; 3]) -> Result<Vec<[f64; 3]>, f64> {
        let r = h[0].hypot(h[1]);
        let z = h[2] - self.arm.base_height_m;
        let q = self.dh().quartic(r, z);
        let l = &self.joints.stroke_m;
        let span = (l.max - l.min).max(1.0);
        let roots = real_roots(&q, l.min - 20.0 * span, l.max + 20.0 * span);
        let inside: Vec<f64> = roots
            .iter()
            .copied()
            .filter(|d| *d >= l.min && *d <= l.max)
            .collect();
        if inside.is_empty() {
            let nearest = roots
                .iter()
                .copied()
                .min_by(|a, b| l.limit().excess(*a).total_cmp(&l.limit().excess(*b)));
            // No torus passes through H at all: report the stroke whose
            // torus comes nearest (the quartic's lowest point).
            return Err(nearest.unwrap_or_else(|| {
                let d = [l.min, l.max];
                let dq = super::envelope::poly_derivative(&q);
                real_roots(&dq, l.min - 20.0 * span, l.max + 20.0 * span)
                    .into_iter()
                    .chain(d)
                    .min_by(|a, b| {
                        super::envelope::poly_eval(&q, *a)
                            .total_cmp(&super::envelope::poly_eval(&q, *b))
                    })
                    .unwrap_or(l.max)
            }));
        }
        Ok(inside
            .into_iter()
            .filter_map(|d| self.arm_at_stroke(h, d))
            .collect())
    }

    /// (θ1, θ2, d) putting H at `h` with stroke `d`, a root of eq. 1 at H
    /// (θ1 wrapped to (−π, π]); None where the stroke's circle degenerates.
    pub fn arm_at_stroke(&self, h: [f64; 3], d: f64) -> Option<[f64; 3]> {
        let k = self.dh();
        let (s1, c1) = k.alpha1.sin_cos();
        let r = h[0].hypot(h[1]);
        let z = h[2] - self.arm.base_height_m;
        let (r2, z2) = k.r2_z2(d);
        let w = k.h2 + z2;
        if r2 <= 0.0 {
            return None;
        }
        // 002 eq. 1: r² + z² − A = 2·a1·r2·cos φ; eq. 4: z = r2·sin φ·sin α1 + w·cos α1.
        let cos = (r * r + z * z - k.coefficients(d).a) / (2.0 * k.a1 * r2);
        let sin = (z - w * c1) / (r2 * s1);
        let phi = sin.atan2(cos);
        let theta2 = phi + (d * k.alpha2.sin()).atan2(k.a2);
        // H across the base axis in the θ1 = 0 frame.
        let u = [k.a1 + r2 * phi.cos(), r2 * phi.sin() * c1 - w * s1];
        let theta1 = wrap_pi(h[1].atan2(h[0]) - u[1].atan2(u[0]));
        Some([theta1, theta2, d])
    }

    pub fn problems(&self) -> Vec<(String, String)> {
        let a = &self.arm;
        let mut out = electric_problems(
            &self.paint,
            &self.control,
            [a.tip_height_min_m, a.tip_height_max_m],
            &JOINT_NAMES,
            self.joints.all(),
            3,
        );
        if self.kind != Kind::Telescopic {
            out.push(("kind".into(), "must be \"telescopic\" here".into()));
        }
        out.extend(super::ranges::outside(super::ranges::rows(
            "arm",
            a,
            super::ranges::TELESCOPIC_ARM,
        )));
        if a.alpha1_rad.sin().abs() < 0.05 {
            out.push((
                "arm.alpha1_rad".into(),
                format!(
                    "sin α1 must not be near 0 (got α1 = {} rad): 002 eq. 1–2 divide by it; a boom joint \
                     parallel to the base axis is a different arm",
                    a.alpha1_rad
                ),
            ));
        }
        let j = &self.joints;
        if j.stroke_m.min < 0.0 {
            out.push((
                "joints.stroke_m.min".into(),
                "a telescopic stroke cannot be negative".into(),
            ));
        }
        if j.tilt_rad.min < -1.2 || j.tilt_rad.max > 1.2 {
            out.push((
                "joints.tilt_rad.max".into(),
                "the tilt range must lie within ±1.2 rad (the nozzle must face the road)".into(),
            ));
        }
        out
    }
}

impl ArmKind for Telescopic {
    fn name(&self) -> &str {
        &self.name
    }
    fn kind(&self) -> Kind {
        Kind::Telescopic
    }
    fn joint_names(&self) -> [&'static str; 5] {
        JOINT_NAMES
    }
    fn limits(&self) -> [JointLimit; 5] {
        self.joints.all().map(ServoJoint::limit)
    }

    fn fk(&self, q: &Q) -> NozzlePose {
        let h = self.wrist(q[0], q[1], q[2]);
        let psi = q[0] + q[3];
        let s = spray_axis(psi, q[4]);
        let l = self.arm.nozzle_m;
        NozzlePose {
            x_m: h[0] + l * s[0],
            y_m: h[1] + l * s[1],
            z_m: h[2] + l * s[2],
            yaw_rad: wrap_pi(psi),
            tilt_rad: q[4],
        }
    }

    fn ik(&self, pose: &NozzlePose) -> Result<Vec<Q>, Unreachable> {
        check_pose_finite(pose)?;
        let limits = self.limits();
        let mut found = Vec::new();
        let mut closest = None;
        // The fan paints the same as (ψ, β) and (ψ + π, −β) (SPEC §2); both
        // lean the spray axis the same way, so H is the same.
        let s = spray_axis(pose.yaw_rad, pose.tilt_rad);
        let l = self.arm.nozzle_m;
        let h = [
            pose.x_m - l * s[0],
            pose.y_m - l * s[1],
            pose.z_m - l * s[2],
        ];
        match self.wrist_ik(h) {
            Err(d) => keep_closest(&mut closest, Unreachable::of("stroke_m", &limits[2], d)),
            Ok(arms) => {
                for [t1, t2, d] in arms {
                    for (psi, beta) in [
                        (pose.yaw_rad, pose.tilt_rad),
                        (pose.yaw_rad + std::f64::consts::PI, 0.0 - pose.tilt_rad),
                    ] {
                        let q = [t1, t2, d, wrap_pi(psi - t1), beta];
                        expand_turns(
                            q,
                            &JOINT_NAMES,
                            &limits,
                            &REVOLUTE,
                            &mut found,
                            &mut closest,
                        );
                    }
                }
            }
        }
        if found.is_empty() {
            return Err(
                closest.unwrap_or_else(|| Unreachable::of("stroke_m", &limits[2], f64::NAN))
            );
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
        self.wrist(q[0], q[1], q[2])
    }
    fn section_joints(&self) -> [usize; 2] {
        [1, 2]
    }
    fn problems(&self) -> Vec<(String, String)> {
        Telescopic::problems(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kind::TELESCOPIC_TOML;
    use crate::AnyRobot;
    use proptest::prelude::*;

    fn shipped() -> Telescopic {
        match AnyRobot::from_toml_str(TELESCOPIC_TOML, "shipped").unwrap() {
            AnyRobot::Telescopic(t) => t,
            _ => unreachable!(),
        }
    }

    proptest! {
        /// FK∘IK = identity for every solution, over the joint space.
        #[test]
        fn fk_of_every_ik_solution_is_the_pose(u in proptest::array::uniform5(0.0f64..1.0)) {
            let r = shipped();
            let lim = r.limits();
            let q: Q = std::array::from_fn(|k| lim[k].min + u[k] * (lim[k].max - lim[k].min));
            let pose = r.fk(&q);
            let all = r.ik(&pose).unwrap();
            prop_assert!(all.iter().any(|s| s.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-6)),
                "{q:?} not among {all:?}");
            for s in &all {
                let p = r.fk(s);
                prop_assert!(p.same_spray(&pose, 1e-7), "{p:?} vs {pose:?}");
                for (k, l) in r.limits().iter().enumerate() {
                    prop_assert!(l.contains(s[k]));
                }
            }
        }
    }

    #[test]
    fn a_point_beyond_the_boom_names_the_stroke() {
        let r = shipped();
        let pose = NozzlePose {
            x_m: 0.0,
            y_m: 30.0,
            z_m: 0.2,
            yaw_rad: 0.0,
            tilt_rad: 0.0,
        };
        let e = r.ik(&pose).unwrap_err();
        assert_eq!(e.joint, "stroke_m");
        assert!(e.value > r.joints.stroke_m.max);
    }
}
