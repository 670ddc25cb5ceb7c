//! The planner's choices for a marking: the spray tip the robot carries
//! that paints it, the gentle tilt and the tilt method, each tried only
//! where the job before it has problems ([`compile_strokes`]); each job is
//! planned by `planned_job::compile_for_tip`.

use crate::job::Job;
use crate::layout;

use super::planned_job::{compile_for_tip, Placed, PlannedJob};
use basr_plan::error::CompileError;
use basr_plan::placed::PlacedStrokes;
use basr_plan::request::{CompileRequest, Tilt};
use rayon::prelude::*;

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
    let choices = choices(req, &robot);
    // The request as it is, with the first tip: verified as asked (the
    // job kept when no other paints), its error the compile's.
    let Some(((first_req, first_robot), others)) = choices.split_first() else {
        return compile_for_tip(req, placed, robot).map(|p| p.job);
    };
    let first = compile_for_tip(first_req, placed, first_robot.clone())?.job;
    if problems(&first) == 0 {
        return Ok(first);
    }
    // The tips (with their tilt method) whose fan is wider than the
    // strokes it paints, a problem of the plan's geometry before any
    // timing: gently planned the fan is as wide, and with ends held in the
    // rungs are only shorter, so such a tip is not planned again under
    // the same method (B at 6 ft: 15 plans instead of 23).
    let mut too_wide: Vec<(Tilt, Option<String>)> = vec![];
    let note_wide = |too_wide: &mut Vec<_>, r: &CompileRequest, job: &Job| {
        if !r.hold_ends && fan_wider_than_strokes(job) {
            too_wide.push(tip_key(r, &job.robot));
        }
    };
    note_wide(&mut too_wide, first_req, &first);
    // Two plans at a time, in order, the first of a pair that paints
    // chosen: each plan's own stages keep two cores busy only in part (a
    // NOT READY B at 6 ft: 1.58 s of CPU in 1.10 s), and more at once
    // would only hold more jobs in memory where the first of them paints.
    let mut rest = others.iter();
    loop {
        let pair: Vec<&(CompileRequest, crate::robot::AnyRobot)> = rest
            .by_ref()
            .filter(|(r, robot)| !too_wide.contains(&tip_key(r, robot)))
            .take(2)
            .collect();
        if pair.is_empty() {
            return Ok(first);
        }
        let open: Vec<Result<PlannedJob, CompileError>> = pair
            .par_iter()
            .map(|(r, robot)| {
                let open_loop = CompileRequest {
                    verify: false,
                    ..r.clone()
                };
                compile_for_tip(&open_loop, placed, robot.clone())
            })
            .collect();
        for ((r, robot), planned) in pair.into_iter().zip(open) {
            if let Ok(p) = &planned {
                note_wide(&mut too_wide, r, &p.job);
            }
            // A plan that already has problems (its film, its strokes
            // against its fan) is no choice, and is not verified (STOP at
            // 6 ft once verified all three tips it had: 3.4 s of a NOT
            // READY compile). Verification only slows a job (gentler
            // accelerations, and slower speeds where a joint's limit
            // binds), and is taken not to take a planned problem away;
            // were it ever to, a choice would be passed over that a
            // verified compile would have kept: the cautious side. A
            // request that cannot be planned at all (a fan too wide for
            // every stroke) is no choice either.
            let Some(job) = paints(planned) else { continue };
            if !r.verify {
                return Ok(job);
            }
            if let Some(job) = paints(compile_for_tip(r, placed, robot.clone())) {
                return Ok(job);
            }
        }
    }
}

/// A plan's tilt method and its robot's tip: what [`compile_strokes`]
/// skips once the tip's fan is wider than the strokes.
fn tip_key(r: &CompileRequest, robot: &crate::robot::AnyRobot) -> (Tilt, Option<String>) {
    (r.tilt, robot.paint().mounted.clone())
}

/// Whether `job` has a problem of a fan wider than its strokes
/// (`height_clamped`, graded a problem).
fn fan_wider_than_strokes(job: &Job) -> bool {
    job.summary.warnings.iter().any(|w| {
        w.kind == crate::job::WarningKind::HeightClamped
            && w.graded() == crate::job::Severity::Problem
    })
}

/// The plans compile may choose among, in the order it prefers them
/// ([`compile_strokes`]), each a request and the robot with its tip: the
/// request itself, then the gentle tilt, then the trapezoid method (with
/// and without the gentle tilt), then ends held in (likewise); within
/// each, every tip the robot carries in its order. The first is always
/// the request with the robot's first tip.
fn choices(
    req: &CompileRequest,
    robot: &crate::robot::AnyRobot,
) -> Vec<(CompileRequest, crate::robot::AnyRobot)> {
    let at_site = req.site.is_some();
    // The gentle tilt only where the robot tilts: it would plan the same
    // job again on one that does not.
    let tilts = robot.tilt_limit().is_some();
    let gentle = |r: &CompileRequest| -> Vec<CompileRequest> {
        let g = (!r.gentle_tilt && !at_site && tilts).then(|| CompileRequest {
            gentle_tilt: true,
            ..r.clone()
        });
        std::iter::once(r.clone()).chain(g).collect()
    };
    let trapezoid =
        (req.tilt == Tilt::Quadrilateral && !req.tilt_named && !at_site && tilts).then(|| {
            CompileRequest {
                tilt: Tilt::Trapezoid,
                tilt_named: true,
                ..req.clone()
            }
        });
    let held = (!req.hold_ends && !at_site).then(|| CompileRequest {
        hold_ends: true,
        ..req.clone()
    });
    // A robot with its tip already mounted (a job's own, planned again by
    // `basr fit` or `preview --compare`) keeps that tip: the crew has it on
    // the gun, and the job's other stops were painted with it.
    let tips: Vec<crate::robot::AnyRobot> = match &robot.paint().mounted {
        Some(_) => vec![robot.clone()],
        None if robot.paint().tips.is_empty() => vec![robot.clone()],
        None => robot
            .paint()
            .tips
            .iter()
            .map(|tip| {
                let mut r = robot.clone();
                let p = r.paint_mut();
                *p = p.with_tip(tip);
                r
            })
            .collect(),
    };
    std::iter::once(req.clone())
        .chain(trapezoid)
        .chain(held)
        .flat_map(|r| gentle(&r))
        .flat_map(|r| tips.iter().map(move |t| (r.clone(), t.clone())))
        .collect()
}

/// The job planned when it has no problems and none of its items (a
/// letter, a symbol) misses a film bound on its own
/// (`film::FilmCheck::items_over`, empty where the request does not
/// measure the film).
fn paints(p: Result<PlannedJob, CompileError>) -> Option<Job> {
    p.ok()
        .filter(|p| problems(&p.job) == 0 && p.items_over.is_empty())
        .map(|p| p.job)
}

/// The job's problems: what makes it NOT READY.
fn problems(job: &Job) -> usize {
    job.summary
        .warnings
        .iter()
        .filter(|w| w.graded() == crate::job::Severity::Problem)
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::AnyRobot;

    /// (tilt, gently, ends held, tip) of each choice.
    fn listed(req: &CompileRequest, robot: &AnyRobot) -> Vec<(Tilt, bool, bool, String)> {
        choices(req, robot)
            .into_iter()
            .map(|(r, robot)| {
                let tip = robot.paint().mounted.clone().unwrap_or_default();
                (r.tilt, r.gentle_tilt, r.hold_ends, tip)
            })
            .collect()
    }

    fn shipped(name: &str) -> AnyRobot {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("robots")
            .join(name);
        AnyRobot::load(&path).expect("a shipped robot loads")
    }

    #[test]
    fn the_choices_go_gently_then_trapezoid_then_held_each_with_every_tip() {
        let robot = AnyRobot::load_or_default(None).unwrap();
        let tips: Vec<String> = robot.paint().tips.iter().map(|t| t.name.clone()).collect();
        assert_eq!(tips.len(), 4, "{tips:?}");
        let list = listed(&CompileRequest::message("B"), &robot);
        let (q, t) = (Tilt::Quadrilateral, Tilt::Trapezoid);
        let groups = [
            (q, false, false),
            (q, true, false),
            (t, false, false),
            (t, true, false),
            (q, false, true),
            (q, true, true),
        ];
        let want: Vec<_> = groups
            .iter()
            .flat_map(|&(tilt, g, h)| tips.iter().map(move |n| (tilt, g, h, n.clone())))
            .collect();
        assert_eq!(list, want);
    }

    #[test]
    fn an_arm_that_does_not_tilt_is_not_planned_gently_or_trapezoid() {
        let robot = shipped("articulated.toml");
        assert!(robot.tilt_limit().is_none());
        let list = listed(&CompileRequest::message("B"), &robot);
        let n = robot.paint().tips.len();
        assert_eq!(list.len(), 2 * n, "{list:?}");
        assert!(list.iter().all(|c| !c.1 && c.0 == Tilt::Quadrilateral));
        assert!(list[..n].iter().all(|c| !c.2) && list[n..].iter().all(|c| c.2));
    }

    #[test]
    fn a_named_tilt_a_mounted_tip_and_the_site_narrow_the_choices() {
        let robot = AnyRobot::load_or_default(None).unwrap();
        // --tilt named: no trapezoid; gently and held with every tip
        let named = CompileRequest {
            tilt_named: true,
            ..CompileRequest::message("B")
        };
        assert!(listed(&named, &robot)
            .iter()
            .all(|c| c.0 == Tilt::Quadrilateral));
        assert_eq!(listed(&named, &robot).len(), 4 * 4);
        // a job's own tip, mounted: that tip alone
        let mut mounted = robot.clone();
        let tip = robot.paint().tips[3].clone();
        let p = mounted.paint_mut();
        *p = p.with_tip(&tip);
        let list = listed(&named, &mounted);
        assert_eq!(list.len(), 4);
        assert!(list.iter().all(|c| c.3 == tip.name));
        // at the site: the job as it was planned, nothing else
        let at_site = CompileRequest {
            site: Some(basr_plan::site::Site {
                stations: vec![],
                fitted: 0,
                road: Default::default(),
                kept: vec![],
                painted: vec![],
            }),
            ..CompileRequest::message("B")
        };
        assert_eq!(listed(&at_site, &mounted).len(), 1);
    }
}
