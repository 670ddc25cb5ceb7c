//! Passes: each stroke's rungs turned into knots (fan direction, height,
//! tilt, painting speed; `knots`), a stroke wider than one fan split into
//! parallel passes. A pass is one continuous gun-on path.

use crate::knots::{self, HeightLaw, Knot, PaintLaw, PlanError, TiltMethod};
use crate::rungs::Rung;
use basr_job::StrokeBalance;
use basr_robot::paint_law::paint_law;
use basr_robot::AnyRobot;

use super::error::CompileError;
use super::placed::PlacedStrokes;
use super::rate;
use super::rungs::StrokeRungs;
use super::tuning::{Rates, Tuning};
use super::warnings::{Note, OneSweep};

/// Rounds of turn limiting and re-pacing per pass. assumed: the speeds
/// settle in two; the third is slack.
const TURN_TRIES: usize = 3;

/// One continuous gun-on path: a stroke, or one pass of a wide stroke.
#[derive(Clone, Debug, PartialEq)]
pub struct Pass {
    /// Index into the placed strokes.
    pub stroke: usize,
    pub knots: Vec<Knot>,
}

/// Every pass of the marking, in stroke order, with each stroke's paint
/// balance and the notes of this stage.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Passes {
    pub passes: Vec<Pass>,
    pub balance: Vec<StrokeBalance>,
    pub notes: Vec<Note>,
    /// Each planned stroke's painted area and the area its clamped knots
    /// paint outside it (m²), in stroke order: the shares in the notes
    /// (`Note::HeightClamped`) are of their sum over the job.
    pub(crate) areas: Vec<StrokeArea>,
}

/// One stroke's painted area, pass by pass, and the area its clamped knots
/// paint outside it (m², none when it has no clamped knots).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct StrokeArea {
    stroke: usize,
    /// Each pass's, in order.
    painted_m2: Vec<f64>,
    outside_m2: Option<f64>,
}

impl Passes {
    /// These passes with the strokes `take` names taken from `other` (the
    /// same marking planned under another paint law: on an uneven road,
    /// the strokes of the stops whose surface asks for it): their passes,
    /// balance and notes; the job-wide share of paint laid outside the
    /// strokes summed again over the strokes kept.
    pub fn with_strokes_from(self, other: Passes, take: impl Fn(usize) -> bool) -> Passes {
        let stroke_of = |n: &Note| match n {
            Note::Passes { stroke, .. }
            | Note::HeightClamped { stroke, .. }
            | Note::Slowed { stroke, .. } => Some(*stroke),
            _ => None,
        };
        // Each stroke's items from one side or the other, in stroke order
        // (a stable sort: a stroke's own items keep theirs).
        fn pick<T>(
            mine: Vec<T>,
            theirs: Vec<T>,
            of: impl Fn(&T) -> usize,
            take: &impl Fn(usize) -> bool,
        ) -> Vec<T> {
            let mut v: Vec<T> = mine
                .into_iter()
                .filter(|x| !take(of(x)))
                .chain(theirs.into_iter().filter(|x| take(of(x))))
                .collect();
            v.sort_by_key(|x| of(x));
            v
        }
        let passes = pick(self.passes, other.passes, |p: &Pass| p.stroke, &take);
        let balance = pick(
            self.balance,
            other.balance,
            |b: &StrokeBalance| b.stroke,
            &take,
        );
        let mut notes: Vec<Note> = self
            .notes
            .into_iter()
            .filter(|n| stroke_of(n).is_none_or(|s| !take(s)))
            .chain(
                other
                    .notes
                    .into_iter()
                    .filter(|n| stroke_of(n).is_some_and(&take)),
            )
            .collect();
        notes.sort_by_key(|n| stroke_of(n).unwrap_or(usize::MAX));
        let areas = pick(self.areas, other.areas, |a: &StrokeArea| a.stroke, &take);
        Passes {
            passes,
            balance,
            notes,
            areas,
        }
        .with_shares()
    }

    /// The notes' shares of the job's paint laid outside the strokes, from
    /// the strokes' areas: each clamped stroke's own and their sum.
    fn with_shares(mut self) -> Passes {
        let painted_m2 = self
            .areas
            .iter()
            .flat_map(|a| &a.painted_m2)
            .fold(0.0, |sum, p| sum + p);
        let share = |a: f64| {
            if painted_m2 > 0.0 {
                a / painted_m2
            } else {
                0.0
            }
        };
        let outside: std::collections::BTreeMap<usize, f64> = self
            .areas
            .iter()
            .filter_map(|a| a.outside_m2.map(|o| (a.stroke, o)))
            .collect();
        let job = share(self.areas.iter().filter_map(|a| a.outside_m2).sum());
        for n in &mut self.notes {
            if let Note::HeightClamped {
                stroke,
                outside_share,
                job_outside_share,
                ..
            } = n
            {
                *outside_share = share(outside.get(stroke).copied().unwrap_or(0.0));
                *job_outside_share = job;
            }
        }
        self
    }
}

/// Knots of every stroke's passes (001 §2.4–2.5).
pub fn passes(
    strokes: &PlacedStrokes,
    rungs: &StrokeRungs,
    robot: &AnyRobot,
    method: TiltMethod,
    tuning: &Tuning,
) -> Result<Passes, CompileError> {
    passes_of(strokes, rungs, robot, method, tuning, &|_| true)
}

/// [`passes`] of the strokes `only` names (their rungs from
/// `rungs::rungs_of`), none of the others: some strokes planned again
/// under another paint law, to be taken into the whole plan with
/// [`Passes::with_strokes_from`] (the strokes over an uneven road).
pub fn passes_of(
    strokes: &PlacedStrokes,
    rungs: &StrokeRungs,
    robot: &AnyRobot,
    method: TiltMethod,
    tuning: &Tuning,
    only: &(dyn Fn(usize) -> bool + Sync),
) -> Result<Passes, CompileError> {
    let rates = &tuning.rates;
    let law = paint_law(robot);
    let limits = Limits {
        max_tilt: max_tilt_rad(robot, rates),
        max_tilt_rate: robot
            .tilt_limit()
            .map_or(f64::INFINITY, |tl| tl.max_vel * rates.tilt_spread_share),
        max_turn: max_turn_rps(robot, rates),
        // The tilt and the height within what their joints follow (`rate`).
        tilt_follow: rate::tilt_follow(robot, rates),
        height_follow: rate::height_follow(robot, rates),
        smoothing: rates.tilt_smoothing,
    };
    // Each stroke's passes are its own: planned in parallel, gathered in
    // the strokes' order (the first error, and the sums, as one by one).
    let per_stroke: Vec<Result<Option<StrokePasses>, CompileError>> = {
        use rayon::prelude::*;
        rungs
            .rungs
            .par_iter()
            .enumerate()
            .map(|(sid, stroke_rungs)| {
                if !only(sid) {
                    return Ok(None);
                }
                stroke_passes(
                    strokes,
                    sid,
                    stroke_rungs,
                    robot,
                    law,
                    method,
                    tuning,
                    limits,
                )
                .map(Some)
            })
            .collect()
    };
    let mut out = Passes::default();
    for (sid, stroke) in per_stroke.into_iter().enumerate() {
        let Some(stroke) = stroke? else { continue };
        out.areas.push(StrokeArea {
            stroke: sid,
            painted_m2: stroke.painted_m2,
            outside_m2: stroke.outside_m2,
        });
        out.passes.extend(stroke.passes);
        out.balance.extend(stroke.balance);
        out.notes.extend(stroke.notes);
    }
    // Shares of the whole job's paint, known once every pass is.
    Ok(out.with_shares())
}

/// The limits a stroke's passes are planned within (`passes`).
#[derive(Clone, Copy)]
struct Limits {
    max_tilt: f64,
    max_tilt_rate: f64,
    max_turn: f64,
    tilt_follow: Option<[f64; 2]>,
    height_follow: Option<[f64; 2]>,
    smoothing: usize,
}

/// One stroke's share of [`passes`].
struct StrokePasses {
    passes: Vec<Pass>,
    /// Each pass's painted area (m²), in order.
    painted_m2: Vec<f64>,
    balance: Option<StrokeBalance>,
    notes: Vec<Note>,
    /// The area its clamped knots paint outside it (m²), when it has any.
    outside_m2: Option<f64>,
}

/// [`passes`] of stroke `sid`.
#[allow(clippy::too_many_arguments)]
fn stroke_passes(
    strokes: &PlacedStrokes,
    sid: usize,
    stroke_rungs: &[Rung],
    robot: &AnyRobot,
    law: PaintLaw,
    method: TiltMethod,
    tuning: &Tuning,
    limits: Limits,
) -> Result<StrokePasses, CompileError> {
    let mut passes = Vec::new();
    let mut painted_m2 = Vec::new();
    let mut balance = None;
    let mut notes = Vec::new();
    let mut kept_outside = None;
    let owner = strokes.owner(sid);
    let what = |e: knots::PlanError| CompileError::Knots(format!("stroke {sid} ({owner}): {e}"));
    let min_width_m = law.width_at_height(law.min_height_m);
    let split = split_passes(stroke_rungs, law.max_width_m(), min_width_m, 0.0).map_err(what)?;
    let mut clamped = 0usize;
    let mut rung_count = 0usize;
    let mut worst = 1.0f64;
    let mut outside_m2 = 0.0;
    // knots::KnotPlan keeps U in percent; the job keeps fractions.
    let mut u_untilted = [f64::INFINITY, f64::NEG_INFINITY];
    let mut u_tilted = u_untilted;
    for pass in &split.passes {
        let mut kp = knots::knots_within(
            pass,
            &law,
            method,
            limits.max_tilt,
            limits.max_tilt_rate,
            limits.smoothing,
        )
        .map_err(what)?;
        tilt_for_turned_fan(
            pass,
            &mut kp,
            &law,
            method,
            [limits.max_tilt, limits.max_tilt_rate],
            limits.max_turn,
            limits.smoothing,
        )
        .map_err(what)?;
        u_untilted = [
            u_untilted[0].min(kp.u_before.0 / 100.0),
            u_untilted[1].max(kp.u_before.1 / 100.0),
        ];
        u_tilted = [
            u_tilted[0].min(kp.u_after.0 / 100.0),
            u_tilted[1].max(kp.u_after.1 / 100.0),
        ];
        // A turned fan sweeps other road: re-pace, and check the turn
        // again at the new speeds.
        // The tilt, likewise, within what its joint follows.
        for _ in 0..TURN_TRIES {
            let turned = super::turn::limit_turn_rate(&mut kp.knots, limits.max_turn);
            let tilted = limits
                .tilt_follow
                .is_some_and(|[v, a]| rate::limit_tilt_rate(&mut kp.knots, &law, v, a));
            if !(turned || tilted) {
                break;
            }
            knots::pace(pass, &mut kp.knots, law.k_m2ps);
        }
        let raised = lift_for_tilt(robot, &law, &mut kp.knots);
        // The height, too, within what the vertical joint follows.
        let lifted = limits
            .height_follow
            .is_some_and(|f| rate::limit_height_rate(&mut kp.knots, &law, f));
        if !raised.is_empty() || lifted {
            // Wider footprints sweep more road: re-pace the pass.
            knots::pace(pass, &mut kp.knots, law.k_m2ps);
        }
        // A fan longer than its rung turned to cover it, then paced
        // for the road it sweeps turned.
        if super::narrow::turn_narrow(
            pass,
            &mut kp.knots,
            limits.max_turn,
            law.k_m2ps,
            &tuning.narrow,
        ) {
            knots::pace(pass, &mut kp.knots, law.k_m2ps);
        }
        // Clamped knots that still paint beside the stroke.
        let wide = |r: usize| {
            kp.knots
                .get(r)
                .is_some_and(|k| k.covered_width_m() > k.width_m * (1.0 + 1e-6))
        };
        clamped += kp
            .clamped
            .iter()
            .filter(|c| !raised.contains(&c.rung) && wide(c.rung))
            .count()
            + raised.iter().filter(|&&r| wide(r)).count();
        rung_count += kp.knots.len();
        let (outside, painted) = outside_area(&kp.knots);
        outside_m2 += outside;
        painted_m2.push(painted);
        for k in &kp.knots {
            if k.width_m > 0.0 {
                worst = worst.max(k.covered_width_m() / k.width_m);
            }
        }
        passes.push(Pass {
            stroke: sid,
            knots: kp.knots,
        });
    }
    if u_untilted[0].is_finite() && u_tilted[0].is_finite() {
        balance = Some(StrokeBalance {
            stroke: sid,
            char: owner.label.clone(),
            line: owner.line,
            u_untilted,
            u_tilted,
        });
    }
    if split.abreast() > 1 {
        notes.push(Note::Passes {
            stroke: sid,
            owner: owner.clone(),
            passes: split.abreast(),
            stretches: split.stretches.len(),
            max_width_m: law.max_width_m(),
        });
    }
    if clamped > 0 {
        notes.push(Note::HeightClamped {
            stroke: sid,
            owner: owner.clone(),
            clamped,
            rungs: rung_count,
            min_height_m: law.min_height_m,
            worst_ratio: worst,
            outside_share: 0.0,
            job_outside_share: 0.0,
            one_sweep: (split.abreast() > 1).then(|| {
                let widest = stroke_rungs.iter().map(Rung::width).fold(0.0, f64::max);
                OneSweep {
                    scale: law.max_width_m() / widest,
                    letter_height_m: strokes.letter_height_m(sid),
                }
            }),
        });
        kept_outside = Some(outside_m2);
    }
    Ok(StrokePasses {
        passes,
        painted_m2,
        balance,
        notes,
        outside_m2: kept_outside,
    })
}

/// Where the turn limit holds the fan off its rungs (`turn`), choose the
/// tilt for the tiles the fan sweeps, not for the rungs: the knots again
/// from the fan's own segments (each knot's width along its limited
/// direction, about the rung's middle), then paced over the stroke's rungs.
///
/// The quadrilateral tilt (001 §2.5) balances the paint of a tile whose
/// rung pivots (one end advancing faster than the other). A loop's short
/// side (the 8's, 6's and 9's, between two 45° seams) has rungs that turn a
/// quarter turn within ≈ 0.25 m, so the tilt was at its limit all along
/// it, while the turn-limited fan turned less than half of that and hardly
/// pivots. The needless tilt lifted the nozzle (the tilt four-bar's rise
/// over the vertical joint's lowest height), so the fan painted 29 % wider
/// than the stroke there, and it laid the film unevenly across the fan.
fn tilt_for_turned_fan(
    pass: &[Rung],
    kp: &mut knots::KnotPlan,
    law: &PaintLaw,
    method: TiltMethod,
    [max_tilt, max_tilt_rate]: [f64; 2],
    max_turn_rps: f64,
    tilt_smoothing: usize,
) -> Result<(), PlanError> {
    // Only where the fan already paints wider than some rung (a narrow
    // stroke), where a needless tilt costs paint outside the stroke.
    if kp.clamped.is_empty() {
        return Ok(());
    }
    let mut turned = kp.knots.clone();
    if !super::turn::limit_turn_rate(&mut turned, max_turn_rps) {
        return Ok(());
    }
    let fans = super::turn::fan_rungs(&turned);
    let mut re = knots::knots_within(&fans, law, method, max_tilt, max_tilt_rate, tilt_smoothing)?;
    knots::pace(pass, &mut re.knots, law.k_m2ps);
    // U (001 eq. 2.7–2.8) of the stroke's own cells at the tilts now used.
    let betas: Vec<f64> = re.knots.iter().map(|k| k.tilt_rad).collect();
    kp.u_after = super::tilt::u_range(&super::tilt::u_ratios(pass, &betas, law.fan_angle_rad));
    kp.knots = re.knots;
    kp.clamped = re.clamped;
    Ok(())
}

/// Road area (m²) a pass's fan lays paint on outside its stroke, where the
/// fan is wider than the rung (a clamped height), and all the road it lays
/// paint on: each knot's width over half the tip travel to each neighbour.
/// The film is on target over the whole fan, so the first over the second
/// is the share of the paint that lands outside the stroke.
pub fn outside_area(ks: &[Knot]) -> (f64, f64) {
    let n = ks.len();
    let mut outside = 0.0;
    let mut painted = 0.0;
    for (i, k) in ks.iter().enumerate() {
        let before = if i > 0 {
            (k.mid - ks[i - 1].mid).hypot()
        } else {
            0.0
        };
        let after = if i + 1 < n {
            (ks[i + 1].mid - k.mid).hypot()
        } else {
            0.0
        };
        let ds = 0.5 * (before + after);
        outside += (k.covered_width_m() - k.width_m).max(0.0) * ds;
        painted += k.covered_width_m().max(k.width_m) * ds;
    }
    (outside, painted)
}

/// The largest tilt either way the knots may take: the tilt joint's range
/// less `tilt_inset_rad`; 0 for a kind that cannot lean the fan (the
/// articulated arm paints untilted).
fn max_tilt_rad(robot: &AnyRobot, rates: &Rates) -> f64 {
    robot.tilt_limit().map_or(0.0, |tl| {
        (tl.max.min(-tl.min) - rates.tilt_inset_rad).max(0.0)
    })
}

/// Turn rate (rad/s) the fan may take while painting: `turn_share` of the
/// fan joint's speed limit.
fn max_turn_rps(robot: &AnyRobot, rates: &Rates) -> f64 {
    robot.limits()[robot.fan_joint()].max_vel * rates.turn_share
}

/// What the robot's fan may turn while painting, for choosing rungs: the
/// share of the fan joint's speed limit the turn limit allows
/// (`tuning::Rates::turn_share`) at the film law's speeds, and what the
/// height and the tilt may take (`rate`), the tilt's judged for the
/// quadrilateral method (the default; the others tilt no more); the
/// search's own tuning.
pub fn turn_budget(robot: &AnyRobot, tuning: &Tuning) -> super::pairing::TurnBudget {
    let rates = &tuning.rates;
    use super::pairing::{HeightFollow, TiltFollow, TurnBudget};
    let law = paint_law(robot);
    let dz_dw = match law.height {
        HeightLaw::Geometric => law.height_for_width(1.0),
        HeightLaw::Linear { c1, .. } => c1,
    };
    let max_tilt_rad = max_tilt_rad(robot, rates);
    TurnBudget {
        k_m2ps: law.k_m2ps,
        min_width_m: law.width_at_height(law.min_height_m),
        max_rate_rps: max_turn_rps(robot, rates),
        height: rate::height_follow(robot, rates).map(|[v, _]| HeightFollow {
            dz_dw,
            max_speed_mps: v,
        }),
        tilt: rate::tilt_follow(robot, rates)
            .filter(|_| max_tilt_rad > 0.0)
            .map(|[v, _]| TiltFollow {
                fan_angle_rad: law.fan_angle_rad,
                max_tilt_rad,
                max_speed_rps: v,
            }),
        tuning: tuning.pairing,
    }
}

/// Raise knots whose tilted tip would need the vertical joint below its
/// stroke: a tilt lifts the tip by the kind's `tilt_lift_m` (BASR's tilt
/// four-bar, by the larger of rise(β) and rise(−β)), so the lowest tip
/// height at tilt ±β is `law.min_height_m` plus that lift. The fan then covers
/// more than the rung, and the speed follows the covered width (as
/// `knots::knots` does for its own clamp). Returns the knots raised.
fn lift_for_tilt(robot: &AnyRobot, law: &PaintLaw, ks: &mut [Knot]) -> Vec<usize> {
    let mut raised = vec![];
    for (i, k) in ks.iter_mut().enumerate() {
        // The fan's other branch (ψ+π, −β) paints the same rung; the four-bar
        // lifts the tip differently at −β, so the height suits both and the
        // tour may pick either branch (`joints`).
        let rise = robot.tilt_lift_m(k.tilt_rad);
        if !(rise.is_finite() && rise > 0.0) {
            continue;
        }
        let z_min = law.min_height_m + rise;
        if k.z_m < z_min {
            let factor = crate::tilt::height_factor(k.tilt_rad, law.fan_angle_rad);
            k.z_m = z_min;
            k.fan_width_m = law.width_at_height(z_min / factor).max(k.width_m);
            raised.push(i);
        }
    }
    raised
}

/// Splits a stroke too wide for one pass into parallel passes.
///
/// The rule: along a stretch of the stroke the number of side-by-side
/// passes n is the same, and every rung of the stretch is cut at the
/// fractions j/n of its length; pass j gets the piece from j/n to
/// (j+1)/n, widened by `overlap_m`/2 into each neighbour (never past the
/// stroke's edges). A piece must fit the fan between its narrowest
/// (`min_width_m`, the fan at the lowest nozzle) and its widest
/// (`max_width_m`): a rung of width w takes n from ⌈w / (max − overlap)⌉
/// to ⌊w / min⌋ pieces (at least one). One n for the whole stroke, the
/// smallest that every rung takes, keeps each pass one continuous stroke
/// with the gun on from end to end. Where no n suits every rung (a bowl
/// wider than the fan at its widest that narrows to under twice the
/// narrowest fan), one n for the whole stroke cut the narrow rungs into
/// slivers the fan paints wider than they are, beside the stroke: the
/// stroke is then cut across, at a rung both stretches share, into
/// stretches each with its own n, as few as can be (taken greedily from
/// the stroke's start, each stretch as long as one n suits it; the
/// smallest such n). Each stretch's passes end on the shared rung, as two
/// strokes of a letter meet: the tiles are painted once.
///
/// With `overlap_m` = 0 the pieces tile every rung exactly: the passes
/// share their boundaries, cover the stroke and paint no area twice. A
/// positive overlap trades a band of double film for tolerance to arm
/// error at the seam. Passes come stretch by stretch from the stroke's
/// start, left to right within a stretch (pass 0 touches the left edge);
/// a stroke narrow enough for one pass comes back unchanged.
pub fn split_passes(
    rungs: &[Rung],
    max_width_m: f64,
    min_width_m: f64,
    overlap_m: f64,
) -> Result<Split, PlanError> {
    if !(max_width_m.is_finite()
        && overlap_m.is_finite()
        && overlap_m >= 0.0
        && max_width_m > overlap_m
        && min_width_m.is_finite()
        && min_width_m >= 0.0)
    {
        return Err(PlanError::BadPassSplit {
            max_width_m,
            overlap_m,
        });
    }
    let widest = rungs.iter().map(Rung::width).fold(0.0_f64, f64::max);
    if !widest.is_finite() {
        return Err(PlanError::NotFinite {
            rung: rungs
                .iter()
                .position(|r| !r.width().is_finite())
                .unwrap_or(0),
        });
    }
    if widest <= max_width_m {
        return Ok(Split {
            passes: vec![rungs.to_vec()],
            stretches: vec![(0, rungs.len().saturating_sub(1), 1)],
        });
    }
    // The numbers of pieces rung i takes: lo[i]..=hi[i].
    let step = max_width_m - overlap_m;
    let lo: Vec<usize> = rungs
        .iter()
        .map(|r| (r.width() / step).ceil().max(1.0) as usize)
        .collect();
    let hi: Vec<usize> = rungs
        .iter()
        .zip(&lo)
        .map(|(r, &l)| {
            let most = if min_width_m > 0.0 {
                (r.width() / min_width_m).floor() as usize
            } else {
                usize::MAX
            };
            most.max(l)
        })
        .collect();
    // Stretches [a, b] (rungs, the ends shared) and their n.
    let mut stretches: Vec<(usize, usize, usize)> = Vec::new();
    let mut a = 0usize;
    while a + 1 < rungs.len() {
        let (mut l, mut h) = (lo[a], hi[a]);
        let mut b = a;
        while b + 1 < rungs.len() && lo[b + 1].max(l) <= hi[b + 1].min(h) {
            b += 1;
            l = l.max(lo[b]);
            h = h.min(hi[b]);
        }
        if b == a {
            // Neighbouring rungs no n suits both (a jump in width): the
            // tile between them is cut for the wider, as one n for the
            // whole stroke would cut it.
            b = a + 1;
            l = lo[a].max(lo[b]);
        }
        stretches.push((a, b, l));
        a = b;
    }
    if rungs.len() < 2 {
        stretches.push((0, 0, lo[0]));
    }
    let mut out = Vec::new();
    for &(a, b, n) in &stretches {
        for j in 0..n {
            out.push(
                rungs[a..=b]
                    .iter()
                    .map(|r| {
                        let w = r.width();
                        let ext = if w > 0.0 { 0.5 * overlap_m / w } else { 0.0 };
                        let f0 = if j == 0 {
                            0.0
                        } else {
                            j as f64 / n as f64 - ext
                        };
                        let f1 = if j + 1 == n {
                            1.0
                        } else {
                            (j + 1) as f64 / n as f64 + ext
                        };
                        Rung {
                            left: r.left.lerp(r.right, f0.max(0.0)),
                            right: r.left.lerp(r.right, f1.min(1.0)),
                        }
                    })
                    .collect(),
            );
        }
    }
    Ok(Split {
        passes: out,
        stretches,
    })
}

/// A stroke's passes (`split_passes`) and the stretches of the stroke
/// they paint.
#[derive(Clone, Debug, PartialEq)]
pub struct Split {
    /// Each pass's pieces of its stretch's rungs, stretch by stretch.
    pub passes: Vec<Vec<Rung>>,
    /// (first rung, last rung, passes side by side) of each stretch, from
    /// the stroke's start; neighbouring stretches share their end rung.
    pub stretches: Vec<(usize, usize, usize)>,
}

impl Split {
    /// The most passes side by side anywhere on the stroke.
    pub fn abreast(&self) -> usize {
        self.stretches.iter().map(|s| s.2).max().unwrap_or(1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{Point, Vec2};
    use proptest::prelude::*;

    #[test]
    fn a_loop_side_is_tilted_for_the_fan_that_turns_not_for_its_rungs() {
        // The 8's lower loop side at 8 ft: a band 97.6 mm wide between two
        // 45° seams, its outer edge 0.341 m long and its inner 0.147 m, in
        // 18 equal arc-length rungs. They turn a quarter turn; the fan, held
        // to the yaw joint's rate, turns less than half of that.
        let robot = AnyRobot::load_or_default(None).unwrap();
        let law = paint_law(&robot);
        let tl = robot.tilt_limit().unwrap();
        let rates = Tuning::DEFAULT.rates;
        let limits = [
            max_tilt_rad(&robot, &rates),
            tl.max_vel * rates.tilt_spread_share,
        ];
        let max_turn = max_turn_rps(&robot, &rates);
        let sm = rates.tilt_smoothing;
        let n = 18;
        let rungs: Vec<Rung> = (0..=n)
            .map(|k| {
                let f = k as f64 / n as f64;
                Rung {
                    left: Point::new(0.1952, 0.927 - 0.341 * f),
                    right: Point::new(0.0976, 0.830 - 0.147 * f),
                }
            })
            .collect();
        let method = TiltMethod::Quadrilateral;
        let before = knots::knots_within(&rungs, &law, method, limits[0], limits[1], sm).unwrap();
        let mut after = before.clone();
        tilt_for_turned_fan(&rungs, &mut after, &law, method, limits, max_turn, sm).unwrap();
        let tilt = |kp: &knots::KnotPlan| {
            kp.knots.iter().map(|k| k.tilt_rad.abs()).sum::<f64>() / kp.knots.len() as f64
        };
        let wide = |kp: &knots::KnotPlan| {
            kp.knots
                .iter()
                .map(|k| k.fan_width_m / k.width_m)
                .fold(0.0, f64::max)
        };
        // Measured: mean |β| 0.257 → 0.130 rad; the widest fan over its
        // rung 1.086 → 1.008 (before the tilt four-bar's lift, which grows
        // with |β|).
        assert!(
            tilt(&after) < 0.6 * tilt(&before),
            "{} {}",
            tilt(&after),
            tilt(&before)
        );
        assert!(
            wide(&before) > 1.05 && wide(&after) < 1.03,
            "{} {}",
            wide(&before),
            wide(&after)
        );
        // Rungs the fan follows keep their knots.
        let straight: Vec<Rung> = (0..=n)
            .map(|k| Rung {
                left: Point::new(0.2, 0.02 * k as f64),
                right: Point::new(0.1, 0.02 * k as f64),
            })
            .collect();
        let plain = knots::knots_within(&straight, &law, method, limits[0], limits[1], sm).unwrap();
        let mut same = plain.clone();
        tilt_for_turned_fan(&straight, &mut same, &law, method, limits, max_turn, sm).unwrap();
        assert_eq!(same, plain);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]
        #[test]
        fn passes_tile_every_rung(
            widths in proptest::collection::vec(0.01f64..1.5, 2..12),
            max_w in 0.1f64..0.5, min_frac in 0.0f64..0.5,
            overlap_frac in prop_oneof![Just(0.0f64), 0.0f64..0.5],
            angle in -3.0f64..3.0,
        ) {
            let overlap = overlap_frac * max_w;
            let min_w = min_frac * max_w;
            let d = Vec2::from_angle(angle);
            let rungs: Vec<Rung> = widths.iter().enumerate().map(|(k, &w)| {
                let left = Point::new(0.03 * k as f64, 0.1);
                Rung { left, right: left + w * d }
            }).collect();
            let split = split_passes(&rungs, max_w, min_w, overlap).unwrap();
            // The stretches run from the first rung to the last, each
            // sharing its end rung with the next.
            let st = &split.stretches;
            prop_assert_eq!(st[0].0, 0);
            prop_assert_eq!(st[st.len() - 1].1, rungs.len() - 1);
            for pair in st.windows(2) { prop_assert_eq!(pair[0].1, pair[1].0); }
            prop_assert_eq!(split.passes.len(), st.iter().map(|s| s.2).sum::<usize>());
            // One n suits every rung: one stretch, as before stretches.
            let lo = |w: f64| (w / (max_w - overlap)).ceil().max(1.0);
            let hi = |w: f64| if min_w > 0.0 { (w / min_w).floor().max(lo(w)) } else { f64::MAX };
            let n_lo = widths.iter().map(|&w| lo(w)).fold(1.0, f64::max);
            let n_hi = widths.iter().map(|&w| hi(w)).fold(f64::MAX, f64::min);
            if widths.iter().all(|&w| w <= max_w) || n_lo <= n_hi {
                prop_assert_eq!(st.len(), 1);
            }
            let mut first = 0;
            for &(a, b, n) in st {
                prop_assert!(b > a || rungs.len() == 1);
                let passes = &split.passes[first..first + n];
                first += n;
                for p in passes {
                    prop_assert_eq!(p.len(), b - a + 1);
                    for r in p { prop_assert!(r.width() <= max_w + 1e-9); }
                }
                for (i, r) in rungs[a..=b].iter().enumerate() {
                    let w = r.width();
                    // No sliver where the rung can be cut into n pieces
                    // each at least the narrowest fan.
                    if overlap == 0.0 && min_w > 0.0 && n as f64 <= (w / min_w).floor() {
                        for p in passes { prop_assert!(p[i].width() >= min_w - 1e-9); }
                    }
                    // Pieces in order, first at the left end, last at the
                    // right end, consecutive ones overlapping by exactly
                    // min(overlap, …) and 0 when overlap = 0.
                    prop_assert!((passes[0][i].left - r.left).hypot() < 1e-12);
                    prop_assert!((passes[n - 1][i].right - r.right).hypot() < 1e-12);
                    let covered: f64 = passes.iter().map(|p| p[i].width()).sum();
                    let seams = (n - 1) as f64;
                    prop_assert!(covered >= w - 1e-9);
                    prop_assert!(covered <= w + seams * overlap + 1e-9);
                    for pair in passes.windows(2) {
                        // Next piece starts no later than this one ends: no gap.
                        let end = (pair[0][i].right - r.left).hypot();
                        let start = (pair[1][i].left - r.left).hypot();
                        prop_assert!(start <= end + 1e-12);
                        if overlap == 0.0 { prop_assert!((start - end).abs() < 1e-12); }
                    }
                }
            }
        }
    }
}
