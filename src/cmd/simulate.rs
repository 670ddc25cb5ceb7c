//! `basr simulate JOB`: the arm, its hydraulics and its controller in closed
//! loop; verdict against the tolerance (exit 0 pass, 1 fail, 2 bad input).

use std::io::IsTerminal;
use std::path::PathBuf;

use super::{Global, Outcome};
use basr::sim::{self, ControllerKind};

/// Controller choice for the command line (000 section III's four programs).
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum ControllerArg {
    /// PID on both joints: stable, less accurate.
    Pid,
    /// SJCT + Sohl–Bobrow on the base rotation, PID on extension (the seed's best).
    Sjct,
    /// Simplified Cartesian Computed Torque: unstable without changes, as the seed warns.
    Scct,
    /// Dynamic inversion on the base rotation, PID on extension.
    Dyninv,
}

impl From<ControllerArg> for ControllerKind {
    fn from(c: ControllerArg) -> ControllerKind {
        match c {
            ControllerArg::Pid => ControllerKind::Pid,
            ControllerArg::Sjct => ControllerKind::Sjct,
            ControllerArg::Scct => ControllerKind::Scct,
            ControllerArg::Dyninv => ControllerKind::Dyninv,
        }
    }
}

/// Simulate a job on the arm in closed loop and judge its nozzle accuracy.
///
/// Plays the job's setpoints through the controller (every 5 ms) into a model
/// of the pantograph arm, its hydraulic motor and cylinder, servovalves,
/// end-effector servos and linkage compliance, and measures how far the
/// nozzle strays from the planned path while painting. A job for a
/// telescopic or articulated robot (docs/robot-kinds.md) runs that kind's servo plant
/// instead: each joint's inertia under PID + feed-forward with its drive's
/// torque and speed limits (docs/robot-kinds.md).
#[derive(clap::Args)]
#[command(after_help = "Examples:
  basr simulate STOP.job.json
  basr simulate STOP.job.json --controller pid --svg stop-sim.svg --trace stop-sim.csv
  basr simulate STOP.job.json --json | jq .max_error_m
  basr simulate STOP.job.json --plants 40 --spread 0.1 --seed 7   # verdict on p95 of 40 plants
  basr simulate T.job.json --robot robots/telescopic.toml        # an electric kind's servo plant
  basr simulate STOP.job.json --fault valve-stuck@30   # does the arm stop, where, how much paint off the path

Exit codes: 0 pass, 1 over tolerance or a limit violated, 2 bad input
(unreadable or edited job, job for another robot description).")]
pub struct Args {
    /// The job file written by `basr compile`.
    pub job: PathBuf,

    #[command(flatten)]
    pub trust: basr::job::trust::TrustOptions,

    /// Controller program to run.
    #[arg(long, value_enum, default_value = "sjct")]
    pub controller: ControllerArg,

    /// Largest allowed nozzle error while painting, in millimetres (1/4 in by default).
    #[arg(allow_hyphen_values = true, long, default_value_t = 6.35)]
    pub tolerance_mm: f64,

    /// Robot description the job must have been compiled for (default: the embedded BASR).
    #[arg(long)]
    pub robot: Option<PathBuf>,

    /// Write the desired and actual time series as CSV here.
    #[arg(long, value_name = "CSV")]
    pub trace: Option<PathBuf>,

    /// Write an SVG of desired vs actual path (error magnified) and the error over time.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,

    /// Write the simulation as MCAP (JSON channels with JSON schemas:
    /// nozzle desired/actual in the road frame, joints, error) for
    /// Foxglove or Rerun (docs/exports.md).
    #[arg(long, value_name = "FILE.mcap")]
    pub mcap: Option<PathBuf>,

    /// Print the report as JSON on stdout.
    #[arg(long)]
    pub json: bool,

    /// Simulate this many plants drawn around the robot description (1 = the
    /// description alone); the verdict is then on the 95th percentile of
    /// their max errors (docs/simulate.md).
    #[arg(long, default_value_t = 1, value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..=10000))]
    pub plants: u32,

    /// How far each plant's uncertain numbers are drawn from the
    /// description (0–0.5): a number known as well as most (a mass, a valve's
    /// rated flow) within ± this fraction, friction and the oil's modulus
    /// within twice it, the supply pressure within half and the pressure
    /// transducers within a tenth (docs/simulate.md lists each), none past
    /// ±50 %.
    #[arg(
        long,
        default_value_t = 0.1,
        value_name = "F",
        allow_hyphen_values = true
    )]
    pub spread: f64,

    /// Seed of the plants' draws: the same seed gives the same plants and bytes.
    #[arg(long, default_value_t = 1, value_name = "S")]
    pub seed: u64,

    /// Inject a hardware fault at a time of the job: supply-drop@T (the
    /// supply vents to tank), encoder-glitch@T (the base encoder jumps by
    /// 1000 counts), valve-stuck@T (the base motor's spool jams). May be
    /// given up to 8 times. The report says when the safety monitor stopped
    /// the arm, where it came to rest and how much paint went off the path.
    #[arg(long, value_name = "KIND@T", value_parser = parse_fault)]
    pub fault: Vec<sim::fault::Fault>,

    /// RK4 sub-steps per control period (default: as few as the plant's fastest mode allows; four
    /// of 1.25 ms on the default robot), 1–100.
    #[arg(allow_hyphen_values = true, long, hide = true,
          value_parser = clap::value_parser!(u32).range(1..=100))]
    pub substeps: Option<u32>,
}

fn parse_fault(s: &str) -> Result<sim::fault::Fault, sim::fault::FaultError> {
    s.parse()
}

/// Before any work, the same content checks as `basr check` (time base,
/// indices, joint limits, forward kinematics of the columns): a correctly
/// sealed job can still hold a tilt of 90° or a row at t = 1e9 s.
/// Exit 2 naming every problem found.
pub fn content_checks(job: &basr::job::Job, path: &std::path::Path) -> anyhow::Result<()> {
    let problems = basr::job::verify::problems(job, &path.display().to_string());
    if !problems.is_empty() {
        anyhow::bail!(
            "the job fails the content checks of `basr check` (compile it again):\n  {}",
            problems.join("\n  ")
        );
    }
    Ok(())
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    if !(args.spread.is_finite() && (0.0..=0.5).contains(&args.spread)) {
        anyhow::bail!(
            "--spread {} must be a fraction 0–0.5 (0.1 = most uncertain numbers within ±10 %; docs/simulate.md lists each)",
            args.spread
        );
    }
    if !(args.tolerance_mm.is_finite() && args.tolerance_mm > 0.0) {
        anyhow::bail!(
            "--tolerance-mm {} must be a positive number of millimetres",
            args.tolerance_mm
        );
    }
    if !args.fault.is_empty() && args.plants > 1 {
        anyhow::bail!(
            "--fault and --plants {} together: a fault is simulated on the description's plant \
             alone; leave one of them out",
            args.plants
        );
    }
    if args.fault.len() > sim::fault::MAX_FAULTS {
        anyhow::bail!(
            "{} --fault flags: give at most {}",
            args.fault.len(),
            sim::fault::MAX_FAULTS
        );
    }
    let mut outputs: Vec<(&str, &std::path::Path)> = vec![];
    if let Some(p) = &args.trace {
        outputs.push(("--trace", p));
    }
    if let Some(p) = &args.svg {
        outputs.push(("--svg", p));
    }
    if let Some(p) = &args.mcap {
        outputs.push(("--mcap", p));
    }
    let mut inputs: Vec<(&str, &std::path::Path)> = vec![("the job", &args.job)];
    if let Some(p) = &args.robot {
        inputs.push(("the robot file (--robot)", p));
    }
    super::refuse_clashes(&outputs, &inputs)?;
    if let Some(p) = &args.trace {
        super::outputs::check("--trace", p, &["csv"])?;
    }
    if let Some(p) = &args.svg {
        super::outputs::check("--svg", p, &["svg"])?;
    }
    if let Some(p) = &args.mcap {
        super::outputs::check("--mcap", p, &["mcap"])?;
    }
    for (_, p) in &outputs {
        basr::io::check_writable(p)?;
    }
    let job = super::read_job(&args.job, &args.trust)?;
    // A robot listing tips is compared with the tip the job mounts.
    let robot = basr::robot::AnyRobot::load_or_default(args.robot.as_deref())?
        .with_mounted(job.paint.tip.as_deref());
    let want = robot.sha256();
    if job.robot_sha256 != want {
        anyhow::bail!(
            "{}: the job was compiled for another robot description (robot_sha256 {}), not {} ({}); compile it again for this robot or pass the right one with --robot",
            args.job.display(),
            job.robot_sha256,
            args.robot
                .as_ref()
                .map_or("the embedded BASR".to_string(), |p| p.display().to_string()),
            want
        );
    }
    content_checks(&job, &args.job)?;
    let Some(basr_robot) = job.robot.basr() else {
        return run_servo(&args, global, &job);
    };
    let model = sim::SimModel::from_robot(basr_robot).map_err(|e| {
        anyhow::anyhow!(
            "{}: the robot description cannot be simulated: {e}",
            args.job.display()
        )
    })?;
    let opts = sim::Options {
        controller: args.controller.into(),
        tolerance_m: args.tolerance_mm * 1e-3,
        keep_trace: args.trace.is_some() || args.svg.is_some() || args.mcap.is_some(),
        substeps: args.substeps,
        stop_over_m: None,
        waviness: true,
    };
    let show = super::shows_progress(global.quiet, args.json, std::io::stderr().is_terminal());
    let bar = if show {
        let b = indicatif::ProgressBar::new(1);
        b.set_style(
            indicatif::ProgressStyle::with_template(
                "simulating {bar:40} {percent:>3}% of the job, {eta} left",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b
    } else {
        indicatif::ProgressBar::hidden()
    };
    let outcome = sim::simulate_faulted(&job, &model, &opts, &args.fault, &mut |done, total| {
        bar.set_length(total);
        bar.set_position(done);
    })?;
    bar.finish_and_clear();
    let mut outcome = outcome;
    if args.plants > 1 {
        let p = sim::plants::PlantsOptions {
            n: args.plants,
            spread: args.spread,
            seed: args.seed,
        };
        let bar = super::progress_bar(
            !global.quiet && !args.json,
            &format!("simulating {} plants", args.plants),
        );
        let summary = sim::plants::run_with_progress(&job, &model, &opts, &p, &|done, total| {
            bar.set_length(total.into());
            bar.set_position(done.into());
        });
        bar.finish_and_clear();
        let summary = summary?;
        let r = &mut outcome.report;
        // the verdict is the plants' p95, with the description's limits
        r.reasons.retain(|m| !m.starts_with("nozzle error"));
        if summary.p95_max_error_m > r.tolerance_m {
            r.reasons.insert(
                0,
                format!(
                    "the 95th percentile of the nozzle error over {} plants, {:.3} mm, exceeds the tolerance {:.3} mm{}",
                    summary.n,
                    summary.p95_max_error_m * 1e3,
                    r.tolerance_m * 1e3,
                    summary
                        .deciding_parameter
                        .as_ref()
                        .map(|d| format!(" (most often deciding: {d})"))
                        .unwrap_or_default()
                ),
            );
        }
        r.verdict = basr::sim::report::Verdict::of(&r.reasons);
        r.verdict_on = basr::sim::report::VerdictOn::PlantsP95;
        r.plants = Some(summary);
    }
    let report = &outcome.report;

    // Both outputs or neither: main renames them into place together, or
    // drops both when the SVG (or anything else) fails.
    if let Some(p) = &args.trace {
        basr::io::write_atomic_with(p, |w| {
            let mut out = csv::Writer::from_writer(w);
            for row in &outcome.trace {
                out.serialize(row).map_err(std::io::Error::other)?;
            }
            out.flush()
        })?;
    }
    if let Some(p) = &args.svg {
        basr::io::write_atomic(p, sim::svg::render(&outcome.trace, report).as_bytes())?;
    }
    if let Some(p) = &args.mcap {
        let bytes = basr::export::mcap_trace::trace(&outcome.trace, &job.message)?;
        basr::io::write_atomic(p, &bytes)?;
    }
    for p in args.trace.iter().chain(&args.svg).chain(&args.mcap) {
        super::outputs::after_commit(format!("wrote {}", p.display()));
    }
    say(
        &args,
        global,
        &job.sha256,
        report,
        &report.human(),
        report.passed(),
    )
}

/// The report as JSON on stdout (`--json`, led by the job's `job_sha256`,
/// so that `basr report --sim` takes it only for this job) or its human
/// lines on stderr; exit 0 on pass, 1 on fail.
fn say(
    args: &Args,
    global: &Global,
    job_sha256: &str,
    report: &impl serde::Serialize,
    human: &str,
    passed: bool,
) -> anyhow::Result<Outcome> {
    #[derive(serde::Serialize)]
    struct OfJob<'a, R: serde::Serialize> {
        job_sha256: &'a str,
        #[serde(flatten)]
        report: &'a R,
    }
    if args.json {
        let v = OfJob { job_sha256, report };
        basr::io::print_stdout(&(serde_json::to_string_pretty(&v)? + "\n"))?;
    } else if !global.quiet {
        crate::note_text(human);
    }
    Ok(if passed {
        Outcome::Success
    } else {
        Outcome::Negative
    })
}

/// An electric kind's job (telescopic, articulated): its servo plant
/// (`sim::servo_job`); the hydraulic options do not apply and are refused.
fn run_servo(args: &Args, global: &Global, job: &basr::job::Job) -> anyhow::Result<Outcome> {
    let kind = job.robot.kind().name();
    for (given, flag) in [
        (args.trace.is_some(), "--trace"),
        (args.svg.is_some(), "--svg"),
        (args.mcap.is_some(), "--mcap"),
        (args.plants > 1, "--plants"),
        (args.substeps.is_some(), "--substeps"),
        (!args.fault.is_empty(), "--fault"),
    ] {
        if given {
            anyhow::bail!(
                "{flag} is for BASR's hydraulic simulation; the job's robot is of the {kind} kind, \
                 simulated by its servo plant without it: leave {flag} out (docs/robot-kinds.md)"
            );
        }
    }
    let report = sim::servo_job::simulate_job(job, args.tolerance_mm * 1e-3)?;
    say(
        args,
        global,
        &job.sha256,
        &report,
        &report.human(),
        report.passed(),
    )
}
