//! A decomposed shape into a job, through the planner's placed-strokes seam:
//! the shape's font is laid out like a one-letter message (centred in the
//! lane, its near edge at the anchor) so that `compile --shape FILE` and
//! `compile S --font IMPORTED.toml --letter-height H` place the same
//! strokes, then the strokes are labelled as the shape they are.

use crate::job::{Job, Warning};
use crate::plan::compile::{compile_strokes, CompileError, CompileRequest};
use crate::plan::placed::lay_out;
use crate::plan::warnings::Owner;
use crate::plan::{inputs, request};

use super::{report_lines, Bands, Imported};

/// Compile `imported` (its height is the letter height) with the rest of
/// `req`; `label` names the shape in the job (`layout.glyphs[].char`).
pub fn compile_shape(
    req: &CompileRequest,
    imported: &Imported,
    bands: &Bands,
    label: &str,
) -> Result<Job, CompileError> {
    let mut req = req.clone();
    req.overrides.letter_height_m = Some(imported.height_m);
    req.font = None;
    request::check_settings(&req)?;
    let inputs = inputs::read(&req)?;
    let font = imported
        .font(label)
        .map_err(|e| CompileError::Font(e.to_string()))?;
    let (marking, mut strokes) = lay_out(&req, &font)?;
    for it in &mut strokes.items {
        it.owner = Owner {
            kind: "shape",
            label: label.to_string(),
            line: 0,
        };
    }
    let mut job = compile_strokes(&req, &marking, &font, inputs.robot, &strokes)?;
    // The job says how the shape was decomposed: per region the method kept
    // and the ones it beat, and the places narrower than the fan paints.
    for l in report_lines(&imported.decomposition, bands) {
        job.summary.warnings.push(Warning {
            kind: "shape".into(),
            severity: "info".into(),
            stroke: -1,
            t_s: None,
            factor: None,
            message: format!("shape {l}"),
        });
    }
    job.seal();
    Ok(job)
}
