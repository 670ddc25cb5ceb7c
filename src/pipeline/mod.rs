//! The pipeline: a message, marking file, symbol or shape laid out
//! (`placed`), planned (`basr_plan`), verified on the closed-loop simulator
//! and re-timed where the arm falls behind (`verify`, `compile`), and its
//! film measured by the preview's own stage (`film`). `shapes` chooses an
//! imported outline's decomposition by measuring the candidates' film.
//!
//! This is the only place the planner meets the simulator and the
//! previewer: `basr-plan` cannot see either.

mod choice;
pub mod compile;
pub mod film;
pub mod placed;
mod planned_job;
pub mod shapes;
pub mod verify;
