//! basr: an offline trajectory-planning compiler for roadway-marking robots.
//!
//! The stages, in pipeline order (see DESIGN.md): `geom` (curves, edges,
//! subdivision) → `font` (strokes of glyphs) → `layout` (placed glyphs) →
//! `plan` (rungs, knots, tilt, path, time law) → `robot` (kinematics,
//! actuators, encoders) → `job` (the document). `paint` previews a job's
//! film; `sim` runs it through the arm in closed loop.

pub mod io;
pub mod job;
pub mod robot;
