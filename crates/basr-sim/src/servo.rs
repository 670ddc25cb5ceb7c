//! The plant of the electric kinds (telescopic, articulated): every joint a
//! rigid inertia (the description's `inertia`) driven by a motor whose
//! torque (`max_effort`) and speed are limited, under a PID controller with
//! acceleration and velocity feed-forward, sampled at the description's
//! controller period. Joints are decoupled (each drive sees its own reflected
//! inertia; gravity and coupling torques are taken as compensated by the
//! drive and left out) — enough to judge whether setpoints a planner gives
//! can be followed within the limits, not a multibody model.
//!
//! The tip error is the distance between the forward kinematics of the
//! followed joints and of the setpoints, at every controller sample.

use basr_robot::{ArmKind, ServoJoint, Q};

/// Closed-loop bandwidth of every joint. assumed: 8 Hz, a twenty-fifth of
/// the 200 Hz controller rate (000 §III's 5 ms sample), as servo drives are
/// commonly tuned well under their sampling rate.
pub const BANDWIDTH_HZ: f64 = 8.0;
/// Damping ratio of the position loop. assumed: 1 (critically damped, no
/// overshoot past a painted edge).
pub const DAMPING: f64 = 1.0;
/// Integral action as a fraction of the bandwidth. assumed: ω/5, slow
/// enough not to cut the phase margin.
pub const INTEGRAL_FRACTION: f64 = 0.2;
/// The drive's speed limit over the planning limit `max_vel`. assumed: 10 %
/// headroom, so a trajectory at its limit is still followed.
pub const SPEED_HEADROOM: f64 = 1.1;
/// Integration substeps per controller sample.
const SUBSTEPS: usize = 5;

/// What a simulation of one joint path found.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ServoReport {
    /// Worst distance of the tip from where the setpoints put it (m), and
    /// the setpoint index where it was.
    pub max_tip_error_m: f64,
    pub worst_index: usize,
    pub rms_tip_error_m: f64,
    /// Largest |effort| / max_effort of each joint (1 = at the limit).
    pub effort_fraction: [f64; 5],
    /// Largest |speed| / max_vel of each joint.
    pub speed_fraction: [f64; 5],
}

/// PID + feed-forward gains of one joint, from its inertia.
#[derive(Clone, Copy, Debug)]
struct Loop {
    kp: f64,
    kd: f64,
    ki: f64,
}

impl Loop {
    fn of(j: &ServoJoint) -> Loop {
        let w = std::f64::consts::TAU * BANDWIDTH_HZ;
        // Pole placement for J·s² + kd·s + kp: ω² and 2ζω, scaled by J.
        Loop {
            kp: j.inertia * w * w,
            kd: j.inertia * 2.0 * DAMPING * w,
            ki: j.inertia * w * w * w * INTEGRAL_FRACTION,
        }
    }
}

/// State of one joint (the model's data, apart from the description).
#[derive(Clone, Copy, Debug, Default)]
struct State {
    q: f64,
    v: f64,
    integral: f64,
}

/// Reference at time `t` from setpoints every `period` s: the cubic
/// Hermite curve through them with central-difference tangents (one-sided
/// at the ends), its speed and acceleration the curve's own derivatives —
/// the smooth feed-forward a controller can compute from the setpoint
/// stream. (Piecewise-constant finite differences step the speed reference
/// at every setpoint, and the damping term turns each step into a torque
/// spike: the drives then saturated in air moves whose accelerations were
/// well within their limits.)
fn reference(sp: &[Q], period: f64, t: f64, k: usize) -> (f64, f64, f64) {
    let n = sp.len();
    if n < 2 {
        return (sp.first().map_or(0.0, |q| q[k]), 0.0, 0.0);
    }
    let x = (t / period).clamp(0.0, (n - 1) as f64);
    let i = (x.floor() as usize).min(n - 2);
    let f = x - i as f64;
    let at = |m: usize| sp[m.min(n - 1)][k];
    // Tangent per setpoint step at setpoint m.
    let tangent = |m: usize| {
        let (a, b) = (m.saturating_sub(1), (m + 1).min(n - 1));
        (at(b) - at(a)) / (b - a) as f64
    };
    let (p0, p1, m0, m1) = (at(i), at(i + 1), tangent(i), tangent(i + 1));
    let (f2, f3) = (f * f, f * f * f);
    let q = (2.0 * f3 - 3.0 * f2 + 1.0) * p0
        + (f3 - 2.0 * f2 + f) * m0
        + (-2.0 * f3 + 3.0 * f2) * p1
        + (f3 - f2) * m1;
    let v = (6.0 * f2 - 6.0 * f) * p0
        + (3.0 * f2 - 4.0 * f + 1.0) * m0
        + (-6.0 * f2 + 6.0 * f) * p1
        + (3.0 * f2 - 2.0 * f) * m1;
    let a = (12.0 * f - 6.0) * p0
        + (6.0 * f - 4.0) * m0
        + (-12.0 * f + 6.0) * p1
        + (6.0 * f - 2.0) * m1;
    (q, v / period, a / (period * period))
}

/// One controller sample of a servo simulation.
#[derive(Clone, Copy, Debug)]
pub struct Tick {
    pub t_s: f64,
    /// The setpoint nearest in time.
    pub index: usize,
    /// Tip distance from where the setpoints put it (m).
    pub tip_error_m: f64,
    /// The followed joints.
    pub q: Q,
    /// The reference they follow (the setpoints, linear between them).
    pub want: Q,
    /// |effort| / max_effort asked of each joint (over 1: saturated).
    pub effort_fraction: [f64; 5],
}

/// Follow `setpoints` (joint sets every `period_s`) with the servo loops,
/// starting at rest on the first setpoint.
pub fn simulate(
    arm: &dyn ArmKind,
    joints: &[ServoJoint; 5],
    setpoints: &[Q],
    period_s: f64,
    sample_s: f64,
) -> ServoReport {
    let mut report = ServoReport {
        max_tip_error_m: 0.0,
        worst_index: 0,
        rms_tip_error_m: 0.0,
        effort_fraction: [0.0; 5],
        speed_fraction: [0.0; 5],
    };
    let mut sum2 = 0.0;
    let mut n = 0usize;
    let speeds = follow(arm, joints, setpoints, period_s, sample_s, &mut |tick| {
        let err = tick.tip_error_m;
        sum2 += err * err;
        n += 1;
        if err > report.max_tip_error_m {
            report.max_tip_error_m = err;
            report.worst_index = tick.index;
        }
        for k in 0..5 {
            report.effort_fraction[k] = report.effort_fraction[k].max(tick.effort_fraction[k]);
        }
    });
    report.speed_fraction = speeds;
    if n > 0 {
        report.rms_tip_error_m = (sum2 / n as f64).sqrt();
    }
    report
}

/// The servo loops following `setpoints` from rest on the first, every
/// controller sample given to `tick`; returns each joint's largest
/// |speed| / max_vel.
pub fn follow(
    arm: &dyn ArmKind,
    joints: &[ServoJoint; 5],
    setpoints: &[Q],
    period_s: f64,
    sample_s: f64,
    tick: &mut dyn FnMut(&Tick),
) -> [f64; 5] {
    let mut speed_fraction = [0.0; 5];
    if setpoints.is_empty() || !(period_s > 0.0 && sample_s > 0.0) {
        return speed_fraction;
    }
    let loops = joints.map(|j| Loop::of(&j));
    let mut s: [State; 5] = std::array::from_fn(|k| State {
        q: setpoints[0][k],
        ..State::default()
    });
    let end = (setpoints.len() - 1) as f64 * period_s;
    let steps = (end / sample_s).ceil() as usize;
    let h = sample_s / SUBSTEPS as f64;
    for step in 0..=steps {
        let t = step as f64 * sample_s;
        let mut effort = [0.0; 5];
        let mut fraction = [0.0; 5];
        let mut want = [0.0; 5];
        for k in 0..5 {
            let (qr, vr, ar) = reference(setpoints, period_s, t, k);
            want[k] = qr;
            let j = &joints[k];
            let e = qr - s[k].q;
            let l = &loops[k];
            let u = j.inertia * ar + l.kd * (vr - s[k].v) + l.kp * e + l.ki * s[k].integral;
            effort[k] = u.clamp(-j.max_effort, j.max_effort);
            // Anti-windup: integrate only while the drive is not saturated.
            if effort[k] == u {
                s[k].integral += e * sample_s;
            }
            fraction[k] = u.abs() / j.max_effort;
        }
        let got: Q = std::array::from_fn(|k| s[k].q);
        let (a, b) = (arm.fk(&got), arm.fk(&want));
        let err =
            ((a.x_m - b.x_m).powi(2) + (a.y_m - b.y_m).powi(2) + (a.z_m - b.z_m).powi(2)).sqrt();
        tick(&Tick {
            t_s: t,
            index: ((t / period_s).round() as usize).min(setpoints.len() - 1),
            tip_error_m: err,
            q: got,
            want,
            effort_fraction: fraction,
        });
        for _ in 0..SUBSTEPS {
            for k in 0..5 {
                let j = &joints[k];
                let vmax = j.max_vel * SPEED_HEADROOM;
                s[k].v = (s[k].v + h * effort[k] / j.inertia).clamp(-vmax, vmax);
                s[k].q += h * s[k].v;
                speed_fraction[k] = f64::max(speed_fraction[k], s[k].v.abs() / j.max_vel);
            }
        }
    }
    speed_fraction
}

#[cfg(test)]
mod tests {
    use super::*;
    use basr_robot::kind::{ARTICULATED_TOML, TELESCOPIC_TOML};
    use basr_robot::{AnyRobot, NozzlePose};

    /// Setpoints painting a straight 1 m stroke across the lane 2.5 m behind
    /// the base at 0.16 m/s (SPEC §4's painting speed), fan along it, from
    /// rest to rest with 0.5 s ramps; joints chained by shortest travel.
    fn stroke(arm: &dyn ArmKind, period: f64) -> Vec<Q> {
        let (v, ramp) = (0.16, 0.5);
        let total = 1.0 / v + ramp;
        let n = (total / period).ceil() as usize;
        let s_of = |t: f64| {
            // Trapezoidal speed: s(t) with a linear ramp up and down.
            let t = t.clamp(0.0, total);
            let up = 0.5 * v * t * t / ramp;
            if t < ramp {
                up
            } else if t > total - ramp {
                1.0 - 0.5 * v * (total - t).powi(2) / ramp
            } else {
                0.5 * v * ramp + v * (t - ramp)
            }
        };
        let mut prev = arm.rest();
        (0..=n)
            .map(|i| {
                let s = s_of(i as f64 * period);
                let pose = NozzlePose {
                    x_m: -0.5 + s,
                    y_m: 2.5,
                    z_m: 0.15,
                    yaw_rad: 0.0,
                    tilt_rad: 0.0,
                };
                let all = arm.ik(&pose).unwrap();
                prev = arm.nearest(&all, &prev).unwrap();
                prev
            })
            .collect()
    }

    fn kinds() -> Vec<(AnyRobot, [ServoJoint; 5])> {
        [TELESCOPIC_TOML, ARTICULATED_TOML]
            .iter()
            .map(|t| {
                let r = AnyRobot::from_toml_str(t, "shipped").unwrap();
                let j = match &r {
                    AnyRobot::Telescopic(t) => t.joints.all().map(|j| *j),
                    AnyRobot::Articulated(a) => a.joints.all().map(|j| *j),
                    AnyRobot::Basr(_) => unreachable!(),
                };
                (r, j)
            })
            .collect()
    }

    #[test]
    fn a_painting_stroke_is_followed_within_the_accuracy() {
        for (r, j) in kinds() {
            let sp = stroke(r.arm(), 0.032);
            let rep = simulate(r.arm(), &j, &sp, 0.032, 0.005);
            eprintln!("{}: {rep:?}", r.arm().name());
            // SPEC §4: 1/4 in.
            assert!(rep.max_tip_error_m < 0.00635, "{}: {rep:?}", r.arm().name());
            assert!(rep.effort_fraction.iter().all(|&f| f <= 1.0), "{rep:?}");
        }
    }

    #[test]
    fn a_jump_saturates_the_drive_and_misses() {
        for (r, j) in kinds() {
            let mut sp = stroke(r.arm(), 0.032);
            // Every setpoint after the first 0.5 rad away on joint 0.
            for q in sp.iter_mut().skip(1) {
                q[0] += 0.5;
            }
            let rep = simulate(r.arm(), &j, &sp, 0.032, 0.005);
            assert!(rep.effort_fraction[0] > 1.0, "{rep:?}");
            assert!(rep.max_tip_error_m > 0.5, "{rep:?}");
            assert!(rep.speed_fraction[0] <= SPEED_HEADROOM + 1e-12);
        }
    }
}
