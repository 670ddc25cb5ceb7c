//! The compile pipeline, stage by stage: inputs → layout → placed strokes
//! (`placed`) → the planner's choice of tip and tilt (`choice`), each
//! choice one job planned, verified and its film checked (`planned_job`:
//! rungs → knots and passes → stations → tours → joint paths → timed
//! trajectory → samples → sealed job → verified → film). Each stage is one
//! function in a module named for the value it returns.

use crate::job::Job;

use super::placed::lay_out;
use basr_plan::{inputs, request};

pub use super::choice::compile_strokes;
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
