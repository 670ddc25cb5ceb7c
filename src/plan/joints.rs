//! Joint paths: every knot of every tour solved for the arm's joints (IK on
//! one fan branch per pass), with the leads that bring the nozzle up to
//! speed.

use std::f64::consts::FRAC_PI_2;

use crate::job::Station;
use crate::plan::knots::Knot;
use crate::robot::{Joints, NozzlePose, Robot};

use super::error::CompileError;
use super::leads::{with_leads, LEAD_M};
use super::passes::Passes;
use super::placed::PlacedStrokes;
use super::stations::{self, StationPlan};
use super::stow::stow_joints;
use super::tours::Tours;

/// A pass as the arm runs it: joints at every knot, in painting order.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// Index into the placed strokes.
    pub stroke: usize,
    /// Knots including the lead-in and lead-out.
    pub knots: Vec<Knot>,
    pub joints: Vec<Joints>,
    /// Indices of the first and last painting knot in `knots`.
    pub paint_first: usize,
    pub paint_last: usize,
}

/// Every station's runs, in painting order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct JointPaths {
    pub stations: Vec<Vec<Run>>,
}

/// Solve every tour's knots for the joints, from the stow pose on. A pass
/// out of reach is refused with the stroke, its item and the place.
pub fn joint_paths(
    strokes: &PlacedStrokes,
    passes: &Passes,
    plan: &StationPlan,
    tours: &Tours,
    robot: &Robot,
) -> Result<JointPaths, CompileError> {
    let stow = stow_joints(robot);
    let mut out = JointPaths::default();
    for (si, (station, tour)) in plan.stations.iter().zip(&tours.stations).enumerate() {
        let mut prev = stow;
        let mut runs = vec![];
        for v in tour {
            let pass = &passes.passes[v.item];
            let mut ks = pass.knots.clone();
            if v.reversed {
                ks.reverse();
            }
            let mut solved = None;
            let mut first_err = None;
            for lead in [LEAD_M, 0.5 * LEAD_M, 0.0] {
                let (all, a, b) = with_leads(&ks, lead);
                match solve_run(robot, station, &all, &prev) {
                    Ok(j) => {
                        solved = Some((all, j, a, b));
                        break;
                    }
                    Err((k, e)) => {
                        // Report the painting knot, not a lead's.
                        let k = k.saturating_sub(a).min(ks.len() - 1);
                        first_err.get_or_insert((k, e));
                    }
                }
            }
            let Some((all, joints, a, b)) = solved else {
                let (k, e) = first_err.unwrap_or((0, unreachable_pose()));
                return Err(CompileError::Unreachable(format!(
                    "stroke {} ({}) cannot be painted from station {si} at ({:.3}, {:.3}) m: \
                     {e}; use a smaller --letter-height or check the robot description",
                    pass.stroke,
                    strokes.owner(pass.stroke),
                    ks[k].tip.x,
                    ks[k].tip.y
                )));
            };
            prev = *joints.last().unwrap_or(&prev);
            runs.push(Run {
                stroke: pass.stroke,
                knots: all,
                joints,
                paint_first: a,
                paint_last: b,
            });
        }
        out.stations.push(runs);
    }
    Ok(out)
}

/// Joint travel time between two joint sets at the joints' speed limits.
fn travel(robot: &Robot, a: &Joints, b: &Joints) -> f64 {
    robot
        .limits
        .iter()
        .zip(a.values().into_iter().zip(b.values()))
        .map(|((_, l), (x, y))| (x - y).abs() / l.max_vel)
        .fold(0.0, f64::max)
}

/// The nozzle pose of a knot in a station's base frame.
fn knot_pose(station: &Station, k: &Knot) -> NozzlePose {
    let b = stations::road_to_base(station, [k.tip.x, k.tip.y]);
    NozzlePose {
        x_m: b[0],
        y_m: b[1],
        z_m: k.z_m,
        yaw_rad: k.yaw_rad - (station.heading_rad - FRAC_PI_2),
        tilt_rad: k.tilt_rad,
    }
}

/// Largest yaw-joint change between two knots of a run (rad). Knots are a
/// rung spacing apart (20 mm); the tightest turn in the font, a bowl's rung
/// pivoting about its inner end, turns the fan by well under this. A larger
/// step is a jump to the other fan branch (π) or yaw turn (2π).
const MAX_KNOT_YAW_STEP_RAD: f64 = std::f64::consts::FRAC_PI_2;

/// Joints for every knot of a run. The fan's two branches (ψ with β, ψ+π
/// with −β) and every yaw turn are tried at the first knot; each is followed
/// along the run by the nearest solution, and the branch with the least
/// joint travel (entry included) wins. Err: the knot index and why.
fn solve_run(
    robot: &Robot,
    station: &Station,
    ks: &[Knot],
    prev: &Joints,
) -> Result<Vec<Joints>, (usize, crate::robot::Unreachable)> {
    let first = knot_pose(station, &ks[0]);
    let starts = robot.ik(&first).map_err(|e| (0, e))?;
    let mut best: Option<(f64, Vec<Joints>)> = None;
    let mut last_err = None;
    'branch: for start in starts {
        let mut cost = travel(robot, prev, &start);
        let mut out = Vec::with_capacity(ks.len());
        out.push(start);
        for (i, k) in ks.iter().enumerate().skip(1) {
            let p = *out.last().unwrap_or(&start);
            match robot.ik_nearest(&knot_pose(station, k), &p) {
                // The nearest solution is on another branch or yaw turn: the
                // one this branch follows has left the yaw joint's range.
                // Turning the fan half or whole way round between two knots
                // would spray a disc with the gun on, so the branch fails.
                Ok(j) if (j.ee_yaw_rad - p.ee_yaw_rad).abs() > MAX_KNOT_YAW_STEP_RAD => {
                    let lim = &robot.limits.ee_yaw_rad;
                    let step = j.ee_yaw_rad - p.ee_yaw_rad;
                    // What the branch would have needed: the step less the
                    // half turns the jump added.
                    let own = step - std::f64::consts::PI * (step / std::f64::consts::PI).round();
                    let value = p.ee_yaw_rad + own;
                    last_err = Some((
                        i,
                        crate::robot::Unreachable {
                            joint: "ee_yaw_rad".into(),
                            value,
                            min: lim.min,
                            max: lim.max,
                            excess: (lim.min - value).max(value - lim.max).max(0.0),
                            flipped: false,
                        },
                    ));
                    continue 'branch;
                }
                Ok(j) => {
                    cost += travel(robot, &p, &j);
                    out.push(j);
                }
                Err(e) => {
                    last_err = Some((i, e));
                    continue 'branch;
                }
            }
        }
        if best.as_ref().is_none_or(|(c, _)| cost < *c - 1e-12) {
            best = Some((cost, out));
        }
    }
    match best {
        Some((_, v)) => Ok(v),
        None => Err(last_err.unwrap_or_else(|| (0, unreachable_pose()))),
    }
}

/// Placeholder reason when no IK branch was even tried (never expected).
fn unreachable_pose() -> crate::robot::Unreachable {
    crate::robot::Unreachable {
        joint: "pose".into(),
        value: f64::NAN,
        min: f64::NAN,
        max: f64::NAN,
        excess: f64::NAN,
        flipped: false,
    }
}
