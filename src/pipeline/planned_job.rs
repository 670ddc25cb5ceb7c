//! One job planned, verified and its film checked, for one spray tip and
//! one tilt: the stages from placed strokes on — rungs → knots and passes
//! → stations → tours → joint paths → timed trajectory → samples → sealed
//! job → verified (re-timed where the arm falls behind) → its film
//! checked. Each stage is one function in a module named for the value it
//! returns; `choice` chooses among these jobs.

use crate::job::Job;
use crate::layout;

use super::{film, verify};
use basr_plan::error::CompileError;
use basr_plan::placed::PlacedStrokes;
use basr_plan::request::CompileRequest;
use basr_plan::seal::{self, Planned};
use basr_plan::stow::truck_rows;
use basr_plan::{joints, passes, request, rungs, samples, stations, tours, trajectory};
use rayon::prelude::*;

/// What every job of a marking plans from: the marking, its font and its
/// placed strokes.
#[derive(Clone, Copy)]
pub(super) struct Placed<'a> {
    pub marking: &'a layout::Marking,
    pub font: &'a crate::font::Font,
    pub strokes: &'a PlacedStrokes,
}

/// A job of one tip and one tilt, and what its film check found of each
/// item: what `choice::compile_strokes` chooses among.
pub(super) struct PlannedJob {
    pub job: Job,
    /// The items whose own film misses a bound (`film::FilmCheck::
    /// items_over`); none where the request does not measure the film.
    pub items_over: Vec<String>,
}

/// The planner for the robot's paint table as it is (one tip): the job
/// of one tip and one tilt, which `choice::compile_strokes` chooses among.
pub(super) fn compile_for_tip(
    req: &CompileRequest,
    placed: Placed,
    robot: crate::robot::AnyRobot,
) -> Result<PlannedJob, CompileError> {
    let Placed {
        marking,
        font,
        strokes,
    } = placed;
    let (tilt, tilt_note) = request::tilt_for(req.tilt, &robot);
    let (passes, plan) = passes_on_road(req, marking, strokes, &robot, tilt)?;
    // at the site, each stop whose passes are the job's in the job's order
    let painted = req.site.as_ref().map_or(&[][..], |s| &s.painted[..]);
    let gun_s = req.gun_lead_s.max(req.gun_lag_s);
    let tours = tours::tours(&passes, &plan, &robot, painted, gun_s);
    let paths = joints::joint_paths(strokes, &passes, &plan, &tours, &robot, &req.tuning.joins)?;
    let n = paths.stations.len();
    let mut paces = vec![trajectory::Pace::FULL; n];
    let mut cache = trajectory::StationTimings::default();
    // verdicts[s]: station s's verdict at the pace it was last simulated.
    let mut verdicts: Vec<Option<(trajectory::Pace, verify::Verdict)>> = vec![None; n];
    // runs[s]: a failed station's last rows and its run's checkpoints, so
    // that its next run resumes where its rows first change.
    let mut runs: Vec<Option<LastRun>> = (0..n).map(|_| None).collect();
    // on_spread[s]: each plant of the verification set's largest error on
    // station s (`verify::on_spread`), once the station passed.
    let mut on_spread: Vec<Option<Vec<f64>>> = vec![None; n];
    // nominal_m[s]: station s's largest error on the robot description.
    let mut nominal_m: Vec<f64> = vec![0.0; n];
    // kept_over[s]: a plant's failure on station s compile did not re-time
    // for (`slower` gives none), in words.
    let mut kept_over: Vec<Option<String>> = vec![None; n];
    // unfinished[si]: station s's last run on the description ended at a
    // plant's failure (`Checked::unfinished`).
    let mut unfinished: Vec<bool> = vec![false; n];
    // A fitted stop's job keeps its other stops as the job being fitted
    // timed and verified them (`Site::kept`): not simulated again.
    for (si, k, pace) in kept_stops(req, n, robot.basr().is_some()) {
        paces[si] = pace;
        let verdict = verify::Verdict {
            max_error_m: k.max_error_m,
            ok: true,
            why: String::new(),
            worst: (si as u32, -1),
            worst_t_s: 0.0,
            on_spread: false,
        };
        verdicts[si] = Some((paces[si].clone(), verdict));
        nominal_m[si] = k.max_error_m;
        on_spread[si] = (!k.plants_max_error_m.is_empty()).then(|| k.plants_max_error_m.clone());
        kept_over[si] = k.over.clone();
    }
    if let Some((si, pace)) = warm_pace(req, &tours) {
        paces[si] = pace;
    }
    // The paces of the last round whose motion met every limit, and, per
    // station, why its next re-timing was not taken: a slower join can
    // make a motion the robot's own check refuses (D at 12 ft: a join
    // into a stroke at 8 % of the accelerations carried the tilt's ball
    // nut 0.7 % past its speed). Such a station keeps its last pace, and
    // its failure is then treated as at the slowest re-timing.
    let mut good_paces: Option<Vec<trajectory::Pace>> = None;
    let mut not_taken: Vec<Option<String>> = vec![None; n];
    loop {
        let timed_rows = trajectory::time_law_paced(
            strokes,
            &plan,
            &paths,
            &robot,
            &trajectory::TimeLaw {
                period_s: req.period_s,
                gun_lead_s: req.gun_lead_s,
                gun_lag_s: req.gun_lag_s,
                pace: trajectory::Pace::FULL,
                joins: req.tuning.joins,
            },
            &paces,
            &mut cache,
        )
        .and_then(|timed| {
            let rows = station_rows(&plan, &timed, &robot, req.period_s);
            let notes = timed.notes.clone();
            let samples = samples::sample(&plan, &paths, timed, &robot, req.period_s)?;
            Ok((notes, rows, samples))
        });
        let (timed_notes, rows, samples) = match (timed_rows, &good_paces) {
            (Ok(t), _) => t,
            (Err(e), Some(good)) if *good != paces => {
                for si in 0..n {
                    if paces[si] != good[si] {
                        paces[si] = good[si].clone();
                        not_taken[si] = Some(match &e {
                            CompileError::Timing(why) => why.clone(),
                            other => other.to_string(),
                        });
                    }
                }
                continue;
            }
            (Err(e), _) => return Err(e),
        };
        good_paces = Some(paces.clone());
        let mut notes = strokes.notes.clone();
        notes.extend(tilt_note.iter().cloned());
        notes.extend(passes.notes.iter().cloned());
        notes.extend(timed_notes);
        let mut job = seal::assemble(Planned {
            marking,
            font,
            robot: robot.clone(),
            tilt,
            period_s: req.period_s,
            strokes,
            stations: plan.clone(),
            samples,
            balance: passes.balance.clone(),
            notes,
            options: req.recorded_options(),
            low_speed: req.overrides.low_speed,
        });
        if !req.verify {
            return with_film(req, job, strokes);
        }
        // Stations are independent once the arm is stowed: each is
        // simulated alone from the stow pose at rest, again only when its
        // pace changed, the stations in parallel.
        let stale: Vec<usize> = (0..n)
            .filter(|&si| !matches!(&verdicts[si], Some((p, _)) if *p == paces[si]))
            .collect();
        let skeleton = skeleton(&mut job);
        let last: Vec<(usize, Option<LastRun>)> =
            stale.iter().map(|&si| (si, runs[si].take())).collect();
        // A station verified alone leaves cores idle while its description
        // runs: it runs beside the plant set then, and the first failure
        // in time, the description's or a plant's, is re-timed for.
        // Stations verified together keep the cores busy already, and a
        // description that fails where the whole path is re-timed would
        // leave the set's runs beside it for nothing (200 letters: 34 s to
        // 39 s): each is verified on the description first. Which of the
        // two a round is decided by the job alone, never by the machine's
        // cores: the two can re-time a station's failures in another order
        // (markings/bus_only.toml), and a job's bytes are the same on every
        // machine (tests/core_count.rs).
        let beside = stale.len() == 1;
        let fresh: Vec<Result<Checked, CompileError>> = last
            .into_par_iter()
            .map(|(si, last)| {
                let rows = rows[si].clone();
                verify_station(
                    &job,
                    &skeleton,
                    rows,
                    req.period_s,
                    last,
                    req.retime_on_spread,
                    beside,
                )
            })
            .collect();
        for (si, c) in stale.into_iter().zip(fresh) {
            let c = c?;
            // A station that passed is not simulated again.
            runs[si] = c.run.filter(|_| !c.verdict.ok);
            on_spread[si] = c.on_spread;
            nominal_m[si] = c.nominal_m;
            unfinished[si] = c.unfinished;
            kept_over[si] = None;
            verdicts[si] = Some((paces[si].clone(), c.verdict));
        }
        let failing: Vec<(usize, &verify::Verdict)> = verdicts
            .iter()
            .enumerate()
            .filter_map(|(si, v)| v.as_ref().map(|(_, v)| (si, v)))
            .filter(|(_, v)| !v.ok)
            .collect();
        if failing.is_empty() {
            // The content checks `basr check` and `simulate` make of
            // every job: compile must not write one they refuse.
            verify::content(&job)?;
            job.summary.verified_max_error_m = nominal_m.iter().copied().reduce(f64::max);
            job.summary.verified = verified_on(&on_spread).map(|mut v| {
                v.over = kept_over.iter().flatten().next().cloned();
                v
            });
            // A plant kept over the bound is a notice the crew reads, not
            // only a figure in `summary.verified.over`.
            let arm: Vec<basr_plan::warnings::Note> = kept_over
                .iter()
                .enumerate()
                .filter_map(|(si, over)| {
                    over.as_ref().map(|text| basr_plan::warnings::Note::Arm {
                        text: format!("stop {}: {text}", si + 1),
                    })
                })
                .collect();
            job.summary
                .warnings
                .extend(basr_plan::warnings::render_all(&arm));
            job.summary.stops = (0..n)
                .map(|si| crate::job::StopTiming {
                    air_pace: paces[si].air,
                    path_pace: paces[si].path,
                    join_paces: paces[si].joins.clone(),
                    fly_in: paces[si].fly_in,
                    max_error_m: nominal_m[si],
                    plants_max_error_m: on_spread[si].clone().unwrap_or_default(),
                    over: kept_over[si].clone(),
                })
                .collect();
            return with_film(req, job, strokes);
        }
        let slowed: Vec<(usize, Option<trajectory::Pace>)> = failing
            .iter()
            .map(|&(si, v)| {
                if v.on_spread && !req.retime_on_spread {
                    return Ok((si, None));
                }
                if let Some(why) = &not_taken[si] {
                    return if v.on_spread {
                        Ok((si, None))
                    } else {
                        Err(CompileError::Timing(why.clone()))
                    };
                }
                let range = rows[si].clone();
                slower(
                    &paces[si],
                    v,
                    &paths,
                    &job.samples,
                    range,
                    &req.tuning.retime,
                )
                .map(|p| (si, p))
            })
            .collect::<Result<_, _>>()?;
        for (si, p) in slowed {
            match p {
                Some(p) => paces[si] = p,
                // A plant of the set that only the whole path's pace would
                // bring within the bound (or a shape's, not re-timed for
                // the set): the station is kept as it is and
                // `summary.verified` says how far that plant strays.
                None => {
                    // The description's run ended at the plant's failure:
                    // the rest of it first; failing, it is re-timed for
                    // in the next round as any description's failure.
                    if std::mem::take(&mut unfinished[si]) {
                        if let Some(last) = runs[si].take() {
                            let rows = rows[si].clone();
                            let (d, last) =
                                finish_description(&job, &skeleton, rows, req.period_s, last)?;
                            runs[si] = last;
                            nominal_m[si] = d.max_error_m;
                            if !d.ok {
                                verdicts[si] = Some((paces[si].clone(), d));
                                continue;
                            }
                        }
                    }
                    if let Some((_, v)) = verdicts[si].as_mut() {
                        kept_over[si] = Some(match &not_taken[si] {
                            Some(why) => format!(
                                "{}; not re-timed for it: the slower motion that would help breaks \
                                 a limit ({why})",
                                v.why
                            ),
                            None => format!(
                                "{}; not re-timed for it: only a slower path for the whole station \
                                 would help{}",
                                v.why,
                                if req.retime_on_spread {
                                    ""
                                } else {
                                    " (an imported shape is not re-timed for the set)"
                                }
                            ),
                        });
                        v.ok = true;
                    }
                    // The set ran in step, its other plants ended at the
                    // first one's failure: run them to the end, so that
                    // `summary.verified` has every plant's whole run.
                    if let Some(last) = runs[si].take().filter(|_| req.retime_on_spread) {
                        let rows = rows[si].clone();
                        if let Some(e) = whole_set(&job, &skeleton, rows, req.period_s, last)? {
                            on_spread[si] = Some(e);
                        }
                    }
                }
            }
        }
    }
}

/// The stops a fitted job keeps as the job being fitted timed and verified
/// them (`Site::kept`, every stop but the fitted one), when the request
/// verifies and the records fit this plan: one per station, each with the
/// figures of as many plants as this compile's set has (none for the
/// electric kinds: `on_spread`), finite errors and paces in (0, 1].
/// Otherwise none: every stop is verified again.
fn kept_stops(
    req: &CompileRequest,
    n: usize,
    on_spread: bool,
) -> Vec<(usize, &crate::job::StopTiming, trajectory::Pace)> {
    let Some(site) = req.site.as_ref() else {
        return vec![];
    };
    let plants = if on_spread {
        verify::spread::plants().len()
    } else {
        0
    };
    if !req.verify || site.kept.len() != n {
        return vec![];
    }
    // every record, or none
    let kept: Option<Vec<_>> = site
        .kept
        .iter()
        .enumerate()
        .map(|(si, k)| {
            let figures = k.plants_max_error_m.len() == plants
                && k.plants_max_error_m
                    .iter()
                    .chain([&k.max_error_m])
                    .all(|e| e.is_finite() && *e >= 0.0);
            figures.then(|| Some((si, k, pace_of(k)?))).flatten()
        })
        .collect();
    let mut kept = kept.unwrap_or_default();
    kept.retain(|(si, ..)| *si != site.fitted);
    kept
}

/// The pace a job recorded for a stop, when it is one (every share in
/// (0, 1]).
fn pace_of(k: &crate::job::StopTiming) -> Option<trajectory::Pace> {
    [k.air_pace, k.path_pace]
        .into_iter()
        .chain(k.join_paces.iter().map(|j| j.share))
        .all(|p| p > 0.0 && p <= 1.0)
        .then(|| trajectory::Pace {
            air: k.air_pace,
            path: k.path_pace,
            joins: k.join_paces.clone(),
            fly_in: k.fly_in,
        })
}

/// The pace a fitted stop's verification starts from, when it paints in
/// the job's order (`tours::tours`, `Tours::kept`): the one the job being fitted
/// found for it (`Site::kept`, [`pace_of`]); it is verified again all
/// the same. The same joins in the same order mostly need the same
/// slowing, which compile found in rounds of simulation; a pace slower
/// than the fitted pose needs costs the crew seconds, never the path.
fn warm_pace(req: &CompileRequest, tours: &tours::Tours) -> Option<(usize, trajectory::Pace)> {
    let site = req.site.as_ref()?;
    // a join is named by the stroke it enters, the move out of stow by the
    // first stroke: in another order they are other moves
    if tours.kept.get(site.fitted) != Some(&true) {
        return None;
    }
    Some((site.fitted, pace_of(site.kept.get(site.fitted)?)?))
}

/// Rounds of planning the passes again for the road's surface: each round
/// widens the heights kept clear by what the stations then found; the
/// stations move by centimetres at most between rounds, so the second
/// round already holds (one more is allowed).
const SURFACE_ROUNDS: usize = 3;

/// The marking's passes and the stations that paint them, on the road's
/// surface: on a flat road one round; on a sloped or fitted one the paint
/// law keeps clear the height by which the surface under the marking lies
/// below or above each station's base (`AnyRobot::on_uneven_road`), so
/// every planned height over the surface is one the vertical joint
/// reaches (docs/site.md).
fn passes_on_road(
    req: &CompileRequest,
    marking: &layout::Marking,
    strokes: &PlacedStrokes,
    robot: &crate::robot::AnyRobot,
    tilt: request::Tilt,
) -> Result<(passes::Passes, stations::StationPlan), CompileError> {
    // the tilt's share of its joint's acceleration, gentle where asked
    let tuning = req.planning_tuning();
    // the passes of the strokes `only` names under `planner`'s paint law
    let plan_for = |planner: &crate::robot::AnyRobot,
                    only: &(dyn Fn(usize) -> bool + Sync)|
     -> Result<passes::Passes, CompileError> {
        let rungs = rungs::rungs_of(
            strokes,
            req.rung_spacing_m,
            Some(&passes::turn_budget(planner, &tuning)),
            only,
        );
        // ends held in from edges the rungs meet obliquely, where asked
        let rungs = if req.hold_ends {
            let sigma = crate::robot::paint_law::SHEET_DEPTH_SIGMA_M;
            rungs::held(rungs, sigma * tuning.pairing.end_hold)
        } else {
            rungs
        };
        passes::passes_of(strokes, &rungs, planner, tilt.method(), &tuning, only)
    };
    let stations_for = |passes: &passes::Passes| -> Result<stations::StationPlan, CompileError> {
        // at the site, the job's stops as it grouped them
        let site = req.site.as_ref();
        if let Some(plan) = site.and_then(|s| basr_plan::site::job_stations(passes, s, robot)) {
            return Ok(plan);
        }
        let mut plan =
            stations::for_passes(passes, marking.lane_width_m, req.reach_margin_m, robot)?;
        match &req.site {
            None => plan.road = marking.road.clone(),
            Some(site) => {
                basr_plan::site::put_at_site(&mut plan, passes, site, robot, req.reach_margin_m)?
            }
        }
        Ok(plan)
    };
    let flat = plan_for(robot, &|_| true)?;
    let mut passes = flat.clone();
    let mut plan = stations_for(&passes)?;
    // Heights kept clear below and above at each station, and the strokes
    // they apply to: those over a surface that asks for it (the others
    // keep the flat plan). Each stroke is planned with its own stations'
    // band, so a fitted stop leaves the other stops as they were, however
    // its surface differs from theirs (STOP AHEAD: stop 2 fitted after
    // stop 1 planned stop 1's strokes again with stop 2's wider band).
    let mut kept: std::collections::BTreeMap<usize, [f64; 2]> = Default::default();
    // The largest excursions met, for the note.
    let mut seen = [0.0f64; 2];
    let mut uneven: std::collections::BTreeSet<usize> = Default::default();
    // the excursion left to the joints' clamp (`tuning::Surface`)
    let free = req.tuning.surface.clamp_free_m;
    let widest = |a: [f64; 2], b: [f64; 2]| [a[0].max(b[0]), a[1].max(b[1])];
    for _ in 0..SURFACE_ROUNDS {
        let need = surface_excursion(&plan, &passes, robot);
        let stations_of = stroke_stations(&plan, &passes);
        let mut grew = false;
        for (&stroke, &[below, above]) in &need {
            seen = widest(seen, [below, above]);
            let n = [below, above].map(|n| if n - free < 1e-6 { 0.0 } else { n - free });
            for &si in stations_of.get(&stroke).into_iter().flatten() {
                let k = kept.entry(si).or_default();
                if n[0] > k[0] || n[1] > k[1] {
                    *k = widest(*k, n);
                    grew = true;
                }
            }
            if n != [0.0, 0.0] {
                grew |= uneven.insert(stroke);
            }
        }
        if !grew {
            break;
        }
        // the uneven strokes by the band their stations keep clear
        let mut by_band: std::collections::BTreeMap<(u64, u64), Vec<usize>> = Default::default();
        for &stroke in &uneven {
            let band = stations_of
                .get(&stroke)
                .into_iter()
                .flatten()
                .filter_map(|si| kept.get(si))
                .fold([0.0; 2], |a, &b| widest(a, b));
            by_band
                .entry((band[0].to_bits(), band[1].to_bits()))
                .or_default()
                .push(stroke);
        }
        let mut next = flat.clone();
        for ((below, above), strokes_over) in &by_band {
            let planner = robot.on_uneven_road(f64::from_bits(*below), f64::from_bits(*above));
            let law = basr_robot::paint_law::paint_law(&planner);
            if law.max_height_m <= law.min_height_m {
                return Err(CompileError::Road(format!(
                    "the road under the marking lies up to {:.0} mm below and {:.0} mm above \
                     the plane the truck stands on: the vertical joint has no painting height \
                     left that reaches all of it; check the [road] crown line or the fitted \
                     points",
                    seen[0] * 1e3,
                    seen[1] * 1e3
                )));
            }
            // only these strokes are planned again
            let over = |s: usize| strokes_over.contains(&s);
            next = next.with_strokes_from(plan_for(&planner, &over)?, over);
        }
        passes = next;
        plan = stations_for(&passes)?;
    }
    let kept = kept.values().fold([0.0; 2], |a, &b| widest(a, b));
    if kept != [0.0, 0.0] {
        let flat_law = basr_robot::paint_law::paint_law(robot);
        let law = basr_robot::paint_law::paint_law(&robot.on_uneven_road(kept[0], kept[1]));
        passes.notes.push(basr_plan::warnings::Note::Surface {
            text: format!(
                "the road under {} of the {} strokes lies up to {:.0} mm below and {:.0} mm \
                 above the plane the truck stands on (a crown line, or the plane fit \
                 measured): there the nozzle paints between {:.0} and {:.0} mm over the road \
                 instead of {:.0} to {:.0} mm, so strokes narrower than its lowest fan get a \
                 wider one",
                uneven.len(),
                strokes.strokes.len(),
                seen[0] * 1e3,
                seen[1] * 1e3,
                law.min_height_m * 1e3,
                law.max_height_m * 1e3,
                flat_law.min_height_m * 1e3,
                flat_law.max_height_m * 1e3
            ),
        });
    }
    Ok((passes, plan))
}

/// The stations that paint each stroke's passes.
fn stroke_stations(
    plan: &stations::StationPlan,
    passes: &passes::Passes,
) -> std::collections::BTreeMap<usize, std::collections::BTreeSet<usize>> {
    let mut out: std::collections::BTreeMap<usize, std::collections::BTreeSet<usize>> =
        Default::default();
    for (pass, &si) in passes.passes.iter().zip(&plan.station_of) {
        out.entry(pass.stroke).or_default().insert(si);
    }
    out
}

/// How far (m) the surface under each stroke lies below and above the base
/// origin of the station painting it, with room for the nozzle's lean
/// against the slope (`Road::place` stands it h / cos α over the surface,
/// over a foot moved by h·sin α, and leans it α more); none on a flat road.
fn surface_excursion(
    plan: &stations::StationPlan,
    passes: &passes::Passes,
    robot: &crate::robot::AnyRobot,
) -> std::collections::BTreeMap<usize, [f64; 2]> {
    let mut out = std::collections::BTreeMap::new();
    if plan.road.is_flat() {
        return out;
    }
    for (pass, &si) in passes.passes.iter().zip(&plan.station_of) {
        let Some(st) = plan.stations.get(si) else {
            continue;
        };
        for k in &pass.knots {
            let p = [k.tip.x, k.tip.y];
            let z = plan.road.base_z(si, st, p);
            let g = plan.road.rise_along(si, st, p, k.yaw_rad).abs();
            // The tilt drive lifts the tip by more at the leaned tilt
            // where the kind's does (BASR's four-bar).
            let lift = match robot.tilt_limit() {
                Some(_) => (robot.tilt_lift_m(k.tilt_rad.abs() + g.atan())
                    - robot.tilt_lift_m(k.tilt_rad))
                .max(0.0),
                None => 0.0,
            };
            // h / cos α − h, and the surface's change over the foot's move.
            let lean = k.z_m * ((1.0 + g * g).sqrt() - 1.0) + k.z_m * g * g + lift;
            let e: &mut [f64; 2] = out.entry(pass.stroke).or_default();
            e[0] = e[0].max(-z + lean);
            e[1] = e[1].max(z + lean);
        }
    }
    out
}

/// The rows of each station's own motion in the job (after the truck's
/// drive to it, where the arm holds the stow pose).
fn station_rows(
    plan: &stations::StationPlan,
    timed: &trajectory::TimedTrajectory,
    robot: &crate::robot::AnyRobot,
    period_s: f64,
) -> Vec<std::ops::Range<usize>> {
    let mut at = 0usize;
    let mut out = Vec::with_capacity(timed.stations.len());
    for (si, t) in timed.stations.iter().enumerate() {
        if si > 0 {
            at += truck_rows(robot, &plan.stations[si - 1], &plan.stations[si], period_s);
        }
        out.push(at..at + t.len());
        at += t.len();
    }
    out
}

/// `job` without its samples, glyphs, warnings and balance: what a
/// station's rows are simulated in (a copy per station stays small).
fn skeleton(job: &mut Job) -> Job {
    let samples = std::mem::take(&mut job.samples);
    let glyphs = std::mem::take(&mut job.layout.glyphs);
    let warnings = std::mem::take(&mut job.summary.warnings);
    let balance = std::mem::take(&mut job.summary.balance);
    let skeleton = job.clone();
    job.samples = samples;
    job.layout.glyphs = glyphs;
    job.summary.warnings = warnings;
    job.summary.balance = balance;
    skeleton
}

/// The plant set's figures over the whole job (each plant's largest error
/// over the stations), when every station was run on it.
fn verified_on(on_spread: &[Option<Vec<f64>>]) -> Option<crate::job::VerifiedOn> {
    let per_station: Vec<&Vec<f64>> = on_spread
        .iter()
        .map(Option::as_ref)
        .collect::<Option<_>>()?;
    let first = per_station.first()?;
    let mut worst: Vec<f64> = (0..first.len())
        .map(|k| per_station.iter().map(|e| e[k]).fold(0.0, f64::max))
        .collect();
    worst.sort_by(f64::total_cmp);
    let max_error_m = *worst.last()?;
    Some(crate::job::VerifiedOn {
        plants: worst.len() as u32,
        spread: verify::spread::SPREAD,
        seed: verify::spread::SEED,
        p95_max_error_m: crate::sim::plants::quantile(&worst, 0.95),
        max_error_m,
        over: None,
    })
}

/// A station's verdict, its nominal run for the next, and (when it passed
/// on the robot description) each plant of the spread set's largest error.
struct Checked {
    verdict: verify::Verdict,
    run: Option<LastRun>,
    on_spread: Option<Vec<f64>>,
    /// The largest error on the robot description.
    nominal_m: f64,
    /// A plant failed first (`verify::Together::stopped`): the
    /// description's run ended early, `nominal_m` is of the run up to
    /// there, and the rest is run (`finish_description`) if the station is
    /// kept as it is.
    unfinished: bool,
}

/// A station's last simulated rows and its run's checkpoints, and the
/// plant set's last failed runs with the rows they ran: of the rows, those
/// that decide where the next run resumes ([`rows_that_matter`]).
struct LastRun {
    samples: crate::job::Samples,
    checkpoints: crate::sim::Checkpoints,
    plants: Option<(crate::job::Samples, Vec<crate::sim::Checkpoints>)>,
}

/// The first rows of `samples` that decide where a run resumes from any of
/// `runs` (`Checkpoints::rows_that_matter`): the next round compares its
/// rows with these. A run cut short early (most stations' first round
/// fails a second or two in) keeps a few rows, not its station's whole
/// copy (a long job's kept copies were a fifth of compile's memory).
fn rows_that_matter<'a>(
    samples: &crate::job::Samples,
    runs: impl IntoIterator<Item = &'a crate::sim::Checkpoints>,
) -> crate::job::Samples {
    let n = runs
        .into_iter()
        .map(crate::sim::Checkpoints::rows_that_matter)
        .max()
        .unwrap_or(0)
        .min(samples.len());
    samples.rows(0..n)
}

/// Station `rows` of `job` simulated alone (from the stow pose at rest, as
/// the arm waits after the truck's drive), in a copy of `skeleton`; judged
/// in job time. With the station's `last` run, the run resumes at its last
/// checkpoint before the first row that changed since (a re-timed join or
/// move leaves the rows before it as they were); the verdict is a whole
/// run's either way. A station that passes is then run on the plant set
/// (`verify::on_spread`), whose failure fails it where that plant first
/// strayed. Returns the verdict and this nominal run, for the next.
/// `in_step`: the set's plants end soon after the first of them fails
/// (`verify::on_spread`), where compile re-times for the set; with
/// `beside`, the set then runs beside the description (`verify_together`):
/// the same verdict, sooner on idle cores.
fn verify_station(
    job: &Job,
    skeleton: &Job,
    rows: std::ops::Range<usize>,
    period_s: f64,
    last: Option<LastRun>,
    in_step: bool,
    beside: bool,
) -> Result<Checked, CompileError> {
    let (alone, t0_s) = station_alone(job, skeleton, rows, period_s);
    let (resume, mut plants) = match last {
        Some(l) => (
            Some((l.checkpoints, alone.samples.first_difference(&l.samples))),
            l.plants,
        ),
        None => (None, None),
    };
    if let (true, Some(robot)) = (in_step && beside, alone.robot.basr()) {
        let set_resume = plants.map(|(rows, cps)| (cps, alone.samples.first_difference(&rows)));
        let together = verify::together(&alone, robot, t0_s, resume, set_resume)?;
        return Ok(checked_together(alone, together));
    }
    let (mut verdict, kept) = verify::simulated_resuming(&alone, t0_s, resume)?;
    let nominal_m = verdict.max_error_m;
    let mut on_spread = None;
    if verdict.ok {
        let resume = plants
            .take()
            .map(|(rows, cps)| (cps, alone.samples.first_difference(&rows)));
        if let Some(set) = verify::on_spread(&alone, t0_s, resume, in_step)? {
            on_spread = Some(set.errors);
            if !set.verdict.ok {
                verdict = set.verdict;
                plants = Some((rows_that_matter(&alone.samples, &set.kept), set.kept));
            }
        }
    }
    let run = kept.map(|checkpoints| LastRun {
        samples: rows_that_matter(&alone.samples, [&checkpoints]),
        checkpoints,
        plants,
    });
    Ok(Checked {
        verdict,
        run,
        on_spread,
        nominal_m,
        unfinished: false,
    })
}

/// [`verify_station`]'s result from the station `alone` run on the robot
/// description and the plant set at once (`verify::together`): the same
/// verdict as the description's run first and the set's after it passed;
/// the set's runs are kept whenever they ran (a round the description
/// failed included), so the next round resumes them where the rows first
/// changed.
fn checked_together(alone: Job, t: verify::Together) -> Checked {
    let mut verdict = t.verdict;
    let nominal_m = verdict.max_error_m;
    let mut on_spread = None;
    let kept_set = match t.set {
        // A plant failed first (`t.stopped`): the set's verdict, whatever
        // the description's run said after it.
        Ok(set) if verdict.ok || t.stopped => {
            on_spread = Some(set.errors);
            if set.verdict.ok {
                None
            } else {
                verdict = set.verdict;
                Some(set.kept)
            }
        }
        // the description failed: the set's runs wait for the next round
        Ok(set) => Some(set.kept),
        Err(kept) => Some(kept),
    };
    let plants = kept_set
        .filter(|cps| !cps.is_empty())
        .map(|cps| (rows_that_matter(&alone.samples, &cps), cps));
    Checked {
        verdict,
        run: Some(LastRun {
            samples: rows_that_matter(&alone.samples, [&t.kept]),
            checkpoints: t.kept,
            plants,
        }),
        on_spread,
        nominal_m,
        unfinished: t.stopped,
    }
}

/// Station `rows` of `job` alone, in a copy of `skeleton`, and the job
/// time its first row is at (its runs report in job time).
fn station_alone(
    job: &Job,
    skeleton: &Job,
    rows: std::ops::Range<usize>,
    period_s: f64,
) -> (Job, f64) {
    let t0_s = rows.start as f64 * period_s;
    let mut alone = skeleton.clone();
    alone.samples = job.samples.rows(rows);
    (alone, t0_s)
}

/// Each plant's largest error over the whole station (`rows` of `job`),
/// from `last`, the set's runs in step that ended at its first failure:
/// each resumes at its last checkpoint and runs to its end or to its own
/// failure (`None` where the set did not run).
fn whole_set(
    job: &Job,
    skeleton: &Job,
    rows: std::ops::Range<usize>,
    period_s: f64,
    last: LastRun,
) -> Result<Option<Vec<f64>>, CompileError> {
    let Some((samples, checkpoints)) = last.plants else {
        return Ok(None);
    };
    let (alone, t0_s) = station_alone(job, skeleton, rows, period_s);
    let first = alone.samples.first_difference(&samples);
    Ok(verify::on_spread(&alone, t0_s, Some((checkpoints, first)), false)?.map(|s| s.errors))
}

/// The verdict of the description's whole run on station `rows` of `job`,
/// from `last` (a run a plant's failure ended first, the rows unchanged
/// since): run on from its last checkpoint; `last` with this run's
/// checkpoints, for the next round to resume from (none for a kind
/// without them).
fn finish_description(
    job: &Job,
    skeleton: &Job,
    rows: std::ops::Range<usize>,
    period_s: f64,
    last: LastRun,
) -> Result<(verify::Verdict, Option<LastRun>), CompileError> {
    let (alone, t0_s) = station_alone(job, skeleton, rows, period_s);
    let end = alone.samples.len();
    let (verdict, kept) = verify::simulated_resuming(&alone, t0_s, Some((last.checkpoints, end)))?;
    let last = kept.map(|kept| LastRun {
        samples: rows_that_matter(&alone.samples, [&kept]),
        checkpoints: kept,
        plants: last.plants,
    });
    Ok((verdict, last))
}

/// The station's pace after `verdict` (a failed one): slow where the arm
/// fell behind: the move out of stow when the worst error is in the
/// station's first pass (the first stroke's, entered from stow); else the
/// join into the pass of the worst stroke where the arm arrives behind at
/// its first rungs (a wide stroke's later pass is entered by a join, even
/// on the station's first stroke; every pass of the stroke where the rows
/// do not tell which, `late_pass`); else the strokes' path. A plant of
/// the spread set does not slow the whole path (`None`): on STOP
/// at full reach and the arrow shape at 3 m that cost the film, turning
/// an even job into a NOT READY one for a plant that strays by tenths of a
/// millimetre. `rows`: the station's rows in `samples`.
fn slower(
    pace: &trajectory::Pace,
    verdict: &verify::Verdict,
    paths: &joints::JointPaths,
    samples: &crate::job::Samples,
    rows: std::ops::Range<usize>,
    retime: &basr_plan::tuning::Retime,
) -> Result<Option<trajectory::Pace>, CompileError> {
    let &basr_plan::tuning::Retime {
        arrival_s,
        pace_step,
        min_pace,
    } = retime;
    let mut pace = pace.clone();
    let (si, stroke) = verdict.worst;
    let first_of = |si: u32, stroke: i64| {
        paths
            .stations
            .get(si as usize)
            .and_then(|r| r.first())
            .is_some_and(|r| r.stroke as i64 == stroke)
    };
    // When the gun opened for the pass the worst error is in, and whether
    // that is the station's first pass, the one flown into from stow.
    let pass_start = paint_start(samples, rows.clone(), stroke, verdict.worst_t_s);
    let first_pass = first_of(si, stroke)
        && pass_start.is_some_and(|t0| {
            rows.clone()
                .find(|&i| samples.paint[i] == 1)
                .is_some_and(|i| samples.t_s[i] == t0)
        });
    let after_stow = first_pass && pace.air > min_pace;
    let mut joins_slowed = false;
    // The join into the worst stroke, where the arm arrives behind at the
    // first rungs of a pass (a verification run ends at its first failure,
    // so the worst is that one; a later stroke's is seen once it is fixed).
    let arrival = !after_stow
        && !first_pass
        && pass_start.is_some_and(|t0| verdict.worst_t_s - t0 < arrival_s);
    if arrival {
        // that pass's join alone where the rows tell which pass it is
        let pass = pass_start.and_then(|t0| {
            let runs = paths.stations.get(si as usize)?;
            late_pass(samples, rows.clone(), stroke, t0, runs)
        });
        let named = |j: &basr_job::JoinPace| j.stroke as i64 == stroke && j.pass == pass;
        match pace.joins.iter().position(named) {
            Some(k) if pace.joins[k].share > min_pace => {
                pace.joins[k].share *= pace_step;
                joins_slowed = true;
            }
            Some(_) => {}
            None => {
                pace.joins.push(basr_job::JoinPace {
                    stroke: stroke as usize,
                    share: pace_step,
                    pass,
                });
                joins_slowed = true;
            }
        }
    }
    if after_stow && pace.fly_in {
        pace.fly_in = false;
    } else if after_stow {
        pace.air *= pace_step;
    } else if joins_slowed {
    } else if verdict.on_spread {
        return Ok(None);
    } else if pace.path > min_pace {
        pace.path *= pace_step;
    } else {
        return Err(CompileError::NotFollowed {
            pace: pace.path * 100.0,
            why: verdict.why.clone(),
        });
    }
    Ok(Some(pace))
}

/// Which pass of `stroke` (0 the first painted) the gun opened for at
/// `t0_s` in the station's `rows`, where the stroke has more than one of
/// the station's `runs` and its rows' painting stretches are its runs, one
/// each (a pass painted on from the last without closing the gun, or one
/// the gun closes within, leaves it unknown: None, as for a stroke of one
/// pass, whose joins are all its).
fn late_pass(
    s: &crate::job::Samples,
    rows: std::ops::Range<usize>,
    stroke: i64,
    t0_s: f64,
    runs: &[joints::Run],
) -> Option<usize> {
    let passes = runs.iter().filter(|r| r.stroke as i64 == stroke).count();
    let painting = |i: usize| s.stroke[i] == stroke && s.paint[i] == 1;
    let starts: Vec<f64> = rows
        .clone()
        .filter(|&i| painting(i) && (i == rows.start || !painting(i - 1)))
        .map(|i| s.t_s[i])
        .collect();
    (passes > 1 && starts.len() == passes)
        .then(|| starts.iter().position(|&t| t == t0_s))
        .flatten()
}

/// The job with its film measured (`plan::film`, when `req.film`): the
/// figures in `summary.film` and a problem per failed bound, sealed (once:
/// sealing serialises the whole job to hash it).
fn with_film(
    req: &CompileRequest,
    mut job: Job,
    strokes: &PlacedStrokes,
) -> Result<PlannedJob, CompileError> {
    let mut items_over = vec![];
    if req.film {
        let owners: Vec<_> = strokes.items.iter().map(|it| it.owner.clone()).collect();
        let checked = film::check(&job, &owners)?;
        job.summary
            .warnings
            .extend(basr_plan::warnings::render_all(&checked.notes));
        job.summary.film = Some(checked.summary);
        items_over = checked.items_over;
    }
    job.seal();
    Ok(PlannedJob { job, items_over })
}

/// When the gun opened for the pass of `stroke` that paints at `t_s` (a
/// wide stroke is painted in passes, each its own arrival), within `rows`.
fn paint_start(
    s: &crate::job::Samples,
    rows: std::ops::Range<usize>,
    stroke: i64,
    t_s: f64,
) -> Option<f64> {
    let painting = |i: usize| s.stroke[i] == stroke && s.paint[i] == 1;
    // Row times are rounded to the nanosecond, job times of ticks are not.
    let at = rows
        .clone()
        .rev()
        .find(|&i| s.t_s[i] <= t_s + 1e-9 && painting(i))?;
    let first = (rows.start..=at)
        .rev()
        .take_while(|&i| painting(i))
        .last()?;
    Some(s.t_s[first])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_verified_set_is_each_plants_worst_over_the_stations() {
        let a = vec![1e-3, 2e-3, 3e-3, 1e-3, 1e-3, 1e-3];
        let b = vec![4e-3, 1e-3, 1e-3, 1e-3, 1e-3, 2e-3];
        let v = verified_on(&[Some(a.clone()), Some(b)]).unwrap();
        assert_eq!(v.plants, 6);
        assert_eq!(
            (v.spread, v.seed),
            (verify::spread::SPREAD, verify::spread::SEED)
        );
        // plant 0's worst is station 1's 4 mm; with six plants the 95th
        // percentile (nearest rank) is the worst
        assert_eq!(v.max_error_m, 4e-3);
        assert_eq!(v.p95_max_error_m, 4e-3);
        // a station not run on the set (an electric kind) records none
        assert_eq!(verified_on(&[Some(a), None]), None);
        assert_eq!(verified_on(&[]), None);
    }

    /// The pass the arm arrived late at is told by the gun's openings of
    /// its stroke, where they are its runs one each; else none is named
    /// (the verification then slows every join into the stroke).
    #[test]
    fn the_late_pass_is_the_gun_s_opening_for_it() {
        use crate::job::{SampleRow, Samples};
        // (stroke, paint) per row, 0.1 s apart: stroke 3 in three stretches
        // with stroke 5 between, the station's rows from row 1
        let rows = [
            (-1, 0),
            (3, 1),
            (3, 1),
            (3, 0),
            (5, 1),
            (3, 1),
            (3, 0),
            (3, 1),
            (3, 1),
            (-1, 0),
        ];
        let mut s = Samples::default();
        for (i, &(stroke, paint)) in rows.iter().enumerate() {
            s.push(&SampleRow {
                t_s: 0.1 * i as f64,
                stroke,
                paint,
                ..Default::default()
            });
        }
        let run = |stroke| joints::Run {
            stroke,
            knots: vec![],
            joints: vec![],
            paint_first: 0,
            paint_last: 0,
        };
        let runs = [run(3), run(5), run(3), run(3)];
        // the pass whose stretch starts at row i
        let at = |i: usize, runs: &[joints::Run]| late_pass(&s, 1..rows.len(), 3, s.t_s[i], runs);
        assert_eq!(at(1, &runs), Some(0));
        assert_eq!(at(5, &runs), Some(1));
        assert_eq!(at(7, &runs), Some(2));
        // not a time the gun opened for stroke 3
        assert_eq!(at(2, &runs), None);
        // two runs painted in three stretches, or four in three: unknown
        assert_eq!(at(5, &runs[..3]), None);
        assert_eq!(at(5, &[run(3), run(3), run(3), run(3)]), None);
        // a stroke of one pass: its joins are all its
        let one = late_pass(&s, 4..6, 5, s.t_s[4], &runs);
        assert_eq!(one, None);
    }

    /// `req` as `job` was planned: its robot with the tip compile chose,
    /// its tilt method and options.
    fn as_planned(req: &CompileRequest, job: &Job) -> CompileRequest {
        let mut r = req.clone().with_options(job.layout.options.as_ref());
        r.tilt = request::Tilt::of_job(&job.layout.tilt_method);
        r.tilt_named = true;
        r.robot_description = Some(job.robot.clone());
        r
    }

    /// The least air time each stop of `job` could be flown in
    /// (`joints::air_floor`), its passes planned as the job's were from
    /// `req`, and the passes per stop.
    fn air_floors(req: &CompileRequest, job: &Job) -> (Vec<usize>, Vec<joints::AirFloor>) {
        let r = as_planned(req, job);
        let inputs = basr_plan::inputs::read(&r).expect("inputs");
        let (marking, strokes) = super::super::placed::lay_out(&r, &inputs.font).expect("laid out");
        let robot = inputs.robot;
        assert_eq!(
            robot.paint().mounted,
            job.paint.tip,
            "the job's robot carries its tip"
        );
        let (tilt, _) = request::tilt_for(r.tilt, &robot);
        let (passes, plan) = passes_on_road(&r, &marking, &strokes, &robot, tilt).expect("passes");
        let tours = tours::tours(&passes, &plan, &robot, &[], r.gun_lead_s.max(r.gun_lag_s));
        let floors = joints::air_floor(&strokes, &passes, &plan, &tours, &robot, &r.tuning.joins)
            .expect("solved");
        (tours.stations.iter().map(|t| t.len()).collect(), floors)
    }

    /// How far words' air moves are from the least the arm's limits allow
    /// (docs/planner.md, "How far the air time is from its floor"), and
    /// how much of them the verification's re-timing adds (the same plan
    /// compiled without it). An experiment, not a check of compile: each
    /// stop's floor is a search over the orders of its passes (seconds in
    /// a release build).
    /// `cargo test --release -p basr --lib -- --ignored air_floor --nocapture`
    #[test]
    #[ignore = "an experiment, seconds per word in release: run with --ignored"]
    fn air_floor_of_stop_and_school() {
        const FT: f64 = 0.3048;
        for (text, ft, lane_ft) in [
            ("STOP", 6.0, None),
            ("STOP", 8.0, None),
            ("STOP", 10.0, None),
            ("SCHOOL", 6.0, None),
            ("SCHOOL", 8.0, None),
            ("SCHOOL", 10.0, Some(24.0)),
            ("SCHOOL XING", 6.0, None),
            ("SCHOOL XING", 8.0, None),
            ("SCHOOL XING", 10.0, Some(24.0)),
        ] {
            let mut req = CompileRequest::message(text);
            req.overrides.letter_height_m = Some(ft * FT);
            req.overrides.lane_width_m = lane_ft.map(|w: f64| w * FT);
            let job = super::super::compile::compile_job(&req).expect("compiles");
            let (counts, floors) = air_floors(&req, &job);
            let unverified = super::super::compile::compile_job(&CompileRequest {
                verify: false,
                ..as_planned(&req, &job)
            })
            .expect("compiles");
            let s = &job.summary;
            let truck: f64 = s
                .truck_moves_m
                .iter()
                .filter(|d| **d > 0.0)
                .map(|d| d / job.robot.truck().speed_mps + job.robot.truck().settle_s)
                .fold(0.0, |a, t| a + t);
            let floor: f64 = floors.iter().map(|f| f.s).sum();
            let least = (s.paint_time_s + floor + truck) / s.lower_bound_s;
            let each: Vec<String> = floors
                .iter()
                .zip(&counts)
                .map(|(f, n)| {
                    let how = if f.exact { "" } else { " (assignment)" };
                    format!("{:.2} s over {n} passes{how}", f.s)
                })
                .collect();
            let lane = lane_ft.map_or(String::new(), |w| format!(" on a {w} ft lane"));
            println!(
                "{text} at {ft} ft{lane}, tip {}: air {:.2} s ({:.2} s unverified), of it truck \
                 {truck:.2} s; air floor {}; bound ratio {:.3}, at the floor {least:.3}",
                job.paint.tip.as_deref().unwrap_or("-"),
                s.air_time_s,
                unverified.summary.air_time_s,
                each.join("; "),
                s.bound_ratio,
            );
        }
    }
}
