//! Shapes in the pipeline: the fan's bands a decomposition plans for, a
//! `compile --shape` job through the placed-strokes seam, and the importer
//! a scene's `shape =` items are laid out with (SPEC §5).
//!
//! `compile --shape FILE`: the shape's font is laid out like a one-letter
//! message (centred in the lane, its near edge at the anchor) so that
//! `compile --shape FILE` and `compile S --font IMPORTED.toml
//! --letter-height H` place the same strokes; the strokes are then
//! labelled as the shape they are, and the job's message names the file.

use std::path::{Path, PathBuf};

use crate::job::{Job, Warning};
use crate::layout::{ShapeSize, ShapeStrokes};
use crate::plan::compile::{compile_strokes, CompileError, CompileRequest};
use crate::plan::placed::lay_out;
use crate::plan::warnings::Owner;
use crate::plan::{inputs, request};
use crate::robot::Robot;
use crate::shape::{self, report_lines, Bands, Imported, Size};

/// The bands the robot's nozzle paints: narrowest from the lowest tip
/// height, widest from the highest (`passes::paint_law`).
pub fn bands(robot: &Robot) -> Bands {
    let law = super::passes::paint_law(robot);
    Bands {
        min_width_m: law.width_at_height(law.min_height_m),
        max_width_m: law.max_width_m(),
        k_m2ps: law.k_m2ps,
        yaw_rate_rad_s: robot.limits.ee_yaw_rad.max_vel,
    }
}

/// The job's message for a shape: its file's stem in brackets, as a
/// scene's shape items are written (`layout::Scene::message`).
pub fn message_of(label: &str) -> String {
    format!("[{label}]")
}

/// Compile `imported` (its height is the letter height) with the rest of
/// `req`; `label` names the shape in the job (`layout.glyphs[].char` and
/// the message).
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
    let (mut marking, mut strokes) = lay_out(&req, &font)?;
    marking.lines = vec![message_of(label)];
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

/// The robot a request paints with (as `inputs::read` finds it).
fn robot_of(req: &CompileRequest) -> Result<Robot, String> {
    match &req.robot_description {
        Some(r) => Ok(r.clone()),
        None => Robot::load_or_default(req.robot.as_deref()).map_err(|e| e.to_string()),
    }
}

/// A scene item's shape file: relative paths are relative to the marking
/// file's folder (SPEC §5).
pub fn resolve(path: &Path, marking_file: &str) -> PathBuf {
    if path.is_absolute() {
        return path.to_path_buf();
    }
    Path::new(marking_file)
        .parent()
        .unwrap_or(Path::new(""))
        .join(path)
}

/// Import one scene shape for the robot: its strokes in the shape's frame
/// (lower-left corner at the origin, metres) and its size.
pub fn import_item(
    robot: &Robot,
    marking_file: &str,
    path: &Path,
    size: ShapeSize,
) -> Result<ShapeStrokes, String> {
    let file = resolve(path, marking_file);
    let size = match size {
        ShapeSize::HeightM(h) => Size::HeightM(h),
        ShapeSize::WidthM(w) => Size::WidthM(w),
    };
    let imported = shape::import(&file, size, &bands(robot)).map_err(|e| e.to_string())?;
    Ok(ShapeStrokes {
        strokes: imported.decomposition.strokes,
        width_m: imported.width_m,
        height_m: imported.height_m,
    })
}

/// The importer `layout::lay_scene_with` takes, for a scene read from
/// `marking_file` and compiled with `req`'s robot.
pub fn importer<'a>(
    req: &'a CompileRequest,
    marking_file: &'a str,
) -> impl Fn(&Path, ShapeSize) -> Result<ShapeStrokes, String> + 'a {
    move |path, size| import_item(&robot_of(req)?, marking_file, path, size)
}
