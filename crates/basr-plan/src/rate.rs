//! Rate limits along a pass: the knots' tilt kept within what its joint
//! can follow at the knots' painting speeds (`turn` does the same for the
//! fan's direction).
//!
//! Where a value asks to change faster per metre than the joint can move
//! at the film law's speed, the time law would have to slow the nozzle
//! there and the film would pile up (the 8's waist, where the rung-centre
//! path turns a corner and the tilt that balances the tiles swings by
//! 0.13 rad in 50 mm: film 2.2×; the heart's lobe tops at 2 m, where the
//! tilt swings across its range along a 0.2 m stroke: 1.8–2.1×). Instead
//! the value's change is spread: it starts before such a place and ends
//! after it, its corners rounded within the joint's acceleration
//! (`smooth`), and the caller re-paces the pass.

use basr_robot::AnyRobot;

use super::knots::{Knot, PaintLaw, MIN_TIP_STEP_M};
use super::tilt;
use super::tuning::Rates;

/// Most relaxation sweeps (each moves every too-steep step half-way).
/// assumed: far more than a swing over tens of knots needs.
const MAX_SWEEPS: usize = 20_000;

/// No range for [`smooth`] to keep values within.
pub const UNBOUNDED: [f64; 2] = [f64::NEG_INFINITY, f64::INFINITY];

/// Keep `values` (at times whose steps are `tau`, s) within `max_rate` per
/// s between neighbours and `max_acc` per s² between neighbouring steps'
/// rates, (with `floor`) never below `floor[i]`, and within `range`.
/// Returns false, leaving them alone, when they already are.
///
/// Alternating projections onto each constraint (all convex, and a constant
/// meets every one): a step too steep moves its two values towards each
/// other by half the excess; a rate change too sharp moves the
/// three values by the least change (along the gradient of the change in
/// rate) that brings it to the bound, which smooths the corner a rate limit
/// leaves; a value under its floor or outside the range is brought back
/// after every sweep.
/// Sweeps alternate in direction and stop when nothing exceeds by more than
/// 1e-9 of its bound.
pub fn smooth(
    values: &mut [f64],
    tau: &[f64],
    [max_rate, max_acc]: [f64; 2],
    floor: Option<&[f64]>,
    [lo, hi]: [f64; 2],
) -> bool {
    let n = values.len();
    let rate = |v: &[f64], i: usize| (v[i + 1] - v[i]) / tau[i];
    let too_fast = |v: &[f64]| {
        (0..n.saturating_sub(1)).any(|i| rate(v, i).abs() > max_rate * (1.0 + 1e-9))
            || (1..n.saturating_sub(1)).any(|i| {
                (rate(v, i) - rate(v, i - 1)).abs()
                    > max_acc * 0.5 * (tau[i] + tau[i - 1]) * (1.0 + 1e-9)
            })
    };
    if n < 3 || !too_fast(values) {
        return false;
    }
    for sweep in 0..MAX_SWEEPS {
        let mut worst = 0.0f64;
        for k in 0..n - 1 {
            let i = if sweep % 2 == 0 { k } else { n - 2 - k };
            // The step's rate.
            let d = values[i + 1] - values[i];
            let excess = d.abs() - max_rate * tau[i];
            if excess > 0.0 {
                let half = 0.5 * excess * d.signum();
                values[i + 1] -= half;
                values[i] += half;
                worst = worst.max(excess / (max_rate * tau[i]));
            }
            // The change of rate into the step.
            if i >= 1 {
                let g = [
                    1.0 / tau[i - 1],
                    -(1.0 / tau[i - 1] + 1.0 / tau[i]),
                    1.0 / tau[i],
                ];
                let change = rate(values, i) - rate(values, i - 1);
                let bound = max_acc * 0.5 * (tau[i] + tau[i - 1]);
                let excess = change.abs() - bound;
                if excess > 0.0 {
                    let norm2: f64 = g.iter().map(|x| x * x).sum();
                    let m = excess * change.signum() / norm2;
                    for (o, gk) in g.iter().enumerate() {
                        values[i - 1 + o] -= m * gk;
                    }
                    worst = worst.max(excess / bound);
                }
            }
        }
        if let Some(floor) = floor {
            for (v, &f) in values.iter_mut().zip(floor) {
                *v = v.max(f);
            }
        }
        for v in values.iter_mut() {
            *v = v.clamp(lo, hi);
        }
        if worst < 1e-9 {
            break;
        }
    }
    true
}

/// Time (s) the nozzle takes over each step between knots at their
/// painting speeds (infinite where they do not move).
pub fn step_times(ks: &[Knot]) -> Vec<f64> {
    ks.windows(2)
        .map(|w| {
            let ds = (w[1].tip - w[0].tip).hypot().max(MIN_TIP_STEP_M);
            let v = 0.5 * (w[1].speed_mps + w[0].speed_mps);
            if v > 0.0 && v.is_finite() {
                ds / v
            } else {
                f64::INFINITY
            }
        })
        .collect()
}

/// The tilt joint's speed (rad/s) and acceleration (rad/s²) the tilt may
/// take while painting: `tilt_share` and `tilt_acc_share` of its limits,
/// the speed as its drive allows (`AnyRobot::tilt_speed_limit`: for BASR
/// also the ball nut's, SPEC §4: 0.11 m/s); None for a kind that paints
/// untilted.
pub fn tilt_follow(robot: &AnyRobot, rates: &Rates) -> Option<[f64; 2]> {
    let own = robot.tilt_limit()?;
    let vel = robot.tilt_speed_limit()?;
    Some([vel * rates.tilt_share, own.max_acc * rates.tilt_acc_share])
}

/// Limit the tilt's change between knots to `max_rate_rps` at each knot's
/// painting speed. A knot whose tilt changes gets the nozzle position and
/// height of its new tilt (eq. 2.21–2.24, as `knots::knots` places them).
/// Returns whether any knot changed (the caller then re-paces the pass).
pub fn limit_tilt_rate(
    ks: &mut [Knot],
    law: &PaintLaw,
    max_rate_rps: f64,
    max_acc_rps2: f64,
) -> bool {
    if !(max_rate_rps.is_finite() && max_rate_rps > 0.0 && max_acc_rps2 > 0.0) {
        return false;
    }
    let mut beta: Vec<f64> = ks.iter().map(|k| k.tilt_rad).collect();
    // Within the tilts the knots already take: smoothing a corner held at
    // the tilt limit moves its neighbours past it otherwise (the 6's stem
    // at 5 mm rungs asked 15.06° of the tilt joint's ±15°).
    let (lo, hi) = beta
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &b| {
            (lo.min(b), hi.max(b))
        });
    if !smooth(
        &mut beta,
        &step_times(ks),
        [max_rate_rps, max_acc_rps2],
        None,
        [lo, hi],
    ) {
        return false;
    }
    for (k, b) in ks.iter_mut().zip(beta) {
        if b != k.tilt_rad {
            retilt(k, law, b);
        }
    }
    true
}

/// The vertical joint's speed (m/s) and acceleration (m/s²) the nozzle
/// height may take while painting: the tilt's share of its speed limit
/// and its own of its acceleration limit (`tuning::Rates`), for the same
/// spline; None for a kind without a vertical joint.
pub fn height_follow(robot: &AnyRobot, rates: &Rates) -> Option<[f64; 2]> {
    let j = robot
        .joint_names()
        .iter()
        .position(|n| *n == "vertical_m")?;
    let l = robot.limits()[j];
    Some([
        l.max_vel * rates.tilt_share,
        l.max_acc * rates.height_acc_share,
    ])
}

/// Keep the nozzle height's change between knots within `follow` (speed,
/// acceleration) at each knot's painting speed, only ever raising a knot
/// (a lower nozzle would leave the rung's ends bare): where a stroke
/// narrows faster than the vertical joint can lower the nozzle (a cell cut
/// by a slanted edge, the arrow's head at 3 m: film 2.1×), the fan stays
/// wider than the rung for a while and its speed follows the width it
/// covers, so the film stays on target and the extra lands outside (the
/// knots' `fan_width_m`, counted as outside paint). Returns whether any
/// knot changed (the caller then re-paces the pass).
pub fn limit_height_rate(ks: &mut [Knot], law: &PaintLaw, follow: [f64; 2]) -> bool {
    if !follow.iter().all(|v| v.is_finite() && *v > 0.0) {
        return false;
    }
    let floor: Vec<f64> = ks.iter().map(|k| k.z_m).collect();
    let mut z = floor.clone();
    if !smooth(&mut z, &step_times(ks), follow, Some(&floor), UNBOUNDED) {
        return false;
    }
    for (k, z) in ks.iter_mut().zip(z) {
        let z = z.min(law.max_height_m);
        if z > k.z_m {
            let factor = tilt::height_factor(k.tilt_rad, law.fan_angle_rad);
            k.z_m = z;
            k.fan_width_m = law.width_at_height(z / factor).max(k.width_m);
            k.speed_mps = law.k_m2ps / k.fan_width_m; // 001 eq. 2.6; re-paced by the caller
        }
    }
    true
}

/// Knot `k` painted with tilt `beta`: the foot moves against the lean so the
/// fan still spans the rung (eq. 2.21–2.23), the nozzle lowers by eq. 2.24
/// (clamped up to the vertical joint's lowest height, where the fan then
/// covers more than the rung).
fn retilt(k: &mut Knot, law: &PaintLaw, beta: f64) {
    let fan = law.fan_angle_rad;
    let dir = kurbo::Vec2::from_angle(k.yaw_rad);
    k.tip = k.mid - tilt::foot_offset(k.width_m, beta, fan) * dir;
    let factor = tilt::height_factor(beta, fan);
    let wanted = law.height_for_width(k.width_m) * factor;
    (k.z_m, k.fan_width_m) = if wanted < law.min_height_m {
        (
            law.min_height_m,
            law.width_at_height(law.min_height_m / factor)
                .max(k.width_m),
        )
    } else {
        (wanted, k.width_m)
    };
    k.tilt_rad = beta;
    k.speed_mps = law.k_m2ps / k.fan_width_m; // 001 eq. 2.6; re-paced by the caller
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knots::HeightLaw;
    use kurbo::Point;

    fn law() -> PaintLaw {
        PaintLaw {
            fan_angle_rad: 63.5f64.to_radians(),
            k_m2ps: 0.0158,
            height: HeightLaw::Geometric,
            min_height_m: 0.078,
            max_height_m: 0.5,
        }
    }

    fn knot(x: f64, beta: f64) -> Knot {
        let law = law();
        let mut k = Knot {
            mid: Point::new(x, 0.0),
            tip: Point::new(x, 0.0),
            z_m: 0.0,
            yaw_rad: std::f64::consts::FRAC_PI_2,
            tilt_rad: 0.0,
            width_m: 0.15,
            fan_width_m: 0.15,
            turn_rad: 0.0,
            swept_width_m: 0.15,
            speed_mps: 0.0,
        };
        retilt(&mut k, &law, beta);
        k
    }

    #[test]
    fn a_tilt_swing_is_spread_within_the_rate_and_the_knots_follow() {
        // 0.25 rad between two knots 20 mm apart at ≈ 0.105 m/s.
        let mut ks: Vec<Knot> = (0..40)
            .map(|i| knot(0.02 * i as f64, if i < 20 { -0.125 } else { 0.125 }))
            .collect();
        let rate = 0.2;
        // The step times it is limited at (the feet then move with the tilt).
        let taus = step_times(&ks);
        assert!(limit_tilt_rate(&mut ks, &law(), rate, 1e9));
        for (w, tau) in ks.windows(2).zip(taus) {
            assert!((w[1].tilt_rad - w[0].tilt_rad).abs() <= rate * tau * (1.0 + 1e-6));
        }
        // Spread to both sides: the middle is level, the ends untouched.
        assert!((ks[19].tilt_rad + ks[20].tilt_rad).abs() < 1e-9);
        assert_eq!(ks[0].tilt_rad, -0.125);
        assert_eq!(ks[39].tilt_rad, 0.125);
        // Every changed knot sits where `knots::knots` puts that tilt.
        for k in &ks {
            let fresh = knot(k.mid.x, k.tilt_rad);
            assert!((k.tip - fresh.tip).hypot() < 1e-12);
            assert!((k.z_m - fresh.z_m).abs() < 1e-12);
        }
    }

    #[test]
    fn a_tilt_within_the_rate_is_kept() {
        let mut ks: Vec<Knot> = (0..10)
            .map(|i| knot(0.02 * i as f64, 0.001 * i as f64))
            .collect();
        let before = ks.clone();
        assert!(!limit_tilt_rate(&mut ks, &law(), 0.2, 1e9));
        assert_eq!(ks, before);
    }

    #[test]
    fn a_sharp_change_of_rate_is_rounded_within_the_acceleration() {
        // A ramp that starts at full rate: the corner is rounded.
        let tau = vec![0.1; 30];
        let mut v: Vec<f64> = (0..31)
            .map(|i| if i < 15 { 0.0 } else { 0.02 * (i - 15) as f64 })
            .collect();
        let (rate, acc) = (0.3, 1.0);
        assert!(smooth(&mut v, &tau, [rate, acc], None, UNBOUNDED));
        for i in 0..30 {
            let r = (v[i + 1] - v[i]) / tau[i];
            assert!(r.abs() <= rate * (1.0 + 1e-6), "{i}: {r}");
            if i > 0 {
                let a = (r - (v[i] - v[i - 1]) / tau[i - 1]) / tau[i];
                assert!(a.abs() <= acc * (1.0 + 1e-6), "{i}: {a}");
            }
        }
        // Already smooth: left alone.
        let before = v.clone();
        assert!(!smooth(&mut v, &tau, [rate, acc], None, UNBOUNDED));
        assert_eq!(v, before);
    }

    #[test]
    fn smoothing_a_swing_held_at_a_limit_stays_within_the_bounds() {
        // A tilt held at +0.25 rad that swings to -0.25 within two steps:
        // rounding the corners moves the held values past ±0.25 unless the
        // bounds hold them (the 6's stem asked 15.06° of ±15°).
        let tau = vec![0.05; 30];
        let swing: Vec<f64> = (0..31)
            .map(|i| match i {
                0..=14 => 0.25,
                15 => 0.0,
                _ => -0.25,
            })
            .collect();
        let (rate, acc) = (3.0, 4.0);
        let mut free = swing.clone();
        assert!(smooth(&mut free, &tau, [rate, acc], None, UNBOUNDED));
        let past = free.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(
            past > 0.25 + 1e-3,
            "unbounded smoothing stays within: {past}"
        );
        let mut held = swing;
        assert!(smooth(&mut held, &tau, [rate, acc], None, [-0.25, 0.25]));
        for (i, v) in held.iter().enumerate() {
            assert!(v.abs() <= 0.25 + 1e-12, "{i}: {v}");
        }
        for i in 0..30 {
            let r = (held[i + 1] - held[i]) / tau[i];
            assert!(r.abs() <= rate * (1.0 + 1e-6), "{i}: rate {r}");
        }
    }

    #[test]
    fn a_stroke_that_narrows_fast_keeps_the_nozzle_up_and_never_lowers_it() {
        let law = law();
        // A 0.3 m band narrowing to 0.1 m within one 20 mm step.
        let mut ks: Vec<Knot> = (0..30)
            .map(|i| {
                let mut k = knot(0.02 * i as f64, 0.0);
                k.width_m = if i < 15 { 0.3 } else { 0.1 };
                retilt(&mut k, &law, 0.0);
                k
            })
            .collect();
        let before = ks.clone();
        let taus = step_times(&ks);
        let follow = [0.5, 5.0];
        assert!(limit_height_rate(&mut ks, &law, follow));
        for (i, (k, b)) in ks.iter().zip(&before).enumerate() {
            assert!(k.z_m >= b.z_m - 1e-12, "{i}: lowered");
            // The fan covers what its height paints, and is paced for it.
            assert!(k.fan_width_m >= k.width_m);
            assert!((k.speed_mps * k.fan_width_m - law.k_m2ps).abs() < 1e-12);
        }
        for (i, w) in ks.windows(2).enumerate() {
            assert!(
                (w[1].z_m - w[0].z_m).abs() <= follow[0] * taus[i] * (1.0 + 1e-6),
                "{i}"
            );
        }
        // The wide part keeps its height; the narrow end comes down to its own.
        assert_eq!(ks[0].z_m, before[0].z_m);
        assert!((ks[29].z_m - before[29].z_m).abs() < 1e-9);
    }
}
