//! State-to-state moves for the air between strokes: every joint goes from
//! its position and speed at one instant to another position and speed, all
//! joints in the same time, each within its own speed and acceleration
//! limit, and the move is as short as the slowest joint allows (a
//! time-synchronised, acceleration-limited profile per joint; Kröger &
//! Wahl, "Online trajectory generation", IEEE T-RO 26(1) 2010, type II
//! without the jerk).
//!
//! One joint's profile of a given duration T accelerates at ±A from v₀ to
//! a cruise speed v_c, cruises, and accelerates at ±A to v₁. Its distance
//! grows monotonically with v_c (d distance / d v_c is the cruise time ≥ 0),
//! so the v_c that covers the joint's travel is found by bisection, and the
//! durations for which some v_c does form a set of intervals (a joint that
//! arrives fast may be unable to take a little longer). The move's duration
//! is the shortest T every joint can take.

/// One joint's profile: from (p₀, v₀) accelerate at `a1` for `t1` to `vc`,
/// cruise for `t2`, accelerate at `a3` for `t3`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ramp {
    p0: f64,
    v0: f64,
    a1: f64,
    t1: f64,
    vc: f64,
    t2: f64,
    a3: f64,
    t3: f64,
}

impl Ramp {
    fn with_cruise(p0: f64, v0: f64, v1: f64, vc: f64, duration: f64, acc: [f64; 2]) -> Ramp {
        let (t1, t3) = ((vc - v0).abs() / acc[0], (v1 - vc).abs() / acc[1]);
        Ramp {
            p0,
            v0,
            a1: acc[0].copysign(vc - v0),
            t1,
            vc,
            t2: (duration - t1 - t3).max(0.0),
            a3: acc[1].copysign(v1 - vc),
            t3,
        }
    }

    fn distance(&self) -> f64 {
        let v1 = self.vc + self.a3 * self.t3;
        0.5 * (self.v0 + self.vc) * self.t1 + self.vc * self.t2 + 0.5 * (self.vc + v1) * self.t3
    }

    /// Times at which the acceleration switches.
    pub fn switches(&self) -> [f64; 3] {
        [self.t1, self.t1 + self.t2, self.t1 + self.t2 + self.t3]
    }

    /// Position, speed and acceleration at `t` from the start (held at the
    /// end speed past the end).
    pub fn at(&self, t: f64) -> (f64, f64, f64) {
        let t = t.max(0.0);
        let Ramp {
            p0,
            v0,
            a1,
            t1,
            vc,
            t2,
            a3,
            t3,
        } = *self;
        if t < t1 {
            return (p0 + v0 * t + 0.5 * a1 * t * t, v0 + a1 * t, a1);
        }
        let p1 = p0 + 0.5 * (v0 + vc) * t1;
        if t < t1 + t2 {
            return (p1 + vc * (t - t1), vc, 0.0);
        }
        let p2 = p1 + vc * t2;
        let u = (t - t1 - t2).min(t3);
        let p = p2 + vc * u + 0.5 * a3 * u * u;
        let past = (t - t1 - t2 - t3).max(0.0);
        let v = vc + a3 * u;
        (p + v * past, v, if t < t1 + t2 + t3 { a3 } else { 0.0 })
    }
}

/// Joint limits and end states of a move (per joint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ends<const N: usize> {
    pub p0: [f64; N],
    pub v0: [f64; N],
    pub p1: [f64; N],
    pub v1: [f64; N],
    pub vel: [f64; N],
    pub acc: [f64; N],
    /// Acceleration of the last phase, arriving (at most `acc`).
    pub acc_end: [f64; N],
}

/// The profile of one joint that takes exactly `duration`, if there is one
/// (`acc`: leaving and arriving accelerations).
fn ramp_in(
    (p0, v0): (f64, f64),
    (p1, v1): (f64, f64),
    vel: f64,
    acc: [f64; 2],
    duration: f64,
) -> Option<Ramp> {
    // The ramps' time is convex and piecewise linear in the cruise speed,
    // least at v0 or v1: the cruise speeds whose ramps fit in the duration
    // form an interval around that, cut to the speed limit (a little above
    // it where an end state already is).
    if p0 == p1 && v0 == 0.0 && v1 == 0.0 {
        // A joint at rest stays exactly where it is.
        return Some(Ramp::with_cruise(p0, 0.0, 0.0, 0.0, duration, acc));
    }
    let ramps = |vc: f64| (vc - v0).abs() / acc[0] + (v1 - vc).abs() / acc[1];
    let best = if ramps(v0) <= ramps(v1) { v0 } else { v1 };
    if ramps(best) > duration * (1.0 + 1e-12) + 1e-15 {
        return None;
    }
    let vmax = vel.max(v0.abs()).max(v1.abs());
    let edge = |far: f64| {
        if ramps(far) <= duration {
            return far;
        }
        let (mut a, mut b) = (best, far);
        for _ in 0..80 {
            let m = 0.5 * (a + b);
            if ramps(m) <= duration {
                a = m;
            } else {
                b = m;
            }
        }
        a
    };
    let (lo, hi) = (edge(-vmax), edge(vmax));
    let dist = |vc: f64| Ramp::with_cruise(p0, v0, v1, vc, duration, acc).distance();
    let d = p1 - p0;
    let tol = 1e-12 * (1.0 + d.abs());
    if d < dist(lo) - tol || d > dist(hi) + tol {
        return None;
    }
    let (mut a, mut b) = (lo, hi);
    for _ in 0..80 {
        let m = 0.5 * (a + b);
        if dist(m) < d {
            a = m;
        } else {
            b = m;
        }
    }
    Some(Ramp::with_cruise(p0, v0, v1, 0.5 * (a + b), duration, acc))
}

/// Every joint's profile for one duration, if each has one.
fn ramps_in<const N: usize>(e: &Ends<N>, duration: f64) -> Option<[Ramp; N]> {
    let mut out = [Ramp::with_cruise(0.0, 0.0, 0.0, 0.0, 0.0, [1.0; 2]); N];
    for (j, r) in out.iter_mut().enumerate() {
        let acc = [e.acc[j], e.acc_end[j].min(e.acc[j])];
        *r = ramp_in(
            (e.p0[j], e.v0[j]),
            (e.p1[j], e.v1[j]),
            e.vel[j],
            acc,
            duration,
        )?;
    }
    Some(out)
}

/// A time-synchronised move of N joints.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Synced<const N: usize> {
    pub duration_s: f64,
    pub ramps: [Ramp; N],
}

impl<const N: usize> Synced<N> {
    /// Sample times from 0 to the end: about every `step` s, and at every
    /// joint's acceleration switch (so a cubic between two samples never
    /// spans one), none closer than a tenth of `step` to another.
    pub fn sample_times(&self, step: f64, most: usize) -> Vec<f64> {
        let end = self.duration_s;
        let n = ((end / step).ceil() as usize).clamp(1, most);
        // (time, kept before a plain sample): the ends and the switches.
        let mut ts: Vec<(f64, bool)> = (0..=n)
            .map(|k| (end * k as f64 / n as f64, k == 0 || k == n))
            .collect();
        ts.extend(
            self.ramps
                .iter()
                .flat_map(|r| r.switches())
                .filter(|&t| t > 0.0 && t < end)
                .map(|t| (t, true)),
        );
        ts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let gap = 0.1 * end / n as f64;
        let mut out: Vec<(f64, bool)> = Vec::with_capacity(ts.len());
        for (t, firm) in ts {
            match out.last_mut() {
                Some(l) if t - l.0 < gap => {
                    // Too close: the firmer one stays (the end over all).
                    if (firm && !l.1) || t == end {
                        *l = (t, firm);
                    }
                }
                _ => out.push((t, firm)),
            }
        }
        if let Some(f) = out.first_mut() {
            *f = (0.0, true);
        }
        let out: Vec<f64> = out.into_iter().map(|(t, _)| t).collect();
        out
    }

    /// Joint positions and speeds at `t` from the start.
    pub fn at(&self, t: f64) -> ([f64; N], [f64; N]) {
        let mut q = [0.0; N];
        let mut qd = [0.0; N];
        for j in 0..N {
            (q[j], qd[j], _) = self.ramps[j].at(t);
        }
        (q, qd)
    }
}

/// Shortest time one joint takes from (p₀, v₀) to (p₁, v₁) within `vel`,
/// leaving at `acc[0]` and arriving at `acc[1]`, in closed form: speed up
/// to a peak and brake (or the mirror image), cruising at the speed limit
/// if the peak would pass it. The ordering's join cost (the slowest
/// joint's); `synced` finds the common duration.
pub fn min_time((p0, v0): (f64, f64), (p1, v1): (f64, f64), vel: f64, acc: [f64; 2]) -> f64 {
    let d = p1 - p0;
    let vel = vel.max(v0.abs()).max(v1.abs());
    let (h0, h1) = (0.5 / acc[0], 0.5 / acc[1]);
    let time = |top: f64| (top - v0).abs() / acc[0] + (top - v1).abs() / acc[1];
    // sign +1: up to a peak ≥ both speeds; −1: down to a trough ≤ both.
    let family = |sign: f64| -> Option<f64> {
        let x = (sign * d + v0 * v0 * h0 + v1 * v1 * h1) / (h0 + h1);
        if x < 0.0 {
            return None;
        }
        let peak = sign * x.sqrt();
        let (hi, lo) = (v0.max(v1), v0.min(v1));
        if (sign > 0.0 && peak < hi - 1e-12) || (sign < 0.0 && peak > lo + 1e-12) {
            return None;
        }
        if peak.abs() <= vel {
            return Some(time(peak));
        }
        let top = sign * vel;
        let ramp_d = sign * ((vel * vel - v0 * v0) * h0 + (vel * vel - v1 * v1) * h1);
        Some(time(top) + (d - ramp_d).abs() / vel)
    };
    match (family(1.0), family(-1.0)) {
        (Some(a), Some(b)) => a.min(b),
        (Some(a), None) | (None, Some(a)) => a,
        // Arriving slower than leaving, the fastest move may ramp the same
        // way twice (harder first): found by search.
        (None, None) => {
            let fits = |t: f64| ramp_in((p0, v0), (p1, v1), vel, acc, t).is_some();
            first_feasible(0.0, &fits).unwrap_or(f64::INFINITY)
        }
    }
}

/// The first duration from `lo` on for which `fits` holds: 1 % steps, then
/// bisection to `DURATION_TOL_S`; None past `MAX_DURATION_S`.
fn first_feasible(mut lo: f64, fits: &dyn Fn(f64) -> bool) -> Option<f64> {
    if fits(lo) {
        return Some(lo);
    }
    loop {
        let hi = lo * GROWTH + 1e-3;
        if hi > MAX_DURATION_S {
            return None;
        }
        if fits(hi) {
            let (mut a, mut b) = (lo, hi);
            while b - a > DURATION_TOL_S {
                let m = 0.5 * (a + b);
                if fits(m) {
                    b = m;
                } else {
                    a = m;
                }
            }
            return Some(b);
        }
        lo = hi;
    }
}

/// Longest move looked for (s). assumed: far above any join of a station
/// (a yaw turn of 4π at 30°/s takes 24 s).
const MAX_DURATION_S: f64 = 120.0;
/// Growth of the duration while looking for the first feasible one: 1 %
/// plus 1 ms a step, then bisection to `DURATION_TOL_S`.
const GROWTH: f64 = 1.01;
const DURATION_TOL_S: f64 = 1e-6;

/// The shortest move every joint can make in the same time, from
/// (p₀, v₀) to (p₁, v₁) within its limits; None if none is found under
/// `MAX_DURATION_S` or a number is not finite.
pub fn synced<const N: usize>(e: &Ends<N>) -> Option<Synced<N>> {
    let finite = |a: &[f64; N]| a.iter().all(|v| v.is_finite());
    if ![e.p0, e.v0, e.p1, e.v1, e.vel, e.acc, e.acc_end]
        .iter()
        .all(finite)
        || e.vel
            .iter()
            .chain(&e.acc)
            .chain(&e.acc_end)
            .any(|&l| l <= 0.0)
    {
        return None;
    }
    // No duration below the slowest joint's own shortest.
    let mut lo = (0..N)
        .map(|j| {
            let acc = [e.acc[j], e.acc_end[j].min(e.acc[j])];
            min_time((e.p0[j], e.v0[j]), (e.p1[j], e.v1[j]), e.vel[j], acc)
        })
        .fold(0.0, f64::max);
    if !lo.is_finite() {
        return None;
    }
    // Rounding: a hair above (the slowest joint's window can be that thin:
    // one arriving fast may not be able to take a little longer).
    lo = lo * (1.0 + 1e-9) + 1e-12;
    let t = first_feasible(lo, &|t| ramps_in(e, t).is_some())?;
    ramps_in(e, t).map(|ramps| Synced {
        duration_s: t,
        ramps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn ends(p0: f64, v0: f64, p1: f64, v1: f64) -> Ends<1> {
        Ends {
            p0: [p0],
            v0: [v0],
            p1: [p1],
            v1: [v1],
            vel: [1.0],
            acc: [2.0],
            acc_end: [2.0],
        }
    }

    #[test]
    fn rest_to_rest_is_the_trapezoid() {
        // 2 m at 1 m/s, 2 m/s²: 0.5 s up, 1.5 s cruise, 0.5 s down.
        let m = synced(&ends(0.0, 0.0, 2.0, 0.0)).unwrap();
        assert!((m.duration_s - 2.5).abs() < 1e-5, "{}", m.duration_s);
        // Short: a triangle, 2·sqrt(d/a).
        let m = synced(&ends(0.0, 0.0, 0.18, 0.0)).unwrap();
        assert!((m.duration_s - 0.6).abs() < 1e-5, "{}", m.duration_s);
    }

    #[test]
    fn flying_through_takes_distance_over_speed() {
        let m = synced(&ends(0.0, 1.0, 3.0, 1.0)).unwrap();
        assert!((m.duration_s - 3.0).abs() < 1e-5);
    }

    #[test]
    fn a_slower_joint_is_stretched_to_the_slowest() {
        let e = Ends {
            p0: [0.0, 0.0],
            v0: [0.0, 0.5],
            p1: [2.0, 0.1],
            v1: [0.0, -0.5],
            vel: [1.0, 1.0],
            acc: [2.0, 2.0],
            acc_end: [2.0, 2.0],
        };
        let m = synced(&e).unwrap();
        assert!((m.duration_s - 2.5).abs() < 1e-5);
        let (q, qd) = m.at(m.duration_s);
        assert!((q[1] - 0.1).abs() < 1e-6 && (qd[1] + 0.5).abs() < 1e-9);
    }

    proptest! {
        /// The closed form is the single-joint move's duration.
        #[test]
        fn min_time_is_the_one_joint_move(
            p0 in -3.0..3.0f64, v0 in -1.0..1.0f64, p1 in -3.0..3.0f64, v1 in -1.0..1.0f64,
        ) {
            let e = Ends { acc_end: [0.7], ..ends(p0, v0, p1, v1) };
            let m = synced(&e).unwrap();
            let t = min_time((p0, v0), (p1, v1), 1.0, [2.0, 0.7]);
            prop_assert!((t - m.duration_s).abs() < 1e-5, "{t} vs {}", m.duration_s);
        }
    }

    proptest! {
        /// Every joint ends at its target state, within its limits on the way.
        #[test]
        fn ends_where_asked_within_limits(
            p0 in -3.0..3.0f64, v0 in -1.0..1.0f64, p1 in -3.0..3.0f64, v1 in -1.0..1.0f64,
            p0b in -3.0..3.0f64, v0b in -0.5..0.5f64, p1b in -3.0..3.0f64, v1b in -0.5..0.5f64,
        ) {
            let e = Ends {
                p0: [p0, p0b], v0: [v0, v0b], p1: [p1, p1b], v1: [v1, v1b],
                vel: [1.0, 0.5], acc: [2.0, 5.0], acc_end: [1.0, 5.0],
            };
            let m = synced(&e).unwrap();
            let (q, qd) = m.at(m.duration_s);
            for j in 0..2 {
                prop_assert!((q[j] - e.p1[j]).abs() < 1e-6, "joint {j}: {} vs {}", q[j], e.p1[j]);
                prop_assert!((qd[j] - e.v1[j]).abs() < 1e-6);
            }
            let n = 200;
            let mut prev = m.at(0.0).1;
            for k in 1..=n {
                let t = m.duration_s * k as f64 / n as f64;
                let (_, v) = m.at(t);
                for j in 0..2 {
                    prop_assert!(v[j].abs() <= e.vel[j] + 1e-9);
                    let a = (v[j] - prev[j]) / (m.duration_s / n as f64);
                    prop_assert!(a.abs() <= e.acc[j] * (1.0 + 1e-6) + 1e-9);
                }
                prev = v;
            }
        }
    }
}
