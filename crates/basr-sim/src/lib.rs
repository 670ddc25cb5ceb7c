//! # basr-sim
//!
//! The arm in closed loop. Imports `basr-io`, `basr-robot`, `basr-job` and `basr-plot`; never the planner or the previewer. The workspace's crates are the pipeline (docs/architecture.md).
//!
//! ```
//! use basr_sim::{simulate, synthetic, Options, SimModel};
//!
//! // A letter-sized synthetic job through the default arm and controller.
//! let job = synthetic::letter_job();
//! let outcome = simulate(&job, &SimModel::basr(), &Options::default(), &mut |_, _| {}).unwrap();
//! assert!(outcome.report.max_error_m < 6.35e-3);
//! ```
//!
//! Closed-loop simulation: arm and hydraulics plant, sensors, controllers, integrator, report.
//!
//! `simulate(job, model, options, progress)` plays a job's setpoints through
//! the controller of 000 section III into the plant of section II, every
//! 5 ms with RK4 sub-steps, and measures where the nozzle actually went.

pub mod circuit;
pub mod control;
pub mod ee;
pub mod fault;
mod lockstep;
pub mod model;
pub mod plant;
pub mod plants;
mod reference;
pub mod report;
mod run;
pub mod safety;
pub mod servo;
pub mod servo_job;
pub mod svg;
pub mod synthetic;
mod tally;

pub use control::{Command, Controller, ControllerKind, Measurement, Reference};
pub use model::SimModel;
pub use report::{Report, TraceRow};
pub use run::Checkpoints;

use basr_job::Job;

/// Errors from setting up a simulation (bad input: exit 2).
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    #[error("job cannot be simulated: {0}")]
    Job(String),
    #[error("robot dynamics invalid: {0}; fix the robot description's [dynamics] table")]
    Model(String),
    #[error("simulation option invalid: {0}")]
    Option(String),
}

/// How to run.
#[derive(Clone, Debug)]
pub struct Options {
    pub controller: ControllerKind,
    /// Verdict threshold on the nozzle error while painting (m).
    pub tolerance_m: f64,
    /// Keep one `TraceRow` per control tick.
    pub keep_trace: bool,
    /// Override the model's RK4 sub-steps per control period (convergence checks).
    pub substeps: Option<u32>,
    /// End the run at the first painting tick whose nozzle error is over
    /// this (m): a caller that only asks whether a run stays within it
    /// (compile's verification) learns the answer and where it first
    /// failed without simulating the rest. The report then covers the run
    /// up to that tick (`Report::cut_short_at_s`).
    pub stop_over_m: Option<f64>,
    /// Log the painting error per tick for the report's waviness (its
    /// high-pass filtered error, `Report::waviness`). A caller that judges
    /// the error and the limits only (compile's verification) leaves it off:
    /// a long job's kept runs held tens of MB of it. Off, the waviness's
    /// figures read zero.
    pub waviness: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            controller: ControllerKind::Sjct,
            tolerance_m: 6.35e-3, // SPEC §4: 1/4 in
            keep_trace: false,
            substeps: None,
            stop_over_m: None,
            waviness: true,
        }
    }
}

/// What a run returns.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub report: Report,
    /// Empty unless `Options::keep_trace`.
    pub trace: Vec<TraceRow>,
}

/// Yaw axis meets the road: W = R·(cos θ1, sin θ1) + a2·(sin θ1, −cos θ1) (SPEC §2).
pub fn nozzle_base(model: &SimModel, theta: f64, r: f64) -> [f64; 2] {
    let (s, c) = theta.sin_cos();
    let a2 = model.arm.a2_m;
    [r * c + a2 * s, r * s - a2 * c]
}

/// Check the job's numbers before running (bad input → exit 2).
fn validate_job(job: &Job) -> Result<(), SimError> {
    let s = &job.samples;
    let n = s
        .check_lengths()
        .map_err(|e| SimError::Job(e.to_string()))?;
    if n < 2 {
        return Err(SimError::Job(format!(
            "it has {n} setpoint rows; at least 2 are needed"
        )));
    }
    if !(job.control_period_s.is_finite() && job.control_period_s > 0.0) {
        return Err(SimError::Job(format!(
            "control_period_s = {} must be a positive number of seconds",
            job.control_period_s
        )));
    }
    let cols: [(&str, &Vec<f64>); 8] = [
        ("x_m", &s.x_m),
        ("y_m", &s.y_m),
        ("base_rot_rad", &s.base_rot_rad),
        ("extension_m", &s.extension_m),
        ("vertical_m", &s.vertical_m),
        ("ee_yaw_rad", &s.ee_yaw_rad),
        ("tilt_nut_m", &s.tilt_nut_m),
        ("t_s", &s.t_s),
    ];
    for (name, col) in cols {
        if let Some(i) = col.iter().position(|v| !v.is_finite()) {
            return Err(SimError::Job(format!(
                "samples.{name}[{i}] is not a finite number"
            )));
        }
    }
    for (i, st) in s.station.iter().enumerate() {
        if *st as usize >= job.stations.len() {
            return Err(SimError::Job(format!(
                "samples.station[{i}] = {st} but the job has {} stations",
                job.stations.len()
            )));
        }
    }
    for (i, st) in job.stations.iter().enumerate() {
        if ![st.x_m, st.y_m, st.heading_rad]
            .iter()
            .all(|v| v.is_finite())
        {
            return Err(SimError::Job(format!(
                "stations[{i}] has a non-finite value"
            )));
        }
    }
    Ok(())
}

/// Run `job` through `model` in closed loop. `progress(done, total)` is called
/// now and then with control ticks.
pub fn simulate(
    job: &Job,
    model: &SimModel,
    opts: &Options,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Outcome, SimError> {
    simulate_plant(job, model, model, opts, progress)
}

/// [`simulate`], resumed where `resume` allows: the checkpoints a run of
/// the same `model` and `opts` kept, and the first row at which `job`'s
/// rows differ from that run's job (the rows before it the same, bit for
/// bit: the caller's promise). The report is the one [`simulate`] gives;
/// the run keeps its own checkpoints for the next.
pub fn simulate_resumable(
    job: &Job,
    model: &SimModel,
    opts: &Options,
    resume: Option<(Checkpoints, usize)>,
) -> Result<(Outcome, Checkpoints), SimError> {
    simulate_plant_resumable(job, model, model, opts, resume)
}

/// [`simulate_resumable`] with the controller built for the `nominal`
/// model driving another `model` (a plant drawn around it).
pub fn simulate_plant_resumable(
    job: &Job,
    nominal: &SimModel,
    model: &SimModel,
    opts: &Options,
    resume: Option<(Checkpoints, usize)>,
) -> Result<(Outcome, Checkpoints), SimError> {
    run::run_resumable(
        job,
        nominal,
        model,
        opts,
        &[],
        &mut |_, _| {},
        resume,
        true,
        None,
    )
}

/// [`simulate`] with hardware faults injected (`--fault`): the report's
/// `safety` says what happened, when and where, and how the arm stopped.
pub fn simulate_faulted(
    job: &Job,
    model: &SimModel,
    opts: &Options,
    faults: &[fault::Fault],
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Outcome, SimError> {
    run::run_resumable(job, model, model, opts, faults, progress, None, false, None).map(|(o, _)| o)
}

/// [`simulate`] with the controller built for the `nominal` model (the
/// robot description) driving another `model` (a plant drawn around it).
pub fn simulate_plant(
    job: &Job,
    nominal: &SimModel,
    model: &SimModel,
    opts: &Options,
    progress: &mut dyn FnMut(u64, u64),
) -> Result<Outcome, SimError> {
    run::run_resumable(job, nominal, model, opts, &[], progress, None, false, None).map(|(o, _)| o)
}
