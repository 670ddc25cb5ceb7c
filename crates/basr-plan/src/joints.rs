//! Joint paths: every knot of every tour solved for the arm's joints (IK on
//! one fan branch per pass), with the leads that bring the nozzle up to
//! speed.

use std::f64::consts::FRAC_PI_2;

use crate::knots::Knot;
use basr_job::Station;
use basr_robot::{AnyRobot, NozzlePose, Q};

use super::chain::Side;
use super::error::CompileError;
use super::leads::with_leads;
use super::passes::Passes;
use super::placed::PlacedStrokes;
use super::stations::StationPlan;
use super::stow::stow_joints;
use super::tours::Tours;
use super::tuning::Joins;

/// A pass as the arm runs it: joints at every knot, in painting order.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// Index into the placed strokes.
    pub stroke: usize,
    /// Knots including the lead-in and lead-out.
    pub knots: Vec<Knot>,
    /// The robot kind's joints (`AnyRobot::joint_names` order) at each knot.
    pub joints: Vec<Q>,
    /// Indices of the first and last painting knot in `knots`.
    pub paint_first: usize,
    pub paint_last: usize,
}

/// Every station's runs, in painting order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct JointPaths {
    pub stations: Vec<Vec<Run>>,
}

/// A pass's knots with leads and the joint solutions of each fan branch
/// and yaw turn that follows the whole pass.
struct Candidates {
    /// 2 × the pass's place in the tour + reversed: the join costs' key.
    id: usize,
    stroke: usize,
    knots: Vec<Knot>,
    paint_first: usize,
    paint_last: usize,
    /// (joint travel inside the pass, joints at every knot) per branch.
    branches: Vec<(f64, Vec<Q>)>,
    arcs: Vec<f64>,
}

/// Flown join durations between passes' branches, each found once.
struct JoinCosts {
    limits: super::timing::JointLimits<5>,
    joins: Joins,
    /// Candidates' ids (0..ids) and branches (0..branches) of the station.
    ids: usize,
    branches: usize,
    known: std::cell::RefCell<Known>,
}

/// Join durations found so far, keyed by (from id, its branch, to id, its
/// branch): a table indexed by the key, NaN until found, where it is
/// small enough (the station's order search makes hundreds of thousands
/// of look-ups on a station of STOP, and spent most of its time hashing
/// them), else a map holding only what was found.
enum Known {
    Table(Vec<f64>),
    Map(std::collections::HashMap<usize, f64>),
}

/// Largest table of join durations (entries): 8 MB, a station of about
/// 128 passes with four branches each; a larger station keeps a map.
const JOIN_TABLE_MAX: usize = 1 << 20;

impl JoinCosts {
    /// The costs between the candidates of `ways`.
    fn new(robot: &AnyRobot, joins: &Joins, ways: &[[Option<Candidates>; 2]]) -> Self {
        Self::with_table_max(robot, joins, ways, JOIN_TABLE_MAX)
    }

    /// [`JoinCosts::new`] with a table of at most `table_max` entries.
    fn with_table_max(
        robot: &AnyRobot,
        joins: &Joins,
        ways: &[[Option<Candidates>; 2]],
        table_max: usize,
    ) -> Self {
        let ids = 2 * ways.len();
        let branches = ways
            .iter()
            .flatten()
            .flatten()
            .map(|c| c.branches.len())
            .max()
            .unwrap_or(0);
        let side = ids * branches;
        JoinCosts {
            limits: super::trajectory::timing_limits(robot, 1.0, joins.jerk_per_acc),
            joins: *joins,
            ids,
            branches,
            known: std::cell::RefCell::new(match side.checked_mul(side) {
                Some(n) if n <= table_max => Known::Table(vec![f64::NAN; n]),
                _ => Known::Map(Default::default()),
            }),
        }
    }

    /// The index of (from id, its branch, to id, its branch) in the table:
    /// one of its `(ids · branches)²` entries, each once.
    fn key(&self, a: usize, ba: usize, b: usize, bb: usize) -> usize {
        debug_assert!(a < self.ids && b < self.ids && ba < self.branches && bb < self.branches);
        let side = self.ids * self.branches;
        (a * self.branches + ba) * side + b * self.branches + bb
    }

    /// The join from pass a (branch ba) into pass b (branch bb): the flown
    /// join's duration, or the rest-to-rest joint travel between their
    /// leads where none is found.
    fn join(&self, robot: &AnyRobot, a: &Candidates, ba: usize, b: &Candidates, bb: usize) -> f64 {
        let key = self.key(a.id, ba, b.id, bb);
        let found = match &*self.known.borrow() {
            Known::Table(t) => Some(t[key]).filter(|t| !t.is_nan()),
            Known::Map(m) => m.get(&key).copied(),
        };
        if let Some(t) = found {
            return t;
        }
        let (ja, jb) = (&a.branches[ba].1, &b.branches[bb].1);
        let t = super::chain::join_time(
            &self.limits,
            Side::new((&a.knots, ja, &a.arcs), a.paint_last, true),
            Side::new((&b.knots, jb, &b.arcs), b.paint_first, false),
            &self.joins,
        )
        .unwrap_or_else(|| travel(robot, &ja[ja.len() - 1], &jb[0]));
        match &mut *self.known.borrow_mut() {
            Known::Table(table) => table[key] = t,
            Known::Map(m) => {
                m.insert(key, t);
            }
        }
        t
    }
}

/// Solve every pass of every station for the joints, both ways round, and
/// choose the painting order, each pass's direction and its fan branch
/// (ψ, β) / (ψ+π, −β) and yaw turn over the whole station: the tour's order
/// is the starting point, and moves that reverse a pass, move it or reverse
/// a run of passes are kept while they shorten the station's joint-time
/// estimate, each priced with the shortest path over the branches
/// (`best_branches`, every joint counted); a tour `Tours::kept` is painted
/// as it is (where a pass reaches only the other way round, that way). A
/// pass out of reach either way is refused with the stroke, its item and
/// the place.
pub fn joint_paths(
    strokes: &PlacedStrokes,
    passes: &Passes,
    plan: &StationPlan,
    tours: &Tours,
    robot: &AnyRobot,
    joins: &Joins,
) -> Result<JointPaths, CompileError> {
    use rayon::prelude::*;
    let stow = stow_joints(robot);
    // Stations are independent, and so is each pass's solution: both are
    // solved in parallel; the results, and the first error, keep their
    // order whatever the core count.
    let n = plan.stations.len().min(tours.stations.len());
    let stations: Vec<Result<Vec<Run>, CompileError>> = tours.stations[..n]
        .par_iter()
        .enumerate()
        .map(|(si, tour)| {
            let kept = tours.kept.get(si).copied().unwrap_or(false);
            station_runs(strokes, passes, plan, robot, joins, &stow, si, tour, kept)
        })
        .collect();
    Ok(JointPaths {
        stations: stations.into_iter().collect::<Result<_, _>>()?,
    })
}

/// [`joint_paths`] of station `si` of `plan` (its `tour`, painted as it is
/// when `kept`): its passes solved both ways round, its order and
/// branches chosen.
#[allow(clippy::too_many_arguments)]
fn station_runs(
    strokes: &PlacedStrokes,
    passes: &Passes,
    plan: &StationPlan,
    robot: &AnyRobot,
    joins: &Joins,
    stow: &Q,
    si: usize,
    tour: &[super::order::Visit],
    kept: bool,
) -> Result<Vec<Run>, CompileError> {
    let ways = station_ways(strokes, passes, plan, robot, joins, si, tour)?;
    // The tour as (index into ways, reversed), each way one that exists.
    let mut seq: Vec<(usize, bool)> = tour
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let rev = if ways[k][v.reversed as usize].is_some() {
                v.reversed
            } else {
                !v.reversed
            };
            (k, rev)
        })
        .collect();
    let costs = JoinCosts::new(robot, joins, &ways);
    if !kept {
        improve(robot, stow, &ways, &mut seq, &costs);
    }
    let picked: Vec<&Candidates> = seq
        .iter()
        .filter_map(|&(k, r)| ways[k][r as usize].as_ref())
        .collect();
    let (_, choice) = best_branches(robot, stow, &picked, &costs);
    Ok(picked
        .into_iter()
        .zip(choice)
        .map(|(c, b)| Run {
            stroke: c.stroke,
            knots: c.knots.clone(),
            joints: c.branches[b].1.clone(),
            paint_first: c.paint_first,
            paint_last: c.paint_last,
        })
        .collect())
}

/// Every pass of station `si`'s `tour` solved both ways round (forward,
/// reversed), with the longest leads the arm reaches and every fan branch;
/// a way out of reach is None, a pass out of reach both ways an error.
fn station_ways(
    strokes: &PlacedStrokes,
    passes: &Passes,
    plan: &StationPlan,
    robot: &AnyRobot,
    joins: &Joins,
    si: usize,
    tour: &[super::order::Visit],
) -> Result<Vec<[Option<Candidates>; 2]>, CompileError> {
    use rayon::prelude::*;
    let at = Stop::new(si, &plan.stations[si], &plan.road, robot);
    // ways[k] = (forward, reversed) candidates of the tour's k-th pass.
    let ways: Vec<Result<[Option<Candidates>; 2], CompileError>> = tour
        .par_iter()
        .enumerate()
        .map(|(k, v)| {
            let pass = &passes.passes[v.item];
            let id = 2 * k;
            let fwd = candidates(robot, &at, &pass.knots, false, pass.stroke, joins)
                .map(|c| Candidates { id, ..c });
            let rev = candidates(robot, &at, &pass.knots, true, pass.stroke, joins)
                .map(|c| Candidates { id: id + 1, ..c });
            match (fwd, rev) {
                (Err((k, e)), Err(_)) => {
                    let tip = pass.knots[k.min(pass.knots.len() - 1)].tip;
                    Err(CompileError::Unreachable(format!(
                        "stroke {} ({}) cannot be painted from station {} at ({:.3}, {:.3}) \
                         m: {e}; use a smaller --letter-height or check the robot description",
                        pass.stroke,
                        strokes.owner(pass.stroke),
                        si + 1,
                        tip.x,
                        tip.y
                    )))
                }
                (f, r) => Ok([f.ok(), r.ok()]),
            }
        })
        .collect();
    ways.into_iter().collect()
}

/// Most passes a station may have for [`air_floor`] to search every
/// order: its table holds 2^n subsets × every way and branch of a pass.
pub const AIR_FLOOR_MAX_PASSES: usize = 16;

/// A station's least air time ([`air_floor`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AirFloor {
    /// Seconds no job of the station's passes flies its air moves in less.
    pub s: f64,
    /// Found over every order (the least such time); else a floor under
    /// it, the least assignment of a next pass to every pass.
    pub exact: bool,
}

/// The least air time (s) each station's passes could be painted in, in
/// any order, each either way round and on any fan branch: out of stow,
/// every join and back, each move no shorter than its slowest joint alone
/// takes at the robot's full speed and acceleration limits from one
/// rung's state at painting speed to the next (`chain::least_time`; no
/// jerk limit, no margin, no drive's speed cap). A station of up to
/// [`AIR_FLOOR_MAX_PASSES`] passes is searched over every order (a dynamic
/// program over the subsets of its passes): the least such time. A larger
/// one gets a floor under that: every pass (and the stow pose) given the
/// next it is cheapest to fly to such that each is flown into once (an
/// assignment, which may close in several loops; each pass's way and
/// branch chosen apart at its two ends). It measures how far a job's air
/// moves are from what the arm's limits allow (docs/planner.md, "How far
/// the air time is from its floor"); compile does not call it.
pub fn air_floor(
    strokes: &PlacedStrokes,
    passes: &Passes,
    plan: &StationPlan,
    tours: &Tours,
    robot: &AnyRobot,
    joins: &Joins,
) -> Result<Vec<AirFloor>, CompileError> {
    let stow = stow_joints(robot);
    let limits = full_limits(robot);
    let n = plan.stations.len().min(tours.stations.len());
    (0..n)
        .map(|si| {
            let ways = station_ways(strokes, passes, plan, robot, joins, si, &tours.stations[si])?;
            Ok(least_air(&ways, &limits, &stow, AIR_FLOOR_MAX_PASSES))
        })
        .collect()
}

/// The robot's own speed and acceleration limits in full (no drive's cap,
/// no jerk limit): what [`air_floor`] holds each move to.
fn full_limits(robot: &AnyRobot) -> super::timing::JointLimits<5> {
    let l = robot.limits();
    super::timing::JointLimits {
        vel: l.map(|l| l.max_vel),
        acc: l.map(|l| l.max_acc),
        jerk: [f64::INFINITY; 5],
    }
}

/// [`air_floor`] of one station's passes, searched over every order where
/// there are at most `max_exact` of them.
fn least_air(
    ways: &[[Option<Candidates>; 2]],
    limits: &super::timing::JointLimits<5>,
    stow: &Q,
    max_exact: usize,
) -> AirFloor {
    // nodes: (pass, its way and branch) with the rungs painting starts and
    // ends at
    let mut nodes: Vec<(usize, Side, Side)> = vec![];
    for (k, w) in ways.iter().enumerate() {
        for c in w.iter().flatten() {
            for (_, js) in &c.branches {
                let at = |i: usize, leaving: bool| Side::new((&c.knots, js, &c.arcs), i, leaving);
                nodes.push((k, at(c.paint_first, false), at(c.paint_last, true)));
            }
        }
    }
    let time = |a: Option<Side>, b: Option<Side>| {
        super::chain::least_time(limits, a, b, stow).unwrap_or(f64::INFINITY)
    };
    let m = nodes.len();
    let out: Vec<f64> = nodes.iter().map(|n| time(None, Some(n.1))).collect();
    let back: Vec<f64> = nodes.iter().map(|n| time(Some(n.2), None)).collect();
    let join: Vec<f64> = (0..m * m)
        .map(|i| time(Some(nodes[i / m].2), Some(nodes[i % m].1)))
        .collect();
    let passes = ways.len();
    if passes > max_exact {
        // cost[a][b], 0 the stow pose, pass k node k + 1: the cheapest
        // way and branch of each
        let side = passes + 1;
        let mut cost = vec![f64::INFINITY; side * side];
        for (v, nv) in nodes.iter().enumerate() {
            let a = nv.0 + 1;
            cost[a] = cost[a].min(out[v]);
            cost[a * side] = cost[a * side].min(back[v]);
            for (w, nw) in nodes.iter().enumerate() {
                if nw.0 != nv.0 {
                    let c = &mut cost[a * side + nw.0 + 1];
                    *c = c.min(join[v * m + w]);
                }
            }
        }
        return AirFloor {
            s: least_assignment(&cost, side),
            exact: false,
        };
    }
    let full = (1usize << passes) - 1;
    // best[mask · m + v]: least air having painted the passes of mask,
    // node v last
    let mut best = vec![f64::INFINITY; (full + 1) * m];
    for v in 0..m {
        best[(1 << nodes[v].0) * m + v] = out[v];
    }
    for mask in 1..=full {
        for v in 0..m {
            let here = best[mask * m + v];
            if !here.is_finite() || mask & (1 << nodes[v].0) == 0 {
                continue;
            }
            for w in 0..m {
                let bit = 1 << nodes[w].0;
                if mask & bit != 0 {
                    continue;
                }
                let t = here + join[v * m + w];
                let slot = &mut best[(mask | bit) * m + w];
                if t < *slot {
                    *slot = t;
                }
            }
        }
    }
    AirFloor {
        s: (0..m)
            .map(|v| best[full * m + v] + back[v])
            .fold(f64::INFINITY, f64::min),
        exact: true,
    }
}

/// The least total of an assignment of one column to every row of the
/// `n` × `n` matrix `cost` (row-major, each column once; infinite entries
/// forbidden): the Hungarian method with potentials, O(n³).
fn least_assignment(cost: &[f64], n: usize) -> f64 {
    // Kuhn–Munkres with row and column potentials u, v (1-based, column 0
    // a sentinel); way[j]: the column before j on the augmenting path.
    let big = cost
        .iter()
        .copied()
        .filter(|c| c.is_finite())
        .fold(0.0, f64::max)
        * (n as f64 + 1.0)
        + 1.0;
    let at = |i: usize, j: usize| {
        let c = cost[(i - 1) * n + j - 1];
        if c.is_finite() {
            c
        } else {
            big
        }
    };
    let (mut u, mut v) = (vec![0.0; n + 1], vec![0.0; n + 1]);
    let (mut row_of, mut way) = (vec![0usize; n + 1], vec![0usize; n + 1]);
    for i in 1..=n {
        row_of[0] = i;
        let mut j0 = 0;
        let mut min_to = vec![f64::INFINITY; n + 1];
        let mut used = vec![false; n + 1];
        loop {
            used[j0] = true;
            let (i0, mut delta, mut j1) = (row_of[j0], f64::INFINITY, 0);
            for j in 1..=n {
                if !used[j] {
                    let reduced = at(i0, j) - u[i0] - v[j];
                    if reduced < min_to[j] {
                        min_to[j] = reduced;
                        way[j] = j0;
                    }
                    if min_to[j] < delta {
                        delta = min_to[j];
                        j1 = j;
                    }
                }
            }
            for j in 0..=n {
                if used[j] {
                    u[row_of[j]] += delta;
                    v[j] -= delta;
                } else {
                    min_to[j] -= delta;
                }
            }
            j0 = j1;
            if row_of[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            row_of[j0] = row_of[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    (1..=n).map(|j| at(row_of[j], j)).sum()
}

/// Most improvement sweeps over a station's order (each strictly lowers the
/// cost; the bound keeps a long station's compile time in hand).
const MAX_SWEEPS: usize = 8;
/// Gains below this (s) are ignored, so rounding cannot make the search cycle.
const MIN_GAIN_S: f64 = 1e-6;

/// Local search over the order and directions (see `joint_paths`).
fn improve(
    robot: &AnyRobot,
    stow: &Q,
    ways: &[[Option<Candidates>; 2]],
    seq: &mut Vec<(usize, bool)>,
    costs: &JoinCosts,
) {
    let cost_of = |seq: &[(usize, bool)]| -> f64 {
        let picked: Vec<&Candidates> = seq
            .iter()
            .filter_map(|&(k, r)| ways[k][r as usize].as_ref())
            .collect();
        if picked.len() < seq.len() {
            return f64::INFINITY;
        }
        best_branches(robot, stow, &picked, costs).0
    };
    let n = seq.len();
    let mut best = cost_of(seq);
    for _ in 0..MAX_SWEEPS {
        let mut gained = false;
        // Reverse one pass.
        for i in 0..n {
            let mut t = seq.clone();
            t[i].1 = !t[i].1;
            let c = cost_of(&t);
            if c < best - MIN_GAIN_S {
                (*seq, best, gained) = (t, c, true);
            }
        }
        // Reverse a run of passes (2-opt), each pass flipped.
        for i in 0..n {
            for j in i + 1..n {
                let mut t = seq.clone();
                t[i..=j].reverse();
                for v in &mut t[i..=j] {
                    v.1 = !v.1;
                }
                let c = cost_of(&t);
                if c < best - MIN_GAIN_S {
                    (*seq, best, gained) = (t, c, true);
                }
            }
        }
        // Move one pass elsewhere (or-opt), either way round.
        for i in 0..n {
            for j in 0..n {
                if i == j {
                    continue;
                }
                for flip in [false, true] {
                    let mut t = seq.clone();
                    let mut v = t.remove(i);
                    v.1 ^= flip;
                    t.insert(j, v);
                    let c = cost_of(&t);
                    if c < best - MIN_GAIN_S {
                        (*seq, best, gained) = (t, c, true);
                    }
                }
            }
        }
        if !gained {
            break;
        }
    }
}

/// A pass's knots (reversed when asked) with the longest leads the arm
/// reaches, and every branch that follows it. Err: the painting knot (in
/// the pass's own order) where the last lead length tried fails, and why.
fn candidates(
    robot: &AnyRobot,
    station: &Stop<'_>,
    knots: &[Knot],
    reversed: bool,
    stroke: usize,
    joins: &Joins,
) -> Result<Candidates, (usize, basr_robot::Unreachable)> {
    let mut ks = knots.to_vec();
    if reversed {
        ks.reverse();
    }
    let mut first_err = None;
    for lead in [joins.lead_m, 0.5 * joins.lead_m, 0.0] {
        let (all, a, b) = with_leads(&ks, lead, joins.lead_knots);
        match solve_branches(robot, station, &all) {
            Ok(br) => {
                return Ok(Candidates {
                    id: 0,
                    arcs: super::trajectory::arc_lengths(&all),
                    stroke,
                    knots: all,
                    paint_first: a,
                    paint_last: b,
                    branches: br,
                })
            }
            Err((k, e)) => {
                // Report the painting knot, not a lead's.
                let k = k.saturating_sub(a).min(ks.len() - 1);
                let k = if reversed { ks.len() - 1 - k } else { k };
                first_err.get_or_insert((k, e));
            }
        }
    }
    Err(first_err.unwrap_or((0, unreachable_pose())))
}

/// The branch of every pass on the cheapest path stow → passes → stow
/// (Viterbi over the passes; ties to the lower branch index), and its cost.
fn best_branches(
    robot: &AnyRobot,
    stow: &Q,
    cands: &[&Candidates],
    costs: &JoinCosts,
) -> (f64, Vec<usize>) {
    let n = cands.len();
    if n == 0 {
        return (0.0, vec![]);
    }
    let first = |c: &Candidates, b: usize| c.branches[b].1[0];
    let last = |c: &Candidates, b: usize| *c.branches[b].1.last().unwrap_or(stow);
    // cost[i][b]: cheapest way to have painted passes 0..=i, pass i on branch b.
    let mut cost: Vec<Vec<f64>> = Vec::with_capacity(n);
    let mut from: Vec<Vec<usize>> = Vec::with_capacity(n);
    for (i, c) in cands.iter().enumerate() {
        let mut row = Vec::with_capacity(c.branches.len());
        let mut back = Vec::with_capacity(c.branches.len());
        for (b, (inside, _)) in c.branches.iter().enumerate() {
            let entry = first(c, b);
            let (best, arg) = if i == 0 {
                (travel(robot, stow, &entry), 0)
            } else {
                let p = cands[i - 1];
                (0..p.branches.len())
                    .map(|a| (cost[i - 1][a] + costs.join(robot, p, a, c, b), a))
                    .fold(
                        (f64::INFINITY, 0),
                        |m, x| if x.0 < m.0 - 1e-12 { x } else { m },
                    )
            };
            let mut total = best + inside;
            if i + 1 == n {
                total += travel(robot, &last(c, b), stow);
            }
            row.push(total);
            back.push(arg);
        }
        cost.push(row);
        from.push(back);
    }
    let (mut b, total) = cost[n - 1]
        .iter()
        .enumerate()
        .fold(
            (0, f64::INFINITY),
            |m, (k, &v)| if v < m.1 - 1e-12 { (k, v) } else { m },
        );
    let mut choice = vec![0; n];
    for i in (0..n).rev() {
        choice[i] = b;
        b = from[i][b];
    }
    (total, choice)
}

/// Joint travel time between two joint sets: the slowest joint, each
/// accelerating and braking at its limit up to its speed limit.
fn travel(robot: &AnyRobot, a: &Q, b: &Q) -> f64 {
    robot
        .limits()
        .iter()
        .zip(a.iter().zip(b))
        .map(|(l, (x, y))| {
            let d = (x - y).abs();
            if d * l.max_acc <= l.max_vel * l.max_vel {
                2.0 * (d / l.max_acc).sqrt()
            } else {
                d / l.max_vel + l.max_vel / l.max_acc
            }
        })
        .fold(0.0, f64::max)
}

/// A station as the joints are solved from it: its place in the plan, its
/// pose and the road surface under it.
struct Stop<'a> {
    index: usize,
    station: &'a Station,
    road: &'a basr_job::Road,
    /// The tilt joint's range; `None`: the arm cannot lean its fan, and the
    /// fan keeps its planned tilt whatever the surface.
    tilt: Option<basr_robot::JointLimit>,
    /// The painting heights the vertical joint reaches, base frame (m): a
    /// surface a few millimetres off the base's level asks for more, and
    /// the nozzle stops at the end (docs/site.md).
    heights: [f64; 2],
}

impl<'a> Stop<'a> {
    /// Station `index` (`station`, over `road`) as `robot` paints from it.
    fn new(index: usize, station: &'a Station, road: &'a basr_job::Road, robot: &AnyRobot) -> Self {
        let law = basr_robot::paint_law::paint_law(robot);
        Stop {
            index,
            station,
            road,
            tilt: robot.tilt_limit(),
            heights: [law.min_height_m, law.max_height_m],
        }
    }
}

/// The nozzle pose of a knot in a station's base frame: the knot's fan
/// (planned on a flat road) placed on the road's surface, so it keeps its
/// height over the surface and its lean against it (docs/site.md).
fn knot_pose(robot: &AnyRobot, at: &Stop<'_>, k: &Knot) -> NozzlePose {
    let station = at.station;
    let on = at.road.place(
        at.index,
        station,
        [k.tip.x, k.tip.y],
        k.yaw_rad,
        k.z_m,
        k.tilt_rad,
    );
    let b = station.road_to_base(on.xy);
    // The lean the surface asks for, within the tilt's range: a rung
    // already planned at the limit keeps it (the film check judges it).
    let tilt_rad = match at.tilt {
        Some(l) if on.tilt_rad != k.tilt_rad => on
            .tilt_rad
            .clamp(l.min.min(k.tilt_rad), l.max.max(k.tilt_rad)),
        _ => k.tilt_rad,
    };
    NozzlePose {
        x_m: b[0],
        y_m: b[1],
        // Within the painting heights: the lowest as the tilt's drive lifts
        // it at the leaned tilt (`passes::lift_for_tilt`); the highest, or
        // the knot's own where the flat plan put it higher.
        z_m: if on.base_z_m == k.z_m {
            on.base_z_m
        } else {
            let lift = robot.tilt_lift_m(tilt_rad);
            let low = at.heights[0] + if lift.is_finite() { lift.max(0.0) } else { 0.0 };
            let high = at.heights[1].max(k.z_m);
            on.base_z_m.clamp(low.min(high), high)
        },
        yaw_rad: k.yaw_rad - (station.heading_rad - FRAC_PI_2),
        tilt_rad,
    }
}

/// Largest yaw-joint change between two knots of a run (rad). Knots are a
/// rung spacing apart (20 mm); the tightest turn in the font, a bowl's rung
/// pivoting about its inner end, turns the fan by well under this. A larger
/// step is a jump to the other fan branch (π) or yaw turn (2π). The
/// electric kinds' other joints are held to it too (rad or m): a larger
/// step between knots 20 mm apart is a jump to another IK solution (the
/// articulated arm's elbow flipping, say).
const MAX_KNOT_YAW_STEP_RAD: f64 = std::f64::consts::FRAC_PI_2;

/// The joint whose step between knots `p` → `j` is a jump (see
/// `MAX_KNOT_YAW_STEP_RAD`): only the fan joint for a kind whose other
/// joints have one solution per pose (`fan_joint_alone_jumps`), any joint
/// for the rest, the fan joint first.
fn jump(robot: &AnyRobot, p: &Q, j: &Q) -> Option<usize> {
    let fan = robot.fan_joint();
    let step = |k: usize| (j[k] - p[k]).abs() > MAX_KNOT_YAW_STEP_RAD;
    if robot.fan_joint_alone_jumps() {
        return step(fan).then_some(fan);
    }
    std::iter::once(fan).chain(0..5).find(|&k| step(k))
}

/// Joints for every knot of a run, per branch: the fan's two branches (ψ
/// with β, ψ+π with −β) and every yaw turn are tried at the first knot, and
/// each is followed along the run by the nearest solution; those that hold
/// to the end come back with their joint travel. Err: no branch does (the
/// knot index and why).
#[allow(clippy::type_complexity)]
fn solve_branches(
    robot: &AnyRobot,
    station: &Stop<'_>,
    ks: &[Knot],
) -> Result<Vec<(f64, Vec<Q>)>, (usize, basr_robot::Unreachable)> {
    let first = knot_pose(robot, station, &ks[0]);
    let starts = robot.ik(&first).map_err(|e| (0, e))?;
    let mut found = vec![];
    let mut last_err = None;
    'branch: for start in starts {
        let mut cost = 0.0;
        let mut out = Vec::with_capacity(ks.len());
        out.push(start);
        for (i, k) in ks.iter().enumerate().skip(1) {
            let p = *out.last().unwrap_or(&start);
            match robot.ik_nearest(&knot_pose(robot, station, k), &p) {
                // The nearest solution is on another branch or yaw turn: the
                // one this branch follows has left the yaw joint's range.
                // Turning the fan half or whole way round between two knots
                // would spray a disc with the gun on, so the branch fails.
                Ok(j) if jump(robot, &p, &j).is_some() => {
                    let jj = jump(robot, &p, &j).unwrap_or(robot.fan_joint());
                    let lim = robot.limits()[jj];
                    let step = j[jj] - p[jj];
                    // What the branch would have needed: the step less the
                    // half turns the jump added.
                    let own = step - std::f64::consts::PI * (step / std::f64::consts::PI).round();
                    let value = p[jj] + own;
                    last_err = Some((
                        i,
                        basr_robot::Unreachable {
                            joint: robot.joint_names()[jj].into(),
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
        found.push((cost, out));
    }
    if found.is_empty() {
        Err(last_err.unwrap_or_else(|| (0, unreachable_pose())))
    } else {
        Ok(found)
    }
}

/// Placeholder reason when no IK branch was even tried (never expected).
fn unreachable_pose() -> basr_robot::Unreachable {
    basr_robot::Unreachable {
        joint: "pose".into(),
        value: f64::NAN,
        min: f64::NAN,
        max: f64::NAN,
        excess: f64::NAN,
        flipped: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use basr_job::{Road, StopPlane};
    use basr_robot::Robot;
    use kurbo::Point;

    fn knot(x: f64, y: f64, z: f64, yaw: f64, tilt: f64) -> Knot {
        Knot {
            mid: Point::new(x, y),
            tip: Point::new(x, y),
            z_m: z,
            yaw_rad: yaw,
            tilt_rad: tilt,
            width_m: 0.2,
            fan_width_m: 0.2,
            turn_rad: 0.0,
            swept_width_m: 0.2,
            speed_mps: 0.2,
        }
    }

    /// Passes of six knots 64 mm apart from (x, y) with the fan at yaw,
    /// solved both ways round from a station 4.6 m up the lane.
    fn short_passes(robot: &AnyRobot, starts: &[(f64, f64, f64)]) -> Vec<[Option<Candidates>; 2]> {
        let joins = crate::tuning::Tuning::DEFAULT.joins;
        let station = Station {
            x_m: 0.0,
            y_m: 4.6,
            heading_rad: -FRAC_PI_2,
        };
        let road = Road::default();
        let at = Stop::new(0, &station, &road, robot);
        starts
            .iter()
            .enumerate()
            .map(|(k, &(x, y, yaw))| {
                let knots: Vec<Knot> = (0..6)
                    .map(|i| knot(x + 0.04 * i as f64, y + 0.05 * i as f64, 0.15, yaw, 0.0))
                    .collect();
                let way = |rev: bool, id: usize| {
                    candidates(robot, &at, &knots, rev, k, &joins)
                        .ok()
                        .map(|c| Candidates { id, ..c })
                };
                [way(false, 2 * k), way(true, 2 * k + 1)]
            })
            .collect()
    }

    /// The station's order search chooses the same order, directions and
    /// branches whether its join durations are kept in a table or, for a
    /// station too large for one, a map.
    #[test]
    fn join_costs_in_a_table_or_a_map_choose_alike() {
        let robot = AnyRobot::Basr(Robot::basr());
        let joins = crate::tuning::Tuning::DEFAULT.joins;
        let ways = short_passes(
            &robot,
            &[
                (-0.6, 1.2, 0.2),
                (0.4, 0.9, 0.2),
                (-0.2, 2.0, 0.2),
                (0.7, 1.6, 0.2),
            ],
        );
        assert!(ways.iter().all(|w| w[0].is_some() && w[1].is_some()));
        let stow = stow_joints(&robot);
        let chosen = |table_max: usize| {
            let costs = JoinCosts::with_table_max(&robot, &joins, &ways, table_max);
            assert_eq!(
                matches!(&*costs.known.borrow(), Known::Table(_)),
                table_max > 0
            );
            let mut seq: Vec<(usize, bool)> = (0..ways.len()).map(|k| (k, false)).collect();
            improve(&robot, &stow, &ways, &mut seq, &costs);
            let picked: Vec<&Candidates> = seq
                .iter()
                .filter_map(|&(k, r)| ways[k][r as usize].as_ref())
                .collect();
            let (cost, branches) = best_branches(&robot, &stow, &picked, &costs);
            (seq, cost.to_bits(), branches)
        };
        let table = chosen(JOIN_TABLE_MAX);
        assert_eq!(table, chosen(0));
        assert!(f64::from_bits(table.1).is_finite());
        // every (id, branch, id, branch) has its own entry of the table
        let costs = JoinCosts::new(&robot, &joins, &ways);
        let (n, b) = (costs.ids, costs.branches);
        assert!(n == 8 && b >= 1, "{n} ids, {b} branches");
        let mut keys: Vec<usize> = (0..n * b * n * b)
            .map(|k| {
                let (a, rest) = (k / (b * n * b), k % (b * n * b));
                let (ba, rest) = (rest / (n * b), rest % (n * b));
                costs.key(a, ba, rest / b, rest % b)
            })
            .collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), n * b * n * b);
        assert!(keys.iter().all(|&k| k < n * b * n * b));
    }

    /// A station's air floor searched over every order is the least of
    /// every order, way round and branch of its passes (tried one by one
    /// here), and the assignment floor is no more than it.
    #[test]
    fn the_air_floor_is_the_least_of_every_order() {
        let robot = AnyRobot::Basr(Robot::basr());
        let ways = short_passes(
            &robot,
            &[
                (-0.6, 1.2, 0.2),
                (0.4, 0.9, 1.0),
                (-0.2, 2.0, -0.5),
                (0.7, 1.6, 0.4),
            ],
        );
        let limits = full_limits(&robot);
        let stow = stow_joints(&robot);
        let time = |a: Option<Side>, b: Option<Side>| {
            crate::chain::least_time(&limits, a, b, &stow).unwrap_or(f64::INFINITY)
        };
        // every pass's (first rung, last rung) on each way and branch
        let ends: Vec<Vec<(Side, Side)>> = ways
            .iter()
            .map(|w| {
                w.iter()
                    .flatten()
                    .flat_map(|c| {
                        c.branches.iter().map(|(_, js)| {
                            let at = |i, leaving| Side::new((&c.knots, js, &c.arcs), i, leaving);
                            (at(c.paint_first, false), at(c.paint_last, true))
                        })
                    })
                    .collect()
            })
            .collect();
        assert!(ends.iter().all(|e| e.len() >= 2), "both ways round");
        // the least over the passes left, arriving from `from`
        fn least(
            left: &mut Vec<usize>,
            from: Option<Side>,
            ends: &[Vec<(Side, Side)>],
            time: &dyn Fn(Option<Side>, Option<Side>) -> f64,
        ) -> f64 {
            if left.is_empty() {
                return time(from, None);
            }
            let mut best = f64::INFINITY;
            for k in 0..left.len() {
                let p = left.remove(k);
                for &(first, last) in &ends[p] {
                    best = best.min(time(from, Some(first)) + least(left, Some(last), ends, time));
                }
                left.insert(k, p);
            }
            best
        }
        let brute = least(&mut (0..ways.len()).collect(), None, &ends, &time);
        let exact = least_air(&ways, &limits, &stow, AIR_FLOOR_MAX_PASSES);
        assert!(exact.exact && brute.is_finite());
        assert!((exact.s - brute).abs() < 1e-9, "{} vs {brute}", exact.s);
        let assigned = least_air(&ways, &limits, &stow, 0);
        assert!(!assigned.exact);
        assert!(
            assigned.s > 0.0 && assigned.s <= exact.s + 1e-9,
            "{} vs {}",
            assigned.s,
            exact.s
        );
    }

    /// The assignment floor is the least of every assignment, found by
    /// trying them all on small matrices (forbidden entries avoided).
    #[test]
    fn least_assignment_is_the_least_of_all() {
        fn permutations(n: usize) -> Vec<Vec<usize>> {
            if n == 0 {
                return vec![vec![]];
            }
            let mut all = vec![];
            for p in permutations(n - 1) {
                for k in 0..n {
                    let mut q = p.clone();
                    q.insert(k, n - 1);
                    all.push(q);
                }
            }
            all
        }
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) as f64 / (1u64 << 31) as f64
        };
        for n in 1..=6 {
            for _ in 0..40 {
                let cost: Vec<f64> = (0..n * n)
                    .map(|k| {
                        if n > 1 && k % (n + 1) == 0 {
                            f64::INFINITY
                        } else {
                            3.0 * next()
                        }
                    })
                    .collect();
                let brute = permutations(n)
                    .iter()
                    .map(|p| {
                        p.iter()
                            .enumerate()
                            .map(|(i, &j)| cost[i * n + j])
                            .sum::<f64>()
                    })
                    .fold(f64::INFINITY, f64::min);
                let found = least_assignment(&cost, n);
                assert!((found - brute).abs() < 1e-9, "n {n}: {found} vs {brute}");
            }
        }
    }

    /// A knot placed on a fitted plane reads back, as the film sees it
    /// (`Road::relative`), as the knot: its foot, its height over the
    /// surface and its lean against it; and where the joint stops the
    /// nozzle, its height is off by the surface's excursion at most.
    #[test]
    fn a_knot_keeps_its_fan_over_the_surface() {
        let robot = AnyRobot::Basr(Robot::basr());
        let law = basr_robot::paint_law::paint_law(&robot);
        let station = Station {
            x_m: 0.1,
            y_m: 4.6,
            heading_rad: -FRAC_PI_2 + 0.03,
        };
        let road = Road {
            planes: vec![StopPlane {
                stop: 1,
                z_m: -0.002,
                dz_dx: 0.02,
                dz_dy: 0.01,
            }],
            ..Road::default()
        };
        let at = Stop::new(0, &station, &road, &robot);
        for k in [
            knot(0.5, 1.0, 0.15, 0.3, 0.1),
            knot(-0.8, 2.0, 0.2, -1.2, -0.05),
            knot(0.0, 0.5, 0.12, 2.5, 0.0),
        ] {
            let pose = knot_pose(&robot, &at, &k);
            let xy = station.base_to_road([pose.x_m, pose.y_m]);
            let yaw = pose.yaw_rad + station.heading_rad - FRAC_PI_2;
            let r = road.relative(0, &station, xy, pose.z_m, yaw, pose.tilt_rad);
            assert!(
                (r.height_m - k.z_m).abs() < 1e-5,
                "{} vs {}",
                r.height_m,
                k.z_m
            );
            assert!((r.tilt_rad - k.tilt_rad).abs() < 1e-9);
            assert!((r.xy[0] - k.tip.x).hypot(r.xy[1] - k.tip.y) < 1e-5);
        }
        // At the lowest height over a surface 2 mm under the base's level
        // (as it is near the axis here), the nozzle stops at its lowest:
        // 2 mm over the plan, not more.
        let low = knot(0.0, 4.0, law.min_height_m, 0.0, 0.0);
        let pose = knot_pose(&robot, &at, &low);
        let xy = station.base_to_road([pose.x_m, pose.y_m]);
        let r = road.relative(0, &station, xy, pose.z_m, 0.0, pose.tilt_rad);
        assert!(
            r.height_m > low.z_m && r.height_m - low.z_m <= 0.003,
            "{}",
            r.height_m
        );
    }
}
