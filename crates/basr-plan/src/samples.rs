//! Samples: the timed trajectory as the job's setpoint rows (joints,
//! actuators, encoders, nozzle pose in the road frame, gun and width), after
//! the robot's own check of every joint's range and rate: no job that breaks
//! a limit leaves the compiler.

use std::f64::consts::FRAC_PI_2;

use rayon::prelude::*;

use crate::knots::Knot;
use basr_job::{self as job, SampleRow, Samples, Station};
use basr_robot::kinematics::wrap_pi;
use basr_robot::{AnyRobot, NozzlePose, Q};

use super::error::CompileError;
use super::joints::{JointPaths, Run};
use super::stations::StationPlan;
use super::stow::{stow_joints, truck_rows};
use super::trajectory::{arc_lengths, Timed, TimedTrajectory};

/// Largest joint overshoot `clamp_to_range` absorbs (m or rad); anything
/// larger is a planning error.
const CLAMP_MAX: f64 = 1e-3;

/// The job's setpoint rows, station after station.
pub fn sample(
    plan: &StationPlan,
    paths: &JointPaths,
    timed: TimedTrajectory,
    robot: &AnyRobot,
    period_s: f64,
) -> Result<Samples, CompileError> {
    let n = plan.stations.len().min(timed.stations.len());
    // Each station's rows: the truck's drive to it (none before the
    // first), then its own motion.
    let counts: Vec<usize> = (0..n)
        .map(|si| {
            let drive = match si {
                0 => 0,
                _ => truck_rows(robot, &plan.stations[si - 1], &plan.stations[si], period_s),
            };
            drive + timed.stations[si].len()
        })
        .collect();
    let mut samples = Samples {
        kind_columns: robot.own_sample_columns(),
        ..Samples::default()
    };
    samples.reserve_exact(counts.iter().sum());
    // each station with the job's row its rows start at
    let mut start = 0usize;
    let mut stations = timed
        .stations
        .into_iter()
        .take(n)
        .enumerate()
        .map(|(si, rows)| {
            let at = start;
            start += counts[si];
            (si, rows, at)
        });
    // Stations are sampled in parallel, a few at a time and appended in
    // order (the same rows as one after another): a long job's rows are
    // held twice only for the stations in hand, not the whole job.
    let group = 2 * rayon::current_num_threads();
    loop {
        let hand: Vec<(usize, Vec<Timed>, usize)> = stations.by_ref().take(group).collect();
        if hand.is_empty() {
            break;
        }
        let blocks: Vec<Result<Samples, CompileError>> = hand
            .into_par_iter()
            .map(|(si, rows, at)| station_samples(plan, paths, robot, si, rows, at, period_s))
            .collect();
        for block in blocks {
            samples.append(&mut block?);
        }
    }
    Ok(samples)
}

/// Station `si`'s rows (`rows`, its own motion), the truck's drive to it
/// put before them, checked and made the job's rows from row `start` on.
fn station_samples(
    plan: &StationPlan,
    paths: &JointPaths,
    robot: &AnyRobot,
    si: usize,
    mut rows: Vec<Timed>,
    start: usize,
    period_s: f64,
) -> Result<Samples, CompileError> {
    let station = &plan.stations[si];
    if si > 0 {
        // The truck drives to this station with the arm stowed: rows of
        // the station being driven to (the road frame jumps where the
        // rows change station), one piece with the station's own rows so
        // the speed column's differences run across the seam.
        let hold = Timed {
            q: stow_joints(robot),
            run: None,
            s: 0.0,
            gun: None,
        };
        let n = truck_rows(robot, &plan.stations[si - 1], station, period_s);
        rows.splice(0..0, std::iter::repeat_n(hold, n));
    }
    clamp_to_range(robot, &mut rows)?;
    check_sampled(robot, &rows, si + 1, period_s)?;
    let mut samples = Samples {
        kind_columns: robot.own_sample_columns(),
        ..Samples::default()
    };
    samples.reserve_exact(rows.len());
    append_samples(
        &mut samples,
        robot,
        StationRows {
            station,
            index: si as u32,
            origin_z: plan.road.origin_z(station),
            start,
        },
        &paths.stations[si],
        &rows,
        period_s,
    );
    Ok(samples)
}

/// The robot's own check of the sampled joints (ranges, speeds,
/// accelerations; BASR's ball-nut speed too); `si` is the station's number
/// from 1, as messages count.
fn check_sampled(
    robot: &AnyRobot,
    rows: &[Timed],
    si: usize,
    period_s: f64,
) -> Result<(), CompileError> {
    let qs: Vec<Q> = rows.iter().map(|p| p.q).collect();
    robot.check_sampled(&qs, period_s).map_err(|f| {
        CompileError::Timing(match f.setpoint {
            Some(k) => format!("station {si}, setpoint {k}: {}", f.what),
            None => format!("station {si}: {}", f.what),
        })
    })
}

/// Clamp setpoints that the smooth joint curves carry a hair past a joint's
/// range (a knot held at the bottom of the vertical stroke); the rate
/// checks that follow still see every clamped sample.
fn clamp_to_range(robot: &AnyRobot, timed: &mut [Timed]) -> Result<(), CompileError> {
    let names = robot.joint_names();
    let limits = robot.limits();
    for (k, p) in timed.iter_mut().enumerate() {
        for (j, l) in limits.iter().enumerate() {
            let name = names[j];
            let v = p.q[j];
            let c = v.clamp(l.min, l.max);
            if (c - v).abs() > CLAMP_MAX {
                return Err(CompileError::PastRange {
                    setpoint: k,
                    joint: name,
                    value: v,
                    past: (c - v).abs(),
                    min: l.min,
                    max: l.max,
                });
            }
            p.q[j] = c;
        }
    }
    Ok(())
}

/// The station whose rows are being appended.
struct StationRows<'a> {
    station: &'a Station,
    /// Its index in the job (the `station` column).
    index: u32,
    /// The road-frame height of its base frame's origin: the z_m column is
    /// the road frame's (docs/site.md).
    origin_z: f64,
    /// Its first row's number in the job (the `t_s` column counts ticks
    /// from the job's start).
    start: usize,
}

/// Append a station's samples to `samples`.
fn append_samples(
    samples: &mut Samples,
    robot: &AnyRobot,
    at: StationRows<'_>,
    runs: &[Run],
    timed: &[Timed],
    period: f64,
) {
    let StationRows {
        station,
        index: station_index,
        origin_z,
        start: t0,
    } = at;
    let arcs: Vec<Vec<f64>> = runs.iter().map(|r| arc_lengths(&r.knots)).collect();
    // Nozzle in the road frame at every sample.
    let poses: Vec<(NozzlePose, [f64; 2], f64)> = timed
        .iter()
        .map(|p| {
            let pose = robot.fk(&p.q);
            let r = station.base_to_road([pose.x_m, pose.y_m]);
            let yaw = wrap_pi(pose.yaw_rad + station.heading_rad - FRAC_PI_2);
            (pose, r, yaw)
        })
        .collect();
    for (i, p) in timed.iter().enumerate() {
        let (pose, r, yaw) = &poses[i];
        // Central difference of the nozzle position (one-sided at the ends).
        let (a, b) = (i.saturating_sub(1), (i + 1).min(timed.len() - 1));
        let speed = if b > a {
            let (pa, pb) = (&poses[a], &poses[b]);
            (pb.1[0] - pa.1[0]).hypot(pb.1[1] - pa.1[1]) / ((b - a) as f64 * period)
        } else {
            0.0
        };
        let (stroke, paint, width) = match p.gun {
            Some(ri) => {
                let run = &runs[ri];
                // Before the run's motion (a gun lead) the width is the first rung's.
                let s = if p.run == Some(ri) {
                    p.s
                } else {
                    arcs[ri][run.paint_first]
                };
                let (w, _) = interp_knot(&run.knots, &arcs[ri], s);
                (run.stroke as i64, 1u8, w)
            }
            None => (-1, 0u8, 0.0),
        };
        let nozzle = SampleRow {
            t_s: job::tick_time(t0 + i, period),
            station: station_index,
            stroke,
            paint,
            x_m: r[0],
            y_m: r[1],
            z_m: pose.z_m + origin_z,
            yaw_rad: *yaw,
            tilt_rad: pose.tilt_rad,
            speed_mps: speed,
            width_m: width,
            ..SampleRow::default()
        };
        // BASR's joints in the job's own columns; another kind's in its
        // own after them, the job's joint columns left 0 (not applicable,
        // docs/robot-kinds.md).
        samples.push_joints(&nozzle, &robot.row_joints(&p.q));
    }
}

/// Rung width and painting speed at arc length `s`, linear between knots.
fn interp_knot(ks: &[Knot], arcs: &[f64], s: f64) -> (f64, f64) {
    let n = ks.len();
    let i = arcs.partition_point(|&a| a < s).clamp(1, n - 1);
    let (s0, s1) = (arcs[i - 1], arcs[i]);
    let f = if s1 > s0 {
        ((s - s0) / (s1 - s0)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let lerp = |a: f64, b: f64| a + f * (b - a);
    (
        lerp(ks[i - 1].swept_width_m, ks[i].swept_width_m),
        lerp(ks[i - 1].speed_mps, ks[i].speed_mps),
    )
}
