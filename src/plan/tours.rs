//! Tours: per station, the order and direction in which its passes are
//! painted, starting from the stow pose (`order` solves the open tour).

use crate::job::Station;
use crate::robot::Robot;

use super::order::{self, Ends, Visit};
use super::passes::Passes;
use super::stations::{self, StationPlan};
use super::stow::stow_joints;

/// The painting order of every station.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Tours {
    /// `stations[s]`: visits in painting order; `Visit::item` indexes
    /// `passes`, `reversed` paints the pass end → start.
    pub stations: Vec<Vec<Visit>>,
}

/// Order each station's passes to minimise the estimated air time.
pub fn tours(passes: &Passes, plan: &StationPlan, robot: &Robot) -> Tours {
    let stow_pose = robot.fk(&stow_joints(robot));
    let stations = plan
        .stations
        .iter()
        .enumerate()
        .map(|(si, station)| {
            let mine: Vec<usize> = (0..passes.passes.len())
                .filter(|&i| plan.station_of[i] == si)
                .collect();
            let ends: Vec<Ends> = mine
                .iter()
                .map(|&i| {
                    let k = &passes.passes[i].knots;
                    let first = k.first().map(|k| k.tip).unwrap_or_default();
                    let last = k.last().map(|k| k.tip).unwrap_or_default();
                    Ends {
                        start: [first.x, first.y],
                        end: [last.x, last.y],
                    }
                })
                .collect();
            let from = stations::base_to_road(station, [stow_pose.x_m, stow_pose.y_m]);
            let cost = |a: [f64; 2], b: [f64; 2]| air_time_estimate(robot, station, a, b);
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
    let b = stations::road_to_base(station, p);
    (b[1].atan2(b[0]), b[0].hypot(b[1]))
}

/// Estimated time of an air move of the arm between two road points: the
/// slower of base rotation and extension, each accelerating and braking at
/// its limit (symmetric, as the ordering needs).
fn air_time_estimate(robot: &Robot, station: &Station, a: [f64; 2], b: [f64; 2]) -> f64 {
    let (ta, ra) = polar(station, a);
    let (tb, rb) = polar(station, b);
    let l = &robot.limits;
    let t = |d: f64, v: f64, acc: f64| {
        let d = d.abs();
        if d * acc <= v * v {
            2.0 * (d / acc).sqrt()
        } else {
            d / v + v / acc
        }
    };
    t(tb - ta, l.base_rot_rad.max_vel, l.base_rot_rad.max_acc).max(t(
        rb - ra,
        l.extension_m.max_vel,
        l.extension_m.max_acc,
    ))
}
