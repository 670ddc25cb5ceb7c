//! Inputs: the request's marking, robot description and font, read and
//! checked (the first stage; every later one takes them as values).

use std::borrow::Cow;

use crate::font::Font;
use crate::layout::Marking;
use crate::robot::Robot;

use super::error::CompileError;
use super::request::{CompileRequest, Source};

/// What a compile paints, with what and with which font.
pub struct Inputs {
    pub marking: Marking,
    pub robot: Robot,
    pub font: Cow<'static, Font>,
}

/// Read the marking (message or file), the robot and the font.
pub fn read(req: &CompileRequest) -> Result<Inputs, CompileError> {
    let marking = match &req.source {
        Source::Message(m) => Marking::from_message(m, &req.overrides)?,
        Source::Marking { text, origin } => Marking::from_toml(text, origin, &req.overrides)?,
    };
    let robot = match &req.robot_description {
        Some(r) => r.clone(),
        None => Robot::load_or_default(req.robot.as_deref())
            .map_err(|e| CompileError::Robot(e.to_string()))?,
    };
    let font = match &req.font {
        None => Cow::Borrowed(Font::embedded()),
        Some(name) => Cow::Owned(
            Font::from_name_or_path(name).map_err(|e| CompileError::Font(e.to_string()))?,
        ),
    };
    Ok(Inputs {
        marking,
        robot,
        font,
    })
}
