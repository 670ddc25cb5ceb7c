//! The fan's turn along a pass, kept within what the yaw joint can turn at
//! painting speed.
//!
//! Each knot's fan lies along its rung. Where rungs turn faster per metre
//! than the yaw servo can follow at the film law's speed (the end of a
//! bowl's quarter, where one edge runs straight while the other still
//! curves; the loops of 6, 8 and 9), the time law would have to slow the
//! nozzle there and the film would pile up. Instead the fan's direction is
//! rate-limited along the pass: it starts turning before such a place and
//! finishes after it, a little off the rung (the fan still spans the
//! stroke: its ends fall short of the edges by w/2 · (1 − cos δ), under 1 mm
//! for δ = 15° on a 0.1 m stroke), and the caller re-paces the knots so each
//! tile still gets the target film.

use basr_robot::kinematics::wrap_pi;

use super::knots::{Knot, MIN_TIP_STEP_M};
use super::rungs::Rung;

/// Most relaxation sweeps (each moves every too-steep step half-way).
/// assumed: far more than a bowl's turn needs to spread (tens of knots).
const MAX_SWEEPS: usize = 20_000;

/// Limit the fan's turn between knots to `max_rate_rps` at each knot's
/// painting speed; the foot of a tilted nozzle turns with it. Returns
/// whether any knot changed (the caller then re-paces the pass).
pub fn limit_turn_rate(ks: &mut [Knot], max_rate_rps: f64) -> bool {
    let n = ks.len();
    if n < 3 || !(max_rate_rps.is_finite() && max_rate_rps > 0.0) {
        return false;
    }
    // The rungs' directions, unwrapped along the pass.
    let mut want = Vec::with_capacity(n);
    want.push(ks[0].yaw_rad);
    for i in 1..n {
        let prev: f64 = want[i - 1];
        want.push(prev + wrap_pi(ks[i].yaw_rad - prev));
    }
    // Largest turn per step: rate × the time the nozzle takes over it.
    let step: Vec<f64> = (1..n)
        .map(|i| {
            let ds = (ks[i].tip - ks[i - 1].tip).hypot().max(MIN_TIP_STEP_M);
            let v = 0.5 * (ks[i].speed_mps + ks[i - 1].speed_mps);
            if v > 0.0 && v.is_finite() {
                max_rate_rps * ds / v
            } else {
                f64::INFINITY
            }
        })
        .collect();
    if (1..n).all(|i| (want[i] - want[i - 1]).abs() <= step[i - 1]) {
        return false;
    }
    let mut yaw = want;
    spread_steps(&mut yaw, &step);
    for (k, &yaw) in ks.iter_mut().zip(&yaw) {
        let (old, new) = (
            kurbo::Vec2::from_angle(k.yaw_rad),
            kurbo::Vec2::from_angle(yaw),
        );
        // The foot sits `foot` along the fan from the rung's middle.
        let foot = (k.tip - k.mid).dot(old);
        k.tip = k.mid + new * foot;
        k.yaw_rad = wrap_pi(yaw);
    }
    true
}

/// The segments the fans of `ks` paint across: each knot's rung width
/// along its fan direction, about the rung's middle (its left end towards
/// −ψ, as a rung's). Where the turn limit left the fan off its rung, these
/// are the tiles the fan really sweeps.
pub fn fan_rungs(ks: &[Knot]) -> Vec<Rung> {
    ks.iter()
        .map(|k| {
            let half = 0.5 * k.width_m * kurbo::Vec2::from_angle(k.yaw_rad);
            Rung {
                left: k.mid - half,
                right: k.mid + half,
            }
        })
        .collect()
}

/// Keep every step `values[i] − values[i − 1]` within ±`step[i − 1]`,
/// moving the values as little as it takes and evenly to both sides of a
/// step that is too steep. Each such step moves both its values towards each
/// other by half the excess, sweep after sweep (projections onto every
/// step's constraint), so the change spreads to both sides of where it was
/// asked and the values stay put elsewhere; a last forward clamp removes
/// what the sweeps leave. The values stay within their first range.
pub fn spread_steps(values: &mut [f64], step: &[f64]) {
    let n = values.len();
    for sweep in 0..MAX_SWEEPS {
        let mut worst = 0.0f64;
        // Alternate directions so neither side is favoured.
        for k in 1..n {
            let i = if sweep % 2 == 0 { k } else { n - k };
            let d = values[i] - values[i - 1];
            let excess = d.abs() - step[i - 1];
            if excess > 0.0 {
                let half = 0.5 * excess * d.signum();
                values[i] -= half;
                values[i - 1] += half;
                worst = worst.max(excess);
            }
        }
        if worst < 1e-9 {
            break;
        }
    }
    for i in 1..n {
        values[i] = values[i].clamp(values[i - 1] - step[i - 1], values[i - 1] + step[i - 1]);
    }
}

/// [`spread_steps`] with the corners of the change rounded: around every
/// value it moved (and `passes` knots either side) the values are smoothed
/// by `passes` rounds of a (¼, ½, ¼) filter, ends kept, so the rate starts
/// and stops over a few knots instead of at one (the joint's acceleration).
/// Smoothing averages neighbouring steps, so each stays within the bounds
/// of its neighbourhood.
pub fn spread_smooth_steps(values: &mut [f64], step: &[f64], passes: usize) {
    let asked = values.to_vec();
    spread_steps(values, step);
    let n = values.len();
    let moved: Vec<usize> = (0..n)
        .filter(|&i| (values[i] - asked[i]).abs() > 1e-9)
        .collect();
    let near = |i: usize| moved.iter().any(|&m| m.abs_diff(i) <= passes);
    let mask: Vec<bool> = (0..n).map(|i| i > 0 && i + 1 < n && near(i)).collect();
    for _ in 0..passes {
        let prev = values.to_vec();
        for i in (0..n).filter(|&i| mask[i]) {
            values[i] = 0.25 * prev[i - 1] + 0.5 * prev[i] + 0.25 * prev[i + 1];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Vec2;

    fn knot(x: f64, yaw: f64) -> Knot {
        Knot {
            z_m: 0.1,
            yaw_rad: yaw,
            ..Knot::at(x, 0.0)
        }
    }

    #[test]
    fn a_sudden_turn_is_spread_within_the_rate() {
        // 90° between two knots 20 mm apart, at 0.2 m/s and 0.5 rad/s.
        let mut ks: Vec<Knot> = (0..40)
            .map(|i| knot(0.02 * i as f64, if i < 20 { 0.0 } else { 1.5 }))
            .collect();
        assert!(limit_turn_rate(&mut ks, 0.5));
        let max_step = 0.5 * 0.02 / 0.2;
        for w in ks.windows(2) {
            assert!(wrap_pi(w[1].yaw_rad - w[0].yaw_rad).abs() <= max_step + 1e-12);
        }
        // Centred: half the turn done at the place it was asked, and the
        // fan on its rungs away from it.
        let mid = 0.5 * (ks[19].yaw_rad + ks[20].yaw_rad);
        assert!((mid - 0.75).abs() < 0.02, "{mid}");
        assert!(ks[0].yaw_rad.abs() < 1e-9 && (ks[39].yaw_rad - 1.5).abs() < 1e-9);
    }

    #[test]
    fn a_turn_within_the_rate_is_kept() {
        let mut ks: Vec<Knot> = (0..10)
            .map(|i| knot(0.02 * i as f64, 0.01 * i as f64))
            .collect();
        let before = ks.clone();
        assert!(!limit_turn_rate(&mut ks, 0.5));
        assert_eq!(ks, before);
    }

    #[test]
    fn the_foot_turns_with_the_fan() {
        let mut ks: Vec<Knot> = (0..40)
            .map(|i| knot(0.02 * i as f64, if i < 20 { 0.0 } else { 1.5 }))
            .collect();
        for k in &mut ks {
            k.tip = k.mid - 0.01 * Vec2::from_angle(k.yaw_rad);
        }
        limit_turn_rate(&mut ks, 0.5);
        for k in &ks {
            let off = k.tip - k.mid;
            assert!((off.hypot() - 0.01).abs() < 1e-12);
            assert!(off.cross(Vec2::from_angle(k.yaw_rad)).abs() < 1e-12);
        }
    }
}
