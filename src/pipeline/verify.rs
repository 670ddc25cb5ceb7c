//! Verification: every job compile writes is run through the closed-loop
//! simulator (`sim::simulate`, the default controller, the job's robot
//! dynamics) before it is written; a job whose nozzle strays more than
//! `VERIFY_SHARE` of the tolerance while painting, or that breaks a limit
//! of the plant, is re-timed slower by the caller or refused.
//!
//! A job that passes on the robot description is then run on a fixed set
//! of plants drawn around it ([`spread`]): the arm on the truck is not the
//! description. A plant that strays over `spread::SHARE` of the tolerance
//! fails the station, and the caller re-times where the first of them
//! failed, or keeps the station and records the failure where only a
//! slower whole path would help.

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
    /// The verdict of a plant of the spread set (`on_spread`), not of the
    /// robot description.
    pub on_spread: bool,
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
/// report job time; an electric kind's servo plant reads the rows' own
/// times, job times already, and takes no offset).
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
        return verify_servo(job).map(|v| (v, None));
    };
    let (model, opts) = verifying(robot)?;
    let (outcome, kept) = sim::simulate_resumable(job, &model, &opts, resume)
        .map_err(|e| CompileError::Verify(e.to_string()))?;
    Ok((judged(&outcome.report, t0_s, &opts), Some(kept)))
}

/// The robot's simulator model and the options every verification run
/// takes: the default controller and tolerance, the run ended at its
/// first painting error over the bound (whether it stays within is all
/// the verdict asks, and re-timing starts where it first failed).
fn verifying(robot: &crate::robot::Robot) -> Result<(SimModel, sim::Options), CompileError> {
    let model = SimModel::from_robot(robot)
        .map_err(|e| CompileError::Verify(format!("the robot's dynamics: {e}")))?;
    let tolerance_m = sim::Options::default().tolerance_m;
    let opts = sim::Options {
        stop_over_m: Some(VERIFY_SHARE * tolerance_m),
        // the verdict reads the error and the limits, not the waviness
        waviness: false,
        ..sim::Options::default()
    };
    Ok((model, opts))
}

/// [`judge`] of a run's report, its times `t0_s` later; a run ended where
/// its error first passed the bound says "at least".
fn judged(r: &sim::Report, t0_s: f64, opts: &sim::Options) -> Verdict {
    let mut worst = r.worst.clone();
    worst.t_s += t0_s;
    let broken: Vec<&str> = r
        .limits
        .iter()
        .filter(|l| l.fails)
        .map(|l| l.message.as_str())
        .collect();
    judge(
        r.max_error_m,
        &worst,
        &broken,
        opts.tolerance_m,
        r.cut_short_at_s.is_some(),
    )
}

/// Compile's verification on the plant spread: the draws `basr simulate
/// --plants N --spread 0.1 --seed 1` makes first (plants 0 to
/// `DRAWS − 1`), and the corner of the number that moves STOP's error most
/// within its own spread, the supply pressure at +5 % (3.90 → 4.46 mm on
/// STOP; −5 % lowers it to 3.64 mm, and every other number at its own
/// spread moves it by at most 0.33 mm). docs/simulate.md says which
/// numbers and how far.
pub mod spread {
    /// The spread the set is drawn at: `basr simulate`'s default.
    pub const SPREAD: f64 = 0.1;
    /// Seed of the draws.
    pub const SEED: u64 = 1;
    /// Monte Carlo draws in the set. source: six plants (with the corner)
    /// are three rounds of the two cores compile is sized for, each round
    /// a simulation of the station; the set's worst against the 95th
    /// percentile of 40 plants is measured in docs/simulate.md.
    pub const DRAWS: u32 = 5;
    /// The corner: the number deciding failures (`basr simulate`'s "most
    /// often deciding" on STOP over seeds 1–10 before the spreads were
    /// weighted, and the largest one-at-a-time effect after), at the top
    /// of its spread.
    pub const CORNER: &str = "hydraulics.supply_pa";
    /// Share of the tolerance every plant of the set may use: the
    /// description's own. source: six plants see less than forty; over
    /// STOP, SCHOOL, SCHOOL XING, STOP at full reach and the shipped
    /// markings the 95th percentile of 40 plants (seeds 1–3) was up to
    /// 1.25× the set's worst (STOP at full reach: 6.99 mm against 5.60 mm),
    /// and with the set held to 0.8 × the tolerance (1/1.25) a seed there
    /// still failed (6.46 mm); at 0.75 seeds 1–10 pass (docs/simulate.md).
    pub const SHARE: f64 = super::VERIFY_SHARE;

    /// The set: each plant's factors (as `sim::plants::draw` gives them)
    /// and how a message names it.
    pub fn plants() -> Vec<(String, Vec<f64>)> {
        let mut set: Vec<(String, Vec<f64>)> = (0..DRAWS)
            .map(|i| {
                (
                    format!("plant {i} of `--plants {DRAWS} --spread {SPREAD} --seed {SEED}`"),
                    crate::sim::plants::draw(SEED, i, SPREAD),
                )
            })
            .collect();
        let shares = crate::sim::plants::shares(SPREAD);
        let share = shares
            .iter()
            .find(|(n, _)| *n == CORNER)
            .map(|s| s.1)
            .expect("CORNER names an uncertain number of sim::plants");
        let corner: Vec<f64> = shares
            .iter()
            .map(|(n, _)| if *n == CORNER { 1.0 + share } else { 1.0 })
            .collect();
        set.push((
            format!("the plant with {CORNER} +{:.0} %", share * 100.0),
            corner,
        ));
        set
    }
}

/// What the plant set made of a station.
pub struct OnSpread {
    pub verdict: Verdict,
    /// Each plant's largest painting error (m, in [`spread::plants`]'
    /// order).
    pub errors: Vec<f64>,
    /// Each plant's run, for the next to resume from.
    pub kept: Vec<sim::Checkpoints>,
}

/// The plant set's verdict on a job (its rows one station's, reported
/// `t0_s` later), resumed as [`simulated_resuming`] is from `resume` (the
/// set's runs of the job as it was and the first row that changed);
/// `None` for the electric kinds, whose servo plant has no drawn numbers.
/// A plant that strays more than `spread::SHARE` of the tolerance fails
/// the job at that plant's first failure. `in_step`: the plants run
/// together and end soon after the first failure
/// (`sim::plants::run_each_in_step`: the same verdict; a passing plant's
/// error is then its largest up to there), for a caller that re-times
/// where the set fails; else each runs to its end or its own failure.
pub fn on_spread(
    job: &Job,
    t0_s: f64,
    resume: Option<(Vec<sim::Checkpoints>, usize)>,
    in_step: bool,
) -> Result<Option<OnSpread>, CompileError> {
    let Some(robot) = job.robot.basr() else {
        return Ok(None);
    };
    let (model, opts) = verifying(robot)?;
    let set = spread::plants();
    let factors: Vec<Vec<f64>> = set.iter().map(|p| p.1.clone()).collect();
    let runs = if in_step {
        sim::plants::run_each_in_step(job, &model, &opts, &factors, resume)
    } else {
        sim::plants::run_each(job, &model, &opts, &factors, resume)
    };
    let runs = runs.map_err(|e| CompileError::Verify(e.to_string()))?;
    Ok(judged_set(runs, t0_s, &opts, &set))
}

/// The plant set's verdict on its runs (`set`'s reports and checkpoints,
/// in order), as [`on_spread`] gives it.
fn judged_set(
    runs: Vec<(sim::Report, sim::Checkpoints)>,
    t0_s: f64,
    opts: &sim::Options,
    set: &[(String, Vec<f64>)],
) -> Option<OnSpread> {
    // the set is held to the description's own share (`spread::SHARE`)
    let bound_m = spread::SHARE * opts.tolerance_m;
    let (reports, kept): (Vec<sim::Report>, Vec<sim::Checkpoints>) = runs.into_iter().unzip();
    let errors: Vec<f64> = reports.iter().map(|r| r.max_error_m).collect();
    // The plant that failed first in the job (re-timing starts there),
    // else the one with the largest error.
    let failed = |r: &sim::Report| r.max_error_m > bound_m || r.limits.iter().any(|l| l.fails);
    let pick = reports
        .iter()
        .enumerate()
        .filter(|(_, r)| failed(r))
        .min_by(|a, b| a.1.worst.t_s.total_cmp(&b.1.worst.t_s))
        .or_else(|| {
            reports
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.max_error_m.total_cmp(&b.1.max_error_m))
        });
    let (k, r) = pick?;
    let mut v = judged(r, t0_s, opts);
    v.on_spread = true;
    if !v.ok {
        v.why = format!("on {} (the arm as it may be): {}", set[k].0, v.why);
    }
    Some(OnSpread {
        verdict: v,
        errors,
        kept,
    })
}

/// The robot description's verdict and the plant set's, the runs made
/// together (`sim::plants::run_beside_description_in_step`).
pub struct Together {
    /// The description's verdict and its run, for the next to resume from.
    pub verdict: Verdict,
    pub kept: sim::Checkpoints,
    /// A plant failed first (`sim::plants::Beside::stopped`): `verdict` is
    /// not the description's on the whole station, and `set` failed.
    pub stopped: bool,
    /// The set's verdict as [`on_spread`] in step gives it, when the
    /// description's run was not cut short by its own failure; else `Err`
    /// of the plants' runs as far as the group let them go, for the next
    /// round to resume from.
    pub set: Result<OnSpread, Vec<sim::Checkpoints>>,
}

/// [`simulated_resuming`] and [`on_spread`] in step, run together for a
/// job of BASR's kind (`robot`, the job's; the electric kinds have no
/// plant set) (`resume`: the description's last run and the first row
/// that changed; `set_resume`: the set's): the same verdicts, on two
/// cores that the description's run no longer leaves one of idle, except
/// that a plant failing first ends the description's run too
/// (`Together::stopped`).
pub fn together(
    job: &Job,
    robot: &crate::robot::Robot,
    t0_s: f64,
    resume: Option<(sim::Checkpoints, usize)>,
    set_resume: Option<(Vec<sim::Checkpoints>, usize)>,
) -> Result<Together, CompileError> {
    let (model, opts) = verifying(robot)?;
    let set = spread::plants();
    let factors: Vec<Vec<f64>> = set.iter().map(|p| p.1.clone()).collect();
    let beside = sim::plants::run_beside_description_in_step(
        job, &model, &opts, resume, &factors, set_resume,
    )
    .map_err(|e| CompileError::Verify(e.to_string()))?;
    let (outcome, kept) = beside.description;
    let verdict = judged(&outcome.report, t0_s, &opts);
    let set = match beside.plants {
        Ok(runs) => match judged_set(runs, t0_s, &opts, &set) {
            Some(s) => Ok(s),
            None => Err(Vec::new()),
        },
        Err(kept) => Err(kept),
    };
    Ok(Together {
        verdict,
        kept,
        stopped: beside.stopped,
        set,
    })
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
    let share = VERIFY_SHARE;
    let bound = share * tolerance_m;
    let ok = max_error_m <= bound && broken.is_empty();
    let why = if ok {
        String::new()
    } else {
        let mut w = format!(
            "the simulated nozzle strays {}{:.2} mm while painting (at most {:.2} mm = {share} \
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
        on_spread: false,
    }
}

/// An electric kind's job through its servo plant (`sim::servo_job`),
/// judged as BASR's: within `VERIFY_SHARE` of the default tolerance, no
/// joint out of its range. The servo plant reports the rows' own times
/// (`t_s`), which a station's rows keep from the whole job: its times are
/// job times already (adding the station's start, as BASR's runs from 0
/// need, put the worst error a station's start too late).
fn verify_servo(job: &Job) -> Result<Verdict, CompileError> {
    let tolerance = sim::Options::default().tolerance_m;
    let r = sim::servo_job::simulate_job(job, tolerance)
        .map_err(|e| CompileError::Verify(e.to_string()))?;
    Ok(judge(
        r.max_error_m,
        &r.worst,
        &r.broken_limits(),
        tolerance,
        false,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spread_set_is_the_first_draws_of_simulate_and_the_supply_corner() {
        let set = spread::plants();
        assert_eq!(set.len(), spread::DRAWS as usize + 1);
        for (i, (name, f)) in set.iter().take(spread::DRAWS as usize).enumerate() {
            // the draws `basr simulate --plants N --spread 0.1 --seed 1` makes
            assert_eq!(
                f,
                &sim::plants::draw(spread::SEED, i as u32, spread::SPREAD)
            );
            assert!(name.contains(&format!("plant {i} of")), "{name}");
        }
        let (name, corner) = set.last().unwrap();
        let names = sim::plants::names();
        for (n, f) in names.iter().zip(corner) {
            let want = if *n == spread::CORNER { 1.05 } else { 1.0 };
            assert!((f - want).abs() < 1e-12, "{n}: {f}");
        }
        assert!(name.contains("hydraulics.supply_pa +5 %"), "{name}");
    }

    #[test]
    fn a_plant_is_held_to_the_same_share_as_the_description() {
        let place = sim::report::Place::default();
        let none: [&str; 0] = [];
        let tol = 6.35e-3;
        let at = |e: f64| judge(e, &place, &none, tol, false);
        assert!(at(0.75 * tol - 1e-9).ok);
        let v = at(0.75 * tol + 1e-6);
        assert!(!v.ok);
        assert!(v.why.contains("0.75 × the 6.35 mm tolerance"), "{}", v.why);
        assert!(!judge(1e-3, &place, &["joint out of range"], tol, false).ok);
        assert_eq!(spread::SHARE, VERIFY_SHARE);
    }
}
