//! Painting paths: the time-optimal speed profile under joint speed and
//! acceleration limits (TOPP-RA's two passes, see the module docs).

use super::spline::{GridPoint, Spline};
use super::{
    Binding, JointLimits, Kind, PathOptions, PathPoint, Slowdown, TimingError, Trajectory,
};

/// Painting speeds count as met within this fraction.
const SLOW_TOLERANCE: f64 = 1e-3;

/// Share of the next point's largest ṡ² that each step must still reach
/// where it can (assumed: ½; see the backward pass in `time_path`).
const FLOOR_SHARE: f64 = 0.5;

/// Speeds are capped here (m/s of s) where no joint moves along the path.
const SPEED_CAP: f64 = 1e3;

/// One constraint α·u + β·x ≤ γ on (u = s̈, x = ṡ²).
type Con = (f64, f64, f64);

/// Joint acceleration constraints of the step from s0 to s1 = s0 + Δ,
/// holding at every point of the step, not only at grid points.
///
/// With f = (s − s0)/Δ, u constant and x(f) = x + 2uΔf over the step, joint
/// j's acceleration q'u + q''x(f) is a cubic in f whose coefficients are
/// linear in (u, x) (q' is quadratic and q'' linear on a Hermite segment).
/// A cubic on [0, 1] lies within the hull of its four Bernstein
/// coefficients, so bounding those bounds the whole step.
fn step_constraints<const N: usize>(
    spline: &Spline<N>,
    seg: usize,
    s0: f64,
    s1: f64,
    acc: &[f64; N],
    out: &mut Vec<Con>,
) {
    let delta = s1 - s0;
    let (_, d0, dd0) = spline.eval(seg, s0);
    let (_, dm, _) = spline.eval(seg, s0 + 0.5 * delta);
    let (_, d1, dd1) = spline.eval(seg, s1);
    for j in 0..N {
        // q'(f) = p0 + p1 f + p2 f², q''(f) = r0 + r1 f.
        let p2 = 2.0 * (d1[j] - 2.0 * dm[j] + d0[j]);
        let (p0, p1) = (d0[j], d1[j] - d0[j] - p2);
        let (r0, r1) = (dd0[j], dd1[j] - dd0[j]);
        // Monomial coefficients (f⁰…f³) of the u and x parts.
        let cu = [p0, p1 + 2.0 * delta * r0, p2 + 2.0 * delta * r1, 0.0];
        let cx = [r0, r1, 0.0, 0.0];
        let bern = |c: [f64; 4]| {
            [
                c[0],
                c[0] + c[1] / 3.0,
                c[0] + 2.0 * c[1] / 3.0 + c[2] / 3.0,
                c[0] + c[1] + c[2] + c[3],
            ]
        };
        let (bu, bx) = (bern(cu), bern(cx));
        for i in 0..4 {
            out.push((bu[i], bx[i], acc[j]));
            out.push((-bu[i], -bx[i], acc[j]));
        }
    }
}

/// Largest x ≥ 0 (≤ `x_cap`) for which some u satisfies every constraint;
/// (x, u) = (0, 0) is always feasible.
///
/// At a given x the admissible u form [lo(x), hi(x)], lo the largest of the
/// lower lines and hi the smallest of the upper ones, so the gap hi − lo is
/// concave and piecewise linear. From x = cap we step to where the two
/// active lines meet: that line pair bounds the gap from above, so the step
/// never overshoots the answer and ends after a few pieces (usually one).
pub(super) fn max_x(cons: &[Con], x_cap: f64) -> f64 {
    const TINY: f64 = 1e-12;
    let mut x = x_cap;
    for &(a, b, g) in cons {
        if a.abs() <= TINY && b > 0.0 {
            x = x.min(g / b);
        }
    }
    x = x.max(0.0);
    for _ in 0..64 {
        // Active lines u = c + d·x at this x.
        let (mut lo, mut lo_line) = (f64::NEG_INFINITY, (0.0, 0.0));
        let (mut hi, mut hi_line) = (f64::INFINITY, (0.0, 0.0));
        for &(a, b, g) in cons {
            if a.abs() > TINY {
                let (c, d) = (g / a, -b / a);
                let u = c + d * x;
                if a > 0.0 && u < hi {
                    hi = u;
                    hi_line = (c, d);
                } else if a < 0.0 && u > lo {
                    lo = u;
                    lo_line = (c, d);
                }
            }
        }
        if lo <= hi + 1e-12 * (1.0 + hi.abs()) {
            return x;
        }
        let slope = lo_line.1 - hi_line.1;
        let next = if slope > 0.0 {
            (hi_line.0 - lo_line.0) / slope
        } else {
            0.0
        };
        if next.is_nan() || next >= x {
            break;
        }
        x = next.max(0.0);
    }
    max_x_exhaustive(cons, x_cap)
}

/// The same by Fourier–Motzkin elimination of u over every pair of
/// constraints: slow but plain; the fallback and the tests' oracle.
pub(super) fn max_x_exhaustive(cons: &[Con], x_cap: f64) -> f64 {
    const TINY: f64 = 1e-12;
    let mut best = x_cap;
    for &(ap, bp, gp) in cons {
        if ap > TINY {
            for &(an, bn, gn) in cons {
                if an < -TINY {
                    let b = -an * bp + ap * bn;
                    let g = -an * gp + ap * gn;
                    if b > 0.0 {
                        best = best.min(g / b);
                    }
                }
            }
        } else if ap.abs() <= TINY && bp > 0.0 {
            best = best.min(gp / bp);
        }
    }
    best.max(0.0)
}

/// Admissible range of u at x.
fn u_range(cons: &[Con], x: f64) -> (f64, f64) {
    const TINY: f64 = 1e-12;
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for &(a, b, g) in cons {
        if a > TINY {
            hi = hi.min((g - b * x) / a);
        } else if a < -TINY {
            lo = lo.max((g - b * x) / a);
        }
    }
    (lo, hi)
}

/// Time-optimal speed profile along a joint path, from rest to rest, never
/// faster than each waypoint's requested speed (see the module docs).
pub fn time_path<const N: usize>(
    points: &[PathPoint<N>],
    limits: &JointLimits<N>,
    options: &PathOptions,
) -> Result<Trajectory<N>, TimingError> {
    time_path_between(points, limits, options, [0.0, 0.0])
}

/// [`time_path`] from path speed ṡ = `ends[0]` at the first waypoint to at
/// most `ends[1]` at the last (m/s; a flown join meets the path there).
/// Each end speed is lowered to what the limits allow there: the
/// trajectory's own end states say what was reached.
pub fn time_path_between<const N: usize>(
    points: &[PathPoint<N>],
    limits: &JointLimits<N>,
    options: &PathOptions,
    ends: [f64; 2],
) -> Result<Trajectory<N>, TimingError> {
    validate_path(points, limits, options)?;
    if !ends.iter().all(|v| v.is_finite() && *v >= 0.0) {
        return Err(TimingError::BadOption {
            field: "end speed",
            value: ends[0].min(ends[1]),
            why: "must be a finite speed ≥ 0",
        });
    }
    let keep = 1.0 - options.margin;
    let vel: [f64; N] = std::array::from_fn(|j| limits.vel[j] * keep);
    let acc: [f64; N] = std::array::from_fn(|j| limits.acc[j] * keep);
    let spline = Spline::new(points);

    // The grid: every waypoint, plus equal sub-steps of at most max_step.
    let mut grid: Vec<GridPoint> = Vec::with_capacity(points.len() * 3);
    let mut waypoint_grid = Vec::with_capacity(points.len());
    let mut v_req: Vec<Option<f64>> = Vec::with_capacity(points.len() * 3);
    for k in 0..points.len() - 1 {
        let (s0, s1) = (points[k].s_m, points[k + 1].s_m);
        let steps = (((s1 - s0) / options.max_step_m).ceil() as usize).max(2);
        waypoint_grid.push(grid.len());
        for i in 0..steps {
            let f = i as f64 / steps as f64;
            grid.push(GridPoint {
                s: s0 + f * (s1 - s0),
                seg: k,
                sd: 0.0,
                sdd: 0.0,
                t: 0.0,
            });
            let limit = match (points[k].max_speed_mps, points[k + 1].max_speed_mps) {
                _ if i == 0 => points[k].max_speed_mps,
                (Some(a), Some(b)) => Some(a + f * (b - a)),
                (a, b) => a.or(b),
            };
            v_req.push(limit);
        }
    }
    let last = points.len() - 1;
    waypoint_grid.push(grid.len());
    grid.push(GridPoint {
        s: points[last].s_m,
        seg: last - 1,
        sd: 0.0,
        sdd: 0.0,
        t: 0.0,
    });
    v_req.push(points[last].max_speed_mps);

    let n = grid.len();
    // Velocity bounds on x = ṡ². Between grid points ṡ lies between its
    // values at the ends, so bounding x at a point by the largest |q'| over
    // both adjacent steps keeps |q' ṡ| within the limit everywhere.
    let step_slope = |i: usize| spline.max_slope(grid[i].seg, grid[i].s, grid[i + 1].s);
    let x_vel: Vec<f64> = (0..n)
        .map(|i| {
            let before = if i > 0 { step_slope(i - 1) } else { [0.0; N] };
            let after = if i + 1 < n { step_slope(i) } else { [0.0; N] };
            let mut x = SPEED_CAP * SPEED_CAP;
            for j in 0..N {
                let d = before[j].max(after[j]);
                if d > 0.0 {
                    x = x.min((vel[j] / d).powi(2));
                }
            }
            if let Some(v) = v_req[i] {
                x = x.min(v * v);
            }
            x
        })
        .collect();

    // Backward pass: the largest x at each point from which rest at the end
    // stays reachable. Each step must also arrive with at least FLOOR_SHARE
    // of the next point's largest x where that is possible: without it the
    // greedy forward pass can ride the edge of the set, where the only
    // admissible move is a full stop, and then stall on the final step
    // (rest to rest takes forever at constant s̈).
    let mut x_max = vec![0.0; n];
    x_max[n - 1] = (ends[1] * ends[1]).min(x_vel[n - 1]);
    let mut floor = vec![0.0; n];
    let mut cons: Vec<Con> = Vec::with_capacity(8 * N + 2);
    let step = |i: usize, x_next_max: f64, x_next_min: f64, cons: &mut Vec<Con>| {
        let (s0, s1) = (grid[i].s, grid[i + 1].s);
        let delta = s1 - s0;
        cons.clear();
        step_constraints(&spline, grid[i].seg, s0, s1, &acc, cons);
        cons.push((2.0 * delta, 1.0, x_next_max));
        cons.push((-2.0 * delta, -1.0, -x_next_min));
        delta
    };
    let feasible = |cons: &[Con], x: f64| {
        let (lo, hi) = u_range(cons, x);
        lo <= hi + 1e-9 * (1.0 + hi.abs().min(lo.abs()))
    };
    for i in (0..n - 1).rev() {
        let want = FLOOR_SHARE * x_max[i + 1];
        step(i, x_max[i + 1], want, &mut cons);
        let x = max_x(&cons, x_vel[i]);
        if want > 0.0 && feasible(&cons, x) {
            floor[i + 1] = want;
            x_max[i] = x;
        } else {
            step(i, x_max[i + 1], 0.0, &mut cons);
            x_max[i] = max_x(&cons, x_vel[i]);
        }
    }

    // Forward pass: greatest admissible acceleration at every step.
    let mut x = (ends[0] * ends[0]).min(x_max[0]);
    let mut t = 0.0_f64;
    // (ṡ, s̈, t) per grid point, written into the grid after the pass.
    let mut timed = vec![(0.0, 0.0, 0.0); n];
    for i in 0..n - 1 {
        let mut delta = step(i, x_max[i + 1], floor[i + 1], &mut cons);
        if !feasible(&cons, x) {
            // From rest the floor may be out of reach in one step.
            delta = step(i, x_max[i + 1], 0.0, &mut cons);
        }
        let (lo, hi) = u_range(&cons, x);
        // hi ≥ lo by construction of x_max; rounding can flip them by ~1 ulp.
        let u = if hi.is_finite() {
            hi.max(lo.min(hi))
        } else {
            0.0
        };
        let x_next = (x + 2.0 * delta * u).clamp(0.0, x_max[i + 1]);
        let (sd0, sd1) = (x.sqrt(), x_next.sqrt());
        if sd0 + sd1 <= 1e-12 {
            let k = grid[i].seg;
            return Err(TimingError::Stalled {
                index: k,
                next: k + 1,
            });
        }
        let dt = 2.0 * delta / (sd0 + sd1);
        // The step's exact constant acceleration joining the two speeds.
        timed[i] = (sd0, (x_next - x) / (2.0 * delta), t);
        t += dt;
        x = x_next;
    }
    timed[n - 1] = (x.sqrt(), 0.0, t);
    for (g, (sd, sdd, tg)) in grid.iter_mut().zip(timed) {
        g.sd = sd;
        g.sdd = sdd;
        g.t = tg;
    }

    let slowdowns = find_slowdowns(points, &spline, &grid, &waypoint_grid, &vel, &acc);
    Ok(Trajectory {
        kind: Kind::Path { spline, grid },
        duration_s: t,
        slowdowns,
    })
}

fn validate_path<const N: usize>(
    points: &[PathPoint<N>],
    limits: &JointLimits<N>,
    options: &PathOptions,
) -> Result<(), TimingError> {
    limits.validate()?;
    if !(options.margin.is_finite() && (0.0..0.5).contains(&options.margin)) {
        return Err(TimingError::BadOption {
            field: "margin",
            value: options.margin,
            why: "must lie in [0, 0.5)",
        });
    }
    if !(options.max_step_m.is_finite() && options.max_step_m > 0.0) {
        return Err(TimingError::BadOption {
            field: "max_step_m",
            value: options.max_step_m,
            why: "must be positive",
        });
    }
    if points.len() < 2 {
        return Err(TimingError::TooFewPoints(points.len()));
    }
    for (index, p) in points.iter().enumerate() {
        if !p.s_m.is_finite() || p.q.iter().any(|v| !v.is_finite()) {
            return Err(TimingError::NotFinite { index });
        }
        if let Some(v) = p.max_speed_mps {
            if !v.is_finite() {
                return Err(TimingError::NotFinite { index });
            }
            if v <= 0.0 {
                return Err(TimingError::BadSpeed { index, value: v });
            }
        }
        if index > 0 && p.s_m <= points[index - 1].s_m {
            return Err(TimingError::NotIncreasing {
                index,
                s_m: p.s_m,
                prev_m: points[index - 1].s_m,
            });
        }
    }
    Ok(())
}

/// Runs of waypoints whose speed falls short of the request, with the limit that binds at the worst one.
fn find_slowdowns<const N: usize>(
    points: &[PathPoint<N>],
    spline: &Spline<N>,
    grid: &[GridPoint],
    waypoint_grid: &[usize],
    vel: &[f64; N],
    acc: &[f64; N],
) -> Vec<Slowdown> {
    let mut out: Vec<Slowdown> = Vec::new();
    let mut open: Option<Slowdown> = None;
    for (k, p) in points.iter().enumerate() {
        let g = waypoint_grid[k];
        let short = p
            .max_speed_mps
            .filter(|_| !p.cap_only)
            .map(|v| (grid[g].sd / v, v))
            .filter(|&(f, _)| f < 1.0 - SLOW_TOLERANCE);
        match (short, open.as_mut()) {
            (Some((f, _)), Some(run)) => {
                run.last_waypoint = k;
                if f < run.factor {
                    run.factor = f;
                    run.worst_waypoint = k;
                }
            }
            (Some((f, _)), None) => {
                open = Some(Slowdown {
                    first_waypoint: k,
                    last_waypoint: k,
                    worst_waypoint: k,
                    factor: f,
                    binding: Binding::Rest,
                })
            }
            (None, _) => out.extend(open.take()),
        }
    }
    out.extend(open.take());
    for run in &mut out {
        run.binding = binding_at(spline, grid, waypoint_grid[run.worst_waypoint], vel, acc);
    }
    out
}

/// Which limit holds the speed down at grid point g: the one active
/// there, else the one active where the profile falls to its nearest low
/// point (a slow-down ahead is braked for, one behind is accelerated
/// out of); `Rest` only where that low point is a path end.
fn binding_at<const N: usize>(
    spline: &Spline<N>,
    grid: &[GridPoint],
    g: usize,
    vel: &[f64; N],
    acc: &[f64; N],
) -> Binding {
    let n = grid.len();
    // Braking after g: the cause lies ahead; else behind.
    let ahead = g + 1 < n && grid[g].sdd < 0.0;
    let mut i = g;
    loop {
        if let Some(b) = active_at(spline, grid, i, vel, acc) {
            return b;
        }
        let next = if ahead { i + 1 } else { i.wrapping_sub(1) };
        if next >= n || grid[next].sd > grid[i].sd + 1e-12 {
            return Binding::Rest;
        }
        i = next;
    }
}

/// The limit active at grid point g as the time law imposed it: a joint's
/// speed bound over the steps on either side, or an acceleration bound of
/// either step (its Bernstein bounds, `step_constraints`).
fn active_at<const N: usize>(
    spline: &Spline<N>,
    grid: &[GridPoint],
    g: usize,
    vel: &[f64; N],
    acc: &[f64; N],
) -> Option<Binding> {
    let gp = grid[g];
    let n = grid.len();
    let steps: Vec<usize> = [g.checked_sub(1), (g + 1 < n).then_some(g)]
        .into_iter()
        .flatten()
        .collect();
    // Velocity: the joint nearest its limit, if within 0.1 %.
    let mut best = (0, 0.0);
    for &h in &steps {
        let slope = spline.max_slope(grid[h].seg, grid[h].s, grid[h + 1].s);
        for j in 0..N {
            let r = slope[j] * gp.sd / vel[j];
            if r > best.1 {
                best = (j, r);
            }
        }
    }
    if best.1 > 0.999 {
        return Some(Binding::Velocity { joint: best.0 });
    }
    if gp.sd <= 0.0 {
        return None;
    }
    // Acceleration: the step's constraint rows (8 per joint) at its own
    // (ṡ², s̈).
    let mut best = (0, 0.0);
    let mut cons = Vec::with_capacity(8 * N);
    for &h in &steps {
        let (a, b) = (grid[h], grid[h + 1]);
        cons.clear();
        step_constraints(spline, a.seg, a.s, b.s, acc, &mut cons);
        // The rows are in (s̈, ṡ² at the step's start).
        let x = a.sd * a.sd;
        for (row, &(cu, cx, lim)) in cons.iter().enumerate() {
            let r = (cu * a.sdd + cx * x) / lim;
            if r > best.1 {
                best = (row / 8, r);
            }
        }
    }
    (best.1 > 0.98).then_some(Binding::Acceleration { joint: best.0 })
}
