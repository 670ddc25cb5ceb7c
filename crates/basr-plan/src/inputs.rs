//! Inputs: the request's robot description and font, read and checked (the
//! first stage; every later one takes them as values). The marking itself is
//! read by the layout stage (`placed::lay_out`).

use std::borrow::Cow;

use basr_robot::AnyRobot;
use basr_shape::font::Font;

use super::error::CompileError;
use super::request::CompileRequest;

/// What a compile paints with, and with which font.
pub struct Inputs {
    pub robot: AnyRobot,
    pub font: Cow<'static, Font>,
}

/// Read the robot and the font.
pub fn read(req: &CompileRequest) -> Result<Inputs, CompileError> {
    let robot = match &req.robot_description {
        Some(r) => r.clone(),
        None => AnyRobot::load_or_default(req.robot.as_deref())
            .map_err(|e| CompileError::Robot(e.to_string()))?,
    };
    let font = match &req.font {
        None => Cow::Borrowed(Font::embedded()),
        Some(name) => Cow::Owned(
            Font::from_name_or_path(name).map_err(|e| CompileError::Font(e.to_string()))?,
        ),
    };
    Ok(Inputs { robot, font })
}
