//! The compile pipeline, stage by stage: inputs → layout → placed strokes →
//! rungs → knots and passes → stations → tours → joint paths → timed
//! trajectory → samples → sealed job. Each stage is one function in a
//! module named for the value it returns.

use crate::job::Job;
use crate::layout;

use super::placed::{lay_out, PlacedStrokes};
use super::seal::{seal, Planned};
use super::{inputs, joints, passes, request, rungs, samples, stations, tours, trajectory};

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
    robot: crate::robot::Robot,
    strokes: &PlacedStrokes,
) -> Result<Job, CompileError> {
    let rungs = rungs::rungs(strokes, req.rung_spacing_m);
    let passes = passes::passes(strokes, &rungs, &robot, req.tilt.method())?;
    let plan = stations::for_passes(&passes, marking.lane_width_m, req.reach_margin_m, &robot)?;
    let tours = tours::tours(&passes, &plan, &robot);
    let paths = joints::joint_paths(strokes, &passes, &plan, &tours, &robot)?;
    let timed = trajectory::time_law(
        strokes,
        &paths,
        &robot,
        req.period_s,
        req.gun_lead_s,
        req.gun_lag_s,
    )?;
    let mut notes = strokes.notes.clone();
    notes.extend(passes.notes);
    notes.extend(timed.notes.iter().cloned());
    let samples = samples::sample(&plan, &paths, timed, &robot, req.period_s)?;
    Ok(seal(Planned {
        marking,
        font,
        robot,
        tilt: req.tilt,
        period_s: req.period_s,
        strokes,
        stations: plan,
        samples,
        balance: passes.balance,
        notes,
    }))
}
