//! # basr-plan
//!
//! The planner. Imports `basr-io`, `basr-geom`, `basr-robot`, `basr-job` and `basr-shape`; never `basr-sim` or `basr-paint` (Cargo.toml does not list them, so the compiler refuses it). The workspace's crates are the pipeline (docs/architecture.md).
//!
//! ```
//! use basr_plan::placed::PlacedStrokes;
//! use basr_plan::request::{self, CompileRequest};
//! use basr_plan::{inputs, passes, rungs, stations};
//! use basr_shape::layout::{lay_marking, Marking};
//!
//! // The first stages of the planner on the letter I.
//! let req = CompileRequest::message("I");
//! let inputs::Inputs { robot, font } = inputs::read(&req).unwrap();
//! let marking = Marking::from_message("I", &req.overrides).unwrap();
//! let laid = lay_marking(&marking, &font, false).unwrap();
//! let strokes = PlacedStrokes::from_laid(&laid);
//! let budget = passes::turn_budget(&robot, &req.tuning);
//! let rungs = rungs::rungs(&strokes, req.rung_spacing_m, Some(&budget));
//! let (tilt, _) = request::tilt_for(req.tilt, &robot);
//! let passes = passes::passes(&strokes, &rungs, &robot, tilt.method(), &req.tuning).unwrap();
//! let plan = stations::for_passes(&passes, laid.lane_width_m, req.reach_margin_m, &robot).unwrap();
//! assert_eq!(plan.stations.len(), 1);
//! ```
//!
//! The planner alone: placed strokes ([`placed`]) to a sealed job, a
//! module per value: `rungs` → `passes` (knots, 001 §2.4, tilt §2.5) →
//! `stations` → `tours` (`order`) → `joints` (with `leads`) → `trajectory`
//! (the `timing` time law) → `samples` → `seal`. `warnings` holds every note
//! a stage makes; `request` what a compile is asked; `inputs` the robot and
//! font it reads; `tuning` every value the stages use that is chosen rather
//! than derived, in one typed value.
//!
//! It imports geom, robot, job and shape (the strokes it plans), never the
//! simulator or the previewer: verifying a plan on the arm and measuring
//! its film are the pipeline's (the `basr` crate), which calls the stages
//! here and re-times with [`trajectory::Pace`].

pub mod chain;
pub mod error;
pub mod fit;
pub mod flight;
pub mod inputs;
pub mod joints;
pub mod knots;
pub mod leads;
pub mod narrow;
pub mod order;
pub mod pairing;
pub mod passes;
pub mod placed;
pub mod rate;
pub mod request;
pub mod rungs;
pub mod samples;
pub mod seal;
pub mod site;
pub mod stations;
pub mod stow;
pub mod tilt;
pub mod timing;
pub mod tours;
pub mod trajectory;
pub mod tuning;
pub mod turn;
pub mod warnings;
