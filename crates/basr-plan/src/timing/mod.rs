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
//! after the last, with no speed limit (`max_speed_mps: None`) or capped at
//! the painting speed (`cap_only`: the station's first run-up, which must
//! not overshoot and brake into the first rung). The time law then
//! accelerates in the run-up and arrives at the first rung at painting
//! speed; a run-up too short shows up as a [`Slowdown`] bound by `Rest`. The
//! gun is switched by time: [`Trajectory::gun_times`] gives the command
//! times that make the spray, after the valve's opening and closing delays
//! (the gun's lead and lag), start exactly at the first rung and stop at the
//! last.

mod air;
pub mod join;
mod path;
mod resample;
mod spline;
pub mod sync;
#[cfg(test)]
mod tests;

pub use air::air_move;
pub use join::{join_move, Kinematic};
pub use path::{time_path, time_path_between};
pub use resample::{resample, Samples};

use air::DoubleS;
use spline::{GridPoint, Spline};

/// Share of each velocity and acceleration limit held back as a safety
/// margin against the grid's discretisation (assumed: 3 %, ample for the
/// 20 mm rung spacing; the property tests check the sampled output).
pub const DEFAULT_MARGIN: f64 = 0.03;

/// Longest grid step along the path (m); each waypoint interval gets at
/// least two steps (assumed: 10 mm, half the default rung spacing; the
/// constraints hold between grid points anyway, so this only trades a
/// little optimality for speed).
pub const DEFAULT_MAX_STEP_M: f64 = 0.01;

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
    /// `max_speed_mps` only caps the speed (gun off): falling short of it
    /// is no slowdown.
    pub cap_only: bool,
    /// dq/ds here where the caller knows it exactly (a designed join);
    /// else the shape-preserving spline's own.
    pub dq_ds: Option<[f64; N]>,
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
    #[error("no jerk-limited join between the strokes: {0}")]
    NoJoin(String),
    #[error(
        "the speed profile stalls between waypoints {index} and {next}: no joint can move there"
    )]
    Stalled { index: usize, next: usize },
    #[error(
        "the motion lasts {} s: {} setpoints at control.period_s = {} s, more than the {} one \
         job holds (resample::MAX_SAMPLES); the robot's joint speed and acceleration limits \
         (max_vel, max_acc) are far below a real arm's, or the period is too short",
        basr_io::show_num(*duration_s),
        basr_io::show_num(*samples),
        basr_io::show_num(*period_s),
        resample::MAX_SAMPLES
    )]
    TooLong {
        duration_s: f64,
        samples: f64,
        period_s: f64,
    },
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
    /// A flown join between two paths (`join`).
    Join(Box<rsruckig::prelude::Trajectory<N>>),
}

/// A timed motion in continuous time: from rest to rest, except a path
/// timed between given speeds and a join between two paths.
#[derive(Clone, Debug)]
pub struct Trajectory<const N: usize> {
    kind: Kind<N>,
    duration_s: f64,
    /// Where painting could not run at the requested speed (empty for air moves).
    pub slowdowns: Vec<Slowdown>,
}

/// The time (s) at which each of `pieces`, played one after another, starts.
pub fn start_times<const N: usize>(pieces: &[Trajectory<N>]) -> Vec<f64> {
    pieces
        .iter()
        .scan(0.0, |t, p| {
            let t0 = *t;
            *t += p.duration_s;
            Some(t0)
        })
        .collect()
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

    /// Whether this is a flown join between two paths.
    pub fn is_join(&self) -> bool {
        matches!(self.kind, Kind::Join(_))
    }

    /// Joint positions, rates and accelerations at the start (`end`:
    /// false) or the end of a path; None for air moves and joins.
    pub fn path_end(&self, end: bool) -> Option<Kinematic<N>> {
        let Kind::Path { spline, grid } = &self.kind else {
            return None;
        };
        let n = grid.len();
        let (g, sdd) = if end {
            (grid[n - 1], grid[n - 2].sdd)
        } else {
            (grid[0], grid[0].sdd)
        };
        let (q, d1, d2) = spline.eval(g.seg, g.s);
        Some(Kinematic {
            q,
            qd: std::array::from_fn(|j| d1[j] * g.sd),
            qdd: std::array::from_fn(|j| d1[j] * sdd + d2[j] * g.sd * g.sd),
        })
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
            Kind::Join(_) => s.clamp(0.0, 1.0) * self.duration_s,
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
                    // On the last waypoint, exactly (at rest unless the
                    // path was timed to end at a speed).
                    let (q, dq, _) = spline.eval(grid[last].seg, grid[last].s);
                    let sd = grid[last].sd;
                    return State {
                        q,
                        qd: std::array::from_fn(|j| dq[j] * sd),
                        s: grid[last].s,
                        sd,
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
            Kind::Join(traj) => {
                let (q, qd) = join::eval(traj, t);
                let d = self.duration_s.max(1e-12);
                State {
                    q,
                    qd,
                    s: (t / d).clamp(0.0, 1.0),
                    sd: 1.0 / d,
                }
            }
        }
    }
}
