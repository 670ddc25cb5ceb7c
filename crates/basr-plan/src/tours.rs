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
    /// `kept[s]`: station s is painted in exactly this order and these
    /// directions (a fitted job's, `as_painted`); the others' tours are
    /// where `joints::joint_paths`' search for a shorter one starts.
    pub kept: Vec<bool>,
}

/// Order each station's passes to minimise the estimated air time; or,
/// re-planning a job at the site (`painted`: each stop's passes as the job
/// being fitted paints them, `site::painted_passes`; `gun_s`: the longer
/// of the gun's lead and lag, s), keep each stop whose passes are the
/// job's in the job's order ([`as_painted`], `Tours::kept`). The fitted
/// stop then paints in the order of the crew's job sheet, not one ordered
/// afresh from where the truck stopped, and the job's own pace for it
/// meets the joins it was found on (STOP's stop 0.3 m back and 2.5°
/// turned, ordered afresh, started at the other end of the word and took
/// seven rounds of verification); the other stops move as the job's did,
/// whether it ordered them afresh or kept them from an earlier fit.
pub fn tours(
    passes: &Passes,
    plan: &StationPlan,
    robot: &AnyRobot,
    painted: &[Vec<crate::site::PaintedPass>],
    gun_s: f64,
) -> Tours {
    let stow_pose = robot.fk(&stow_joints(robot));
    let (stations, kept): (Vec<Vec<Visit>>, Vec<bool>) = plan
        .stations
        .iter()
        .enumerate()
        .map(|(si, station)| {
            let as_job = painted
                .get(si)
                .filter(|p| !p.is_empty())
                .and_then(|p| as_painted(passes, plan, si, p, gun_s));
            if let Some(visits) = as_job {
                return (visits, true);
            }
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
            let visits = order::order(&ends, from, cost)
                .into_iter()
                .map(|v| Visit {
                    item: mine[v.item],
                    reversed: v.reversed,
                })
                .collect();
            (visits, false)
        })
        .unzip();
    Tours { stations, kept }
}

/// Farthest (m) a painted run's ends may lie from a planned pass's for
/// the two to start or end together, past what the gun's lead or lag
/// moves them at the pass's painting speed. assumed: the rows and the
/// knots a pass is sampled at put its ends within a few millimetres of
/// each other (the reviewer measured up to 7 mm on a bicycle's wheels),
/// and two passes of one stroke lie a band apart (7 cm or more); the
/// nearest pass is taken either way.
const SAME_PASS_M: f64 = 0.05;

/// Station `si`'s visits in the order `painted` paints its passes (a job
/// being fitted, `site::painted_passes`): each painted run the pass of
/// its stroke whose start lies nearest the run's, the right way round,
/// then (where a run goes on without the gun closing, a join that
/// continues) the next whose start lies nearest that one's end, until one
/// ends where the run does. A closed pass (a wheel: both ends at the
/// run's start) is painted the way round whose quarter point lies nearer
/// the run's. Ends match within [`SAME_PASS_M`] and what `gun_s`, the
/// longer of the gun's lead and lag (s), moves them at the station's
/// fastest painting speed. `None` when they are not the station's passes
/// one to one (the surface re-planned a stroke into other passes): the
/// station is ordered afresh.
pub fn as_painted(
    passes: &Passes,
    plan: &StationPlan,
    si: usize,
    painted: &[crate::site::PaintedPass],
    gun_s: f64,
) -> Option<Vec<Visit>> {
    let mine: Vec<usize> = (0..passes.passes.len())
        .filter(|&i| plan.station_of.get(i) == Some(&si))
        .collect();
    let fastest = mine
        .iter()
        .flat_map(|&i| &passes.passes[i].knots)
        .map(|k| k.speed_mps)
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    let near = SAME_PASS_M + gun_s.max(0.0) * fastest;
    let tip = |k: Option<&Knot>| k.map(|k| [k.tip.x, k.tip.y]);
    // each pass's start and end, and its points a quarter of the way in
    // from each
    let ends: Vec<[[f64; 2]; 4]> = mine
        .iter()
        .map(|&i| {
            let k = &passes.passes[i].knots;
            let n = k.len().saturating_sub(1);
            Some([
                tip(k.first())?,
                tip(k.last())?,
                tip(k.get(n / 4))?,
                tip(k.get(n - n / 4))?,
            ])
        })
        .collect::<Option<_>>()?;
    let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let mut used = vec![false; mine.len()];
    let mut out = Vec::with_capacity(mine.len());
    for p in painted {
        let mut at = p.from_m;
        loop {
            // the unused pass of the run's stroke starting nearest `at`
            let (j, mut reversed, off) = (0..mine.len())
                .filter(|&j| !used[j] && passes.passes[mine[j]].stroke == p.stroke)
                .flat_map(|j| {
                    let [a, b, ..] = ends[j];
                    [(j, false, d(a, at)), (j, true, d(b, at))]
                })
                .min_by(|x, y| x.2.total_cmp(&y.2))?;
            if off > near {
                return None;
            }
            let [a, b, fwd, back] = ends[j];
            // a closed pass starts where the run does either way round
            if at == p.from_m && d(a, at).max(d(b, at)) <= near {
                reversed = d(back, p.quarter_m) < d(fwd, p.quarter_m);
            }
            used[j] = true;
            out.push(Visit {
                item: mine[j],
                reversed,
            });
            at = if reversed { a } else { b };
            if d(at, p.to_m) <= near {
                break;
            }
        }
    }
    used.iter().all(|&u| u).then_some(out)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::passes::Pass;
    use crate::site::PaintedPass;

    /// A pass of `stroke` through `points`.
    fn through(stroke: usize, points: &[[f64; 2]]) -> Pass {
        Pass {
            stroke,
            knots: points.iter().map(|&[x, y]| Knot::at(x, y)).collect(),
        }
    }

    /// A pass of `stroke` from (x0, y) to (x1, y), two knots.
    fn pass(stroke: usize, x0: f64, x1: f64, y: f64) -> Pass {
        through(stroke, &[[x0, y], [x1, y]])
    }

    /// Stations on a flat road, pass i painted by station `station_of[i]`.
    fn plan_of(station_of: Vec<usize>) -> StationPlan {
        let n = station_of.iter().max().map_or(0, |m| m + 1);
        let st = Station {
            x_m: 0.0,
            y_m: 4.0,
            heading_rad: -FRAC_PI_2,
        };
        StationPlan {
            stations: vec![st; n],
            station_of,
            margin_m: vec![0.5; n],
            road: basr_job::Road::default(),
        }
    }

    fn ran(stroke: usize, from: [f64; 2], to: [f64; 2]) -> PaintedPass {
        PaintedPass {
            stroke,
            from_m: from,
            to_m: to,
            quarter_m: from,
        }
    }

    /// The painted runs name the station's passes in their order and
    /// directions, a run that goes on without the gun closing naming each
    /// pass it joins; anything that is not the station's passes one to one
    /// is none.
    #[test]
    fn a_job_s_runs_give_its_order() {
        // stroke 0 cut across into two stretches the second of which
        // continues the first, stroke 1 in one pass; a pass of another
        // station between them
        let passes = Passes {
            passes: vec![
                pass(0, 0.0, 1.0, 0.0),
                pass(0, 1.003, 2.0, 0.0),
                pass(5, 0.0, 1.0, 3.0),
                pass(1, 2.5, 3.5, 0.5),
            ],
            ..Passes::default()
        };
        let plan = plan_of(vec![0, 0, 1, 0]);
        let v = |item, reversed| Visit { item, reversed };
        // stroke 1 backwards, then both stretches of stroke 0 backwards in
        // one run (the gun 2 cm short of the ends, as its lead and lag
        // leave it)
        let runs = [
            ran(1, [3.5, 0.5], [2.5, 0.5]),
            ran(0, [1.98, 0.0], [0.02, 0.0]),
        ];
        assert_eq!(
            as_painted(&passes, &plan, 0, &runs, 0.0),
            Some(vec![v(3, true), v(1, true), v(0, true)])
        );
        // the other station's own pass
        assert_eq!(
            as_painted(&passes, &plan, 1, &[ran(5, [1.0, 3.0], [0.0, 3.0])], 0.0),
            Some(vec![v(2, true)])
        );
        // a pass left unpainted, a run far from every pass, or of a
        // stroke the station does not paint: ordered afresh
        assert_eq!(as_painted(&passes, &plan, 0, &runs[..1], 0.0), None);
        let far = [ran(1, [3.5, 0.8], [2.5, 0.8]), runs[1]];
        assert_eq!(as_painted(&passes, &plan, 0, &far, 0.0), None);
        let other = [ran(5, [3.5, 0.5], [2.5, 0.5]), runs[1]];
        assert_eq!(as_painted(&passes, &plan, 0, &other, 0.0), None);
        // a gun that opens 0.5 s early at the passes' 0.2 m/s starts its
        // runs 10 cm before them (and closes 0.5 s before their ends)
        let early = [
            ran(1, [3.6, 0.5], [2.6, 0.5]),
            ran(0, [2.08, 0.0], [0.1, 0.0]),
        ];
        assert_eq!(as_painted(&passes, &plan, 0, &early, 0.0), None);
        assert_eq!(
            as_painted(&passes, &plan, 0, &early, 0.5),
            Some(vec![v(3, true), v(1, true), v(0, true)])
        );
    }

    /// A closed pass (a wheel) starts and ends where its run does either
    /// way round: the run's quarter point says which.
    #[test]
    fn a_closed_pass_is_painted_the_way_round_the_job_paints_it() {
        let ring = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.003]];
        let passes = Passes {
            passes: vec![through(0, &ring)],
            ..Passes::default()
        };
        let plan = plan_of(vec![0]);
        let run = |quarter: [f64; 2], from: [f64; 2], to: [f64; 2]| PaintedPass {
            stroke: 0,
            from_m: from,
            to_m: to,
            quarter_m: quarter,
        };
        let v = |reversed| Some(vec![Visit { item: 0, reversed }]);
        // out along y = 0 first, or up x = 0 first (either end may start it)
        for (from, to) in [([0.0, 0.0], [0.0, 0.003]), ([0.0, 0.003], [0.0, 0.0])] {
            assert_eq!(
                as_painted(&passes, &plan, 0, &[run([0.95, 0.0], from, to)], 0.0),
                v(false)
            );
            assert_eq!(
                as_painted(&passes, &plan, 0, &[run([0.0, 0.95], from, to)], 0.0),
                v(true)
            );
        }
    }
}
