//! Tours: per station, the order and direction in which its passes are
//! painted, starting from the stow pose (`order` solves the open tour).

use std::f64::consts::{FRAC_PI_2, PI};

use crate::knots::Knot;
use basr_job::Station;
use basr_robot::kinematics::wrap_pi;
use basr_robot::{AnyRobot, JointLimit, Robot};

use super::order::{self, Ends, Visit};
use super::passes::Passes;
use super::stations::StationPlan;
use super::stow::stow_joints;

/// The painting order of every station.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Tours {
    /// `stations[s]`: visits in painting order; `Visit::item` indexes
    /// `passes`, `reversed` paints the pass end → start.
    pub stations: Vec<Vec<Visit>>,
}

/// Order each station's passes to minimise the estimated air time.
pub fn tours(passes: &Passes, plan: &StationPlan, robot: &AnyRobot) -> Tours {
    let stow_pose = robot.fk(&stow_joints(robot));
    let stations = plan
        .stations
        .iter()
        .enumerate()
        .map(|(si, station)| {
            let mine: Vec<usize> = (0..passes.passes.len())
                .filter(|&i| plan.station_of[i] == si)
                .collect();
            let ends: Vec<Ends<EndPose>> = mine
                .iter()
                .map(|&i| {
                    let k = &passes.passes[i].knots;
                    let at = |k: Option<&Knot>| {
                        k.map(|k| EndPose {
                            xy: [k.tip.x, k.tip.y],
                            yaw: k.yaw_rad,
                            tilt: k.tilt_rad,
                        })
                        .unwrap_or_default()
                    };
                    Ends {
                        start: at(k.first()),
                        end: at(k.last()),
                    }
                })
                .collect();
            let from = EndPose {
                xy: station.base_to_road([stow_pose.x_m, stow_pose.y_m]),
                yaw: stow_pose.yaw_rad + station.heading_rad - FRAC_PI_2,
                tilt: stow_pose.tilt_rad,
            };
            let cost = |a: EndPose, b: EndPose| air_time_estimate(robot, station, a, b);
            order::order(&ends, from, cost)
                .into_iter()
                .map(|v| Visit {
                    item: mine[v.item],
                    reversed: v.reversed,
                })
                .collect()
        })
        .collect();
    Tours { stations }
}

/// Base-frame polar coordinates (θ1, R) of a road point.
fn polar(station: &Station, p: [f64; 2]) -> (f64, f64) {
    let b = station.road_to_base(p);
    (b[1].atan2(b[0]), b[0].hypot(b[1]))
}

/// Where a pass starts or ends: the nozzle's road point, the fan's
/// direction ψ (road frame) and its tilt β there.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EndPose {
    pub xy: [f64; 2],
    pub yaw: f64,
    pub tilt: f64,
}

/// Time to move `d` from rest to rest at speed limit `v` and acceleration `acc`.
fn rest_to_rest(d: f64, v: f64, acc: f64) -> f64 {
    let d = d.abs();
    if d * acc <= v * v {
        2.0 * (d / acc).sqrt()
    } else {
        d / v + v / acc
    }
}

/// Estimated time of an air move of the arm between two pass ends (BASR's
/// joints, or an electric kind's: `servo_air_time`).
fn air_time_estimate(robot: &AnyRobot, station: &Station, a: EndPose, b: EndPose) -> f64 {
    match robot.basr() {
        Some(r) => basr_air_time(r, station, a, b),
        None => servo_air_time(robot, station, a, b),
    }
}

/// Tip speed and acceleration of an electric arm's air moves along its
/// reach, for ordering only. assumed: 0.5 m/s and 0.5 m/s², the shipped
/// arms' boom and stroke limits (robots/telescopic.toml).
const SERVO_TIP_SPEED_MPS: f64 = 0.5;
const SERVO_TIP_ACC_MPS2: f64 = 0.5;

/// An electric kind's estimate: the slowest of its base joint (the tip's
/// azimuth), the tip's move towards or away from the base axis, the fan's
/// turn (on whichever fan branch turns it least) and the tilt, each from
/// rest to rest (joint-path optimisation prices the true joints later).
fn servo_air_time(robot: &AnyRobot, station: &Station, a: EndPose, b: EndPose) -> f64 {
    let (ta, ra) = polar(station, a.xy);
    let (tb, rb) = polar(station, b.xy);
    let l = robot.limits();
    let t = |d: f64, l: &JointLimit| rest_to_rest(d, l.max_vel, l.max_acc);
    let fan = &l[robot.fan_joint()];
    // Both kinds turn the fan by the base rotation plus (or less) the fan joint.
    let turn = wrap_pi((b.yaw - a.yaw) - (tb - ta));
    let tilt = |d: f64| robot.tilt_limit().map_or(0.0, |tl| t(d, &tl));
    let same = t(turn, fan).max(tilt(b.tilt - a.tilt));
    let flipped = t(wrap_pi(turn + PI), fan).max(tilt(b.tilt + a.tilt));
    t(tb - ta, &l[0])
        .max(rest_to_rest(
            rb - ra,
            SERVO_TIP_SPEED_MPS,
            SERVO_TIP_ACC_MPS2,
        ))
        .max(same.min(flipped))
}

/// BASR's estimate: the slowest of base rotation, extension, and the fan's
/// yaw and tilt joints (on whichever fan branch, (ψ, β) or (ψ+π, −β),
/// turns them least), each accelerating and braking at its limit
/// (symmetric, as the ordering needs).
fn basr_air_time(robot: &Robot, station: &Station, a: EndPose, b: EndPose) -> f64 {
    let (ta, ra) = polar(station, a.xy);
    let (tb, rb) = polar(station, b.xy);
    let l = &robot.limits;
    let t = rest_to_rest;
    // The yaw joint turns ψ less the base rotation (ψ = θ1 + yaw joint).
    let turn = wrap_pi((b.yaw - a.yaw) - (tb - ta));
    let fan = |dyaw: f64, dtilt: f64| {
        t(dyaw, l.ee_yaw_rad.max_vel, l.ee_yaw_rad.max_acc).max(t(
            dtilt,
            l.tilt_rad.max_vel,
            l.tilt_rad.max_acc,
        ))
    };
    let same = fan(turn, b.tilt - a.tilt);
    let flipped = fan(wrap_pi(turn + PI), b.tilt + a.tilt);
    t(tb - ta, l.base_rot_rad.max_vel, l.base_rot_rad.max_acc)
        .max(t(rb - ra, l.extension_m.max_vel, l.extension_m.max_acc))
        .max(same.min(flipped))
}
