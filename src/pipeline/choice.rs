//! The planner's choices for a marking: the spray tip the robot carries
//! that paints it, the gentle tilt and the tilt method, each tried only
//! where the job before it has problems ([`compile_strokes`]); each job is
//! planned by `planned_job::compile_for_tip`.

use crate::job::Job;
use crate::layout;

use super::planned_job::{compile_for_tip, Placed};
use basr_plan::error::CompileError;
use basr_plan::placed::PlacedStrokes;
use basr_plan::request::{CompileRequest, Tilt};

/// The planner proper, from placed strokes on: what a scene of symbols,
/// words or shapes calls once it has placed its strokes.
///
/// A robot listing tips (`[[paint.tip]]`) is planned with the first; when
/// that job has problems, with each other tip in turn, and the first tip
/// whose job has none is chosen (the job records it in `paint.tip` and
/// its robot's `paint.mounted`). When no tip paints it without problems
/// the first tip's job is kept: its notes name the tip. A robot whose tip
/// is mounted already is planned with that tip alone.
///
/// A job that has problems so is planned again with a gentler tilt
/// (`CompileRequest::gentle_tilt`: a smaller share of the tilt joint's
/// acceleration, `tuning::Rates::gentle_tilt_acc_share`), first without
/// the closed loop as another tip is; the gentle job is kept when it has
/// none (it records `options.gentle_tilt`). Small letters' bowls ask the
/// tilt for more acceleration than the time law then gives, and the
/// slowed nozzle lays a heavy film there; a job that paints with the
/// default share keeps it (a gentler tilt slows some 8 ft tails instead).
/// Not at the site: `basr fit` plans as the job being fitted was planned.
///
/// A job that still has problems, its tilt method not named
/// (`CompileRequest::tilt_named`), is planned all over again with the
/// trapezoid method on a robot that tilts, first without the closed loop;
/// that job is kept when it has none (it records `layout.tilt_method`).
/// The quadrilateral method leans the fan along a curve's rungs to match
/// its inner and outer edges; on the smallest letters' tightest bowl that
/// lean asks more of the tilt than the trapezoid's does (Q at 6 ft with
/// the 509 tip, gently: cv 0.098 against 0.048, docs/planner.md).
///
/// A job that has problems still is planned once more with its rungs'
/// ends held in from edges they meet obliquely (`CompileRequest::
/// hold_ends`, `rungs::held`), with the request's tilt method, tips and
/// gentle tilt as before; that job is kept when it has none (it records
/// `options.hold_ends`). The fan sheet's depth carries paint across such
/// an edge, a band that does not shrink with the letter: C, G and J at 6
/// ft lay 3.1–3.2 % of their paint outside, over the 3 % bound.
pub fn compile_strokes(
    req: &CompileRequest,
    marking: &layout::Marking,
    font: &crate::font::Font,
    robot: crate::robot::AnyRobot,
    strokes: &PlacedStrokes,
) -> Result<Job, CompileError> {
    let placed = Placed {
        marking,
        font,
        strokes,
    };
    let plan = |r: &CompileRequest| compile_gently(r, placed, &robot);
    let trapezoid = (req.tilt == Tilt::Quadrilateral
        && !req.tilt_named
        && req.site.is_none()
        && robot.tilt_limit().is_some())
    .then(|| CompileRequest {
        tilt: Tilt::Trapezoid,
        tilt_named: true,
        ..req.clone()
    });
    let job = or_one_that_paints(plan(req)?, trapezoid, plan);
    let held = (!req.hold_ends && req.site.is_none()).then(|| CompileRequest {
        hold_ends: true,
        ..req.clone()
    });
    Ok(or_one_that_paints(job, held, plan))
}

/// [`compile_tips`], and again with a gentle tilt where that has problems
/// ([`compile_strokes`]).
fn compile_gently(
    req: &CompileRequest,
    placed: Placed,
    robot: &crate::robot::AnyRobot,
) -> Result<Job, CompileError> {
    let plan = |r: &CompileRequest| compile_tips(r, placed, robot.clone());
    let gentle = (!req.gentle_tilt && req.site.is_none()).then(|| CompileRequest {
        gentle_tilt: true,
        ..req.clone()
    });
    Ok(or_one_that_paints(plan(req)?, gentle, plan))
}

/// `job` when it has no problems; else the job `plan` makes of `other`
/// when that has none (`if_it_paints`); else `job`.
fn or_one_that_paints(
    job: Job,
    other: Option<CompileRequest>,
    plan: impl Fn(&CompileRequest) -> Result<Job, CompileError>,
) -> Job {
    if problems(&job) == 0 {
        return job;
    }
    other.and_then(|r| if_it_paints(&r, plan)).unwrap_or(job)
}

/// The job `plan` makes of `req` when it has no problems, else `None`.
/// Where `req` verifies, it is first planned without the closed loop: a
/// plan that already has problems (its film, its strokes against its fan)
/// is no choice, and is not verified (STOP at 6 ft once verified all three
/// tips it had: 3.4 s of a NOT READY compile). Verification only slows a
/// job (gentler accelerations, and slower speeds where a joint's limit
/// binds), and is taken not to take a planned problem away; were it ever
/// to, a choice would be passed over that a verified compile would have
/// kept: the cautious side. A request that cannot be planned at all (a fan
/// too wide for every stroke) is no choice either, nor is a job one of
/// whose items (a letter, a symbol) misses a film bound on its own
/// (`film::items_over`), where the request measures the film.
fn if_it_paints(
    req: &CompileRequest,
    plan: impl Fn(&CompileRequest) -> Result<Job, CompileError>,
) -> Option<Job> {
    let each = |j: &Job| !req.film || super::film::items_over(j).is_ok_and(|o| o.is_empty());
    let paints = |job: Result<Job, CompileError>| job.ok().filter(|j| problems(j) == 0 && each(j));
    if req.verify {
        let planned = CompileRequest {
            verify: false,
            ..req.clone()
        };
        paints(plan(&planned))?;
    }
    paints(plan(req))
}

/// [`compile_strokes`] with the request's tilt as it is: each tip the
/// robot carries, in turn (below).
fn compile_tips(
    req: &CompileRequest,
    placed: Placed,
    robot: crate::robot::AnyRobot,
) -> Result<Job, CompileError> {
    // A robot with its tip already mounted (a job's own, planned again by
    // `basr fit` or `preview --compare`) keeps that tip: the crew has it on
    // the gun, and the job's other stops were painted with it.
    let tips = match &robot.paint().mounted {
        None => robot.paint().tips.clone(),
        Some(_) => vec![],
    };
    let Some((first, others)) = tips.split_first() else {
        return compile_for_tip(req, placed, robot);
    };
    let mounted = |tip: &crate::robot::Tip| {
        let mut r = robot.clone();
        let p = r.paint_mut();
        *p = p.with_tip(tip);
        r
    };
    let preferred = compile_for_tip(req, placed, mounted(first))?;
    if problems(&preferred) == 0 {
        return Ok(preferred);
    }
    // Another tip, each in turn (`if_it_paints`); the first that paints is
    // chosen, else the preferred tip's job stands.
    let other = others
        .iter()
        .find_map(|tip| if_it_paints(req, |r| compile_for_tip(r, placed, mounted(tip))));
    Ok(other.unwrap_or(preferred))
}

/// The job's problems: what makes it NOT READY.
fn problems(job: &Job) -> usize {
    job.summary
        .warnings
        .iter()
        .filter(|w| w.graded() == crate::job::Severity::Problem)
        .count()
}
