//! basr: an offline trajectory-planning compiler for roadway-marking robots.
//!
//! The workspace's crates are the pipeline (docs/architecture.md), each
//! re-exported here under the name of what it holds:
//!
//! - [`io`] (`basr-io`): files read and written, canonical bytes, hashes;
//! - [`geom`] (`basr-geom`): curves, edges, lengths with units;
//! - [`robot`] (`basr-robot`): robot descriptions behind one `ArmKind` trait;
//! - [`job`] (`basr-job`): the job document;
//! - [`shape`] (`basr-shape`): fonts ([`font`]), the symbol library, outline
//!   import and decomposition, the layout in the lane ([`layout`]);
//! - [`plan`] (`basr-plan`): the planner alone, placed strokes to a sealed job;
//! - [`paint`] (`basr-paint`): the film a job lays (the preview);
//! - [`sim`] (`basr-sim`): the arm in closed loop;
//! - [`plot`] (`basr-plot`): SVG drawing.
//!
//! This crate joins them: [`pipeline`] (lay out → plan → verify on the
//! simulator → re-time → measure the film) and [`report`] (the job sheet);
//! the `basr` binary is its command line.
//!
//! ```no_run
//! use basr::pipeline::compile::{compile_job, CompileRequest};
//!
//! // What `basr compile STOP` does: plan, verify on the simulated arm,
//! // measure the film, seal.
//! let job = compile_job(&CompileRequest::message("STOP")).unwrap();
//! assert_eq!(job.message, "STOP");
//! assert!(job.summary.verified_max_error_m.is_some());
//! ```

pub use basr_geom as geom;
pub use basr_geom::units;
pub use basr_io as io;
pub use basr_io::canon;
pub use basr_job as job;
pub use basr_paint as paint;
pub use basr_plan as plan;
pub use basr_plot as plot;
pub use basr_robot as robot;
pub use basr_shape as shape;
pub use basr_shape::{chars, font, layout};
pub use basr_sim as sim;

pub mod export;
pub mod pipeline;
pub mod report;
