//! Verification: every job compile writes is run through the closed-loop
//! simulator (`sim::simulate`, the default controller, the job's robot
//! dynamics) before it is written; a job whose nozzle strays more than
//! `VERIFY_SHARE` of the tolerance while painting, or that breaks a limit
//! of the plant, is re-timed slower by the caller or refused.

use crate::job::Job;
use crate::sim::{self, SimModel};

use basr_plan::error::CompileError;

/// Share of the tolerance the verified error may use (issue 11: 0.75 ×
/// 6.35 mm), leaving the rest for what the model does not know.
pub const VERIFY_SHARE: f64 = 0.75;

/// What the simulator made of a job.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    pub max_error_m: f64,
    /// Within `VERIFY_SHARE` of the tolerance and no plant limit broken.
    pub ok: bool,
    /// Where and why it failed (empty when `ok`).
    pub why: String,
    /// Station and stroke of the worst error (stroke −1 in an air move).
    pub worst: (u32, i64),
    /// Job time of the worst error (s): where the run first went over the
    /// bound, for a run ended there.
    pub worst_t_s: f64,
}

/// Simulate `job` with the default options and judge it.
pub fn verify(job: &Job) -> Result<Verdict, CompileError> {
    content(job)?;
    simulated(job, 0.0)
}

/// The checks `basr check` and `simulate` make of every job: compile must
/// not write one they refuse.
pub fn content(job: &Job) -> Result<(), CompileError> {
    let problems = crate::job::verify::problems(job, "the compiled job");
    if let Some(first) = problems.first() {
        return Err(CompileError::Verify(format!(
            "the job fails the content checks of `basr check` ({} problem(s)), first: {first}; \
             this is a planner bug, please report it",
            problems.len()
        )));
    }
    Ok(())
}

/// Simulate `job` (the content checks already made) and judge it; its
/// times are reported `t0_s` later (a station's rows simulated alone
/// report job time).
pub fn simulated(job: &Job, t0_s: f64) -> Result<Verdict, CompileError> {
    simulated_resuming(job, t0_s, None).map(|(v, _)| v)
}

/// [`simulated`], resumed from `resume` (a run of the job as it was before
/// its rows changed from a row on: its checkpoints and that row) and
/// keeping checkpoints for the next (none for the electric kinds, whose
/// runs are short). The verdict is the one a whole run gives.
pub fn simulated_resuming(
    job: &Job,
    t0_s: f64,
    resume: Option<(sim::Checkpoints, usize)>,
) -> Result<(Verdict, Option<sim::Checkpoints>), CompileError> {
    let Some(robot) = job.robot.basr() else {
        return verify_servo(job, t0_s).map(|v| (v, None));
    };
    let model = SimModel::from_robot(robot)
        .map_err(|e| CompileError::Verify(format!("the robot's dynamics: {e}")))?;
    // A run is ended at its first painting error over the bound: whether
    // it stays within is all the verdict asks, and re-timing starts where
    // it first failed.
    let tolerance_m = sim::Options::default().tolerance_m;
    let opts = sim::Options {
        stop_over_m: Some(VERIFY_SHARE * tolerance_m),
        ..sim::Options::default()
    };
    let (outcome, kept) = sim::simulate_resumable(job, &model, &opts, resume)
        .map_err(|e| CompileError::Verify(e.to_string()))?;
    let mut r = outcome.report;
    r.worst.t_s += t0_s;
    let broken: Vec<&str> = r
        .limits
        .iter()
        .filter(|l| l.fails)
        .map(|l| l.message.as_str())
        .collect();
    // A run ended where its error first passed the bound says "at least".
    let verdict = judge(
        r.max_error_m,
        &r.worst,
        &broken,
        opts.tolerance_m,
        r.cut_short_at_s.is_some(),
    );
    Ok((verdict, Some(kept)))
}

/// The verdict on a simulated job: its painting error within
/// `VERIFY_SHARE` of `tolerance_m` and no limit `broken`; `cut_short`: the
/// run ended at its first error over the bound, so the error is a least.
fn judge(
    max_error_m: f64,
    worst: &sim::report::Place,
    broken: &[impl AsRef<str>],
    tolerance_m: f64,
    cut_short: bool,
) -> Verdict {
    let bound = VERIFY_SHARE * tolerance_m;
    let ok = max_error_m <= bound && broken.is_empty();
    let why = if ok {
        String::new()
    } else {
        let mut w = format!(
            "the simulated nozzle strays {}{:.2} mm while painting (at most {:.2} mm = {VERIFY_SHARE} \
             × the {:.2} mm tolerance) at {}",
            if cut_short { "at least " } else { "" },
            max_error_m * 1e3,
            bound * 1e3,
            tolerance_m * 1e3,
            worst.describe()
        );
        if !broken.is_empty() {
            let b: Vec<&str> = broken.iter().map(AsRef::as_ref).collect();
            w.push_str(&format!("; limits broken: {}", b.join("; ")));
        }
        w
    };
    Verdict {
        max_error_m,
        ok,
        why,
        worst: (worst.station, worst.stroke),
        worst_t_s: worst.t_s,
    }
}

/// An electric kind's job through its servo plant (`sim::servo_job`),
/// judged as BASR's: within `VERIFY_SHARE` of the default tolerance, no
/// joint out of its range.
fn verify_servo(job: &Job, t0_s: f64) -> Result<Verdict, CompileError> {
    let tolerance = sim::Options::default().tolerance_m;
    let mut r = sim::servo_job::simulate_job(job, tolerance)
        .map_err(|e| CompileError::Verify(e.to_string()))?;
    r.worst.t_s += t0_s;
    Ok(judge(
        r.max_error_m,
        &r.worst,
        &r.broken_limits(),
        tolerance,
        false,
    ))
}
