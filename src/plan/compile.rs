//! The compile pipeline, stage by stage: inputs → layout → placed strokes →
//! rungs → knots and passes → stations → tours → joint paths → timed
//! trajectory → samples → sealed job. Each stage is one function in a
//! module named for the value it returns.

use crate::job::Job;
use crate::layout;

use super::placed::{lay_out, PlacedStrokes};
use super::seal::{seal, Planned};
use super::{inputs, joints, passes, request, rungs, samples, stations, tours, trajectory, verify};

pub use super::error::CompileError;
pub use super::request::{CompileRequest, Source, Tilt, DEFAULT_PERIOD_S, DEFAULT_RUNG_SPACING_M};

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
    let rungs = rungs::rungs(strokes, req.rung_spacing_m);
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
                pace,
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
            return Ok(job);
        }
        let verdict = verify::verify(&job)?;
        if verdict.ok {
            job.summary.verified_max_error_m = Some(verdict.max_error_m);
            job.seal();
            return Ok(job);
        }
        // Slow where the arm fell behind: the move out of stow when the
        // worst error is on a station's first stroke, else the strokes' path.
        let (si, stroke) = verdict.worst;
        let first = paths.stations.get(si as usize).and_then(|r| r.first());
        let after_stow = first.is_some_and(|r| r.stroke as i64 == stroke) && pace.air > MIN_PACE;
        if after_stow {
            pace.air *= PACE_STEP;
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

/// Each re-timing uses this share of the last one's accelerations.
/// assumed: a few steps reach `MIN_PACE` while each still gains.
const PACE_STEP: f64 = 0.6;
/// Slowest re-timing tried before the job is refused (share of the limits).
const MIN_PACE: f64 = 0.1;
