//! Planning: the compile pipeline (`compile`) and its stages, a module per
//! value: `inputs` → `placed` strokes → `rungs` → `passes` (knots, 001
//! §2.4, tilt §2.5) → `stations` → `tours` (`order`) → `joints` (with
//! `leads`) → `trajectory` (the `timing` time law) → `samples` → `seal` → `verify`
//! (the closed-loop simulator) → `film` (the preview's film check).
//! `warnings` holds every note a stage makes and renders it.

pub mod chain;
pub mod compile;
pub mod error;
pub mod film;
pub mod flight;
pub mod inputs;
pub mod joints;
pub mod knots;
pub mod leads;
pub mod order;
pub mod pairing;
pub mod passes;
pub mod placed;
pub mod rate;
pub mod request;
pub mod rungs;
pub mod samples;
pub mod seal;
pub mod shapes;
pub mod stations;
pub mod stow;
pub mod tilt;
pub mod timing;
pub mod tours;
pub mod trajectory;
pub mod turn;
pub mod verify;
pub mod warnings;
