//! Forward and inverse kinematics of BASR in the base frame (SPEC §2):
//! nozzle pose ↔ joints, and joints ↔ actuators ↔ encoder counts.
//!
//! Chain: base rotation θ1 and extension R place the yaw axis at
//! W = R·(cos θ1, sin θ1) + a2·(sin θ1, −cos θ1) (SPEC §2; 000 app. B eq.
//! 2.21–2.26); the yaw joint turns the end-effector to fan direction
//! ψ_B = θ1 + yaw; the vertical joint lowers it (0 = top, positive down); the
//! tilt four-bar tilts the nozzle by β in the fan's plane and moves the tip
//! by the linkage's exact tip offset (along ψ_B, up). The seed compensates the
//! height with d3 = (r2/2)·sin θ2e (000 app. B eq. 3.16); here the vertical
//! joint takes the exact vertical tip offset instead.

use std::f64::consts::{PI, TAU};

use serde::{Deserialize, Serialize};

use super::{JointLimit, Robot};

/// Nozzle tip pose in the base frame B.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct NozzlePose {
    pub x_m: f64,
    pub y_m: f64,
    /// Tip height over the road.
    pub z_m: f64,
    /// Fan direction ψ_B in the base frame (from +x_B, counter-clockwise).
    pub yaw_rad: f64,
    /// Tilt β: > 0 leans the nozzle towards +ψ (SPEC §2).
    pub tilt_rad: f64,
}

impl NozzlePose {
    /// Whether two poses paint the same: same tip, and the same fan up to
    /// its symmetry (ψ with β, or ψ+π with −β), within `tol` (m and rad).
    pub fn same_spray(&self, other: &NozzlePose, tol: f64) -> bool {
        let pos = (self.x_m - other.x_m).abs() <= tol
            && (self.y_m - other.y_m).abs() <= tol
            && (self.z_m - other.z_m).abs() <= tol;
        let d = wrap_pi(self.yaw_rad - other.yaw_rad);
        let same = d.abs() <= tol && (self.tilt_rad - other.tilt_rad).abs() <= tol;
        let flipped = (PI - d.abs()).abs() <= tol && (self.tilt_rad + other.tilt_rad).abs() <= tol;
        pos && (same || flipped)
    }
}

/// Joint positions, named as the CSV columns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Joints {
    /// θ1.
    pub base_rot_rad: f64,
    /// R: rotation axis to the yaw axis.
    pub extension_m: f64,
    /// 0 = top of the stroke, positive down.
    pub vertical_m: f64,
    /// End-effector yaw joint: ψ_B − θ1.
    pub ee_yaw_rad: f64,
    /// β.
    pub tilt_rad: f64,
}

impl Joints {
    /// The joints of a joint set in CSV column order (inverse of [`Joints::values`]).
    pub fn of(q: &[f64; 5]) -> Joints {
        Joints {
            base_rot_rad: q[0],
            extension_m: q[1],
            vertical_m: q[2],
            ee_yaw_rad: q[3],
            tilt_rad: q[4],
        }
    }

    /// Values in CSV column order (see `Limits::NAMES`).
    pub fn values(&self) -> [f64; 5] {
        [
            self.base_rot_rad,
            self.extension_m,
            self.vertical_m,
            self.ee_yaw_rad,
            self.tilt_rad,
        ]
    }
}

/// Actuator positions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Actuators {
    /// Hydraulic base motor angle.
    pub base_motor_rad: f64,
    /// Extension cylinder stroke from fully retracted.
    pub cylinder_m: f64,
    /// Vertical cylinder (0 = top, positive down).
    pub vertical_m: f64,
    /// Yaw servo motor angle (before the 10:1 gearbox).
    pub yaw_motor_rad: f64,
    /// Ball-screw nut travel from its centre.
    pub tilt_nut_m: f64,
    /// Tilt servo motor angle.
    pub tilt_motor_rad: f64,
}

/// Encoder counts, named as the CSV columns `enc_*`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Encoders {
    #[serde(rename = "enc_base")]
    pub base: i64,
    #[serde(rename = "enc_extension")]
    pub extension: i64,
    #[serde(rename = "enc_yaw")]
    pub yaw: i64,
    #[serde(rename = "enc_tilt")]
    pub tilt: i64,
    #[serde(rename = "enc_vertical")]
    pub vertical: i64,
}

/// A pose (or joint set) the robot cannot take: the binding limit, the value
/// it would need, the range and by how much it is exceeded.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}", self.describe())]
pub struct Unreachable {
    /// Joint (CSV column name) or pose field that binds.
    pub joint: String,
    /// The value it would need (NaN when the input itself is not finite).
    pub value: f64,
    pub min: f64,
    pub max: f64,
    /// Distance outside [min, max], in the joint's unit.
    pub excess: f64,
    /// Whether the limit binds on the flipped fan (ψ+π, −β), the branch IK
    /// came closest with.
    pub flipped: bool,
}

/// `v` with `decimals` decimals for a person to read: never `-0.000`
/// (a rounded-away sign says nothing), and in scientific form from 10⁶ up
/// (`--tilt-deg 1e300` must not print 300 digits).
pub fn show_number(v: f64, decimals: usize) -> String {
    if v.is_finite() && v.abs() >= 1e6 {
        return format!("{v:.4e}");
    }
    let s = format!("{v:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => s,
    }
}

/// Decimals that show `excess` with two significant digits, at least `min`
/// (15 at most: an f64 holds no more). A limit broken by 1e-9 rad must not
/// read "by 0.0000 rad".
fn decimals_for(excess: f64, min: usize) -> usize {
    if !(excess.is_finite() && excess > 0.0) {
        return min;
    }
    let needed = 1.0 - excess.log10().floor();
    if needed <= min as f64 {
        min
    } else {
        (needed as usize).min(15)
    }
}

impl Unreachable {
    /// A pose field (`yaw_rad`, …) that is not a finite number.
    pub(crate) fn not_finite(field: &str, value: f64) -> Unreachable {
        Unreachable {
            joint: field.into(),
            value,
            min: f64::NAN,
            max: f64::NAN,
            excess: f64::NAN,
            flipped: false,
        }
    }

    fn describe(&self) -> String {
        if !self.value.is_finite() {
            return format!(
                "unreachable: {} is not a finite number; give finite coordinates",
                self.joint
            );
        }
        let angle = self.joint.ends_with("_rad");
        // Radians and metres to 0.1 mm / 0.1 mrad, degrees to 0.01°, more
        // when the excess is smaller.
        let (d, d_deg) = if angle {
            (
                decimals_for(self.excess, 4),
                decimals_for(self.excess.to_degrees(), 2),
            )
        } else {
            (decimals_for(self.excess, 4), 0)
        };
        let show = |v: f64| {
            if angle {
                format!(
                    "{} rad ({}°)",
                    show_number(v, d),
                    show_number(v.to_degrees(), d_deg)
                )
            } else {
                format!("{} m", show_number(v, d))
            }
        };
        format!(
            "unreachable: {}{} would be {}, outside its range {} .. {} by {}",
            if self.flipped {
                // The fan as asked came out further from its limits.
                "with the fan flipped (ψ+π, the tilt negated; as asked it is further out of reach) "
            } else {
                ""
            },
            self.joint,
            show(self.value),
            show(self.min),
            show(self.max),
            show(self.excess),
        )
    }

    pub(super) fn of(name: &str, l: &JointLimit, value: f64) -> Unreachable {
        Unreachable {
            joint: name.to_string(),
            value,
            min: l.min,
            max: l.max,
            excess: l.excess(value),
            flipped: false,
        }
    }

    /// Excess relative to the joint's range: compares different units.
    pub(super) fn severity(&self) -> f64 {
        let span = (self.max - self.min).abs().max(1e-12);
        self.excess / span
    }
}

/// A sampled joint trajectory breaking a speed or acceleration limit.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "{joint} {what} {value:.4} exceeds its limit {limit:.4} (SI units) at sample {index}; \
     slow the motion there"
)]
pub struct RateViolation {
    /// Sample index where the violation is found.
    pub index: usize,
    /// Joint (CSV column name), or `tilt_nut_m` for the nut speed.
    pub joint: String,
    /// `"speed"` or `"acceleration"`.
    pub what: &'static str,
    pub value: f64,
    pub limit: f64,
}

/// Angle wrapped to (−π, π].
pub fn wrap_pi(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI {
        w - TAU
    } else {
        w
    }
}

impl Robot {
    /// Yaw axis on the road for base rotation and extension (SPEC §2).
    pub fn yaw_axis(&self, base_rot_rad: f64, extension_m: f64) -> [f64; 2] {
        let (s, c) = base_rot_rad.sin_cos();
        let a2 = self.arm.a2_m;
        [extension_m * c + a2 * s, extension_m * s - a2 * c]
    }

    /// Tip translation caused by tilt β: (along +ψ, up), metres. NaN when the
    /// four-bar cannot be assembled at β (never within valid tilt limits).
    pub fn tilt_tip_offset(&self, tilt_rad: f64) -> [f64; 2] {
        self.end_effector
            .fourbar
            .tip_offset(tilt_rad)
            .unwrap_or([f64::NAN, f64::NAN])
    }

    /// Forward kinematics: joints → nozzle pose (yaw wrapped to (−π, π]).
    /// Joints outside the limits still give their pose; check them with
    /// [`Robot::check_joints`].
    pub fn fk(&self, j: &Joints) -> NozzlePose {
        let w = self.yaw_axis(j.base_rot_rad, j.extension_m);
        let psi = j.base_rot_rad + j.ee_yaw_rad;
        let off = self.tilt_tip_offset(j.tilt_rad);
        let (s, c) = psi.sin_cos();
        NozzlePose {
            x_m: w[0] + off[0] * c,
            y_m: w[1] + off[0] * s,
            z_m: self.end_effector.tip_height_top_m - j.vertical_m + off[1],
            yaw_rad: wrap_pi(psi),
            tilt_rad: j.tilt_rad,
        }
    }

    /// The first limit the joints break (the worst relative excess), if any.
    pub fn check_joints(&self, j: &Joints) -> Result<(), Unreachable> {
        let mut worst: Option<Unreachable> = None;
        for ((name, l), v) in self.limits.iter().zip(j.values()) {
            if !v.is_finite() {
                return Err(Unreachable {
                    joint: name.into(),
                    value: v,
                    min: l.min,
                    max: l.max,
                    excess: f64::NAN,
                    flipped: false,
                });
            }
            if !l.contains(v) {
                let u = Unreachable::of(name, l, v);
                if worst.as_ref().is_none_or(|w| u.severity() > w.severity()) {
                    worst = Some(u);
                }
            }
        }
        worst.map_or(Ok(()), Err)
    }

    /// Inverse kinematics: every joint set within limits that puts the tip
    /// at the pose (fan symmetry ψ/ψ+π with β negated, every yaw turn inside
    /// the yaw range; the arm's second θ1 branch, R < 0, never is). The
    /// four-bar is used in its built assembly mode (coupler below the ground
    /// link; the mirrored mode cannot be reached without disassembly).
    /// Sorted by base rotation, then yaw. Err names the binding limit of the
    /// candidate that comes closest.
    pub fn ik(&self, pose: &NozzlePose) -> Result<Vec<Joints>, Unreachable> {
        super::kind::check_pose_finite(pose)?;
        let mut found = Vec::new();
        let mut closest: Option<Unreachable> = None;
        let mut note_on = |flip: bool, u: Unreachable| {
            let u = Unreachable { flipped: flip, ..u };
            if closest.as_ref().is_none_or(|c| u.severity() < c.severity()) {
                closest = Some(u);
            }
        };
        for flip in [false, true] {
            let (psi, beta) = if flip {
                // 0 − β: a zero tilt flipped stays +0.0.
                (pose.yaw_rad + PI, 0.0 - pose.tilt_rad)
            } else {
                (pose.yaw_rad, pose.tilt_rad)
            };
            let mut note = |u: Unreachable| note_on(flip, u);
            if !self.limits.tilt_rad.contains(beta) {
                note(Unreachable::of("tilt_rad", &self.limits.tilt_rad, beta));
                continue;
            }
            let Some(off) = self.end_effector.fourbar.tip_offset(beta) else {
                note(Unreachable::of("tilt_rad", &self.limits.tilt_rad, beta));
                continue;
            };
            let (s, c) = psi.sin_cos();
            let w = [pose.x_m - off[0] * c, pose.y_m - off[0] * s];
            let vertical = self.end_effector.tip_height_top_m + off[1] - pose.z_m;
            let arm = self.arm_ik(w);
            if arm.is_empty() {
                // |W| < a2: the yaw axis would have to be nearer the base
                // axis than the arm's offset allows; R would be about |W|,
                // far below its minimum.
                note(Unreachable::of(
                    "extension_m",
                    &self.limits.extension_m,
                    w[0].hypot(w[1]),
                ));
            }
            for (theta1, ext) in arm {
                let mut j = Joints {
                    base_rot_rad: theta1,
                    extension_m: ext,
                    vertical_m: vertical,
                    ee_yaw_rad: wrap_pi(psi - theta1),
                    tilt_rad: beta,
                };
                // Every turn of the yaw joint that stays inside its range.
                let yl = &self.limits.ee_yaw_rad;
                let base_yaw = j.ee_yaw_rad;
                let k_lo = ((yl.min - base_yaw) / TAU).ceil() as i64;
                let k_hi = ((yl.max - base_yaw) / TAU).floor() as i64;
                if k_lo > k_hi {
                    // No turn fits: report the nearest one.
                    let k = if base_yaw < yl.min {
                        k_lo - 1
                    } else {
                        k_hi + 1
                    };
                    j.ee_yaw_rad = base_yaw + TAU * k.clamp(-4, 4) as f64;
                    match self.check_joints(&j) {
                        Err(u) => note(u),
                        Ok(()) => note(Unreachable::of("ee_yaw_rad", yl, j.ee_yaw_rad)),
                    }
                    continue;
                }
                for k in k_lo..=k_hi.min(k_lo + 8) {
                    j.ee_yaw_rad = base_yaw + TAU * k as f64;
                    match self.check_joints(&j) {
                        Ok(()) => found.push(j),
                        Err(u) => note(u),
                    }
                }
            }
        }
        if found.is_empty() {
            // Every branch above either finds joints or notes why not, so
            // `closest` is set; the fallback only keeps this panic-free.
            return Err(closest.unwrap_or_else(|| {
                Unreachable::of("tilt_rad", &self.limits.tilt_rad, pose.tilt_rad)
            }));
        }
        found.sort_by(|a, b| {
            a.base_rot_rad
                .total_cmp(&b.base_rot_rad)
                .then(a.ee_yaw_rad.total_cmp(&b.ee_yaw_rad))
        });
        Ok(found)
    }

    /// Arm inverse kinematics for the yaw axis point `w`: (θ1, R) branches.
    /// |W|² = R² + a2² and arg W = θ1 − atan2(a2, R) (SPEC §2; the two roots
    /// of 000 app. B eq. 2.40 are R = ±√(|W|² − a2²)). θ1 is taken in the
    /// turn that holds the base window when one does.
    fn arm_ik(&self, w: [f64; 2]) -> Vec<(f64, f64)> {
        let a2 = self.arm.a2_m.abs();
        // √(|W|² − a2²) as √(|W| − a2)·√(|W| + a2): squaring a tip 1e300 m
        // away would overflow to an infinite R.
        let d = w[0].hypot(w[1]);
        if d < a2 {
            return vec![];
        }
        let r = (d - a2).sqrt() * (d + a2).sqrt();
        let a2 = self.arm.a2_m;
        let arg = w[1].atan2(w[0]);
        let bl = &self.limits.base_rot_rad;
        let mut out = Vec::with_capacity(2);
        for ext in [r, -r] {
            let mut t = wrap_pi(arg + a2.atan2(ext));
            let mid = 0.5 * (bl.min + bl.max);
            t += TAU * ((mid - t) / TAU).round();
            out.push((t, ext));
        }
        out
    }

    /// The IK solution with the shortest travel from `prev` (seed 003:
    /// choose the shorter travel), travel measured as the time of the
    /// slowest joint at its speed limit, ties broken by the summed times.
    pub fn ik_nearest(&self, pose: &NozzlePose, prev: &Joints) -> Result<Joints, Unreachable> {
        let all = self.ik(pose)?;
        // `ik` returns Ok only with at least one solution.
        Ok(self.nearest_of(&all, prev).unwrap_or(all[0]))
    }

    /// The joint set of `all` with the shortest travel from `prev` (None
    /// when `all` is empty).
    pub fn nearest_of(&self, all: &[Joints], prev: &Joints) -> Option<Joints> {
        let qs: Vec<[f64; 5]> = all.iter().map(Joints::values).collect();
        let limits = super::ArmKind::limits(self);
        super::kind::shortest_travel(&qs, &prev.values(), &limits).map(|i| all[i])
    }

    /// Check a joint trajectory sampled every `dt` seconds against every
    /// joint's speed and acceleration limits (finite differences) and the
    /// ball nut's speed limit; the first violation in sample order.
    /// Limits are met up to a relative 1e-9 (rounding).
    pub fn check_rates(&self, samples: &[Joints], dt: f64) -> Result<(), RateViolation> {
        let over = |v: f64, lim: f64| v.abs() > lim * (1.0 + 1e-9);
        let fb = &self.end_effector.fourbar;
        let nut_lim = self.end_effector.tilt_nut_max_speed_mps;
        for i in 1..samples.len() {
            let (a, b) = (samples[i - 1].values(), samples[i].values());
            for (k, (name, l)) in self.limits.iter().enumerate() {
                let v = (b[k] - a[k]) / dt;
                if over(v, l.max_vel) {
                    return Err(RateViolation {
                        index: i,
                        joint: name.into(),
                        what: "speed",
                        value: v.abs(),
                        limit: l.max_vel,
                    });
                }
                if i >= 2 {
                    let z = samples[i - 2].values()[k];
                    let acc = (b[k] - 2.0 * a[k] + z) / (dt * dt);
                    if over(acc, l.max_acc) {
                        return Err(RateViolation {
                            index: i - 1,
                            joint: name.into(),
                            what: "acceleration",
                            value: acc.abs(),
                            limit: l.max_acc,
                        });
                    }
                }
            }
            let nut = |j: &Joints| fb.nut_m(j.tilt_rad).unwrap_or(f64::NAN);
            let v = (nut(&samples[i]) - nut(&samples[i - 1])) / dt;
            if v.is_nan() || over(v, nut_lim) {
                return Err(RateViolation {
                    index: i,
                    joint: "tilt_nut_m".into(),
                    what: "speed",
                    value: v.abs(),
                    limit: nut_lim,
                });
            }
        }
        Ok(())
    }

    /// Radians of tilt motor per metre of nut travel.
    fn tilt_motor_rad_per_m(&self) -> f64 {
        let e = &self.end_effector;
        TAU * e.tilt_motor_turns_per_screw_turn / e.tilt_screw_pitch_m
    }

    /// Joints → actuator positions.
    pub fn actuators(&self, j: &Joints) -> Actuators {
        let nut = self
            .end_effector
            .fourbar
            .nut_m(j.tilt_rad)
            .unwrap_or(f64::NAN);
        Actuators {
            base_motor_rad: j.base_rot_rad * self.arm.base_motor_ratio,
            // 001 eq. 2.26: r = (R − R0)/8.333.
            cylinder_m: (j.extension_m - self.arm.retracted_extension_m)
                / self.arm.pantograph_ratio,
            vertical_m: j.vertical_m,
            yaw_motor_rad: j.ee_yaw_rad * self.end_effector.yaw_gear_ratio,
            tilt_nut_m: nut,
            tilt_motor_rad: nut * self.tilt_motor_rad_per_m(),
        }
    }

    /// Actuator positions → joints (the tilt from the nut; `tilt_motor_rad`
    /// is redundant with it). Err when the nut is outside the tilt range.
    pub fn joints_from_actuators(&self, a: &Actuators) -> Result<Joints, Unreachable> {
        Ok(Joints {
            base_rot_rad: a.base_motor_rad / self.arm.base_motor_ratio,
            extension_m: self.arm.retracted_extension_m + a.cylinder_m * self.arm.pantograph_ratio,
            vertical_m: a.vertical_m,
            ee_yaw_rad: a.yaw_motor_rad / self.end_effector.yaw_gear_ratio,
            tilt_rad: self.tilt_from_nut(a.tilt_nut_m)?,
        })
    }

    /// Tilt for a nut position, searched a little beyond the tilt limits.
    pub fn tilt_from_nut(&self, nut_m: f64) -> Result<f64, Unreachable> {
        let l = &self.limits.tilt_rad;
        let span = l.min.abs().max(l.max.abs()) * 1.5;
        let fb = &self.end_effector.fourbar;
        fb.tilt_from_nut(nut_m, span).ok_or_else(|| {
            let lo = fb.nut_m(l.min).unwrap_or(f64::NAN);
            let hi = fb.nut_m(l.max).unwrap_or(f64::NAN);
            let (min, max) = (lo.min(hi), lo.max(hi));
            Unreachable {
                joint: "tilt_nut_m".into(),
                value: nut_m,
                min,
                max,
                excess: if nut_m < min {
                    min - nut_m
                } else {
                    nut_m - max
                },
                flipped: false,
            }
        })
    }

    /// Metres (or radians) per count of each axis, in `Encoders` order:
    /// base, extension, yaw, tilt (nut metres), vertical.
    pub fn encoder_scales(&self) -> [f64; 5] {
        let n = &self.encoders;
        let e = &self.end_effector;
        [
            TAU / f64::from(n.base_counts_per_rev),
            n.extension_m_per_count,
            TAU / (f64::from(n.yaw_counts_per_motor_rev) * e.yaw_gear_ratio),
            e.tilt_screw_pitch_m
                / (e.tilt_motor_turns_per_screw_turn * f64::from(n.tilt_counts_per_motor_rev)),
            n.vertical_m_per_count,
        ]
    }

    /// Joints → encoder counts (nearest count). Zeros: θ1 = 0 (000 §III
    /// reads q1 = counts·2π/88000), R fully retracted, yaw joint 0, nut
    /// centre, top of the vertical stroke.
    pub fn encoders(&self, j: &Joints) -> Encoders {
        let s = self.encoder_scales();
        let nut = self
            .end_effector
            .fourbar
            .nut_m(j.tilt_rad)
            .unwrap_or(f64::NAN);
        // `as` saturates; joints are finite by contract (IK never returns NaN).
        let count = |v: f64, scale: f64| (v / scale).round() as i64;
        Encoders {
            base: count(j.base_rot_rad, s[0]),
            extension: count(j.extension_m - self.arm.retracted_extension_m, s[1]),
            yaw: count(j.ee_yaw_rad, s[2]),
            tilt: count(nut, s[3]),
            vertical: count(j.vertical_m, s[4]),
        }
    }

    /// Encoder counts → joints. Err when the tilt count is beyond the linkage.
    pub fn joints_from_encoders(&self, e: &Encoders) -> Result<Joints, Unreachable> {
        let s = self.encoder_scales();
        Ok(Joints {
            base_rot_rad: e.base as f64 * s[0],
            extension_m: self.arm.retracted_extension_m + e.extension as f64 * s[1],
            vertical_m: e.vertical as f64 * s[4],
            ee_yaw_rad: e.yaw as f64 * s[2],
            tilt_rad: self.tilt_from_nut(e.tilt as f64 * s[3])?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn robot() -> Robot {
        Robot::basr()
    }

    #[test]
    fn pose_0_3_tilt_10() {
        let r = robot();
        let pose = NozzlePose {
            x_m: 0.0,
            y_m: 3.0,
            z_m: 0.2,
            yaw_rad: 0.0,
            tilt_rad: 10f64.to_radians(),
        };
        let all = r.ik(&pose).unwrap();
        assert!(!all.is_empty());
        for j in &all {
            assert!(r.fk(j).same_spray(&pose, 1e-12), "{j:?}");
            assert!(r.check_joints(j).is_ok());
        }
        // Straight back: θ1 ≈ π/2 + a2/R.
        assert!((all[0].base_rot_rad - (PI / 2.0 + (0.01f64 / 3.0).atan())).abs() < 0.01);
        // Both fan orientations, each in two yaw turns within ±2π.
        assert_eq!(all.len(), 4);
    }

    #[test]
    fn zero_tilt_tip_on_yaw_axis() {
        let r = robot();
        let j = Joints {
            base_rot_rad: 1.2,
            extension_m: 3.0,
            vertical_m: 0.1,
            ee_yaw_rad: 0.3,
            tilt_rad: 0.0,
        };
        let p = r.fk(&j);
        let w = r.yaw_axis(1.2, 3.0);
        assert!((p.x_m - w[0]).abs() < 1e-15 && (p.y_m - w[1]).abs() < 1e-15);
        assert!((p.z_m - (0.332 - 0.1)).abs() < 1e-15);
        // |W|² = R² + a2².
        assert!((w[0].hypot(w[1]) - (9.0f64 + 1e-4).sqrt()).abs() < 1e-14);
    }

    #[test]
    fn out_of_reach_names_extension() {
        let r = robot();
        let pose = NozzlePose {
            x_m: 0.0,
            y_m: 6.0,
            z_m: 0.2,
            yaw_rad: 0.0,
            tilt_rad: 0.0,
        };
        let e = r.ik(&pose).unwrap_err();
        assert_eq!(e.joint, "extension_m");
        assert!(
            (e.excess - (6.0f64.hypot(0.0).powi(2) - 1e-4).sqrt() + 5.305416666666667).abs() < 1e-9
        );
        assert!(e.to_string().contains("extension_m"), "{e}");
    }

    #[test]
    fn outside_window_names_base() {
        let r = robot();
        let pose = NozzlePose {
            x_m: 3.0,
            y_m: 0.5,
            z_m: 0.2,
            yaw_rad: 0.0,
            tilt_rad: 0.0,
        };
        assert_eq!(r.ik(&pose).unwrap_err().joint, "base_rot_rad");
        let too_high = NozzlePose {
            z_m: 0.5,
            x_m: 0.0,
            y_m: 3.0,
            ..pose
        };
        assert_eq!(r.ik(&too_high).unwrap_err().joint, "vertical_m");
        let tilted = NozzlePose {
            tilt_rad: 0.5,
            x_m: 0.0,
            y_m: 3.0,
            ..pose
        };
        assert_eq!(r.ik(&tilted).unwrap_err().joint, "tilt_rad");
        let nan = NozzlePose {
            x_m: f64::NAN,
            ..pose
        };
        assert_eq!(r.ik(&nan).unwrap_err().joint, "x_m");
    }

    #[test]
    fn numbers_for_people() {
        assert_eq!(show_number(-0.0, 4), "0.0000");
        assert_eq!(show_number(-1e-17, 6), "0.000000");
        assert_eq!(show_number(-0.5, 2), "-0.50");
        assert_eq!(show_number(1e300, 4), "1.0000e300");
        assert_eq!(decimals_for(0.6417, 4), 4);
        assert_eq!(decimals_for(1.745e-9, 4), 10);
        assert_eq!(decimals_for(1e-300, 4), 15);
        assert_eq!(decimals_for(0.0, 2), 2);
    }

    #[test]
    fn tip_on_the_base_axis_names_extension_and_its_excess() {
        let r = robot();
        // Within a2 = 0.01 m of the axis no (θ1, R) exists at all
        // (|W|² = R² + a2²): R would be about |W|.
        for (x, y) in [(0.0, 0.0), (0.0, 0.005), (-0.003, 0.004)] {
            let pose = NozzlePose {
                x_m: x,
                y_m: y,
                z_m: 0.2,
                yaw_rad: 0.0,
                tilt_rad: 0.0,
            };
            let e = r.ik(&pose).unwrap_err();
            let w = f64::hypot(x, y);
            assert_eq!(e.joint, "extension_m");
            assert!((e.value - w).abs() < 1e-12, "{e:?}");
            assert!((e.excess - (1.55 - w)).abs() < 1e-12, "{e:?}");
            assert!(e.to_string().contains("would be"), "{e}");
        }
    }

    #[test]
    fn nearest_prefers_short_travel() {
        let r = robot();
        let pose = NozzlePose {
            x_m: 0.5,
            y_m: 3.0,
            z_m: 0.2,
            yaw_rad: 3.0,
            tilt_rad: 0.1,
        };
        let prev = r.ik(&pose).unwrap()[0];
        let mut p2 = pose;
        p2.yaw_rad += 0.05;
        let next = r.ik_nearest(&p2, &prev).unwrap();
        assert!((next.ee_yaw_rad - prev.ee_yaw_rad).abs() < 0.1);
        assert!((next.tilt_rad - prev.tilt_rad).abs() < 1e-12);
    }

    #[test]
    fn rates_checked_per_joint() {
        let r = robot();
        let dt = 0.032;
        let start = Joints {
            base_rot_rad: 1.5,
            extension_m: 3.0,
            vertical_m: 0.1,
            ee_yaw_rad: 0.0,
            tilt_rad: 0.0,
        };
        // Yaw at 29°/s: fine (acceleration from rest would not be, so
        // start already moving).
        let at = |w: f64, n: usize| -> Vec<Joints> {
            (0..n)
                .map(|i| Joints {
                    ee_yaw_rad: w * dt * i as f64,
                    ..start
                })
                .collect()
        };
        assert!(r.check_rates(&at(29f64.to_radians(), 10), dt).is_ok());
        let e = r.check_rates(&at(31f64.to_radians(), 10), dt).unwrap_err();
        assert_eq!(
            (e.joint.as_str(), e.what, e.index),
            ("ee_yaw_rad", "speed", 1)
        );
        // A jump to 20°/s within one period breaks the yaw acceleration.
        let mut v = at(0.0, 3);
        v.extend(at(20f64.to_radians(), 3).into_iter().map(|j| Joints {
            ee_yaw_rad: j.ee_yaw_rad + 20f64.to_radians() * dt,
            ..j
        }));
        let e = r.check_rates(&v, dt).unwrap_err();
        assert_eq!((e.joint.as_str(), e.what), ("ee_yaw_rad", "acceleration"));
        // Tilt at 14°/s moves the nut at ≈ 0.106 m/s (< 0.11): fine.
        let tilt: Vec<_> = (0..5)
            .map(|i| Joints {
                tilt_rad: 14f64.to_radians() * dt * i as f64,
                ..start
            })
            .collect();
        assert!(r.check_rates(&tilt, dt).is_ok());
    }

    #[test]
    fn encoder_scales_match_spec() {
        let r = robot();
        let s = r.encoder_scales();
        assert!((s[0] - 7.1399e-5).abs() < 1e-9); // 000 §III: 7.1399e-5 rad/count
        assert_eq!(s[1], 1.05833e-4);
        assert!((s[2] - TAU / 10_000.0).abs() < 1e-18);
        // 3.175 mm / (1.1 · 1000).
        assert!((s[3] - 0.003175 / 1100.0).abs() < 1e-18);
        let j = Joints {
            base_rot_rad: PI / 2.0,
            extension_m: 1.55 + 0.105833,
            ..Default::default()
        };
        let e = r.encoders(&j);
        assert_eq!(e.base, 22_000);
        assert_eq!(e.extension, 1000);
        // Cylinder stroke (001 eq. 2.26) for R = 5.358 m: the full 0.457 m.
        let a = r.actuators(&Joints {
            extension_m: 5.358333333333333,
            ..j
        });
        assert!((a.cylinder_m - 0.457).abs() < 1e-12);
    }
}
