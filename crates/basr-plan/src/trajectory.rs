//! The timed trajectory: each station's runs joined by air moves from and
//! back to the stow pose, timed by the time law (`timing`) and sampled at
//! the control period, with the gun's command windows and the places where
//! a limit holds the nozzle below the painting speed.

use basr_robot::{AnyRobot, Joints};

use super::chain::{chain, StopReason};
use super::error::CompileError;
use super::flight;
use super::joints::{JointPaths, Run};
use super::knots::{self, Knot};
use super::placed::PlacedStrokes;
use super::stations::StationPlan;
use super::stow::{stow_joints, truck_rows};
use super::timing;
use super::tuning::Joins;
use super::warnings::{Limit, Note, StopWhy};

/// Every station's timed samples, and the notes of the time law.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct TimedTrajectory {
    /// `stations[s]`: samples at t = k · period from the station's start.
    pub stations: Vec<Vec<Timed>>,
    pub notes: Vec<Note>,
}

/// Time every station (see `time_station`); the slow-downs become notes at
/// the job's time (stations follow each other sample after sample).
pub fn time_law(
    strokes: &PlacedStrokes,
    plan: &StationPlan,
    paths: &JointPaths,
    robot: &AnyRobot,
    law: &TimeLaw,
) -> Result<TimedTrajectory, CompileError> {
    let paces = vec![law.pace.clone(); paths.stations.len()];
    let mut cache = StationTimings::default();
    time_law_paced(strokes, plan, paths, robot, law, &paces, &mut cache)
}

/// Each station's timing as last computed and the pace it was computed
/// at: a station whose pace did not change is not timed again.
#[derive(Default)]
pub struct StationTimings(Vec<Option<(Pace, StationTiming)>>);

/// [`time_law`] with a pace per station (`paces[s]`; `law.pace` is not
/// used): the stations whose pace changed since `cache` last saw them are
/// timed again (in parallel: a station's timing depends on its own runs
/// alone), the others reused.
pub fn time_law_paced(
    strokes: &PlacedStrokes,
    plan: &StationPlan,
    paths: &JointPaths,
    robot: &AnyRobot,
    law: &TimeLaw,
    paces: &[Pace],
    cache: &mut StationTimings,
) -> Result<TimedTrajectory, CompileError> {
    use rayon::prelude::*;
    let TimeLaw {
        period_s,
        gun_lead_s,
        gun_lag_s,
        ref joins,
        ..
    } = *law;
    let stow = stow_joints(robot);
    let n = paths.stations.len();
    cache.0.resize_with(n, || None);
    let stale: Vec<usize> = (0..n)
        .filter(|&si| !matches!(&cache.0[si], Some((p, _)) if *p == paces[si]))
        .collect();
    let fresh: Vec<Result<StationTiming, CompileError>> = stale
        .par_iter()
        .map(|&si| {
            let runs = &paths.stations[si];
            time_station(
                robot, &stow, runs, period_s, gun_lead_s, gun_lag_s, &paces[si], joins,
            )
        })
        .collect();
    for (si, timing) in stale.into_iter().zip(fresh) {
        cache.0[si] = Some((paces[si].clone(), timing?));
    }
    let timings = cache
        .0
        .iter()
        .map(|c| c.as_ref().map(|(_, t)| t))
        .collect::<Option<Vec<_>>>()
        .ok_or_else(|| CompileError::Timing("a station was left untimed".into()))?;
    let mut out = TimedTrajectory::default();
    let mut rows = 0usize;
    for ((si, runs), (timed, slows, stops)) in paths.stations.iter().enumerate().zip(timings) {
        if si > 0 {
            rows += truck_rows(robot, &plan.stations[si - 1], &plan.stations[si], period_s);
        }
        let t0 = rows as f64 * period_s;
        let at = |q: &Q| {
            let p = robot.fk(q);
            let st = &plan.stations[si];
            st.base_to_road([p.x_m, p.y_m])
        };
        let last = timed.last().map(|t| t.q).unwrap_or(stow);
        out.notes.push(Note::Stop {
            station: si,
            t_s: t0,
            at_m: at(&stow),
            why: StopWhy::LeaveStow,
        });
        for &(t_s, q, ri, ref why) in stops {
            let StopReason::JointRange { joint } = *why;
            let stroke = runs[ri].stroke;
            out.notes.push(Note::Stop {
                station: si,
                t_s: t0 + t_s,
                at_m: at(&q),
                why: StopWhy::JointRange {
                    stroke,
                    owner: strokes.owner(stroke).clone(),
                    joint,
                },
            });
        }
        for sl in slows {
            let run = &runs[sl.run];
            let k = &run.knots[sl.knot.min(run.knots.len() - 1)];
            out.notes.push(Note::Slowed {
                stroke: run.stroke,
                owner: strokes.owner(run.stroke).clone(),
                limit: sl.limit,
                at_m: [k.tip.x, k.tip.y],
                t_s: t0 + sl.t_s,
                film_ratio: sl.factor,
            });
        }
        out.notes.push(Note::Stop {
            station: si,
            t_s: t0 + timed.len().saturating_sub(1) as f64 * period_s,
            at_m: at(&last),
            why: StopWhy::BackToStow,
        });
        rows += timed.len();
        out.stations.push(timed.clone());
    }
    Ok(out)
}

/// One station's timed samples: joints, the painting run (if any) whose
/// motion the sample belongs to, its path parameter, and the run whose gun
/// is commanded on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timed {
    pub q: Q,
    pub run: Option<usize>,
    pub s: f64,
    pub gun: Option<usize>,
}

/// Joint vector in the robot kind's order (`AnyRobot::joint_names`).
pub use basr_robot::Q;

/// The robot's joint limits for the time law. The tilt's ball nut has its
/// own speed limit (SPEC §4: 0.11 m/s), applied as a tilt-rate limit at the
/// steepest nut travel per radian of the tilt range.
/// How much of the joints' limits the time law uses (each 0–1], lowered
/// by the verification where the arm falls behind: `air` for the moves
/// from and to the stow pose (the arm arrives at its first stroke ringing
/// after a long fast move), `path` for the chained path through the strokes.
/// `joins`: the flown joins into those strokes, or into one pass of one,
/// at a share of the accelerations (the arm arrived behind at the pass's
/// first rungs).
/// `fly_in`: the move out of stow flies into the first stroke's first rung
/// at painting speed; else it comes to rest at the start of the stroke's
/// lead and the time law runs up from there (the first thing the
/// verification gives up where the arm arrives behind).
#[derive(Clone, Debug, PartialEq)]
pub struct Pace {
    pub air: f64,
    pub path: f64,
    pub joins: Vec<basr_job::JoinPace>,
    pub fly_in: bool,
}

impl Pace {
    pub const FULL: Pace = Pace {
        air: 1.0,
        path: 1.0,
        joins: Vec::new(),
        fly_in: true,
    };
}

/// The time law's settings: the setpoint period, the gun valve's delays
/// and the pace.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeLaw {
    pub period_s: f64,
    pub gun_lead_s: f64,
    pub gun_lag_s: f64,
    pub pace: Pace,
    /// How strokes are entered, left and joined (`tuning::Joins`).
    pub joins: Joins,
}

/// `pace` (0–1] scales every acceleration and jerk limit, and the speed
/// limits by its square root; the drives' own speed caps (BASR's tilt
/// ball nut) hold at every pace; the jerk limits are `jerk_per_acc` (1/s)
/// times the acceleration limits.
pub(super) fn timing_limits(
    robot: &AnyRobot,
    pace: f64,
    jerk_per_acc: f64,
) -> timing::JointLimits<5> {
    let mut vel = [0.0; 5];
    let mut acc = [0.0; 5];
    let caps = robot.drive_speed_caps();
    for (j, l) in robot.limits().iter().enumerate() {
        vel[j] = (l.max_vel * pace.sqrt()).min(caps[j]);
        acc[j] = l.max_acc * pace;
    }
    timing::JointLimits {
        vel,
        acc,
        jerk: std::array::from_fn(|j| acc[j] * jerk_per_acc),
    }
}

pub fn joints_of(q: &Q) -> Joints {
    Joints::of(q)
}

/// Nozzle arc length at each knot (road frame, m), strictly increasing:
/// knots closer than 0.1 mm are nudged apart so the path stays defined.
pub fn arc_lengths(ks: &[Knot]) -> Vec<f64> {
    let mut s = Vec::with_capacity(ks.len());
    let mut acc = 0.0;
    for (i, k) in ks.iter().enumerate() {
        if i > 0 {
            let d = (k.tip - ks[i - 1].tip).hypot();
            acc += d.max(knots::MIN_TIP_STEP_M);
        }
        s.push(acc);
    }
    s
}

/// A slowdown of one painting run, for the job's warnings.
struct Slow {
    run: usize,
    factor: f64,
    knot: usize,
    t_s: f64,
    limit: Limit,
}

/// Time a station: stow → air move → the chained path through every run →
/// air move → stow, sampled at `period` from t = 0 (`plan::timing`). The air
/// moves from and to the stow pose are jerk-limited and start and end at
/// rest; the chained path is time-optimal under the joints' speed and
/// acceleration limits and never faster than the film law asks over paint.
/// Gun windows from the runs' first and last painting knots, shifted by the
/// lead and lag.
#[allow(clippy::too_many_arguments)]
fn time_station(
    robot: &AnyRobot,
    stow: &Q,
    runs: &[Run],
    period_s: f64,
    gun_lead_s: f64,
    gun_lag_s: f64,
    pace: &Pace,
    joins: &Joins,
) -> Result<StationTiming, CompileError> {
    let jerk = joins.jerk_per_acc;
    let limits = timing_limits(robot, pace.path, jerk);
    let air_limits = timing_limits(robot, pace.air, jerk);
    let back_limits = timing_limits(robot, 1.0, jerk);
    let options = timing::PathOptions {
        margin: joins.path_margin,
        ..timing::PathOptions::default()
    };
    let err = |what: String| CompileError::Timing(what);
    let home = *stow;
    if runs.is_empty() {
        let still = timing::air_move(home, home, &limits, options.margin)
            .map_err(|e| err(e.to_string()))?;
        let sampled = timing::resample(&[still], period_s).map_err(|e| err(e.to_string()))?;
        return Ok((
            sampled
                .q
                .iter()
                .map(|&q| Timed {
                    q,
                    run: None,
                    s: 0.0,
                    gun: None,
                })
                .collect(),
            vec![],
            vec![],
        ));
    }
    let ch = chain(robot, runs, &limits, &pace.joins, joins);
    let cut = flight::fly(
        robot,
        runs,
        &ch,
        &flight::Limits {
            home,
            path: &limits,
            air: &air_limits,
            back: &back_limits,
            joins: &pace.joins,
            fly_in: pace.fly_in,
            join_margin: joins.join_margin,
        },
        &options,
    )?;
    let pieces = cut.pieces;
    // starts[p]: station time at which piece p starts.
    let starts = timing::start_times(&pieces);
    // Segment k of the path is piece 1 + 2k; the station time at path
    // parameter s.
    let segment_at = |s: f64| {
        cut.ranges
            .iter()
            .rposition(|r| ch.points[r.0].s_m <= s + 1e-12)
            .unwrap_or(0)
    };
    let time_at = |s: f64| {
        let k = segment_at(s);
        starts[1 + 2 * k] + pieces[1 + 2 * k].time_at(s)
    };
    if std::env::var_os("BASR_JOIN_REPORT").is_some() {
        eprintln!(
            "stow out {:.3} s, back {:.3} s",
            pieces[0].duration_s(),
            pieces[pieces.len() - 1].duration_s()
        );
    }
    let sampled = timing::resample(&pieces, period_s).map_err(|e| err(e.to_string()))?;
    // Gun command windows (station time).
    let windows: Vec<(f64, f64)> = runs
        .iter()
        .enumerate()
        .map(|(ri, run)| {
            let s0 = ch.spans[ri].offset;
            (
                time_at(s0 + ch.arcs[ri][run.paint_first]) - gun_lead_s,
                time_at(s0 + ch.arcs[ri][run.paint_last]) - gun_lag_s,
            )
        })
        .collect();
    let mut out = Vec::with_capacity(sampled.len());
    let mut w = 0usize;
    for k in 0..sampled.len() {
        let t = sampled.t_s[k];
        let p = sampled.piece[k];
        let (run, s) = if p >= 1 && p < 2 * cut.ranges.len() && (p - 1) % 2 == 0 {
            ch.run_at(sampled.s[k])
        } else {
            (None, 0.0)
        };
        while w + 1 < windows.len() && t >= windows[w].1 {
            w += 1;
        }
        let gun = windows
            .get(w)
            .filter(|(on, off)| t >= *on && t < *off)
            .map(|_| w);
        out.push(Timed {
            q: sampled.q[k],
            run,
            s,
            gun,
        });
    }
    let mut slows = vec![];
    for (k, r) in cut.ranges.iter().enumerate() {
        for sd in &pieces[1 + 2 * k].slowdowns {
            let wp = r.0 + sd.worst_waypoint;
            let (ri, knot) = ch.knot_of(wp);
            let limit = match sd.binding {
                timing::Binding::Velocity { joint } => Limit::Speed {
                    joint: robot.joint_names()[joint],
                },
                timing::Binding::Acceleration { joint } => Limit::Acceleration {
                    joint: robot.joint_names()[joint],
                },
                timing::Binding::Rest => Limit::RunUp,
            };
            slows.push(Slow {
                run: ri,
                factor: 1.0 / sd.factor.max(1e-9),
                knot,
                t_s: time_at(ch.points[wp].s_m),
                limit,
            });
        }
    }
    let stops = ch
        .stops
        .iter()
        .map(|(ri, why)| {
            let sp = ch.spans[*ri];
            let t = time_at(sp.offset + ch.arcs[*ri][sp.lo]);
            (t, runs[*ri].joints[sp.lo], *ri, why.clone())
        })
        .collect();
    Ok((out, slows, stops))
}

/// A station's samples, slow-downs and stops (station time, joints there,
/// run entered, why).
type StationTiming = (Vec<Timed>, Vec<Slow>, Vec<(f64, Q, usize, StopReason)>);
