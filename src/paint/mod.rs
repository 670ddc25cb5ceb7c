//! Paint: the spray deposition model, the film raster and its metrics.
//!
//! `spray` says where a nozzle pose lays paint; `raster` integrates it along
//! timed poses into a film-thickness grid; `metrics` measures the film against
//! the letters' true outlines, `verdict` judges those figures against
//! documented thresholds; `preview` ties them to a job and draws the SVG.
//! The simulator reuses `deposit` on its own trace (same pose columns).

pub mod metrics;
pub mod preview;
pub mod raster;
pub mod spray;
pub mod verdict;

pub use raster::{deposit, Bounds, Film, Grid};
pub use spray::{planned_tip, Depth, Footprint, Pose, Profile, SprayModel};

/// Errors from the paint model and the preview.
#[derive(Debug, thiserror::Error)]
pub enum PaintError {
    #[error("{option} {value:?}: {why}")]
    Option {
        option: &'static str,
        value: String,
        why: String,
    },
    #[error("spray model: {0}")]
    Model(String),
    #[error("nozzle pose: {0}")]
    Pose(String),
    #[error("job: {0}")]
    Job(String),
}
