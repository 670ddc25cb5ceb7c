//! The compile pipeline, stage by stage: inputs → layout → placed strokes →
//! rungs → knots and passes → stations → tours → joint paths → timed
//! trajectory → samples → sealed job → verified → its film checked. Each stage is one function in a
//! module named for the value it returns.

use crate::job::Job;
use crate::layout;

use super::placed::lay_out;
use super::{film, verify};
use basr_plan::placed::PlacedStrokes;
use basr_plan::seal::{seal, Planned};
use basr_plan::{inputs, joints, passes, request, rungs, samples, stations, tours, trajectory};

pub use basr_plan::error::CompileError;
pub use basr_plan::request::{
    CompileRequest, Source, Tilt, DEFAULT_PERIOD_S, DEFAULT_RUNG_SPACING_M,
};

/// Compile a message or marking into a sealed job.
pub fn compile_job(req: &CompileRequest) -> Result<Job, CompileError> {
    request::check_settings(req)?;
    let inputs::Inputs { robot, font } = inputs::read(req)?;
    let (marking, strokes) = lay_out(req, &font)?;
    compile_strokes(req, &marking, &font, robot, &strokes)
}

/// The planner proper, from placed strokes on: what a scene of symbols,
/// words or shapes calls once it has placed its strokes.
pub fn compile_strokes(
    req: &CompileRequest,
    marking: &layout::Marking,
    font: &crate::font::Font,
    robot: crate::robot::AnyRobot,
    strokes: &PlacedStrokes,
) -> Result<Job, CompileError> {
    let rungs = rungs::rungs(
        strokes,
        req.rung_spacing_m,
        Some(&passes::turn_budget(&robot)),
    );
    let (tilt, tilt_note) = request::tilt_for(req.tilt, &robot);
    let passes = passes::passes(strokes, &rungs, &robot, tilt.method())?;
    let plan = stations::for_passes(&passes, marking.lane_width_m, req.reach_margin_m, &robot)?;
    let tours = tours::tours(&passes, &plan, &robot);
    let paths = joints::joint_paths(strokes, &passes, &plan, &tours, &robot)?;
    let mut pace = trajectory::Pace::FULL;
    loop {
        let timed = trajectory::time_law(
            strokes,
            &plan,
            &paths,
            &robot,
            &trajectory::TimeLaw {
                period_s: req.period_s,
                gun_lead_s: req.gun_lead_s,
                gun_lag_s: req.gun_lag_s,
                pace: pace.clone(),
            },
        )?;
        let mut notes = strokes.notes.clone();
        notes.extend(tilt_note.iter().cloned());
        notes.extend(passes.notes.iter().cloned());
        notes.extend(timed.notes.iter().cloned());
        let samples = samples::sample(&plan, &paths, timed, &robot, req.period_s)?;
        let mut job = seal(Planned {
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
        });
        if !req.verify {
            return with_film(req, job, strokes);
        }
        let verdict = verify::verify(&job)?;
        if verdict.ok {
            job.summary.verified_max_error_m = Some(verdict.max_error_m);
            return with_film(req, job, strokes);
        }
        // Slow where the arm fell behind: the move out of stow when the
        // worst error is on a station's first stroke; else the joins into
        // the strokes alone where the arm arrives behind at their first
        // rungs (every such stroke at once); else the strokes' path.
        let (si, stroke) = verdict.worst;
        let first_of = |si: u32, stroke: i64| {
            paths
                .stations
                .get(si as usize)
                .and_then(|r| r.first())
                .is_some_and(|r| r.stroke as i64 == stroke)
        };
        let after_stow = first_of(si, stroke) && pace.air > MIN_PACE;
        let mut joins_slowed = false;
        if !after_stow {
            // The worst stroke first; others over the bound only if far
            // over it (the hydraulic supply couples them: slowing one often
            // brings the others in).
            let far = FAR_OVER * verify::VERIFY_SHARE * crate::sim::Options::default().tolerance_m;
            let worst = (si, stroke, verdict.worst_t_s);
            let others = verdict.failing.iter().filter(|f| f.stroke != stroke);
            let others = others.filter(|f| f.error_m > far);
            for (fs, fstroke, ft) in
                std::iter::once(worst).chain(others.map(|f| (f.station, f.stroke, f.t_s)))
            {
                let arrival = !first_of(fs, fstroke)
                    && paint_start(&job, fstroke).is_some_and(|t0| ft - t0 < ARRIVAL_S);
                if !arrival {
                    continue;
                }
                match pace.joins.iter().position(|(s, _)| *s as i64 == fstroke) {
                    Some(k) if pace.joins[k].1 > MIN_PACE => {
                        pace.joins[k].1 *= PACE_STEP;
                        joins_slowed = true;
                    }
                    Some(_) => {}
                    None => {
                        pace.joins.push((fstroke as usize, PACE_STEP));
                        joins_slowed = true;
                    }
                }
            }
        }
        if after_stow && pace.fly_in {
            pace.fly_in = false;
        } else if after_stow {
            pace.air *= PACE_STEP;
        } else if joins_slowed {
            continue;
        } else if pace.path > MIN_PACE {
            pace.path *= PACE_STEP;
        } else {
            return Err(CompileError::NotFollowed {
                pace: pace.path * 100.0,
                why: verdict.why,
            });
        }
    }
}

/// The job with its film measured (`plan::film`, when `req.film`): the
/// figures in `summary.film` and a problem per failed bound, resealed.
fn with_film(
    req: &CompileRequest,
    mut job: Job,
    strokes: &PlacedStrokes,
) -> Result<Job, CompileError> {
    if req.film {
        let owners: Vec<_> = strokes.items.iter().map(|it| it.owner.clone()).collect();
        let checked = film::check(&job, &owners)?;
        job.summary
            .warnings
            .extend(basr_plan::warnings::render_all(&checked.notes));
        job.summary.film = Some(checked.summary);
    }
    job.seal();
    Ok(job)
}

/// Job time at which stroke `stroke` starts painting.
fn paint_start(job: &Job, stroke: i64) -> Option<f64> {
    let s = &job.samples;
    (0..s.stroke.len())
        .find(|&i| s.stroke[i] == stroke && s.paint[i] == 1)
        .map(|i| s.t_s[i])
}

/// An error this soon after a stroke starts painting is the join's into
/// it (s). assumed: about the hydraulic arm's settling after a fast join
/// (the verified errors sit within 0.1 s of the first rung).
const ARRIVAL_S: f64 = 1.0;

/// A stroke's error this many times the verified bound has its join slowed
/// in the same round as the worst. assumed: 1.3, where one round of the
/// worst's alone has not brought STOP's or SCHOOL's others in.
const FAR_OVER: f64 = 1.3;

/// Each re-timing uses this share of the last one's accelerations.
/// assumed: a few steps reach `MIN_PACE` while each still gains.
const PACE_STEP: f64 = 0.6;
/// Slowest re-timing tried before the job is refused (share of the limits).
const MIN_PACE: f64 = 0.1;
