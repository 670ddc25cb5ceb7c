//! Strokes narrower than the narrowest fan: the fan turned off the rung.
//!
//! Where a rung is narrower than the fan at the vertical joint's lowest
//! height (`knots::knots` clamps the height there), the fan's footprint is
//! longer than the rung. Turned by φ off the rung's direction, the
//! footprint covers `fan · cos φ` across the stroke; with cos φ = rung /
//! fan it covers the rung exactly, so the paint stays on the stroke
//! instead of landing beside it, and the speed (`knots::pace`, from the
//! road the turned footprint sweeps) keeps the film on target.
//!
//! A turned footprint reaches `fan/2 · sin φ` ahead of and behind its rung,
//! so at a stroke's ends it would paint past the end on one side and leave
//! a wedge on the other: the turn is zero at both ends and grows from them
//! no faster than the fan joint may turn at the painting speed (what the
//! rungs' own turning leaves of `tuning::Rates::turn_share` of its speed limit).
//! Between, the heights stay clamped and the ends paint a little wide, as
//! before.

use basr_robot::kinematics::wrap_pi;

use crate::knots::{Knot, MIN_TIP_STEP_M};
use crate::rungs::Rung;
use crate::tuning::Narrow;

/// Turn each clamped knot's fan off its rung (`rungs[i]`, the pass's
/// rungs) so that it covers the rung, within the fan joint's turn rate
/// `max_turn_rps` at the film's painting speeds (`k_m2ps` / rung width),
/// zero at the pass's ends. A fan the turn limit (`turn`) already left off
/// its rung turns on from there, the same way for the whole pass; the
/// knot's `turn_rad` is then its whole angle off the rung. Returns whether
/// any knot turned (the caller paces the pass again).
pub fn turn_narrow(
    rungs: &[Rung],
    ks: &mut [Knot],
    max_turn_rps: f64,
    k_m2ps: f64,
    tuning: &Narrow,
) -> bool {
    let n = ks.len().min(rungs.len());
    if n < 3 || !(max_turn_rps > 0.0 && k_m2ps > 0.0) {
        return false;
    }
    // How far each fan already is off its rung (rad, signed), and the
    // angle off the rung that covers it (0 where nothing is to turn).
    let off: Vec<f64> = (0..n)
        .map(|i| {
            let d = rungs[i].right - rungs[i].left;
            if d.hypot() > 0.0 {
                // The fan paints a line: ψ and ψ + π are the same fan.
                let a = wrap_pi(ks[i].yaw_rad - d.atan2());
                wrap_pi(2.0 * a) / 2.0
            } else {
                0.0
            }
        })
        .collect();
    let cover: Vec<f64> = (0..n)
        .map(|i| {
            let k = &ks[i];
            let inner = i > 0 && i + 1 < n;
            let clamped = k.fan_width_m > k.width_m * (1.0 + 1e-9) && k.width_m > 0.0;
            if inner && clamped && k.tilt_rad.abs() <= tuning.leaned_rad {
                (k.width_m / k.fan_width_m).acos().min(tuning.max_turn_rad)
            } else {
                0.0
            }
        })
        .collect();
    if cover.iter().all(|&c| c == 0.0) {
        return false;
    }
    // One way for the pass: the way its fans already lean off their rungs
    // (counter-clockwise where they do not).
    let lean: f64 = (0..n).filter(|&i| cover[i] > 0.0).map(|i| off[i]).sum();
    let way = if lean < 0.0 { -1.0 } else { 1.0 };
    // The turn each knot wants on top of where it is, that way.
    let want: Vec<f64> = (0..n)
        .map(|i| (cover[i] - way * off[i]).max(0.0) * f64::from(cover[i] > 0.0))
        .collect();
    // step[i]: the turn allowed between knots i − 1 and i, at the speed
    // the narrower of the two is painted at once covered, less what the
    // fans turn there already.
    let step: Vec<f64> = (0..n)
        .map(|i| {
            if i == 0 {
                return 0.0;
            }
            let (a, b) = (&ks[i - 1], &ks[i]);
            let ds = (b.tip - a.tip).hypot().max(MIN_TIP_STEP_M);
            let w = a.width_m.min(b.width_m).max(MIN_TIP_STEP_M);
            let dt = ds * w / k_m2ps;
            let own = wrap_pi(b.yaw_rad - a.yaw_rad);
            (max_turn_rps * dt - own.abs()).max(0.0)
        })
        .collect();
    let within_rate = |phi: &mut Vec<f64>| {
        for i in 1..n {
            phi[i] = phi[i].min(phi[i - 1] + step[i]);
        }
        for i in (0..n - 1).rev() {
            phi[i] = phi[i].min(phi[i + 1] + step[i + 1]);
        }
    };
    let mut phi = want.clone();
    within_rate(&mut phi);
    // Round the turn's corners (where it starts and stops growing) so the
    // fan joint's acceleration is not asked for a step in its rate, then
    // hold it within the rate again (the mean of three neighbours passes
    // it where the steps differ), never beyond what a rung wants.
    for _ in 0..tuning.smoothing {
        let prev = phi.clone();
        for i in 1..n - 1 {
            phi[i] = want[i].min((prev[i - 1] + prev[i] + prev[i + 1]) / 3.0);
        }
    }
    within_rate(&mut phi);
    let mut any = false;
    for i in 0..n {
        if phi[i] <= 1e-9 {
            continue;
        }
        let k = &mut ks[i];
        let (old, new) = (
            kurbo::Vec2::from_angle(k.yaw_rad),
            kurbo::Vec2::from_angle(k.yaw_rad + way * phi[i]),
        );
        // The foot stays where it was along the fan (as `turn` keeps it).
        let foot = (k.tip - k.mid).dot(old);
        k.tip = k.mid + new * foot;
        k.yaw_rad += way * phi[i];
        k.turn_rad = (off[i] + way * phi[i]).abs();
        any = true;
    }
    any
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The planner's default tuning of the turn.
    const N: Narrow = crate::tuning::Tuning::DEFAULT.narrow;
    use kurbo::Point;

    /// A straight pass along +y of `n` rungs `w` wide, 10 mm apart.
    fn rungs(n: usize, w: f64) -> Vec<Rung> {
        (0..n)
            .map(|i| Rung {
                left: Point::new(-w / 2.0, 0.01 * i as f64),
                right: Point::new(w / 2.0, 0.01 * i as f64),
            })
            .collect()
    }

    /// Their knots, painted with a fan `fan` long (clamped where longer).
    fn pass(n: usize, w: f64, fan: f64) -> Vec<Knot> {
        (0..n)
            .map(|i| {
                let p = Point::new(0.0, 0.01 * i as f64);
                Knot {
                    mid: p,
                    tip: p,
                    z_m: 0.08,
                    yaw_rad: 0.0,
                    tilt_rad: 0.0,
                    width_m: w,
                    fan_width_m: fan.max(w),
                    turn_rad: 0.0,
                    swept_width_m: w,
                    speed_mps: 0.1,
                }
            })
            .collect()
    }

    #[test]
    fn a_clamped_fan_turns_to_cover_the_rung_and_not_at_the_ends() {
        let mut ks = pass(300, 0.073, 0.097);
        assert!(turn_narrow(&rungs(300, 0.073), &mut ks, 0.44, 0.0158, &N));
        let mid = &ks[150];
        assert!((mid.covered_width_m() - 0.073).abs() < 1e-9);
        assert!((mid.yaw_rad - mid.turn_rad).abs() < 1e-12);
        assert_eq!(ks[0].turn_rad, 0.0);
        assert_eq!(ks[299].turn_rad, 0.0);
        // Within the turn rate at the painting speed k / w.
        for w in ks.windows(2) {
            let dt = 0.01 * 0.073 / 0.0158;
            assert!((w[1].turn_rad - w[0].turn_rad).abs() <= 0.44 * dt + 1e-12);
        }
        // Never more than the rung needs.
        assert!(ks.iter().all(|k| k.covered_width_m() >= k.width_m - 1e-12));
    }

    #[test]
    fn a_fan_on_its_rung_or_leaned_does_not_turn() {
        let mut ks = pass(50, 0.2, 0.2);
        assert!(!turn_narrow(&rungs(50, 0.2), &mut ks, 0.44, 0.0158, &N));
        let mut ks = pass(50, 0.07, 0.1);
        for k in &mut ks {
            k.tilt_rad = 0.1;
        }
        assert!(!turn_narrow(&rungs(50, 0.07), &mut ks, 0.44, 0.0158, &N));
        assert!(ks.iter().all(|k| k.turn_rad == 0.0));
    }

    #[test]
    fn a_pointed_rung_turns_no_more_than_the_limit() {
        let mut ks = pass(400, 0.01, 0.1);
        turn_narrow(&rungs(400, 0.01), &mut ks, 10.0, 0.0158, &N);
        assert!(ks.iter().all(|k| k.turn_rad <= N.max_turn_rad + 1e-12));
        assert!((ks[200].turn_rad - N.max_turn_rad).abs() < 1e-12);
        // the limit is the tuning's
        let low = Narrow {
            max_turn_rad: 0.5,
            ..N
        };
        let mut ks = pass(400, 0.01, 0.1);
        turn_narrow(&rungs(400, 0.01), &mut ks, 10.0, 0.0158, &low);
        assert!((ks[200].turn_rad - 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_fan_leaned_up_to_the_tuning_s_lean_still_turns() {
        let leaned = |lean: f64, tuning: &Narrow| {
            let mut ks = pass(300, 0.073, 0.097);
            for k in &mut ks {
                k.tilt_rad = lean;
            }
            turn_narrow(&rungs(300, 0.073), &mut ks, 0.44, 0.0158, tuning)
        };
        let two = 2f64.to_radians();
        assert!(!leaned(two, &N), "2° is leaned at the default 1°");
        let three = Narrow {
            leaned_rad: 3f64.to_radians(),
            ..N
        };
        assert!(leaned(two, &three), "and not at 3°");
    }

    #[test]
    fn a_fan_already_off_its_rung_turns_on_to_cover_it_exactly() {
        // The turn limit left every fan 0.2 rad off its rung.
        let mut ks = pass(300, 0.073, 0.097);
        for k in &mut ks {
            k.yaw_rad += 0.2;
        }
        assert!(turn_narrow(&rungs(300, 0.073), &mut ks, 0.44, 0.0158, &N));
        let mid = &ks[150];
        // The whole angle off the rung covers it: fan · cos(angle) = rung.
        assert!((mid.yaw_rad.cos().abs() * 0.097 - 0.073).abs() < 1e-9);
        assert!((mid.covered_width_m() - 0.073).abs() < 1e-9);
    }

    #[test]
    fn a_turn_limited_by_uneven_steps_stays_within_the_rate_after_smoothing() {
        // Rung spacing alternating 2 and 20 mm: the steps allowed differ.
        let n = 200;
        let rs: Vec<Rung> = (0..n)
            .map(|i| {
                let y = 0.011 * i as f64 + if i % 2 == 0 { 0.0 } else { -0.009 };
                Rung {
                    left: Point::new(-0.0365, y),
                    right: Point::new(0.0365, y),
                }
            })
            .collect();
        let mut ks = pass(n, 0.073, 0.097);
        for (k, r) in ks.iter_mut().zip(&rs) {
            k.mid = r.mid();
            k.tip = r.mid();
        }
        turn_narrow(&rs, &mut ks, 0.44, 0.0158, &N);
        for w in ks.windows(2) {
            let ds = (w[1].tip - w[0].tip).hypot();
            let dt = ds * 0.073 / 0.0158;
            assert!(
                (w[1].turn_rad - w[0].turn_rad).abs() <= 0.44 * dt + 1e-12,
                "{} over {ds} m",
                (w[1].turn_rad - w[0].turn_rad).abs()
            );
        }
    }
}
