//! The timed trajectory: each station's runs joined by air moves from and
//! back to the stow pose, timed by the time law (`timing`) and sampled at
//! the control period, with the gun's command windows and the places where
//! a limit holds the nozzle below the painting speed.

use crate::robot::{Joints, Robot};

use super::error::CompileError;
use super::joints::{JointPaths, Run};
use super::knots::{self, Knot};
use super::placed::PlacedStrokes;
use super::stow::stow_joints;
use super::timing;
use super::warnings::{Limit, Note};

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
    paths: &JointPaths,
    robot: &Robot,
    period_s: f64,
    gun_lead_s: f64,
    gun_lag_s: f64,
) -> Result<TimedTrajectory, CompileError> {
    let stow = stow_joints(robot);
    let mut out = TimedTrajectory::default();
    let mut rows = 0usize;
    for runs in &paths.stations {
        let t0 = rows as f64 * period_s;
        let (timed, slows) = time_station(robot, &stow, runs, period_s, gun_lead_s, gun_lag_s)?;
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
        rows += timed.len();
        out.stations.push(timed);
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

/// Joint vector in `Limits::NAMES` order.
pub type Q = [f64; 5];

/// Jerk limit of every joint, as a multiple of its acceleration limit.
/// assumed: no source gives jerk limits; each joint reaches its
/// acceleration limit in 0.1 s (as the yaw servo reaches 30°/s in 0.1 s,
/// SPEC §4).
const JERK_PER_ACC: f64 = 10.0;

/// The robot's joint limits for the time law. The tilt's ball nut has its
/// own speed limit (SPEC §4: 0.11 m/s), applied as a tilt-rate limit at the
/// steepest nut travel per radian of the tilt range.
fn timing_limits(robot: &Robot) -> timing::JointLimits<5> {
    let mut vel = [0.0; 5];
    let mut acc = [0.0; 5];
    for (j, (_, l)) in robot.limits.iter().enumerate() {
        vel[j] = l.max_vel;
        acc[j] = l.max_acc;
    }
    let t = &robot.limits.tilt_rad;
    let fb = &robot.end_effector.fourbar;
    let steepest = (0..=60)
        .filter_map(|k| fb.nut_rate_m_per_rad(t.min + (t.max - t.min) * k as f64 / 60.0))
        .map(f64::abs)
        .fold(0.0, f64::max);
    if steepest > 0.0 {
        // 1 % below, for the nut rate between the sampled tilts.
        vel[4] = vel[4].min(robot.end_effector.tilt_nut_max_speed_mps / (steepest * 1.01));
    }
    timing::JointLimits {
        vel,
        acc,
        jerk: std::array::from_fn(|j| acc[j] * JERK_PER_ACC),
    }
}

fn q_of(j: &Joints) -> Q {
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

/// Time a station: stow → (air → run)* → air → stow, sampled at `period`
/// from t = 0 (`plan::timing`). Gun windows from the runs' first and last
/// painting knots, shifted by the lead and lag.
fn time_station(
    robot: &Robot,
    stow: &Joints,
    runs: &[Run],
    period_s: f64,
    gun_lead_s: f64,
    gun_lag_s: f64,
) -> Result<(Vec<Timed>, Vec<Slow>), CompileError> {
    let limits = timing_limits(robot);
    let options = timing::PathOptions::default();
    let err = |what: String| CompileError::Timing(what);
    let mut pieces = vec![];
    // Piece index of each run, and each run's arc lengths.
    let mut run_piece = vec![];
    let mut arcs = vec![];
    let mut at = q_of(stow);
    for run in runs {
        let s = arc_lengths(&run.knots);
        let points: Vec<timing::PathPoint<5>> = run
            .knots
            .iter()
            .zip(&run.joints)
            .enumerate()
            .map(|(i, (k, j))| timing::PathPoint {
                s_m: s[i],
                q: q_of(j),
                // Leads are gun-off run-ups: as fast as the joints allow.
                max_speed_mps: (run.paint_first..=run.paint_last)
                    .contains(&i)
                    .then_some(k.speed_mps),
            })
            .collect();
        let first = points[0].q;
        pieces.push(
            timing::air_move(at, first, &limits, options.margin)
                .map_err(|e| err(format!("air move to stroke {}: {e}", run.stroke)))?,
        );
        run_piece.push(pieces.len());
        pieces.push(
            timing::time_path(&points, &limits, &options)
                .map_err(|e| err(format!("stroke {}: {e}", run.stroke)))?,
        );
        at = points[points.len() - 1].q;
        arcs.push(s);
    }
    pieces.push(
        timing::air_move(at, q_of(stow), &limits, options.margin)
            .map_err(|e| err(format!("air move to the stow pose: {e}")))?,
    );
    let sampled = timing::resample(&pieces, period_s).map_err(|e| err(e.to_string()))?;
    let starts: Vec<f64> = pieces
        .iter()
        .scan(0.0, |acc, p| {
            let s0 = *acc;
            *acc += p.duration_s();
            Some(s0)
        })
        .collect();
    // Gun command windows (station time).
    let windows: Vec<(f64, f64)> = runs
        .iter()
        .enumerate()
        .map(|(ri, run)| {
            let p = &pieces[run_piece[ri]];
            let (on, off) = p.gun_times(
                arcs[ri][run.paint_first],
                arcs[ri][run.paint_last],
                gun_lead_s,
                gun_lag_s,
            );
            let t0 = starts[run_piece[ri]];
            (t0 + on, t0 + off)
        })
        .collect();
    let mut out = Vec::with_capacity(sampled.len());
    let mut w = 0usize;
    for k in 0..sampled.len() {
        let t = sampled.t_s[k];
        let piece = sampled.piece[k];
        let run = run_piece.iter().position(|&p| p == piece);
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
            s: sampled.s[k],
            gun,
        });
    }
    let mut slows = vec![];
    for (ri, &pi) in run_piece.iter().enumerate() {
        for sd in &pieces[pi].slowdowns {
            let limit = match sd.binding {
                timing::Binding::Velocity { joint } => Limit::Speed { joint },
                timing::Binding::Acceleration { joint } => Limit::Acceleration { joint },
                timing::Binding::Rest => Limit::RunUp,
            };
            slows.push(Slow {
                run: ri,
                factor: 1.0 / sd.factor.max(1e-9),
                knot: sd.worst_waypoint,
                t_s: starts[pi] + pieces[pi].time_at(arcs[ri][sd.worst_waypoint]),
                limit,
            });
        }
    }
    Ok((out, slows))
}
