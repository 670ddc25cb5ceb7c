//! The layout stage: what the request asks to paint (a message, a marking
//! file of lines or of a scene, a symbol) laid out in the lane as the
//! planner's [`PlacedStrokes`]. A scene's shape items are imported and
//! their decomposition chosen by measuring its film (`shapes`), which is
//! why this stage is the pipeline's and not the planner's.

use basr_plan::placed::PlacedStrokes;
use basr_plan::request::{CompileRequest, Source};
use basr_shape::font::{Font, Library};
use basr_shape::layout::{self, LayoutError, Marking, Scene};

/// The layout stage: the request's message, marking file (lines or a scene
/// of items) or single symbol laid out in the lane, as the marking the job
/// records (its message, letter height and lane) and its placed strokes.
pub fn lay_out(req: &CompileRequest, font: &Font) -> Result<(Marking, PlacedStrokes), LayoutError> {
    let o = &req.overrides;
    let lib = Library::embedded();
    // What the scene's shape items say of their decomposition.
    let shape_notes = std::cell::RefCell::new(vec![]);
    let laid = match &req.source {
        Source::Message(m) => {
            layout::lay_marking(&Marking::from_message(m, o)?, font, o.low_speed)?
        }
        Source::Marking { text, origin } if layout::is_scene(text) => {
            let shapes = super::shapes::importer(req, origin, &shape_notes);
            layout::lay_scene_with(&Scene::from_toml(text, origin, o)?, font, lib, &shapes)?
        }
        Source::Marking { text, origin } => {
            layout::lay_marking(&Marking::from_toml(text, origin, o)?, font, o.low_speed)?
        }
        Source::Symbol(name) => layout::lay_scene(&Scene::single_symbol(name, o)?, font, lib)?,
    };
    let record = Marking {
        lines: laid.message.split('\n').map(str::to_string).collect(),
        letter_height_m: laid.letter_height_m,
        letter_spacing_m: 0.0,
        lane_width_m: laid.lane_width_m,
        line_gap_m: 0.0,
        anchor_x_m: 0.0,
        anchor_y_m: 0.0,
        road: laid.road.clone(),
    };
    let mut placed = PlacedStrokes::from_laid(&laid);
    placed.notes.extend(shape_notes.into_inner());
    Ok((record, placed))
}
