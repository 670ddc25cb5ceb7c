//! A station's flight: its chained path (`chain`) cut at the flown joins
//! into painting segments, each timed by the time law between the painting
//! speeds at its ends, with a jerk-limited state-to-state move (`timing::join`)
//! from the stow pose into the first stroke's first rung, between each two
//! segments, and from the last stroke's last rung back to stow. Every air
//! move is thus jerk-limited on every joint; a seam whose move cannot be
//! found stays in the path as `chain` designed it (flown under the
//! acceleration limits), and a station end without one keeps the lead and
//! a rest-to-rest air move.

use crate::robot::AnyRobot;

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
    /// (stroke entered, share): joins into those strokes at that share of
    /// the accelerations (`join_limits`).
    pub joins: &'a [(usize, f64)],
    /// Fly out of stow into the first rung at speed (else rest at the lead).
    pub fly_in: bool,
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
        if kept.last().map_or(first, |c| c.2) >= last {
            if kept.pop().is_none() {
                // One run too short to cut at all.
                if !(fly_in || fly_out) {
                    return Err(err("the station's path has a single point".into()));
                }
                (fly_in, fly_out) = (false, false);
                continue 'retry;
            }
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
                if k + 1 == nseg && !fly_out { 0.0 } else { speed(b) },
            ];
            let seg = timing::time_path_between(&ch.points[a..=b], lim.path, options, ends)
                .map_err(|e| err(format!("station path: {e}")))?;
            let start = seg.path_end(false).expect("a path");
            if k == 0 {
                let into = if fly_in {
                    timing::join_move(&rest, &start, lim.air, &range, options.margin).ok()
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
                let share = lim
                    .joins
                    .iter()
                    .find(|(st, _)| *st == runs[c.0 + 1].stroke)
                    .map_or(1.0, |&(_, f)| f);
                let from = pieces.last().and_then(|p| p.path_end(true)).expect("a path");
                let join_lim = join_limits(lim.path, share);
                match timing::join_move(&from, &start, &join_lim, &range, options.margin) {
                    Ok(j) => pieces.push(j),
                    Err(_) => {
                        cuts.remove(k - 1);
                        continue 'retry;
                    }
                }
            }
            pieces.push(seg);
        }
        let end = pieces.last().and_then(|p| p.path_end(true)).expect("a path");
        let back = if fly_out {
            timing::join_move(&end, &rest, lim.back, &range, options.margin).ok()
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
        report(robot, runs, ch, &cuts, &ranges, &pieces);
        return Ok(Flight { ranges, pieces });
    }
}

/// The time law's limits slowed to `share` of the accelerations: time
/// stretched by 1/√share, so speeds scale by √share and jerks by share^1.5.
fn join_limits(limits: &JointLimits<5>, share: f64) -> JointLimits<5> {
    JointLimits {
        vel: limits.vel.map(|v| v * share.sqrt()),
        acc: limits.acc.map(|v| v * share),
        jerk: limits.jerk.map(|v| v * share.powf(1.5)),
    }
}

fn report(
    robot: &AnyRobot,
    runs: &[Run],
    ch: &Chain,
    cuts: &[(usize, usize, usize)],
    ranges: &[(usize, usize)],
    pieces: &[Trajectory<5>],
) {
    if std::env::var_os("BASR_JOIN_REPORT").is_none() {
        return;
    }
    eprintln!(
        "stow out {:.3} s ({}), back {:.3} s ({})",
        pieces[0].duration_s(),
        pieces[0].is_join(),
        pieces[pieces.len() - 1].duration_s(),
        pieces[pieces.len() - 1].is_join()
    );
    for (k, p) in pieces[1..pieces.len() - 1].iter().enumerate() {
        if k % 2 == 1 {
            let c = cuts[k / 2];
            let (a, b) = (ch.points[c.1].q, ch.points[c.2].q);
            let (pa, pb) = (robot.fk(&a), robot.fk(&b));
            let d = (pb.x_m - pa.x_m).hypot(pb.y_m - pa.y_m);
            let dq: Vec<String> = (0..5).map(|j| format!("{:+.3}", b[j] - a[j])).collect();
            eprintln!(
                "join {:>2} -> stroke {:>2}: {:.3} s, road {:.3} m, dq {:?}",
                c.0,
                runs[c.0 + 1].stroke,
                p.duration_s(),
                d,
                dq
            );
        } else {
            let r = ranges[k / 2];
            eprintln!(
                "segment {:>2}: {:.3} s over {:.3} m",
                k / 2,
                p.duration_s(),
                ch.points[r.1].s_m - ch.points[r.0].s_m
            );
        }
    }
}
