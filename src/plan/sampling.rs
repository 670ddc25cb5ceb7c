//! Timed joint setpoints of one station at a fixed period: painting runs
//! timed along shape-preserving joint splines by a phase-plane (TOPP-style) speed law,
//! rest-to-rest cycloidal air moves between them, all sampled at the period.
//!
//! A painting run is a joint path through its knots (plus a lead-in and a
//! lead-out). Its path parameter s is the nozzle's arc length on the road;
//! each joint is a shape-preserving cubic (PCHIP) q_j(s) through the knots. The speed
//! ṡ(s) is the largest that (a) does not exceed the painting speed of
//! 001 eq. 2.6 at that place and (b) keeps every joint's velocity
//! |q'_j ṡ| and acceleration |q'_j s̈ + q''_j ṡ²| within its limits (the
//! phase-plane formulation of time-optimal path parameterisation, as in
//! TOPP-RA: a velocity-limit curve, a forward pass at the largest
//! acceleration and a backward pass at the largest braking). Air moves are
//! straight lines in joint space with the cycloidal profile
//! s(τ) = τ − sin(2πτ)/(2π): zero velocity and acceleration at both ends,
//! bounded jerk. The samples are checked against the limits by finite
//! differences; a run that breaks one is re-planned with tighter limits.

use crate::robot::{Joints, Robot};

/// Fraction of each velocity limit the planner uses.
const VEL_SHARE: f64 = 0.97;
/// Fraction of each acceleration limit the planner uses at first.
const ACC_SHARE: f64 = 0.85;
/// Each re-plan multiplies the shares by this.
const RETRY_SHRINK: f64 = 0.7;
/// Re-plans before giving up.
const MAX_RETRIES: usize = 8;
/// Phase-plane grid step along the path (m of nozzle travel).
const GRID_STEP_M: f64 = 0.002;

/// Joint vector in `Limits::NAMES` order.
pub type Q = [f64; 5];

/// Errors of the time law.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SamplingError {
    #[error("a painting run of {0} knots is too short to time (needs ≥ 2 knots)")]
    Short(usize),
    #[error("path parameter not increasing at knot {0}: two knots share one place")]
    NotIncreasing(usize),
    #[error(
        "the time law could not keep {joint} within its limits after {MAX_RETRIES} re-plans; \
         the path is too sharp for the robot"
    )]
    Limits { joint: String },
}

/// A painting run: joints at each knot, the nozzle's arc length there and
/// the largest nozzle speed allowed there (the painting speed).
#[derive(Clone, Debug)]
pub struct RunPath {
    pub q: Vec<Q>,
    pub s: Vec<f64>,
    pub v_max: Vec<f64>,
}

/// One sample of a timed segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub q: Q,
    /// Path parameter (m) for runs; 0..1 fraction for air moves.
    pub s: f64,
    /// ṡ (m/s) for runs.
    pub sdot: f64,
}

/// Limits as plain arrays in `Limits::NAMES` order.
#[derive(Clone, Copy, Debug)]
pub struct JointLimits {
    pub min: Q,
    pub max: Q,
    pub vel: Q,
    pub acc: Q,
}

impl JointLimits {
    pub fn of(robot: &Robot) -> JointLimits {
        let mut l = JointLimits {
            min: [0.0; 5],
            max: [0.0; 5],
            vel: [0.0; 5],
            acc: [0.0; 5],
        };
        for (j, (_, lim)) in robot.limits.iter().enumerate() {
            l.min[j] = lim.min;
            l.max[j] = lim.max;
            l.vel[j] = lim.max_vel;
            l.acc[j] = lim.max_acc;
        }
        // The tilt's ball nut has its own speed limit (SPEC §4: 0.11 m/s):
        // as a tilt-rate limit, at the steepest nut travel per radian.
        let t = &robot.limits.tilt_rad;
        let fb = &robot.end_effector.fourbar;
        let steepest = (0..=60)
            .filter_map(|k| fb.nut_rate_m_per_rad(t.min + (t.max - t.min) * k as f64 / 60.0))
            .map(f64::abs)
            .fold(0.0, f64::max);
        if steepest > 0.0 {
            l.vel[4] = l.vel[4].min(robot.end_effector.tilt_nut_max_speed_mps / (steepest * 1.01));
        }
        l
    }
}

pub fn q_of(j: &Joints) -> Q {
    j.values()
}

pub fn joints_of(q: &Q) -> Joints {
    Joints {
        base_rot_rad: q[0],
        extension_m: q[1],
        vertical_m: q[2],
        ee_yaw_rad: q[3],
        tilt_rad: q[4],
    }
}

/// Names for messages, in `Q` order.
const NAMES: [&str; 5] = crate::robot::Limits::NAMES;

/// Slopes of the shape-preserving piecewise cubic Hermite interpolant
/// (PCHIP, Fritsch–Carlson): no overshoot between knots, so a joint held at
/// its limit over a stretch of knots never leaves its range in between.
fn pchip_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let h: Vec<f64> = (0..n - 1).map(|i| x[i + 1] - x[i]).collect();
    let del: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    let mut d = vec![0.0; n];
    if n == 2 {
        d[0] = del[0];
        d[1] = del[0];
        return d;
    }
    for i in 1..n - 1 {
        if del[i - 1] * del[i] > 0.0 {
            let w1 = 2.0 * h[i] + h[i - 1];
            let w2 = h[i] + 2.0 * h[i - 1];
            d[i] = (w1 + w2) / (w1 / del[i - 1] + w2 / del[i]);
        }
    }
    // One-sided three-point ends, kept shape-preserving.
    let end = |h0: f64, h1: f64, d0: f64, d1: f64| {
        let v = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
        if v * d0 <= 0.0 {
            0.0
        } else if d0 * d1 <= 0.0 && v.abs() > 3.0 * d0.abs() {
            3.0 * d0
        } else {
            v
        }
    };
    d[0] = end(h[0], h[1], del[0], del[1]);
    d[n - 1] = end(h[n - 2], h[n - 3], del[n - 2], del[n - 3]);
    d
}

/// A joint path q(s) as five PCHIP interpolants.
struct JointSpline {
    s: Vec<f64>,
    q: Vec<Q>,
    d: Vec<Q>,
}

impl JointSpline {
    fn new(s: &[f64], q: &[Q]) -> JointSpline {
        let mut d = vec![[0.0; 5]; s.len()];
        for j in 0..5 {
            let y: Vec<f64> = q.iter().map(|v| v[j]).collect();
            for (i, v) in pchip_slopes(s, &y).into_iter().enumerate() {
                d[i][j] = v;
            }
        }
        JointSpline {
            s: s.to_vec(),
            q: q.to_vec(),
            d,
        }
    }

    fn interval(&self, s: f64) -> usize {
        let n = self.s.len();
        self.s.partition_point(|&x| x <= s).clamp(1, n - 1) - 1
    }

    /// q, q' and q'' at s (cubic Hermite on the interval holding s).
    fn eval(&self, s: f64) -> (Q, Q, Q) {
        let i = self.interval(s);
        let (s0, s1) = (self.s[i], self.s[i + 1]);
        let h = s1 - s0;
        let t = ((s - s0) / h).clamp(0.0, 1.0);
        let (t2, t3) = (t * t, t * t * t);
        let mut q = [0.0; 5];
        let mut d1 = [0.0; 5];
        let mut d2 = [0.0; 5];
        for j in 0..5 {
            let (y0, y1) = (self.q[i][j], self.q[i + 1][j]);
            let (m0, m1) = (self.d[i][j] * h, self.d[i + 1][j] * h);
            q[j] = (2.0 * t3 - 3.0 * t2 + 1.0) * y0
                + (t3 - 2.0 * t2 + t) * m0
                + (-2.0 * t3 + 3.0 * t2) * y1
                + (t3 - t2) * m1;
            d1[j] = ((6.0 * t2 - 6.0 * t) * y0
                + (3.0 * t2 - 4.0 * t + 1.0) * m0
                + (-6.0 * t2 + 6.0 * t) * y1
                + (3.0 * t2 - 2.0 * t) * m1)
                / h;
            d2[j] = ((12.0 * t - 6.0) * y0
                + (6.0 * t - 4.0) * m0
                + (-12.0 * t + 6.0) * y1
                + (6.0 * t - 2.0) * m1)
                / (h * h);
        }
        (q, d1, d2)
    }
}

/// Largest and smallest path acceleration s̈ allowed at (q', q'', x = ṡ²).
fn accel_bounds(d1: &Q, d2: &Q, x: f64, acc: &Q) -> (f64, f64) {
    let mut lo = f64::NEG_INFINITY;
    let mut hi = f64::INFINITY;
    for j in 0..5 {
        let c = d2[j] * x;
        if d1[j].abs() < 1e-12 {
            continue;
        }
        let u1 = (acc[j] - c) / d1[j];
        let u2 = (-acc[j] - c) / d1[j];
        lo = lo.max(u1.min(u2));
        hi = hi.min(u1.max(u2));
    }
    (lo, hi)
}

/// Time one painting run and sample it at `period`, starting at rest at
/// its first knot and ending at rest at its last; the last sample is the
/// path's end (held), so the segment lasts `samples.len() × period`.
pub fn time_run(
    run: &RunPath,
    limits: &JointLimits,
    period: f64,
) -> Result<Vec<Sample>, SamplingError> {
    let n = run.q.len();
    if n < 2 {
        return Err(SamplingError::Short(n));
    }
    for i in 1..n {
        if run.s[i].partial_cmp(&run.s[i - 1]) != Some(std::cmp::Ordering::Greater) {
            return Err(SamplingError::NotIncreasing(i));
        }
    }
    let spline = JointSpline::new(&run.s, &run.q);
    let mut vel_share = VEL_SHARE;
    let mut acc_share = ACC_SHARE;
    let mut last_bad = String::new();
    for _ in 0..=MAX_RETRIES {
        let vel: Q = std::array::from_fn(|j| limits.vel[j] * vel_share);
        let acc: Q = std::array::from_fn(|j| limits.acc[j] * acc_share);
        let samples = plan_run(run, &spline, &vel, &acc, period);
        match check_samples(&samples, limits, period) {
            None => return Ok(samples),
            Some(j) => {
                last_bad = NAMES[j].to_string();
                vel_share *= RETRY_SHRINK.sqrt();
                acc_share *= RETRY_SHRINK;
            }
        }
    }
    Err(SamplingError::Limits { joint: last_bad })
}

fn plan_run(run: &RunPath, spline: &JointSpline, vel: &Q, acc: &Q, period: f64) -> Vec<Sample> {
    let s_end = *run.s.last().unwrap_or(&0.0);
    let s_start = run.s[0];
    let steps = (((s_end - s_start) / GRID_STEP_M).ceil() as usize).max(1);
    let ds = (s_end - s_start) / steps as f64;
    let grid: Vec<f64> = (0..=steps).map(|k| s_start + k as f64 * ds).collect();
    let derivs: Vec<(Q, Q)> = grid
        .iter()
        .map(|&s| {
            let (_, d1, d2) = spline.eval(s);
            (d1, d2)
        })
        .collect();
    // Velocity-limit curve on x = ṡ².
    let mut x: Vec<f64> = grid
        .iter()
        .zip(&derivs)
        .map(|(&s, (d1, d2))| {
            let v = v_max_at(run, s);
            let mut xm = v * v;
            for j in 0..5 {
                if d1[j].abs() > 1e-12 {
                    xm = xm.min((vel[j] / d1[j].abs()).powi(2));
                }
                // Leave half the acceleration for speeding up and braking.
                if d2[j].abs() > 1e-12 {
                    xm = xm.min(0.5 * acc[j] / d2[j].abs());
                }
            }
            xm
        })
        .collect();
    x[0] = 0.0;
    x[steps] = 0.0;
    // Forward pass: the fastest speeding up.
    for k in 0..steps {
        let (_, hi) = accel_bounds(&derivs[k].0, &derivs[k].1, x[k], acc);
        let reach = x[k] + 2.0 * ds * hi.max(0.0);
        x[k + 1] = x[k + 1].min(reach);
    }
    // Backward pass: the hardest braking.
    for k in (0..steps).rev() {
        let (lo, _) = accel_bounds(&derivs[k + 1].0, &derivs[k + 1].1, x[k + 1], acc);
        let reach = x[k + 1] + 2.0 * ds * (-lo).max(0.0);
        x[k] = x[k].min(reach);
    }
    // Time at each grid point (constant s̈ between grid points).
    let mut t = vec![0.0; steps + 1];
    for k in 0..steps {
        let v0 = x[k].max(0.0).sqrt();
        let v1 = x[k + 1].max(0.0).sqrt();
        let dt = if v0 + v1 > 0.0 {
            2.0 * ds / (v0 + v1)
        } else {
            0.0
        };
        t[k + 1] = t[k] + dt;
    }
    let total = t[steps];
    let count = (total / period).ceil() as usize + 1;
    let mut out = Vec::with_capacity(count);
    let mut k = 0usize;
    for i in 0..count {
        let ti = (i as f64 * period).min(total);
        while k + 1 < steps && t[k + 1] < ti {
            k += 1;
        }
        let dt_k = t[k + 1] - t[k];
        let (v0, v1) = (x[k].max(0.0).sqrt(), x[k + 1].max(0.0).sqrt());
        let (s, sdot) = if dt_k > 0.0 {
            let a = (v1 - v0) / dt_k;
            let tau = (ti - t[k]).clamp(0.0, dt_k);
            (grid[k] + v0 * tau + 0.5 * a * tau * tau, v0 + a * tau)
        } else {
            (grid[k], v0)
        };
        let s = s.clamp(s_start, s_end);
        let (q, _, _) = spline.eval(s);
        out.push(Sample { q, s, sdot });
    }
    out
}

/// Painting-speed limit at s: linear between knots.
fn v_max_at(run: &RunPath, s: f64) -> f64 {
    let n = run.s.len();
    let i = match run.s.binary_search_by(|x| x.total_cmp(&s)) {
        Ok(i) => return run.v_max[i],
        Err(i) => i.clamp(1, n - 1),
    };
    let (s0, s1) = (run.s[i - 1], run.s[i]);
    let f = ((s - s0) / (s1 - s0)).clamp(0.0, 1.0);
    run.v_max[i - 1] + f * (run.v_max[i] - run.v_max[i - 1])
}

/// Rest-to-rest cycloidal move from `a` to `b`, sampled at `period`,
/// excluding the first sample (`a`) and including the last (`b`).
pub fn air_move(a: &Q, b: &Q, limits: &JointLimits, period: f64) -> Vec<Sample> {
    use std::f64::consts::{PI, TAU};
    // Cycloid: peak ṡ = 2/T, peak s̈ = 2π/T² (s ∈ [0, 1]).
    let mut tm: f64 = 0.0;
    for j in 0..5 {
        let d = (b[j] - a[j]).abs();
        if d > 0.0 {
            tm = tm.max(2.0 * d / (limits.vel[j] * VEL_SHARE));
            tm = tm.max((2.0 * PI * d / (limits.acc[j] * ACC_SHARE)).sqrt());
        }
    }
    let steps = (tm / period).ceil() as usize;
    if steps == 0 {
        return vec![];
    }
    let total = steps as f64 * period;
    (1..=steps)
        .map(|i| {
            let tau = i as f64 / steps as f64;
            let s = tau - (TAU * tau).sin() / TAU;
            let q = std::array::from_fn(|j| a[j] + s * (b[j] - a[j]));
            let sdot = (1.0 - (TAU * tau).cos()) / total;
            Sample { q, s, sdot }
        })
        .collect()
}

/// The first joint whose samples break a limit (finite differences), if any.
pub fn check_samples(samples: &[Sample], limits: &JointLimits, period: f64) -> Option<usize> {
    for j in 0..5 {
        for w in samples.windows(2) {
            if (w[1].q[j] - w[0].q[j]).abs() / period > limits.vel[j] {
                return Some(j);
            }
        }
        for w in samples.windows(3) {
            let a = (w[2].q[j] - 2.0 * w[1].q[j] + w[0].q[j]) / (period * period);
            if a.abs() > limits.acc[j] {
                return Some(j);
            }
        }
        for s in samples {
            if s.q[j] < limits.min[j] - 1e-9 || s.q[j] > limits.max[j] + 1e-9 {
                return Some(j);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> JointLimits {
        JointLimits {
            min: [-10.0; 5],
            max: [10.0; 5],
            vel: [1.0; 5],
            acc: [2.0; 5],
        }
    }

    #[test]
    fn spline_reproduces_a_line_and_never_overshoots() {
        let s = [0.0, 1.0, 2.0, 3.0];
        let q: Vec<Q> = s.iter().map(|&x| [2.0 * x, 0.0, 0.0, 0.0, 0.0]).collect();
        let sp = JointSpline::new(&s, &q);
        let (v, d1, d2) = sp.eval(1.5);
        assert!((v[0] - 3.0).abs() < 1e-12 && (d1[0] - 2.0).abs() < 1e-12 && d2[0].abs() < 1e-12);
        // A step held at a limit: values stay within [0, 1] everywhere.
        let q: Vec<Q> = [0.0, 0.0, 1.0, 1.0, 1.0]
            .iter()
            .map(|&v| [v, 0.0, 0.0, 0.0, 0.0])
            .collect();
        let s = [0.0, 1.0, 2.0, 3.0, 4.0];
        let sp = JointSpline::new(&s, &q);
        for k in 0..=400 {
            let (v, _, _) = sp.eval(k as f64 * 0.01);
            assert!((-1e-12..=1.0 + 1e-12).contains(&v[0]), "{v:?}");
        }
    }

    #[test]
    fn straight_run_reaches_and_holds_the_painting_speed() {
        // 1 m straight in joint 0, painting speed 0.2 m/s.
        let n = 51;
        let s: Vec<f64> = (0..n).map(|i| i as f64 * 0.02).collect();
        let q: Vec<Q> = s.iter().map(|&x| [x, 0.0, 0.0, 0.0, 0.0]).collect();
        let run = RunPath {
            q,
            s: s.clone(),
            v_max: vec![0.2; n],
        };
        let out = time_run(&run, &limits(), 0.032).unwrap();
        assert_eq!(check_samples(&out, &limits(), 0.032), None);
        let cruising = out.iter().filter(|p| (p.sdot - 0.2).abs() < 1e-6).count();
        assert!(
            cruising as f64 > 0.8 * out.len() as f64,
            "{cruising}/{}",
            out.len()
        );
        assert!((out.last().unwrap().s - 1.0).abs() < 1e-12);
        // Duration ≈ 1 m / 0.2 m/s plus the speeding-up and braking.
        let t = out.len() as f64 * 0.032;
        assert!(t > 5.0 && t < 5.5, "{t}");
    }

    #[test]
    fn a_joint_limit_slows_the_run() {
        // Joint 1 turns 10 rad per metre: its 1 rad/s caps ṡ near 0.1 m/s.
        let n = 21;
        let s: Vec<f64> = (0..n).map(|i| i as f64 * 0.05).collect();
        let q: Vec<Q> = s
            .iter()
            .map(|&x| [x, 10.0 * x - 5.0, 0.0, 0.0, 0.0])
            .collect();
        let run = RunPath {
            q,
            s,
            v_max: vec![0.5; n],
        };
        let out = time_run(&run, &limits(), 0.005).unwrap();
        assert_eq!(check_samples(&out, &limits(), 0.005), None);
        assert!(out.iter().all(|p| p.sdot <= 0.1 + 1e-9));
    }

    #[test]
    fn air_move_is_rest_to_rest_within_limits() {
        let a = [0.0; 5];
        let b = [1.0, -0.5, 0.2, 3.0, 0.1];
        let mut out = vec![Sample {
            q: a,
            s: 0.0,
            sdot: 0.0,
        }];
        out.extend(air_move(&a, &b, &limits(), 0.032));
        assert_eq!(out.last().unwrap().q, b);
        assert_eq!(check_samples(&out, &limits(), 0.032), None);
    }
}
