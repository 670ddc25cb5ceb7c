//! Planning: rungs and knots (001 §2.4), tilt (§2.5), path order, stations
//! and the time law that turns a path into timed setpoints.

pub mod compile;
pub mod knots;
pub mod order;
pub mod stations;
pub mod tilt;
pub mod timing;
