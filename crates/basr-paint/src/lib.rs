//! # basr-paint
//!
//! The film a job lays. Imports `basr-io`, `basr-job` and `basr-plot`; never the planner or the simulator. The workspace's crates are the pipeline (docs/architecture.md).
//!
//! Paint: the spray deposition model, the film raster and its metrics.
//!
//! `spray` says where a nozzle pose lays paint; `raster` integrates it along
//! timed poses into a film-thickness grid; `mask` lays the letters' true outlines on
//! the grid, `metrics` measures the film against them, `verdict` judges those figures against
//! documented thresholds, `film` is the stage that does all three for a job
//! (preview and compile both call it); `preview` ties them to a job and
//! `drawing` draws its SVG.
//! The simulator reuses `deposit` on its own trace (same pose columns).

pub mod bands;
mod boxes;
pub mod captions;
pub mod drawing;
pub mod film;
pub mod mask;
pub mod metrics;
pub mod preview;
pub mod raster;
pub mod spray;
pub mod stripe;
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

/// A length in millimetres with four significant digits, trailing zeros
/// dropped (`5`, `2.5`, `0.0125`): a cell of 0.01 mm is not "0.0 mm".
pub fn mm_text(m: f64) -> String {
    let mm = m * 1000.0;
    if !(mm.is_finite() && mm > 0.0) {
        return format!("{mm}");
    }
    let decimals = (3 - mm.log10().floor() as i64).clamp(0, 12) as usize;
    basr_io::fixed(mm, decimals)
}
