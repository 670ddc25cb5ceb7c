//! Time law: a time-optimal parameterisation of a joint path under velocity and acceleration limits, resampled at the control period.
//!
//! # Painting paths
//!
//! [`time_path`] takes waypoints in joint space, each with its path
//! parameter `s_m` and an optional speed limit. `s_m` is the nozzle's arc
//! length in the road plane (m, strictly increasing; the caller computes
//! it from the knots' tip positions), so the limit `max_speed_mps` is the
//! painting speed v = k / w of 001 eq. 2.6 as a bound on ds/dt. Between
//! waypoints the joints follow a C¹ shape-preserving cubic in s (PCHIP,
//! Fritsch & Carlson 1980): no overshoot between waypoints, so a joint held
//! at its position limit over a stretch (a tilt clamped at ±15°) stays there.
//!
//! The speed profile is found as TOPP-RA does (Pham & Pham 2018): with
//! x = ṡ² and u = s̈ on a grid in s, the joint constraints
//! |q'ᵢ ṡ| ≤ vᵢ and |q'ᵢ s̈ + q''ᵢ ṡ²| ≤ aᵢ are linear in (x, u). A backward
//! pass finds, per grid point, the largest x from which the path's end can
//! still be reached at rest (a two-variable LP per step, solved exactly by
//! eliminating u); a forward pass then takes the largest admissible u at
//! every step. The acceleration constraints are imposed at both ends of
//! every point of every step (a Bernstein bound of the step's cubic, see
//! `step_constraints`), and the velocity bound of a grid point uses the
//! largest |q'| of its two steps, so the continuous trajectory, and hence
//! every finite difference of its samples, is within the limits; a small
//! safety `margin` is held back on top. The profile is the greatest
//! speed not above the requested one, so painting runs at v = k / w wherever
//! the arm allows it; where it does not, [`Slowdown`]s say where, by how
//! much and which joint limit binds.
//!
//! # Air moves
//!
//! [`air_move`] goes from rest to rest along the straight line in joint
//! space, so all joints start and finish together, with a seven-phase
//! jerk-limited ("double S", Biagiotti & Melchiorri §3.4) profile of the
//! line's parameter, scaled so that no joint exceeds its velocity,
//! acceleration or jerk limit.
//!
//! # Stitching, stroke ends and the gun
//!
//! Every [`Trajectory`] starts and ends at rest, so a job is simply the
//! concatenation: [`resample`] samples the pieces back to back at exact
//! multiples of the period (t = k·T, never accumulated), holding the last
//! pose for the final partial period. Painting at a standstill would pool
//! paint, so a stroke's path should carry a run-up and a run-out: a few
//! gun-off waypoints along the stroke's tangent before the first rung and
//! after the last, with no speed limit (`max_speed_mps: None`). The time law
//! then accelerates in the run-up and arrives at the first rung at painting
//! speed; a run-up too short shows up as a [`Slowdown`] bound by `Rest`. The
//! gun is switched by time: [`Trajectory::gun_times`] gives the command
//! times that make the spray, after the valve's opening and closing delays
//! (the gun's lead and lag), start exactly at the first rung and stop at the
//! last.

/// Share of each velocity and acceleration limit held back as a safety
/// margin against the grid's discretisation (assumed: 3 %, ample for the
/// 20 mm rung spacing; the property tests check the sampled output).
pub const DEFAULT_MARGIN: f64 = 0.03;

/// Longest grid step along the path (m); each waypoint interval gets at
/// least two steps (assumed: 10 mm, half the default rung spacing; the
/// constraints hold between grid points anyway, so this only trades a
/// little optimality for speed).
pub const DEFAULT_MAX_STEP_M: f64 = 0.01;

/// Painting speeds count as met within this fraction.
const SLOW_TOLERANCE: f64 = 1e-3;

/// Share of the next point's largest ṡ² that each step must still reach
/// where it can (assumed: ½; see the backward pass in `time_path`).
const FLOOR_SHARE: f64 = 0.5;

/// Speeds are capped here (m/s of s) where no joint moves along the path.
const SPEED_CAP: f64 = 1e3;

/// Per-joint limits, in the joints' own units (rad or m, per s, s², s³).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits<const N: usize> {
    pub vel: [f64; N],
    pub acc: [f64; N],
    /// Used by air moves only.
    pub jerk: [f64; N],
}

impl<const N: usize> JointLimits<N> {
    fn validate(&self) -> Result<(), TimingError> {
        for (name, arr) in [("vel", &self.vel), ("acc", &self.acc), ("jerk", &self.jerk)] {
            for (joint, &v) in arr.iter().enumerate() {
                if !(v.is_finite() && v > 0.0) {
                    return Err(TimingError::BadLimit {
                        kind: name,
                        joint,
                        value: v,
                    });
                }
            }
        }
        Ok(())
    }
}

/// One waypoint of a painting path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathPoint<const N: usize> {
    /// Nozzle arc length in the road plane from the path's start (m), strictly increasing.
    pub s_m: f64,
    /// Joint positions.
    pub q: [f64; N],
    /// Requested painting speed ds/dt here (m/s), or `None` (gun off: as fast as the joints allow).
    pub max_speed_mps: Option<f64>,
}

/// Tuning of [`time_path`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathOptions {
    /// Fraction of every velocity and acceleration limit kept in reserve.
    pub margin: f64,
    /// Longest grid step in s (m).
    pub max_step_m: f64,
}

impl Default for PathOptions {
    fn default() -> Self {
        PathOptions {
            margin: DEFAULT_MARGIN,
            max_step_m: DEFAULT_MAX_STEP_M,
        }
    }
}

/// Which limit kept the path below its requested speed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Binding {
    /// That joint's velocity limit.
    Velocity { joint: usize },
    /// That joint's acceleration limit.
    Acceleration { joint: usize },
    /// The path starts or ends at rest and there is not enough room to reach the speed.
    Rest,
}

/// A run of consecutive waypoints painted slower than requested.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slowdown {
    pub first_waypoint: usize,
    pub last_waypoint: usize,
    /// The waypoint where the speed falls furthest short.
    pub worst_waypoint: usize,
    /// Reached / requested speed there (< 1); the film there is 1/factor of the target.
    pub factor: f64,
    /// What binds at the worst waypoint.
    pub binding: Binding,
}

/// Errors of the time law; each names the waypoint or joint at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TimingError {
    #[error("a path needs at least two waypoints, got {0}")]
    TooFewPoints(usize),
    #[error("waypoint {index}: a coordinate or speed is not a finite number")]
    NotFinite { index: usize },
    #[error("waypoint {index}: s = {s_m} m does not increase past the previous {prev_m} m; merge repeated waypoints")]
    NotIncreasing { index: usize, s_m: f64, prev_m: f64 },
    #[error("waypoint {index}: requested speed {value} m/s must be positive")]
    BadSpeed { index: usize, value: f64 },
    #[error("joint {joint}: {kind} limit {value} must be a positive number")]
    BadLimit {
        kind: &'static str,
        joint: usize,
        value: f64,
    },
    #[error("time law option {field} = {value} is invalid: it {why}")]
    BadOption {
        field: &'static str,
        value: f64,
        why: &'static str,
    },
    #[error(
        "the speed profile stalls between waypoints {index} and {next}: no joint can move there"
    )]
    Stalled { index: usize, next: usize },
}

/// Position and rate on a trajectory at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State<const N: usize> {
    pub q: [f64; N],
    pub qd: [f64; N],
    /// Path parameter: nozzle arc length (m) on a painting path; the fraction 0–1 of an air move.
    pub s: f64,
    /// ds/dt: nozzle speed (m/s) on a painting path; rate of the fraction (1/s) on an air move.
    pub sd: f64,
}

/// Shape-preserving cubic Hermite interpolation (PCHIP) of the waypoints in s.
#[derive(Clone, Debug)]
struct Spline<const N: usize> {
    s: Vec<f64>,
    q: Vec<[f64; N]>,
    m: Vec<[f64; N]>,
}

impl<const N: usize> Spline<N> {
    // Index loops read like the formulas (per joint j, per waypoint k).
    #[allow(clippy::needless_range_loop)]
    fn new(points: &[PathPoint<N>]) -> Self {
        let n = points.len();
        let s: Vec<f64> = points.iter().map(|p| p.s_m).collect();
        let q: Vec<[f64; N]> = points.iter().map(|p| p.q).collect();
        let slope = |k: usize| -> [f64; N] {
            let h = s[k + 1] - s[k];
            std::array::from_fn(|j| (q[k + 1][j] - q[k][j]) / h)
        };
        let mut m = vec![[0.0; N]; n];
        for j in 0..N {
            let d = |k: usize| slope(k)[j];
            let h = |k: usize| s[k + 1] - s[k];
            if n == 2 {
                m[0][j] = d(0);
                m[1][j] = d(0);
                continue;
            }
            for k in 1..n - 1 {
                let (d0, d1) = (d(k - 1), d(k));
                // Fritsch–Carlson: flat at a local extremum, else a weighted
                // harmonic mean of the neighbouring chords.
                m[k][j] = if d0 * d1 > 0.0 {
                    let (w1, w2) = (2.0 * h(k) + h(k - 1), h(k) + 2.0 * h(k - 1));
                    (w1 + w2) / (w1 / d0 + w2 / d1)
                } else {
                    0.0
                };
            }
            // Ends: the one-sided three-point slope, kept shape-preserving.
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
            m[0][j] = end(h(0), h(1), d(0), d(1));
            m[n - 1][j] = end(h(n - 2), h(n - 3), d(n - 2), d(n - 3));
        }
        Spline { s, q, m }
    }

    /// q, dq/ds, d²q/ds² at `s` on segment `k` (s may be at either end).
    fn eval(&self, k: usize, s: f64) -> ([f64; N], [f64; N], [f64; N]) {
        let h = self.s[k + 1] - self.s[k];
        let t = ((s - self.s[k]) / h).clamp(0.0, 1.0);
        let (t2, t3) = (t * t, t * t * t);
        let (q0, q1, m0, m1) = (&self.q[k], &self.q[k + 1], &self.m[k], &self.m[k + 1]);
        let mut q = [0.0; N];
        let mut d1 = [0.0; N];
        let mut d2 = [0.0; N];
        for j in 0..N {
            q[j] = (2.0 * t3 - 3.0 * t2 + 1.0) * q0[j]
                + (t3 - 2.0 * t2 + t) * h * m0[j]
                + (-2.0 * t3 + 3.0 * t2) * q1[j]
                + (t3 - t2) * h * m1[j];
            d1[j] = ((6.0 * t2 - 6.0 * t) * q0[j]
                + (3.0 * t2 - 4.0 * t + 1.0) * h * m0[j]
                + (-6.0 * t2 + 6.0 * t) * q1[j]
                + (3.0 * t2 - 2.0 * t) * h * m1[j])
                / h;
            d2[j] = ((12.0 * t - 6.0) * q0[j]
                + (6.0 * t - 4.0) * h * m0[j]
                + (-12.0 * t + 6.0) * q1[j]
                + (6.0 * t - 2.0) * h * m1[j])
                / (h * h);
        }
        // Waypoints exactly, not as the sum of the basis terms.
        if t == 0.0 {
            q = *q0;
        } else if t == 1.0 {
            q = *q1;
        }
        (q, d1, d2)
    }

    /// Largest |dq_j/ds| over [s0, s1] within segment k, per joint: dq/ds is
    /// a quadratic there, so its extremes are at the ends or at its vertex.
    fn max_slope(&self, k: usize, s0: f64, s1: f64) -> [f64; N] {
        let h = self.s[k + 1] - self.s[k];
        let (t0, t1) = (
            ((s0 - self.s[k]) / h).clamp(0.0, 1.0),
            ((s1 - self.s[k]) / h).clamp(0.0, 1.0),
        );
        let (q0, q1, m0, m1) = (&self.q[k], &self.q[k + 1], &self.m[k], &self.m[k + 1]);
        std::array::from_fn(|j| {
            let a = (6.0 * q0[j] - 6.0 * q1[j]) / h + 3.0 * m0[j] + 3.0 * m1[j];
            let b = (-6.0 * q0[j] + 6.0 * q1[j]) / h - 4.0 * m0[j] - 2.0 * m1[j];
            let c = m0[j];
            let f = |t: f64| (a * t * t + b * t + c).abs();
            let mut best = f(t0).max(f(t1));
            if a != 0.0 {
                let tv = -b / (2.0 * a);
                if tv > t0 && tv < t1 {
                    best = best.max(f(tv));
                }
            }
            best
        })
    }
}

/// Grid point of a timed path: s, the spline segment of the step that
/// starts here, ṡ here, s̈ over the step, and the time here.
#[derive(Clone, Copy, Debug)]
struct GridPoint {
    s: f64,
    seg: usize,
    sd: f64,
    sdd: f64,
    t: f64,
}

/// Rest-to-rest jerk-limited profile of a parameter p from 0 to 1.
#[derive(Clone, Debug)]
struct DoubleS {
    /// Per phase: start time, p, ṗ, p̈ at its start, and its jerk.
    phases: Vec<(f64, f64, f64, f64, f64)>,
    duration: f64,
}

impl DoubleS {
    /// Biagiotti & Melchiorri, "Trajectory Planning for Automatic Machines
    /// and Robots" §3.4, for a unit displacement from rest to rest.
    fn new(v: f64, a: f64, j: f64) -> Self {
        let (mut tj, mut ta);
        if v * j >= a * a {
            tj = a / j;
            ta = tj + v / a;
        } else {
            tj = (v / j).sqrt();
            ta = 2.0 * tj;
        }
        let mut tv = 1.0 / v - ta;
        if tv < 0.0 {
            // The top speed is never reached: no cruise phase.
            tv = 0.0;
            tj = a / j;
            ta = 0.5 * (tj + (tj * tj + 4.0 / a).sqrt());
            if ta < 2.0 * tj {
                // Nor the top acceleration.
                tj = (0.5 / j).cbrt();
                ta = 2.0 * tj;
            }
        }
        let durations = [tj, ta - 2.0 * tj, tj, tv, tj, ta - 2.0 * tj, tj];
        let jerks = [j, 0.0, -j, 0.0, -j, 0.0, j];
        let (mut t, mut p, mut pd, mut pdd) = (0.0, 0.0, 0.0, 0.0);
        let mut phases = Vec::with_capacity(7);
        for (&d, &jk) in durations.iter().zip(jerks.iter()) {
            let d = d.max(0.0);
            phases.push((t, p, pd, pdd, jk));
            p += pd * d + 0.5 * pdd * d * d + jk * d * d * d / 6.0;
            pd += pdd * d + 0.5 * jk * d * d;
            pdd += jk * d;
            t += d;
        }
        DoubleS {
            phases,
            duration: t,
        }
    }

    fn eval(&self, t: f64) -> (f64, f64) {
        if t >= self.duration {
            return (1.0, 0.0);
        }
        if t <= 0.0 {
            return (0.0, 0.0);
        }
        let i = self
            .phases
            .partition_point(|ph| ph.0 <= t)
            .saturating_sub(1);
        let (t0, p, pd, pdd, jk) = self.phases[i];
        let d = t - t0;
        let pos = p + pd * d + 0.5 * pdd * d * d + jk * d * d * d / 6.0;
        let vel = pd + pdd * d + 0.5 * jk * d * d;
        (pos.clamp(0.0, 1.0), vel.max(0.0))
    }
}

#[derive(Clone, Debug)]
enum Kind<const N: usize> {
    Path {
        spline: Spline<N>,
        grid: Vec<GridPoint>,
    },
    Air {
        q0: [f64; N],
        q1: [f64; N],
        dq: [f64; N],
        profile: DoubleS,
    },
}

/// A timed motion in continuous time, from rest to rest.
#[derive(Clone, Debug)]
pub struct Trajectory<const N: usize> {
    kind: Kind<N>,
    duration_s: f64,
    /// Where painting could not run at the requested speed (empty for air moves).
    pub slowdowns: Vec<Slowdown>,
}

impl<const N: usize> Trajectory<N> {
    /// Time from start to rest at the end.
    pub fn duration_s(&self) -> f64 {
        self.duration_s
    }

    /// Whether this is an air move (joint-space line) rather than a path.
    pub fn is_air_move(&self) -> bool {
        matches!(self.kind, Kind::Air { .. })
    }

    /// The state at time `t` from this trajectory's start (clamped to [0, duration]).
    pub fn state_at(&self, t: f64) -> State<N> {
        let mut cursor = 0;
        self.state_with_cursor(t, &mut cursor)
    }

    /// Time at which the path parameter reaches `s` (clamped to the path);
    /// for an air move `s` is the fraction of the move.
    pub fn time_at(&self, s: f64) -> f64 {
        match &self.kind {
            Kind::Path { grid, .. } => {
                let s = s.clamp(grid[0].s, grid[grid.len() - 1].s);
                let i = grid
                    .partition_point(|g| g.s <= s)
                    .saturating_sub(1)
                    .min(grid.len() - 2);
                let g = grid[i];
                let ds = s - g.s;
                // s − s_i = ṡ_i τ + s̈ τ²/2, solved for the root in the step.
                let tau = if g.sdd.abs() < 1e-12 {
                    if g.sd > 0.0 {
                        ds / g.sd
                    } else {
                        0.0
                    }
                } else {
                    let disc = (g.sd * g.sd + 2.0 * g.sdd * ds).max(0.0);
                    2.0 * ds / (g.sd + disc.sqrt()).max(1e-300)
                };
                (g.t + tau).min(grid[i + 1].t)
            }
            Kind::Air { profile, .. } => {
                // Bisection on the monotone profile.
                let (mut lo, mut hi) = (0.0, profile.duration);
                for _ in 0..100 {
                    let mid = 0.5 * (lo + hi);
                    if profile.eval(mid).0 < s {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                hi
            }
        }
    }

    /// Times to command the gun on and off so the spray, after the valve's
    /// opening delay `open_delay_s` (lead) and closing delay
    /// `close_delay_s` (lag), starts when the nozzle reaches `s_on` and
    /// stops when it reaches `s_off`. Negative when the run-up is too short
    /// for the lead: the caller then starts the gun with the motion and
    /// reports it.
    pub fn gun_times(
        &self,
        s_on: f64,
        s_off: f64,
        open_delay_s: f64,
        close_delay_s: f64,
    ) -> (f64, f64) {
        (
            self.time_at(s_on) - open_delay_s,
            self.time_at(s_off) - close_delay_s,
        )
    }

    fn state_with_cursor(&self, t: f64, cursor: &mut usize) -> State<N> {
        match &self.kind {
            Kind::Path { spline, grid } => {
                let last = grid.len() - 1;
                if t >= self.duration_s {
                    // At rest on the last waypoint, exactly.
                    let (q, _, _) = spline.eval(grid[last].seg, grid[last].s);
                    return State {
                        q,
                        qd: [0.0; N],
                        s: grid[last].s,
                        sd: 0.0,
                    };
                }
                let t = t.max(0.0);
                if *cursor >= last || grid[*cursor].t > t {
                    *cursor = 0;
                }
                while *cursor + 1 < last && grid[*cursor + 1].t <= t {
                    *cursor += 1;
                }
                let g = grid[*cursor];
                let next = grid[*cursor + 1];
                let tau = (t - g.t).max(0.0);
                let s = (g.s + g.sd * tau + 0.5 * g.sdd * tau * tau).clamp(g.s, next.s);
                let sd = (g.sd + g.sdd * tau).max(0.0);
                let (q, dq, _) = spline.eval(g.seg, s);
                let qd = std::array::from_fn(|j| dq[j] * sd);
                State { q, qd, s, sd }
            }
            Kind::Air {
                q0,
                q1,
                dq,
                profile,
            } => {
                let (p, pd) = profile.eval(t);
                State {
                    // The end pose exactly, not q0 + (q1 − q0).
                    q: if p >= 1.0 {
                        *q1
                    } else {
                        std::array::from_fn(|j| q0[j] + dq[j] * p)
                    },
                    qd: std::array::from_fn(|j| dq[j] * pd),
                    s: p,
                    sd: pd,
                }
            }
        }
    }
}

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
fn max_x(cons: &[Con], x_cap: f64) -> f64 {
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
fn max_x_exhaustive(cons: &[Con], x_cap: f64) -> f64 {
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
    validate_path(points, limits, options)?;
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
    let mut x = 0.0_f64;
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

/// Which limit is active at grid point g.
fn binding_at<const N: usize>(
    spline: &Spline<N>,
    grid: &[GridPoint],
    g: usize,
    vel: &[f64; N],
    acc: &[f64; N],
) -> Binding {
    let gp = grid[g];
    let (_, d1, d2) = spline.eval(gp.seg, gp.s);
    // Velocity: the joint nearest its limit, if within 0.1 %.
    let (vj, vr) = (0..N)
        .map(|j| (j, d1[j].abs() * gp.sd / vel[j]))
        .fold((0, 0.0), |b, c| if c.1 > b.1 { c } else { b });
    if vr > 0.999 {
        return Binding::Velocity { joint: vj };
    }
    // Acceleration, with the s̈ of the steps on either side.
    let mut best = (0, 0.0);
    let x = gp.sd * gp.sd;
    let sdds = [Some(gp.sdd), g.checked_sub(1).map(|h| grid[h].sdd)];
    for sdd in sdds.into_iter().flatten() {
        for j in 0..N {
            let r = (d1[j] * sdd + d2[j] * x).abs() / acc[j];
            if r > best.1 {
                best = (j, r);
            }
        }
    }
    if best.1 > 0.98 && gp.sd > 0.0 {
        return Binding::Acceleration { joint: best.0 };
    }
    Binding::Rest
}

/// Jerk-limited, synchronised point-to-point move from rest at `q0` to rest at `q1`.
pub fn air_move<const N: usize>(
    q0: [f64; N],
    q1: [f64; N],
    limits: &JointLimits<N>,
    margin: f64,
) -> Result<Trajectory<N>, TimingError> {
    limits.validate()?;
    if !(margin.is_finite() && (0.0..0.5).contains(&margin)) {
        return Err(TimingError::BadOption {
            field: "margin",
            value: margin,
            why: "must lie in [0, 0.5)",
        });
    }
    if q0.iter().chain(q1.iter()).any(|v| !v.is_finite()) {
        return Err(TimingError::NotFinite { index: 0 });
    }
    let dq: [f64; N] = std::array::from_fn(|j| q1[j] - q0[j]);
    let keep = 1.0 - margin;
    // The slowest joint sets the line parameter's limits.
    let (mut v, mut a, mut jk) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for (j, d) in dq.iter().map(|d| d.abs()).enumerate() {
        if d > 0.0 {
            v = v.min(limits.vel[j] * keep / d);
            a = a.min(limits.acc[j] * keep / d);
            jk = jk.min(limits.jerk[j] * keep / d);
        }
    }
    if !v.is_finite() {
        // Nothing moves: an empty move.
        let profile = DoubleS {
            phases: vec![(0.0, 1.0, 0.0, 0.0, 0.0)],
            duration: 0.0,
        };
        return Ok(Trajectory {
            kind: Kind::Air {
                q0,
                q1,
                dq,
                profile,
            },
            duration_s: 0.0,
            slowdowns: Vec::new(),
        });
    }
    let profile = DoubleS::new(v, a, jk);
    let duration_s = profile.duration;
    Ok(Trajectory {
        kind: Kind::Air {
            q0,
            q1,
            dq,
            profile,
        },
        duration_s,
        slowdowns: Vec::new(),
    })
}

/// Trajectories played back to back, sampled at a fixed period.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Samples<const N: usize> {
    /// t = k·period exactly.
    pub t_s: Vec<f64>,
    /// Index of the trajectory each sample falls in.
    pub piece: Vec<usize>,
    /// Time since that trajectory's start.
    pub local_t_s: Vec<f64>,
    pub q: Vec<[f64; N]>,
    pub qd: Vec<[f64; N]>,
    /// Path parameter (see [`State::s`]).
    pub s: Vec<f64>,
    /// Its rate (see [`State::sd`]).
    pub sd: Vec<f64>,
}

impl<const N: usize> Samples<N> {
    pub fn len(&self) -> usize {
        self.t_s.len()
    }
    pub fn is_empty(&self) -> bool {
        self.t_s.is_empty()
    }
}

/// Samples `pieces` played one after another (each from rest to rest) at
/// t = k·`period_s`, from 0 through the first multiple of the period at or
/// after the end, which holds the final pose.
pub fn resample<const N: usize>(
    pieces: &[Trajectory<N>],
    period_s: f64,
) -> Result<Samples<N>, TimingError> {
    if !(period_s.is_finite() && period_s > 0.0) {
        return Err(TimingError::BadOption {
            field: "period_s",
            value: period_s,
            why: "must be a positive time",
        });
    }
    let mut out = Samples::default();
    if pieces.is_empty() {
        return Ok(out);
    }
    let starts: Vec<f64> = pieces
        .iter()
        .scan(0.0, |acc, p| {
            let s = *acc;
            *acc += p.duration_s;
            Some(s)
        })
        .collect();
    let total: f64 = pieces.iter().map(|p| p.duration_s).sum();
    // A hair of slack so a total that is an exact multiple does not gain a sample from rounding.
    let count = (total / period_s - 1e-9).ceil().max(0.0) as usize + 1;
    for v in [&mut out.t_s, &mut out.local_t_s, &mut out.s, &mut out.sd] {
        v.reserve(count);
    }
    out.piece.reserve(count);
    out.q.reserve(count);
    out.qd.reserve(count);
    let mut p = 0;
    let mut cursor = 0;
    for k in 0..count {
        let t = k as f64 * period_s;
        while p + 1 < pieces.len() && t >= starts[p + 1] {
            p += 1;
            cursor = 0;
        }
        let local = (t - starts[p]).min(pieces[p].duration_s);
        let st = pieces[p].state_with_cursor(local, &mut cursor);
        out.t_s.push(t);
        out.piece.push(p);
        out.local_t_s.push(local);
        out.q.push(st.q);
        out.qd.push(st.qd);
        out.s.push(st.s);
        out.sd.push(st.sd);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn limits3() -> JointLimits<3> {
        JointLimits {
            vel: [0.5, 0.3, 0.52],
            acc: [1.0, 0.6, 5.0],
            jerk: [10.0, 6.0, 50.0],
        }
    }

    /// Every finite-difference velocity and acceleration of the samples is within the limits.
    fn check_limits<const N: usize>(
        s: &Samples<N>,
        lim: &JointLimits<N>,
        period: f64,
    ) -> Result<(), String> {
        let tol = 1e-9;
        for k in 1..s.len() {
            for j in 0..N {
                let v = (s.q[k][j] - s.q[k - 1][j]) / period;
                if v.abs() > lim.vel[j] * (1.0 + 1e-6) + tol {
                    return Err(format!(
                        "sample {k} joint {j}: velocity {v} > {}",
                        lim.vel[j]
                    ));
                }
                if k + 1 < s.len() {
                    let a = (s.q[k + 1][j] - 2.0 * s.q[k][j] + s.q[k - 1][j]) / (period * period);
                    if a.abs() > lim.acc[j] * (1.0 + 1e-6) + tol {
                        return Err(format!(
                            "sample {k} joint {j}: acceleration {a} > {}",
                            lim.acc[j]
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    fn straight_path(n: usize, speed: Option<f64>) -> Vec<PathPoint<3>> {
        (0..n)
            .map(|k| {
                let s = 0.02 * k as f64;
                PathPoint {
                    s_m: s,
                    q: [s, 0.5 * s, 0.0],
                    max_speed_mps: speed,
                }
            })
            .collect()
    }

    #[test]
    fn cruise_reaches_the_requested_speed_and_ends_at_rest() {
        let mut pts = straight_path(101, Some(0.15));
        // Run-up and run-out without a speed request.
        for k in [0, 1, 2, 3, 4, 96, 97, 98, 99, 100] {
            pts[k].max_speed_mps = None;
        }
        let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
        assert!(tr.slowdowns.is_empty(), "{:?}", tr.slowdowns);
        let mid = tr.state_at(tr.time_at(1.0));
        assert!((mid.sd - 0.15).abs() < 1e-6, "{}", mid.sd);
        let end = tr.state_at(tr.duration_s());
        assert_eq!(end.q, pts[100].q);
        assert!(end.sd.abs() < 1e-9);
        // Bang-coast-bang bound: joint 0 moves 1:1 with s, acc ≤ 0.97.
        assert!(tr.duration_s() > (2.0 - 0.16) / 0.15);
    }

    #[test]
    fn velocity_limit_slows_painting_and_names_the_joint() {
        // Joint 1 moves 2:1 with s: its 0.3 rad/s caps ṡ at 0.15·0.97.
        let pts: Vec<PathPoint<3>> = (0..101)
            .map(|k| {
                let s = 0.02 * k as f64;
                PathPoint {
                    s_m: s,
                    q: [0.0, 2.0 * s, 0.0],
                    max_speed_mps: if (10..90).contains(&k) {
                        Some(0.2)
                    } else {
                        None
                    },
                }
            })
            .collect();
        let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
        assert_eq!(tr.slowdowns.len(), 1, "{:?}", tr.slowdowns);
        let sl = tr.slowdowns[0];
        assert_eq!((sl.first_waypoint, sl.last_waypoint), (10, 89));
        assert_eq!(sl.binding, Binding::Velocity { joint: 1 });
        assert!(
            (sl.factor - 0.15 * 0.97 / 0.2).abs() < 1e-3,
            "{}",
            sl.factor
        );
    }

    #[test]
    fn a_joint_held_at_its_bound_never_overshoots() {
        // Joint 2 climbs to 0.26 and is held there (a tilt clamped at its limit), then comes back.
        let pts: Vec<PathPoint<3>> = (0..40)
            .map(|k| {
                let s = 0.02 * k as f64;
                let held = (0.05 * k as f64).min(0.26).min(0.05 * (39 - k) as f64);
                PathPoint {
                    s_m: s,
                    q: [s, 0.0, held],
                    max_speed_mps: Some(0.1),
                }
            })
            .collect();
        let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
        let samples = resample(std::slice::from_ref(&tr), 0.005).unwrap();
        for q in &samples.q {
            assert!(q[2] <= 0.26 + 1e-12 && q[2] >= -1e-12, "{q:?}");
        }
    }

    #[test]
    fn painting_from_rest_is_reported() {
        let pts = straight_path(20, Some(0.15));
        let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
        assert_eq!(
            tr.slowdowns.first().map(|s| (s.first_waypoint, s.binding)),
            Some((0, Binding::Rest))
        );
    }

    #[test]
    fn bad_input_names_the_waypoint() {
        let mut pts = straight_path(5, None);
        pts[3].s_m = pts[2].s_m;
        assert!(matches!(
            time_path(&pts, &limits3(), &PathOptions::default()),
            Err(TimingError::NotIncreasing { index: 3, .. })
        ));
        let mut pts = straight_path(5, None);
        pts[2].max_speed_mps = Some(0.0);
        assert!(matches!(
            time_path(&pts, &limits3(), &PathOptions::default()),
            Err(TimingError::BadSpeed { index: 2, .. })
        ));
        pts[2].q[1] = f64::NAN;
        assert!(matches!(
            time_path(&pts, &limits3(), &PathOptions::default()),
            Err(TimingError::NotFinite { index: 2 })
        ));
        let mut lim = limits3();
        lim.acc[2] = 0.0;
        assert!(matches!(
            time_path(&straight_path(5, None), &lim, &PathOptions::default()),
            Err(TimingError::BadLimit {
                kind: "acc",
                joint: 2,
                ..
            })
        ));
        assert!(matches!(
            time_path(&straight_path(1, None), &limits3(), &PathOptions::default()),
            Err(TimingError::TooFewPoints(1))
        ));
        assert!(resample::<3>(&[], 0.0).is_err());
    }

    #[test]
    fn air_move_is_synchronised_and_jerk_limited() {
        let lim = limits3();
        let tr = air_move([0.0, 0.0, 0.0], [1.0, -0.2, 0.3], &lim, DEFAULT_MARGIN).unwrap();
        let period = 0.005;
        let s = resample(std::slice::from_ref(&tr), period).unwrap();
        check_limits(&s, &lim, period).unwrap();
        let last = s.q[s.len() - 1];
        assert_eq!(last, [1.0, -0.2, 0.3]);
        // Synchronised: every joint is the same fraction of the way at every sample.
        for q in &s.q {
            let f = q[0];
            assert!((q[1] - -0.2 * f).abs() < 1e-12 && (q[2] - 0.3 * f).abs() < 1e-12);
        }
        // Jerk of the dominant joint (0) by third differences, within its limit.
        for k in 2..s.len() - 1 {
            let j = (s.q[k + 1][0] - 3.0 * s.q[k][0] + 3.0 * s.q[k - 1][0] - s.q[k - 2][0])
                / period.powi(3);
            assert!(j.abs() <= lim.jerk[0] * (1.0 + 1e-6), "{k} {j}");
        }
        // Short moves too (no cruise, no constant-acceleration phase).
        for d in [1e-4, 0.01, 0.05] {
            let tr = air_move([0.0; 3], [d, 0.0, 0.0], &lim, DEFAULT_MARGIN).unwrap();
            let s = resample(std::slice::from_ref(&tr), period).unwrap();
            check_limits(&s, &lim, period).unwrap();
            assert_eq!(s.q[s.len() - 1][0], d);
        }
        let still = air_move([0.3; 3], [0.3; 3], &lim, DEFAULT_MARGIN).unwrap();
        assert_eq!(still.duration_s(), 0.0);
    }

    #[test]
    fn resample_steps_by_exactly_the_period_across_pieces() {
        let lim = limits3();
        let a = air_move([0.0; 3], [0.1, 0.05, 0.0], &lim, DEFAULT_MARGIN).unwrap();
        let mut pts = straight_path(30, Some(0.1));
        for p in &mut pts {
            p.q[0] += 0.1;
            p.q[1] += 0.05;
        }
        let b = time_path(&pts, &lim, &PathOptions::default()).unwrap();
        let pieces = [a, b];
        for period in [0.032, 0.005] {
            let s = resample(&pieces, period).unwrap();
            for (k, &t) in s.t_s.iter().enumerate() {
                assert_eq!(t, k as f64 * period);
            }
            let total = pieces[0].duration_s() + pieces[1].duration_s();
            assert!(s.t_s[s.len() - 1] >= total - 1e-9 && s.t_s[s.len() - 1] < total + period);
            assert_eq!(s.q[s.len() - 1], pts[29].q);
            assert!(s.piece.windows(2).all(|w| w[0] <= w[1]));
            check_limits(&s, &lim, period).unwrap();
        }
    }

    #[test]
    fn gun_times_lead_the_arrival() {
        let mut pts = straight_path(60, Some(0.1));
        for p in pts.iter_mut().take(10) {
            p.max_speed_mps = None;
        }
        let tr = time_path(&pts, &limits3(), &PathOptions::default()).unwrap();
        let (on, off) = tr.gun_times(0.18, 1.0, 0.05, 0.02);
        let t_on = tr.time_at(0.18);
        assert!((tr.state_at(t_on).s - 0.18).abs() < 1e-9);
        assert!((on - (t_on - 0.05)).abs() < 1e-12);
        assert!((off - (tr.time_at(1.0) - 0.02)).abs() < 1e-12);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn fast_lp_matches_elimination(
            lines in proptest::collection::vec((-5.0f64..5.0, -5.0f64..5.0, 0.0f64..3.0), 1..20),
            cap in 0.0f64..10.0,
        ) {
            let fast = max_x(&lines, cap);
            let slow = max_x_exhaustive(&lines, cap);
            prop_assert!((fast - slow).abs() <= 1e-9 * (1.0 + slow.abs()), "{} vs {}", fast, slow);
        }
    }

    /// Random wiggly paths through 3 joints.
    fn random_path() -> impl Strategy<Value = Vec<PathPoint<3>>> {
        proptest::collection::vec(
            (
                0.005f64..0.05,
                -0.02f64..0.02,
                -0.02f64..0.02,
                -0.05f64..0.05,
                proptest::option::of(0.02f64..0.5),
            ),
            2..60,
        )
        .prop_map(|steps| {
            let mut s = 0.0;
            let mut q = [0.0; 3];
            steps
                .into_iter()
                .enumerate()
                .map(|(k, (ds, d0, d1, d2, v))| {
                    if k > 0 {
                        s += ds;
                        q = [q[0] + ds + d0, q[1] + d1, q[2] + d2];
                    }
                    PathPoint {
                        s_m: s,
                        q,
                        max_speed_mps: v,
                    }
                })
                .collect()
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(96))]
        #[test]
        fn sampled_paths_never_exceed_a_limit(pts in random_path(), fine in any::<bool>(),
                                               scale in 0.2f64..3.0) {
            let base = limits3();
            let lim = JointLimits {
                vel: base.vel.map(|v| v * scale),
                acc: base.acc.map(|a| a * scale),
                jerk: base.jerk,
            };
            let period = if fine { 0.005 } else { 0.032 };
            let tr = time_path(&pts, &lim, &PathOptions::default()).unwrap();
            // No stalls: these paths are at most 3 m long at ≥ 0.02 m/s.
            prop_assert!(tr.duration_s() < 1000.0, "duration {}", tr.duration_s());
            let s = resample(std::slice::from_ref(&tr), period).unwrap();
            check_limits(&s, &lim, period).map_err(TestCaseError::fail)?;
            prop_assert_eq!(s.q[s.len() - 1], pts[pts.len() - 1].q);
            // Never faster than requested at a waypoint.
            for p in &pts {
                if let Some(v) = p.max_speed_mps {
                    let st = tr.state_at(tr.time_at(p.s_m));
                    prop_assert!(st.sd <= v * (1.0 + 1e-6), "{} > {}", st.sd, v);
                }
            }
        }

        #[test]
        fn air_moves_never_exceed_a_limit(a in proptest::array::uniform3(-2.0f64..2.0),
                                          b in proptest::array::uniform3(-2.0f64..2.0),
                                          fine in any::<bool>()) {
            let lim = limits3();
            let period = if fine { 0.005 } else { 0.032 };
            let tr = air_move(a, b, &lim, DEFAULT_MARGIN).unwrap();
            let s = resample(std::slice::from_ref(&tr), period).unwrap();
            check_limits(&s, &lim, period).map_err(TestCaseError::fail)?;
            prop_assert_eq!(s.q[0], a);
            prop_assert_eq!(s.q[s.len() - 1], b);
        }
    }
}
