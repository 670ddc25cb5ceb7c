//! A station's flight: its chained path (`chain`) cut at the flown joins
//! into painting segments, each timed by the time law between the painting
//! speeds at its ends, with a jerk-limited state-to-state move (`timing::join`)
//! from the stow pose into the first stroke's first rung, between each two
//! segments, and from the last stroke's last rung back to stow. Every air
//! move is thus jerk-limited on every joint; a seam whose move cannot be
//! found stays in the path as `chain` designed it (flown under the
//! acceleration limits), and a station end without one keeps the lead and
//! a rest-to-rest air move.

use basr_robot::AnyRobot;

use super::chain::Chain;
use super::error::CompileError;
use super::joints::Run;
use super::timing::{self, JointLimits, Kinematic, PathOptions, Trajectory};
use super::trajectory::Q;

/// The limits a station is flown at.
pub struct Limits<'a> {
    /// The stow pose, where the station starts and ends at rest.
    pub home: Q,
    /// The time law's, for the painting path and the joins.
    pub path: &'a JointLimits<5>,
    /// For the move out of the stow pose.
    pub air: &'a JointLimits<5>,
    /// For the move back to it (no painting follows, so it is never
    /// slowed by the verification).
    pub back: &'a JointLimits<5>,
    /// The joins slowed, each at its share of the accelerations
    /// (`chain::join_share`, `join_limits`).
    pub joins: &'a [basr_job::JoinPace],
    /// Fly out of stow into the first rung at speed (else rest at the lead).
    pub fly_in: bool,
    /// Share of the limits the jerk-limited moves hold back
    /// (`tuning::Joins::join_margin`).
    pub join_margin: f64,
}

/// `pieces`: the move out of stow, segment 0, join 0, segment 1, …, the
/// move back to stow (segment k is piece 1 + 2k); `ranges[k]`: the first
/// and last point of segment k in `Chain::points`.
pub struct Flight {
    pub ranges: Vec<(usize, usize)>,
    pub pieces: Vec<Trajectory<5>>,
}

/// Fly the station's chained path `ch` through `runs` (see the module docs).
pub fn fly(
    robot: &AnyRobot,
    runs: &[Run],
    ch: &Chain,
    lim: &Limits,
    options: &PathOptions,
) -> Result<Flight, CompileError> {
    let err = |what: String| CompileError::Timing(what);
    let n = ch.points.len();
    let range: timing::join::Ranges<5> = {
        let l = robot.limits();
        std::array::from_fn(|j| (l[j].min, l[j].max))
    };
    // The rungs the station's painting starts and ends at.
    let (r0, rl) = (0, runs.len() - 1);
    let head = ch.spans[r0].first_point + runs[r0].paint_first - ch.spans[r0].lo;
    let tail = ch.spans[rl].first_point + runs[rl].paint_last - ch.spans[rl].lo;
    let (mut fly_in, mut fly_out) = (lim.fly_in, true);
    // (seam, from point, to point)
    let mut cuts: Vec<(usize, usize, usize)> = ch
        .flown
        .iter()
        .enumerate()
        .filter_map(|(i, f)| f.map(|(a, b)| (i, a, b)))
        .collect();
    let rest = Kinematic {
        q: lim.home,
        qd: [0.0; 5],
        qdd: [0.0; 5],
    };
    'retry: loop {
        let (first, last) = (
            if fly_in { head } else { 0 },
            if fly_out { tail } else { n - 1 },
        );
        // Every segment keeps at least two points.
        let mut kept: Vec<(usize, usize, usize)> = Vec::with_capacity(cuts.len());
        let mut start = first;
        for &c in &cuts {
            if c.1 > start && c.2 < last {
                kept.push(c);
                start = c.2;
            }
        }
        if kept.last().map_or(first, |c| c.2) >= last && kept.pop().is_none() {
            // One run too short to cut at all.
            if !(fly_in || fly_out) {
                return Err(err("the station's path has a single point".into()));
            }
            (fly_in, fly_out) = (false, false);
            continue 'retry;
        }
        cuts = kept;
        let mut ranges = Vec::with_capacity(cuts.len() + 1);
        let mut start = first;
        for c in &cuts {
            ranges.push((start, c.1));
            start = c.2;
        }
        ranges.push((start, last));
        let speed = |i: usize| ch.points[i].max_speed_mps.unwrap_or(0.0);
        let nseg = ranges.len();
        let mut pieces: Vec<Trajectory<5>> = Vec::with_capacity(2 * nseg + 1);
        for (k, &(a, b)) in ranges.iter().enumerate() {
            let ends = [
                if k == 0 && !fly_in { 0.0 } else { speed(a) },
                if k + 1 == nseg && !fly_out {
                    0.0
                } else {
                    speed(b)
                },
            ];
            let seg = timing::time_path_between(&ch.points[a..=b], lim.path, options, ends)
                .map_err(|e| err(format!("station path: {e}")))?;
            let start = seg.path_end(false).expect("a path");
            if k == 0 {
                let into = if fly_in {
                    timing::join_move(&rest, &start, lim.air, &range, lim.join_margin).ok()
                } else {
                    timing::air_move(lim.home, start.q, lim.air, options.margin).ok()
                };
                match into {
                    Some(m) => pieces.push(m),
                    None if fly_in => {
                        fly_in = false;
                        continue 'retry;
                    }
                    None => {
                        return Err(err(format!("no air move to stroke {}", runs[0].stroke)));
                    }
                }
            } else {
                let c = cuts[k - 1];
                let share = super::chain::join_share(lim.joins, runs, c.0 + 1);
                let from = pieces
                    .last()
                    .and_then(|p| p.path_end(true))
                    .expect("a path");
                let join_lim = join_limits(lim.path, share);
                match timing::join_move(&from, &start, &join_lim, &range, lim.join_margin) {
                    Ok(j) => pieces.push(j),
                    Err(_) => {
                        cuts.remove(k - 1);
                        continue 'retry;
                    }
                }
            }
            pieces.push(seg);
        }
        let end = pieces
            .last()
            .and_then(|p| p.path_end(true))
            .expect("a path");
        let back = if fly_out {
            timing::join_move(&end, &rest, lim.back, &range, lim.join_margin).ok()
        } else {
            timing::air_move(end.q, lim.home, lim.back, options.margin).ok()
        };
        match back {
            Some(m) => pieces.push(m),
            None if fly_out => {
                fly_out = false;
                continue 'retry;
            }
            None => return Err(err("no air move back to the stow pose".into())),
        }
        return Ok(Flight { ranges, pieces });
    }
}

/// The time law's limits slowed to `share` of the accelerations and
/// share^1.5 of the jerks (as a move stretched in time by 1/√share); the
/// speeds stay (the arm falls behind on the changes of speed at the
/// stroke's first rungs, and the painting path it meets runs at full pace).
fn join_limits(limits: &JointLimits<5>, share: f64) -> JointLimits<5> {
    JointLimits {
        vel: limits.vel,
        acc: limits.acc.map(|v| v * share),
        jerk: limits.jerk.map(|v| v * share.powf(1.5)),
    }
}

#[cfg(test)]
mod tests {
    use crate::placed::PlacedStrokes;
    use crate::request::CompileRequest;
    use crate::trajectory::{self, timing_limits, Pace, TimeLaw};
    use crate::tuning::Tuning;
    use crate::{inputs, joints, passes, request, rungs, stations, tours};
    use basr_shape::layout::{self, Marking};

    /// STOP at defaults through the stages up to the timed trajectory.
    fn stop_timed() -> (trajectory::TimedTrajectory, basr_robot::AnyRobot, f64) {
        let req = CompileRequest::message("STOP");
        let inputs::Inputs { robot, font } = inputs::read(&req).unwrap();
        let marking = Marking::from_message("STOP", &req.overrides).unwrap();
        let laid = layout::lay_marking(&marking, &font, false).unwrap();
        let strokes = PlacedStrokes::from_laid(&laid);
        let rungs = rungs::rungs(
            &strokes,
            req.rung_spacing_m,
            Some(&passes::turn_budget(&robot, &req.tuning)),
        );
        let (tilt, _) = request::tilt_for(req.tilt, &robot);
        let passes = passes::passes(&strokes, &rungs, &robot, tilt.method(), &req.tuning).unwrap();
        let plan =
            stations::for_passes(&passes, laid.lane_width_m, req.reach_margin_m, &robot).unwrap();
        let tours = tours::tours(&passes, &plan, &robot, &[], 0.0);
        let paths =
            joints::joint_paths(&strokes, &passes, &plan, &tours, &robot, &req.tuning.joins)
                .unwrap();
        let law = TimeLaw {
            period_s: req.period_s,
            gun_lead_s: req.gun_lead_s,
            gun_lag_s: req.gun_lag_s,
            pace: Pace::FULL,
            joins: req.tuning.joins,
        };
        let timed = trajectory::time_law(&strokes, &plan, &paths, &robot, &law).unwrap();
        (timed, robot, req.period_s)
    }

    /// Every air move of STOP (out of stow, each join between strokes, back
    /// to stow) is jerk-limited on every joint: the third differences of
    /// its samples stay within the joint's jerk limit.
    #[test]
    fn every_join_is_jerk_limited() {
        let (timed, robot, period) = stop_timed();
        let jerk = timing_limits(&robot, 1.0, Tuning::DEFAULT.joins.jerk_per_acc).jerk;
        let samples = &timed.stations[0];
        let mut runs_seen = vec![];
        let mut windows = 0;
        let mut worst: f64 = 0.0;
        for w in samples.windows(4) {
            if let Some(r) = w[0].run {
                if runs_seen.last() != Some(&r) {
                    runs_seen.push(r);
                }
            }
            if w.iter().any(|t| t.run.is_some()) {
                continue;
            }
            windows += 1;
            for (j, &limit) in jerk.iter().enumerate() {
                let d3 =
                    (w[3].q[j] - 3.0 * w[2].q[j] + 3.0 * w[1].q[j] - w[0].q[j]) / period.powi(3);
                worst = worst.max(d3.abs() / limit);
                assert!(
                    d3.abs() <= limit * (1.0 + 1e-6),
                    "joint {j}: third difference {d3} over the jerk limit {limit}"
                );
            }
        }
        // Every stroke's run is entered by a join: they are all flown, in order.
        assert_eq!(runs_seen.len(), 16, "{runs_seen:?}");
        // The joins and stow moves are about 20 s of STOP's 145 s: some 600
        // windows of the 32 ms period are checked, and the limit is used,
        // not just respected.
        assert!(windows > 500, "{windows} of {} samples", samples.len());
        assert!(worst > 0.5, "{worst}");
    }
}
