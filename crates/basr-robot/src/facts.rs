//! What the planner asks a robot of any kind, each fact named for what it
//! is rather than for the kind that has it: how fast the fan's tilt may
//! turn, whether only the fan joint can jump between IK solutions, how long
//! an air move between two nozzle poses takes, how far a tilt lifts the
//! tip, what a setpoint row holds of a joint set and the kind's own check
//! of a sampled joint path.
//!
//! Each kind answers on [`crate::ArmKind`]: the electric kinds by the trait's
//! defaults, BASR with its ball nut, tilt four-bar and the job's own joint
//! columns. The answers that need the fan and tilt joints are on
//! [`AnyRobot`]. So the planner never asks which kind a robot is.

use std::f64::consts::PI;

use super::kind::{AnyRobot, Q};
use super::kinematics::wrap_pi;
use super::{Actuators, Encoders, JointLimit, Joints, Robot};

/// Tip speed and acceleration of an electric arm's air moves along its
/// reach, for ordering only. assumed: 0.5 m/s and 0.5 m/s², the shipped
/// arms' boom and stroke limits (robots/telescopic.toml).
const SERVO_TIP_SPEED_MPS: f64 = 0.5;
const SERVO_TIP_ACC_MPS2: f64 = 0.5;

/// One end of an air move, as the tour's ordering prices it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AirEnd {
    /// The tip's azimuth about the base axis (base frame, rad).
    pub azimuth_rad: f64,
    /// The tip's distance from the base axis (m).
    pub radius_m: f64,
    /// The fan's direction ψ, in any frame fixed to the base (only
    /// differences count).
    pub yaw_rad: f64,
    /// The fan's tilt β.
    pub tilt_rad: f64,
}

/// What a setpoint row holds of one joint set ([`crate::ArmKind::row_joints`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RowJoints {
    /// The job's own joint, actuator and encoder columns: BASR's joints
    /// are the columns every job has.
    Spec {
        joints: Joints,
        actuators: Actuators,
        encoders: Encoders,
    },
    /// The kind's own joint and encoder columns, written after the job's
    /// (whose joint, actuator and encoder columns then stay 0; see
    /// docs/robot-kinds.md).
    Own { q: Q, encoders: [i64; 5] },
}

/// A sampled joint path that breaks the kind's own limits
/// ([`crate::ArmKind::check_sampled`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}", self.describe())]
pub struct SampledFault {
    /// The setpoint (from 0) the fault is at, when one is to blame.
    pub setpoint: Option<usize>,
    /// What is wrong, with the joint, its value and its limit.
    pub what: String,
}

impl SampledFault {
    fn describe(&self) -> String {
        match self.setpoint {
            Some(k) => format!("setpoint {k}: {}", self.what),
            None => self.what.clone(),
        }
    }
}

/// Encoder column name of a joint: `enc_` and the joint name without its
/// unit (`boom_rad` → `enc_boom`).
pub(crate) fn encoder_name(joint: &str) -> String {
    let stem = joint
        .strip_suffix("_rad")
        .or_else(|| joint.strip_suffix("_m"))
        .unwrap_or(joint);
    format!("enc_{stem}")
}

/// A servo kind's check of a sampled joint path: each joint's range, and
/// its speed and acceleration by finite differences (as `basr check`
/// measures them), up to a relative 1e-9 (rounding).
pub(crate) fn check_servo_path(
    names: &[&str; 5],
    limits: &[JointLimit; 5],
    qs: &[Q],
    period_s: f64,
) -> Result<(), SampledFault> {
    let over = |v: f64, lim: f64| v.abs() > lim * (1.0 + 1e-9);
    let fail = |k: usize, what: String| {
        Err(SampledFault {
            setpoint: Some(k),
            what,
        })
    };
    for (j, l) in limits.iter().enumerate() {
        let name = names[j];
        let q: Vec<f64> = qs.iter().map(|p| p[j]).collect();
        for (k, &v) in q.iter().enumerate() {
            if !(v.is_finite() && l.contains(v)) {
                return fail(
                    k,
                    format!("{name} = {v} leaves its range [{}, {}]", l.min, l.max),
                );
            }
        }
        for k in 1..q.len() {
            let v = (q[k] - q[k - 1]) / period_s;
            if over(v, l.max_vel) {
                return fail(k, format!("{name} moves at {v}/s, over its {}", l.max_vel));
            }
            if k + 1 < q.len() {
                let a = (q[k + 1] - 2.0 * q[k] + q[k - 1]) / (period_s * period_s);
                if over(a, l.max_acc) {
                    return fail(
                        k,
                        format!("{name} accelerates at {a}/s², over its {}", l.max_acc),
                    );
                }
            }
        }
    }
    Ok(())
}

/// Time to move `d` from rest to rest at speed limit `v` and acceleration `acc`.
fn rest_to_rest(d: f64, v: f64, acc: f64) -> f64 {
    let d = d.abs();
    if d * acc <= v * v {
        2.0 * (d / acc).sqrt()
    } else {
        d / v + v / acc
    }
}

impl Robot {
    /// BASR's tilt-rate limit from its ball nut (SPEC §4: the nut's speed
    /// limit over the steepest nut travel per radian of the tilt range);
    /// infinite when the four-bar gives no nut rate.
    pub fn nut_limited_tilt_rate(&self) -> f64 {
        let t = &self.limits.tilt_rad;
        let fb = &self.end_effector.fourbar;
        let steepest = (0..=60)
            .filter_map(|k| fb.nut_rate_m_per_rad(t.min + (t.max - t.min) * k as f64 / 60.0))
            .map(f64::abs)
            .fold(0.0, f64::max);
        if steepest > 0.0 {
            // 1 % below, for the nut rate between the sampled tilts.
            self.end_effector.tilt_nut_max_speed_mps / (steepest * 1.01)
        } else {
            f64::INFINITY
        }
    }

    /// BASR's air-move estimate: the slowest of base rotation, extension,
    /// and the fan's yaw and tilt joints (on whichever fan branch, (ψ, β)
    /// or (ψ+π, −β), turns them least), each accelerating and braking at
    /// its limit (symmetric, as the ordering needs).
    fn basr_air_time(&self, a: &AirEnd, b: &AirEnd) -> f64 {
        let (ta, ra) = (a.azimuth_rad, a.radius_m);
        let (tb, rb) = (b.azimuth_rad, b.radius_m);
        let l = &self.limits;
        let t = rest_to_rest;
        // The yaw joint turns ψ less the base rotation (ψ = θ1 + yaw joint).
        let turn = wrap_pi((b.yaw_rad - a.yaw_rad) - (tb - ta));
        let fan = |dyaw: f64, dtilt: f64| {
            t(dyaw, l.ee_yaw_rad.max_vel, l.ee_yaw_rad.max_acc).max(t(
                dtilt,
                l.tilt_rad.max_vel,
                l.tilt_rad.max_acc,
            ))
        };
        let same = fan(turn, b.tilt_rad - a.tilt_rad);
        let flipped = fan(wrap_pi(turn + PI), b.tilt_rad + a.tilt_rad);
        t(tb - ta, l.base_rot_rad.max_vel, l.base_rot_rad.max_acc)
            .max(t(rb - ra, l.extension_m.max_vel, l.extension_m.max_acc))
            .max(same.min(flipped))
    }
}

impl AnyRobot {
    /// The kind's own sample columns ([`crate::ArmKind::own_sample_columns`]).
    pub fn own_sample_columns(&self) -> Vec<String> {
        self.arm().own_sample_columns()
    }

    /// What a setpoint row holds of the joints `q` ([`crate::ArmKind::row_joints`]).
    pub fn row_joints(&self, q: &Q) -> RowJoints {
        self.arm().row_joints(q)
    }

    /// The kind's own check of a sampled joint path
    /// ([`crate::ArmKind::check_sampled`]).
    pub fn check_sampled(&self, qs: &[Q], period_s: f64) -> Result<(), SampledFault> {
        self.arm().check_sampled(qs, period_s)
    }

    /// Speed caps the joints' drives add to their limits
    /// ([`crate::ArmKind::drive_speed_caps`]).
    pub fn drive_speed_caps(&self) -> [f64; 5] {
        self.arm().drive_speed_caps()
    }

    /// Whether only the fan joint can jump between IK solutions
    /// ([`crate::ArmKind::fan_joint_alone_jumps`]).
    pub fn fan_joint_alone_jumps(&self) -> bool {
        self.arm().fan_joint_alone_jumps()
    }

    /// How far a tilt of ±`tilt_rad` lifts the tip ([`crate::ArmKind::tilt_lift_m`]).
    pub fn tilt_lift_m(&self, tilt_rad: f64) -> f64 {
        self.arm().tilt_lift_m(tilt_rad)
    }

    /// The fastest the fan's tilt may turn (rad/s): its joint's speed
    /// limit, capped by what its drive allows (BASR's ball nut,
    /// [`crate::ArmKind::drive_speed_caps`]); `None` for a kind that paints with
    /// the fan untilted ([`AnyRobot::tilt_limit`]).
    ///
    /// ```
    /// use basr_robot::{AnyRobot, Robot};
    /// let basr = Robot::basr();
    /// let v = AnyRobot::Basr(basr.clone()).tilt_speed_limit().unwrap();
    /// // BASR's ball nut holds the tilt below its joint's own limit.
    /// assert!(v <= basr.limits.tilt_rad.max_vel);
    /// assert_eq!(v, basr.limits.tilt_rad.max_vel.min(basr.nut_limited_tilt_rate()));
    /// ```
    pub fn tilt_speed_limit(&self) -> Option<f64> {
        let own = self.tilt_limit()?;
        // Every kind that tilts the fan has its tilt as joint 4 (BASR's and
        // the telescopic head's `tilt_rad`).
        Some(own.max_vel.min(self.drive_speed_caps()[4]))
    }

    /// Estimated time (s) of an air move of the arm between two nozzle
    /// poses, for ordering a station's passes: the slowest joint, each
    /// from rest to rest at its limits, on whichever fan branch turns the
    /// fan least. BASR prices its own joints; an electric kind its base
    /// joint (the tip's azimuth), the tip's move towards or away from the
    /// base axis, the fan joint and the tilt (joint-path optimisation
    /// prices the true joints later).
    ///
    /// ```
    /// use basr_robot::{facts::AirEnd, AnyRobot, Robot};
    /// let r = AnyRobot::Basr(Robot::basr());
    /// let a = AirEnd { azimuth_rad: 0.0, radius_m: 2.0, yaw_rad: 0.0, tilt_rad: 0.0 };
    /// let near = AirEnd { radius_m: 2.1, ..a };
    /// let far = AirEnd { radius_m: 3.0, ..a };
    /// assert_eq!(r.air_time_estimate(&a, &a), 0.0);
    /// assert!(r.air_time_estimate(&a, &near) < r.air_time_estimate(&a, &far));
    /// ```
    pub fn air_time_estimate(&self, a: &AirEnd, b: &AirEnd) -> f64 {
        match self {
            AnyRobot::Basr(r) => r.basr_air_time(a, b),
            _ => self.servo_air_time(a, b),
        }
    }

    /// An electric kind's air-move estimate ([`AnyRobot::air_time_estimate`]).
    fn servo_air_time(&self, a: &AirEnd, b: &AirEnd) -> f64 {
        let (ta, ra) = (a.azimuth_rad, a.radius_m);
        let (tb, rb) = (b.azimuth_rad, b.radius_m);
        let l = self.limits();
        let t = |d: f64, l: &JointLimit| rest_to_rest(d, l.max_vel, l.max_acc);
        let fan = &l[self.fan_joint()];
        // Both kinds turn the fan by the base rotation plus (or less) the fan joint.
        let turn = wrap_pi((b.yaw_rad - a.yaw_rad) - (tb - ta));
        let tilt = |d: f64| self.tilt_limit().map_or(0.0, |tl| t(d, &tl));
        let same = t(turn, fan).max(tilt(b.tilt_rad - a.tilt_rad));
        let flipped = t(wrap_pi(turn + PI), fan).max(tilt(b.tilt_rad + a.tilt_rad));
        t(tb - ta, &l[0])
            .max(rest_to_rest(
                rb - ra,
                SERVO_TIP_SPEED_MPS,
                SERVO_TIP_ACC_MPS2,
            ))
            .max(same.min(flipped))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kind::{ARTICULATED_TOML, TELESCOPIC_TOML};

    fn electric() -> Vec<AnyRobot> {
        [TELESCOPIC_TOML, ARTICULATED_TOML]
            .iter()
            .map(|t| AnyRobot::from_toml_str(t, "shipped").unwrap())
            .collect()
    }

    #[test]
    fn only_basr_caps_its_tilt_by_the_nut() {
        let b = Robot::basr();
        let nut = b.nut_limited_tilt_rate();
        // SPEC §4's 0.11 m/s nut limit binds below the tilt joint's own.
        assert!(nut.is_finite() && nut < b.limits.tilt_rad.max_vel, "{nut}");
        let caps = AnyRobot::Basr(b.clone()).drive_speed_caps();
        assert_eq!(caps[4], nut);
        assert!(caps[..4].iter().all(|c| c.is_infinite()));
        for r in electric() {
            assert!(r.drive_speed_caps().iter().all(|c| c.is_infinite()));
            assert_eq!(
                r.tilt_speed_limit(),
                r.tilt_limit().map(|l| l.max_vel),
                "{}",
                r.name()
            );
        }
    }

    #[test]
    fn only_basr_lifts_a_tilted_tip_and_jumps_at_the_fan_alone() {
        let b = AnyRobot::Basr(Robot::basr());
        assert!(b.fan_joint_alone_jumps());
        // The four-bar lifts the tip at a tilt, and not untilted.
        assert!(b.tilt_lift_m(0.2) > 0.0);
        assert!(b.tilt_lift_m(0.2) > b.tilt_lift_m(0.0));
        for r in electric() {
            assert!(!r.fan_joint_alone_jumps());
            assert_eq!(r.tilt_lift_m(0.2), 0.0);
        }
    }

    #[test]
    fn rows_write_basr_in_the_job_columns_and_others_in_their_own() {
        let basr = Robot::basr();
        let b = AnyRobot::Basr(basr.clone());
        assert!(b.own_sample_columns().is_empty());
        let q = b.stow();
        let j = Joints::of(&q);
        assert_eq!(
            b.row_joints(&q),
            RowJoints::Spec {
                joints: j,
                actuators: basr.actuators(&j),
                encoders: basr.encoders(&j),
            }
        );
        let t = AnyRobot::from_toml_str(TELESCOPIC_TOML, "t").unwrap();
        let cols = t.own_sample_columns();
        assert_eq!(cols.len(), 10);
        assert_eq!(cols[2], "stroke_m");
        assert_eq!(cols[7], "enc_stroke");
        let q = t.stow();
        assert_eq!(
            t.row_joints(&q),
            RowJoints::Own {
                q,
                encoders: t.encoders(&q)
            }
        );
    }

    #[test]
    fn sampled_checks_name_the_setpoint_and_joint() {
        for r in electric() {
            let q = r.stow();
            assert_eq!(r.check_sampled(&[q, q, q], 0.01), Ok(()));
            let mut fast = q;
            fast[0] += 1.0; // 100 rad/s at 10 ms: over any joint's limit.
            let e = r.check_sampled(&[q, fast], 0.01).unwrap_err();
            assert_eq!(e.setpoint, Some(1));
            assert!(e.what.contains(r.joint_names()[0]), "{e}");
            let mut out = q;
            out[2] = r.limits()[2].max + 1.0;
            let e = r.check_sampled(&[q, out], 0.01).unwrap_err();
            assert_eq!(e.to_string().split(':').next(), Some("setpoint 1"), "{e}");
        }
        let b = AnyRobot::Basr(Robot::basr());
        let q = b.stow();
        let mut fast = q;
        fast[0] += 1.0;
        let e = b.check_sampled(&[q, fast], 0.01).unwrap_err();
        assert_eq!(e.setpoint, None, "{e}");
        assert!(e.what.contains("base_rot_rad speed"), "{e}");
    }

    #[test]
    fn air_time_takes_the_cheaper_fan_branch() {
        for r in [vec![AnyRobot::Basr(Robot::basr())], electric()].concat() {
            let a = AirEnd {
                azimuth_rad: 0.0,
                radius_m: 2.0,
                yaw_rad: 0.0,
                tilt_rad: 0.0,
            };
            // A half turn of the fan paints the same as none (ψ+π, −β).
            let half = AirEnd { yaw_rad: PI, ..a };
            assert_eq!(r.air_time_estimate(&a, &half), 0.0, "{}", r.name());
            let quarter = AirEnd {
                yaw_rad: 0.5 * PI,
                ..a
            };
            assert!(r.air_time_estimate(&a, &quarter) > 0.0, "{}", r.name());
        }
    }
}
