//! Tours: per station, the order and direction in which its passes are
//! painted, starting from the stow pose (`order` solves the open tour).

use std::f64::consts::FRAC_PI_2;

use crate::knots::Knot;
use basr_job::Station;
use basr_robot::{AirEnd, AnyRobot};

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

/// Estimated time of an air move of the arm between two pass ends (the
/// robot's own estimate, `AnyRobot::air_time_estimate`).
fn air_time_estimate(robot: &AnyRobot, station: &Station, a: EndPose, b: EndPose) -> f64 {
    let end = |e: EndPose| {
        let (azimuth_rad, radius_m) = polar(station, e.xy);
        AirEnd {
            azimuth_rad,
            radius_m,
            yaw_rad: e.yaw,
            tilt_rad: e.tilt,
        }
    };
    robot.air_time_estimate(&end(a), &end(b))
}
