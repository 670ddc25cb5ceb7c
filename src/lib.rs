//! basr: an offline trajectory-planning compiler for roadway-marking robots.
//!
//! The stages, in pipeline order (see DESIGN.md): `geom` (curves, edges,
//! subdivision) → `font` (strokes of glyphs) → `layout` (placed glyphs) →
//! `plan` (rungs, knots, tilt, path, time law) → `robot` (kinematics,
//! actuators, encoders) → `job` (the document). `paint` previews a job's
//! film; `sim` runs it through the arm in closed loop; `plot` draws SVG.

pub mod canon;
pub mod chars;
pub mod export;
pub mod font;
pub mod geom;
pub mod io;
pub mod job;
pub mod layout;
pub mod paint;
pub mod plan;
pub mod plot;
pub mod report;
pub mod robot;
pub mod shape;
pub mod sim;
pub mod units;
