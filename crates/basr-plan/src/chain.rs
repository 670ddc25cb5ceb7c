//! The chained path of a station: every run's knots in painting order,
//! joined by blends in joint space, as one path for the time law, so the
//! nozzle flies out of one stroke's run-out into the next stroke's run-up
//! without stopping unless a limit forces it.
//!
//! A blend from run a's last knot to run b's first is a cubic Hermite curve
//! in joint space whose end tangents are the runs' own joint rates per
//! metre (so the path is C¹ where the blend meets a run). Its path
//! parameter advances by the nozzle's road travel, or by the slowest
//! joint's travel time at `tuning::Joins::blend_speed_mps` where the joints move more than
//! the nozzle (a fan turn on the spot). A blend whose curve would leave a
//! joint's range is flattened (tangents scaled down, at worst to zero: the
//! arm then stops at the seam, and the stop is reported with its reason).

use basr_job::JoinPace;
use basr_robot::AnyRobot;

use super::joints::Run;
use super::timing::sync::{min_time, synced, Ends};
use super::timing::{JointLimits, PathPoint};
use super::trajectory::{arc_lengths, Q};
use super::tuning::Joins;

/// Most waypoints per blend.
const BLEND_MAX_POINTS: usize = 400;
/// Tangent scales tried, largest first.
const TANGENT_SCALES: [f64; 4] = [1.0, 0.5, 0.25, 0.0];

/// Why the arm comes to rest at a seam.
#[derive(Clone, Debug, PartialEq)]
pub enum StopReason {
    /// A smooth blend would carry this joint (and every other moving one)
    /// past its range.
    JointRange { joint: &'static str },
}

/// A station's runs as one path.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    pub points: Vec<PathPoint<5>>,
    /// Per run: its knots `lo..=hi` on the path (the lead-in of the first
    /// run, the lead-out of the last; between runs a blend replaces them).
    pub spans: Vec<Span>,
    /// Per run: arc lengths of its knots from its own first knot.
    pub arcs: Vec<Vec<f64>>,
    /// Seams where the blend was flattened to rest: (run entered, why).
    pub stops: Vec<(usize, StopReason)>,
    /// Per seam (run i into run i + 1): the points of the rungs a flown
    /// join leaves and reaches, which the time law may replace by a
    /// jerk-limited join (its own waypoints between them dropped); None
    /// for a blend or a stroke carried straight on.
    pub flown: Vec<Option<(usize, usize)>>,
}

/// Where a run's knots sit on the chained path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    pub lo: usize,
    pub hi: usize,
    /// Index of knot `lo` in `Chain::points`.
    pub first_point: usize,
    /// Path parameter of knot i is `offset + arcs[i]`.
    pub offset: f64,
}

impl Chain {
    /// The run whose knots span path parameter `s`, and `s` on its own arcs.
    pub fn run_at(&self, s: f64) -> (Option<usize>, f64) {
        for (ri, sp) in self.spans.iter().enumerate() {
            let (a, b) = (
                sp.offset + self.arcs[ri][sp.lo],
                sp.offset + self.arcs[ri][sp.hi],
            );
            if s >= a - 1e-12 && s <= b + 1e-12 {
                return (
                    Some(ri),
                    (s - sp.offset).clamp(self.arcs[ri][sp.lo], self.arcs[ri][sp.hi]),
                );
            }
        }
        (None, 0.0)
    }

    /// The run and knot of a waypoint (a blend's waypoints belong to the
    /// run they lead into).
    pub fn knot_of(&self, waypoint: usize) -> (usize, usize) {
        let ri = self
            .spans
            .iter()
            .rposition(|sp| sp.first_point <= waypoint)
            .unwrap_or(0);
        let sp = self.spans[ri];
        (
            ri,
            (sp.lo + waypoint.saturating_sub(sp.first_point)).min(sp.hi),
        )
    }
}

/// Chain `runs` (at least one) into one path: flown joins (`flown`)
/// from each stroke's last rung straight into the next one's first where
/// they stay in the joints' ranges, else the leads and a blend.
///
/// `slow_joins`: the joins into those strokes, or into one pass of one
/// (`join_share`), are designed to their share of the accelerations (and
/// its square root of the speeds) and flown no faster, where the
/// verification found the arm arriving behind.
pub fn chain(
    robot: &AnyRobot,
    runs: &[Run],
    limits: &JointLimits<5>,
    slow_joins: &[JoinPace],
    joins: &Joins,
) -> Chain {
    let mut out = Chain {
        points: vec![],
        spans: vec![],
        arcs: vec![],
        stops: vec![],
        flown: vec![],
    };
    let arcs: Vec<Vec<f64>> = runs.iter().map(|r| arc_lengths(&r.knots)).collect();
    // flown[i]: the join from run i's last rung into run i + 1's first.
    let mut flown: Vec<Option<Blend>> = (1..runs.len())
        .map(|ri| {
            let share = join_share(slow_joins, runs, ri);
            let design = JointLimits {
                vel: limits.vel.map(|v| v * share.sqrt()),
                acc: limits.acc.map(|v| v * share),
                jerk: limits.jerk,
            };
            let joined = (&runs[ri - 1], &arcs[ri - 1][..], &runs[ri], &arcs[ri][..]);
            flown(robot, &design, joined, share < 1.0, joins)
        })
        .collect();
    // Leads where the stroke needs a run-up; none where the join flies in
    // at speed or the stroke carries on from the last one (same place, same
    // heading: the nozzle flies straight on from paint into paint).
    let direct: Vec<bool> = (1..runs.len())
        .map(|ri| flown[ri - 1].is_some() || continues(&runs[ri - 1], &runs[ri], joins))
        .collect();
    // dq/ds at the rungs a flown join leaves from and arrives at, so the
    // time law's spline meets the join with the join's own tangents.
    let mut rate_out: Vec<Option<Q>> = vec![None; runs.len()];
    let mut rate_in: Vec<Option<Q>> = vec![None; runs.len()];
    for (i, b) in flown.iter().enumerate() {
        if let Some((ra, rb)) = b.as_ref().and_then(|b| b.seam_rates) {
            rate_out[i] = Some(ra);
            rate_in[i + 1] = Some(rb);
        }
    }
    let mut s = 0.0;
    for (ri, run) in runs.iter().enumerate() {
        let arcs = arcs[ri].clone();
        let lo = if ri > 0 && direct[ri - 1] {
            run.paint_first
        } else {
            0
        };
        let hi = if ri + 1 < runs.len() && direct[ri] {
            run.paint_last
        } else {
            run.knots.len() - 1
        };
        if ri > 0 {
            let prev = &runs[ri - 1];
            let from = out.spans[ri - 1].hi;
            let from_point = out.points.len() - 1;
            let blend = match flown[ri - 1].take() {
                Some(b) => {
                    let to_point = from_point + 1 + b.inner.len();
                    out.flown.push(Some((from_point, to_point)));
                    b
                }
                None => {
                    out.flown.push(None);
                    let (blend, stop) =
                        blend(robot, prev, &out.arcs[ri - 1], from, run, &arcs, lo, joins);
                    if let Some(why) = stop {
                        out.stops.push((ri, why));
                    }
                    blend
                }
            };
            for (ds, q, cap, dq_ds) in blend.inner {
                out.points.push(PathPoint {
                    s_m: s + ds,
                    q,
                    max_speed_mps: cap,
                    cap_only: true,
                    dq_ds,
                });
            }
            s += blend.length;
        }
        let offset = s - arcs[lo];
        out.spans.push(Span {
            lo,
            hi,
            first_point: out.points.len(),
            offset,
        });
        for (i, (k, j)) in run
            .knots
            .iter()
            .zip(&run.joints)
            .enumerate()
            .take(hi + 1)
            .skip(lo)
        {
            // The station's first lead-in (where the move out of stow
            // rests at it) runs up to the first rung's painting speed and
            // no faster: as fast as the joints allow, it overshot that
            // speed and braked into the rung, and the arm answered the
            // braking at the gun's opening (STOP's first stroke: 4.50 →
            // 3.90 mm on the description, up to 12.5 → 10.1 mm on plants
            // with a strong pump). Every other lead stays as fast as the
            // joints allow: capped too, STOP at full reach needed a slower
            // path and lost its film (docs/planner.md "The first run-up").
            let painting = (run.paint_first..=run.paint_last).contains(&i);
            let cap = if painting {
                Some(k.speed_mps)
            } else if ri == 0 && i < run.paint_first {
                Some(run.knots[run.paint_first].speed_mps)
            } else {
                None
            };
            out.points.push(PathPoint {
                s_m: offset + arcs[i],
                q: *j,
                max_speed_mps: cap,
                cap_only: !painting,
                dq_ds: match i {
                    _ if i == lo => rate_in[ri],
                    _ if i == hi => rate_out[ri],
                    _ => None,
                },
            });
        }
        s = offset + arcs[hi];
        out.arcs.push(arcs);
    }
    out
}

/// Shortest flown join (m of s); below it the runs meet as they are.
const FLOWN_MIN_M: f64 = 1e-3;

/// One end of a join: a run's knots, joints and arc lengths, and the rung
/// the join leaves from or arrives at.
#[derive(Clone, Copy)]
pub struct Side<'a> {
    knots: &'a [super::knots::Knot],
    joints: &'a [Q],
    arcs: &'a [f64],
    at: usize,
    leaving: bool,
}

impl<'a> Side<'a> {
    /// Rung `at` of a run, the join `leaving` it (else arriving at it).
    pub fn new(
        (knots, joints, arcs): (&'a [super::knots::Knot], &'a [Q], &'a [f64]),
        at: usize,
        leaving: bool,
    ) -> Self {
        Side {
            knots,
            joints,
            arcs,
            at,
            leaving,
        }
    }

    /// Painting speed and joints' rates (per s) at the rung.
    fn state(&self) -> Option<(f64, Q, Q)> {
        let v = self.knots.get(self.at)?.speed_mps;
        let rate = end_rate(self.joints, self.arcs, self.at, self.leaving);
        (v > 0.0).then(|| (v, self.joints[self.at], rate.map(|r| r * v)))
    }
}

/// The end states of the join from `a` to `b` and its design limits, with
/// the painting speeds at both rungs.
fn seam_ends(
    limits: &JointLimits<5>,
    a: Side,
    b: Side,
    joins: &Joins,
) -> Option<(Ends<5>, f64, f64)> {
    let (design, arrival) = (joins.design_share, joins.arrival_share);
    let ((va, p0, v0), (vb, p1, v1)) = (a.state()?, b.state()?);
    let ends = Ends {
        p0,
        v0,
        p1,
        v1,
        vel: limits.vel.map(|v| v * design),
        acc: limits.acc.map(|v| v * design),
        acc_end: limits.acc.map(|v| v * design * arrival),
    };
    Some((ends, va, vb))
}

/// Duration (s) of the join flown from `a` into `b` as `chain` designs it
/// at full pace, estimated for ordering strokes; None where none is found.
pub fn join_time(limits: &JointLimits<5>, a: Side, b: Side, joins: &Joins) -> Option<f64> {
    let (e, _, _) = seam_ends(limits, a, b, joins)?;
    // The slowest joint alone (the synchronised move can take a little
    // longer where another joint cannot stretch to it).
    slowest_joint(&e)
}

/// The least time the slowest joint alone takes between `e`'s ends at its
/// limits; None where it is not finite.
fn slowest_joint(e: &Ends<5>) -> Option<f64> {
    Some(
        (0..5)
            .map(|j| {
                let acc = [e.acc[j], e.acc_end[j]];
                min_time((e.p0[j], e.v0[j]), (e.p1[j], e.v1[j]), e.vel[j], acc)
            })
            .fold(0.0, f64::max),
    )
    .filter(|t| t.is_finite())
}

/// The share of the accelerations (1 where not slowed) the join into run
/// `ri` of a station's `runs` is flown at: the least of the slowed joins
/// that name it, by its stroke or by its stroke and its pass (how many
/// runs of that stroke come before it).
pub fn join_share(slow_joins: &[JoinPace], runs: &[Run], ri: usize) -> f64 {
    let stroke = runs[ri].stroke;
    let pass = runs[..ri].iter().filter(|r| r.stroke == stroke).count();
    slow_joins
        .iter()
        .filter(|j| j.slows(stroke, pass))
        .map(|j| j.share)
        .fold(1.0, f64::min)
}

/// Least time (s) any move takes from `a` to `b`, each a rung's state at
/// its painting speed or, where `None`, `rest` at rest: the slowest joint
/// alone at `limits` in full, with no jerk limit, so no move the arm can
/// fly between them is shorter (`joints::air_floor`). None where a rung
/// has no painting speed.
pub fn least_time(
    limits: &JointLimits<5>,
    a: Option<Side>,
    b: Option<Side>,
    rest: &Q,
) -> Option<f64> {
    let state = |s: Option<Side>| match s {
        Some(s) => s.state().map(|(_, p, v)| (p, v)),
        None => Some((*rest, [0.0; 5])),
    };
    let ((p0, v0), (p1, v1)) = (state(a)?, state(b)?);
    slowest_joint(&Ends {
        p0,
        v0,
        p1,
        v1,
        vel: limits.vel,
        acc: limits.acc,
        acc_end: limits.acc,
    })
}

/// The join flown from run a's last rung at its painting speed into run
/// b's first at its own: every joint from its rate there to its rate at
/// the other end in the same time, the shortest the slowest joint allows
/// (`timing::sync`). Its path parameter runs at the nozzle's speed at both
/// ends and changes at a constant rate between, so the path is C¹ at the
/// rungs and the time law can fly it at that speed or faster. None where it
/// would leave a joint's range.
/// With `capped`, no waypoint of it may be flown faster than designed.
fn flown(
    robot: &AnyRobot,
    limits: &JointLimits<5>,
    (a, arcs_a, b, arcs_b): (&Run, &[f64], &Run, &[f64]),
    capped: bool,
    joins: &Joins,
) -> Option<Blend> {
    let (ends, va, vb) = seam_ends(
        limits,
        Side::new((&a.knots, &a.joints, arcs_a), a.paint_last, true),
        Side::new((&b.knots, &b.joints, arcs_b), b.paint_first, false),
        joins,
    )?;
    let (ra, rb): (Q, Q) = (
        std::array::from_fn(|j| ends.v0[j] / va),
        std::array::from_fn(|j| ends.v1[j] / vb),
    );
    let m = synced(&ends)?;
    let t_end = m.duration_s;
    let length = 0.5 * (va + vb) * t_end;
    if length < FLOWN_MIN_M {
        return None;
    }
    let times = m.sample_times(joins.flown_step_s, BLEND_MAX_POINTS);
    let mut inner = Vec::with_capacity(times.len());
    for &t in &times[1..times.len().saturating_sub(1)] {
        let (q, qd) = m.at(t);
        let inside = robot
            .limits()
            .iter()
            .zip(q)
            .all(|(l, v)| v >= l.min && v <= l.max);
        if !inside {
            return None;
        }
        let rate = va + (vb - va) * t / t_end;
        let cap = capped.then_some(rate);
        let dq_ds = qd.map(|v| v / rate);
        inner.push((
            va * t + (vb - va) * t * t / (2.0 * t_end),
            q,
            cap,
            Some(dq_ds),
        ));
    }
    Some(Blend {
        inner,
        length,
        seam_rates: Some((ra, rb)),
    })
}

/// Whether run b starts where run a ends, heading the same way (within
/// `tuning::Joins::continue_gap_m` and `continue_turn_rad`).
fn continues(a: &Run, b: &Run, joins: &Joins) -> bool {
    let (ka, kb) = (&a.knots, &b.knots);
    let (pa, pb) = (a.paint_last, b.paint_first);
    if pa == 0 || pb + 1 >= kb.len() {
        return false;
    }
    let gap = (kb[pb].tip - ka[pa].tip).hypot();
    let da = ka[pa].tip - ka[pa - 1].tip;
    let db = kb[pb + 1].tip - kb[pb].tip;
    let turn = (da.cross(db)).atan2(da.dot(db)).abs();
    gap <= joins.continue_gap_m && turn <= joins.continue_turn_rad
}

struct Blend {
    /// Waypoints strictly between the two runs: (s from the seam's start,
    /// q, the fastest ds/dt allowed there if any, and dq/ds there if known).
    inner: Vec<(f64, Q, Option<f64>, Option<Q>)>,
    /// A flown join's dq/ds at the rung it leaves and the one it reaches.
    seam_rates: Option<(Q, Q)>,
    /// s from run a's last knot to run b's first.
    length: f64,
}

/// Joint rate per metre of s at knot `at` of a run, leaving it (`out`) or
/// arriving (one-sided difference).
fn end_rate(joints: &[Q], arcs: &[f64], at: usize, out: bool) -> Q {
    let n = joints.len();
    if n < 2 {
        return [0.0; 5];
    }
    let (i, k) = if out {
        (at.saturating_sub(1), at.max(1))
    } else {
        (at.min(n - 2), at.min(n - 2) + 1)
    };
    let (a, b) = (joints[i], joints[k]);
    let ds = arcs[k] - arcs[i];
    std::array::from_fn(|j| (b[j] - a[j]) / ds)
}

/// The blend from knot `from` of run a to knot `to` of run b.
#[allow(clippy::too_many_arguments)]
fn blend(
    robot: &AnyRobot,
    a: &Run,
    arcs_a: &[f64],
    from: usize,
    b: &Run,
    arcs_b: &[f64],
    to: usize,
    joins: &Joins,
) -> (Blend, Option<StopReason>) {
    let qa = a.joints[from];
    let qb = b.joints[to];
    let ta = end_rate(&a.joints, arcs_a, from, true);
    let tb = end_rate(&b.joints, arcs_b, to, false);
    let pa = robot.fk(&qa);
    let pb = robot.fk(&qb);
    let road = (pb.x_m - pa.x_m).hypot(pb.y_m - pa.y_m);
    let slowest = robot
        .limits()
        .iter()
        .enumerate()
        .map(|(j, l)| (qb[j] - qa[j]).abs() / l.max_vel)
        .fold(0.0, f64::max);
    let length = road
        .max(slowest * joins.blend_speed_mps)
        .max(joins.blend_min_m);
    let m = ((length / joins.blend_step_m).ceil() as usize).clamp(2, BLEND_MAX_POINTS);
    // Each joint's curve is its own cubic: a joint whose curve would leave
    // its range has its end tangents scaled down (at worst to zero, where it
    // comes to rest at the seam while the others fly on).
    // A tangent longer than the joint's own chord would carry it past the
    // blend's end and back (a loop in that joint that costs time): each end
    // tangent is cut to the chord, so a joint that keeps its direction flies
    // on and one that must turn back slows to rest near the seam.
    let cap = |t: f64, chord: f64| {
        let full = (length * t).abs();
        if full > chord {
            t * chord / full
        } else {
            t
        }
    };
    let (ta, tb): (Q, Q) = (
        std::array::from_fn(|j| cap(ta[j], (qb[j] - qa[j]).abs())),
        std::array::from_fn(|j| cap(tb[j], (qb[j] - qa[j]).abs())),
    );
    let hermite = |j: usize, u: f64, scale: f64| {
        let (u2, u3) = (u * u, u * u * u);
        let (h00, h10) = (2.0 * u3 - 3.0 * u2 + 1.0, u3 - 2.0 * u2 + u);
        let (h01, h11) = (-2.0 * u3 + 3.0 * u2, u3 - u2);
        h00 * qa[j] + h10 * length * scale * ta[j] + h01 * qb[j] + h11 * length * scale * tb[j]
    };
    let mut scales = [1.0; 5];
    let mut resting = vec![];
    for (j, (name, l)) in robot
        .joint_names()
        .into_iter()
        .zip(robot.limits())
        .enumerate()
    {
        let fits = |scale: f64| {
            (1..m).all(|k| {
                let q = hermite(j, k as f64 / m as f64, scale);
                q >= l.min && q <= l.max
            })
        };
        scales[j] = TANGENT_SCALES
            .into_iter()
            .find(|&sc| fits(sc))
            .unwrap_or(0.0);
        if scales[j] == 0.0 && (ta[j] != 0.0 || tb[j] != 0.0) {
            resting.push(name);
        }
    }
    let inner = (1..m)
        .map(|k| {
            let u = k as f64 / m as f64;
            (
                u * length,
                std::array::from_fn(|j| hermite(j, u, scales[j])),
                None,
                None,
            )
        })
        .collect();
    // The nozzle stops only where every moving joint rests at the seam.
    let moving = (0..5).filter(|&j| ta[j] != 0.0 || tb[j] != 0.0).count();
    let stop = (moving > 0 && resting.len() == moving)
        .then(|| StopReason::JointRange { joint: resting[0] });
    (
        Blend {
            inner,
            length,
            seam_rates: None,
        },
        stop,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A slowed join names a stroke (every join into it) or one pass of
    /// it (counted in the station's painting order); a join named twice
    /// takes the slower share.
    #[test]
    fn a_slowed_join_is_the_pass_it_names() {
        let run = |stroke| Run {
            stroke,
            knots: vec![],
            joints: vec![],
            paint_first: 0,
            paint_last: 0,
        };
        // stroke 3's passes 0, 1, 2 are runs 0, 2, 3
        let runs = [run(3), run(5), run(3), run(3), run(7)];
        let pace = |stroke, share, pass| JoinPace {
            stroke,
            share,
            pass,
        };
        let slow = [
            pace(3, 0.6, Some(1)),
            pace(5, 0.36, None),
            pace(7, 0.6, None),
            pace(7, 0.36, Some(0)),
        ];
        let shares: Vec<f64> = (0..runs.len())
            .map(|ri| join_share(&slow, &runs, ri))
            .collect();
        assert_eq!(shares, [1.0, 0.36, 0.6, 1.0, 0.36]);
        assert_eq!(join_share(&[], &runs, 2), 1.0);
        // a stroke-wide entry slows every pass of it
        let all = [pace(3, 0.6, None)];
        let shares: Vec<f64> = (0..runs.len())
            .map(|ri| join_share(&all, &runs, ri))
            .collect();
        assert_eq!(shares, [0.6, 1.0, 0.6, 0.6, 1.0]);
    }
}
