//! `basr report JOB -o FILE.html`: the job sheet for the crew and the
//! supervisor, one self-contained page to print.

use std::path::{Path, PathBuf};

use anyhow::Context;
use basr::job::trust::Seal;
use basr::paint::film::{FilmOptions, JobFilm};
use basr::paint::preview::{self, Panel};
use basr::report::{self, tally::Tally, SimVerdict};

use super::{Global, Outcome};

/// Write the job sheet: one HTML page a supervisor can print.
///
/// The page says what to paint, where to stop the truck (from the
/// marking's anchor: the lane centre at the near edge of the first line),
/// the time on site, the paint and the spray tip's life left, the film the
/// plan lays with a verdict per letter, the simulated arm's verdict, and the
/// warnings by severity, under one word: READY, READY WITH NOTES or NOT
/// READY. Everything is inline (CSS, SVG): the page needs no network.
#[derive(clap::Args)]
#[command(after_help = "\
Examples:
  basr report STOP.job.json -o STOP.html
  basr report STOP.job.json -o STOP.html --tip-tally tip.toml   # counts the paint
  basr simulate STOP.job.json --json > sim.json
  basr report STOP.job.json -o STOP.html --sim sim.json          # no second simulation

Exit 0 when the page is written and the job is READY or READY WITH NOTES,
1 when it is NOT READY (the page is written and says why), 2 for bad input.
docs/report.md describes the page and the tally file.")]
pub struct Args {
    /// The job file written by `basr compile`.
    pub job: PathBuf,

    #[command(flatten)]
    pub trust: basr::job::trust::TrustOptions,

    /// The page to write (.html) [default: the job's name with .sheet.html,
    /// here: STOP.job.json → STOP.sheet.html].
    #[arg(short, long, value_name = "FILE.html")]
    pub output: Option<PathBuf>,

    /// A `basr simulate --json` result for this job, instead of simulating
    /// it again.
    #[arg(long, value_name = "FILE", conflicts_with = "no_sim")]
    pub sim: Option<PathBuf>,

    /// Leave the simulator out (the page says it was not simulated).
    #[arg(long)]
    pub no_sim: bool,

    /// Units for the truck's stops and the sizes on the page: metric
    /// (4.60 m) or us (feet and inches, 15 ft 1 in).
    #[arg(long, value_enum, default_value = "metric")]
    pub units: super::UnitsArg,

    /// The crew's tally of paint through the current spray tip (TOML; made
    /// when missing). This job's paint is added once; start a new file for
    /// a new tip.
    #[arg(long, value_name = "FILE")]
    pub tip_tally: Option<PathBuf>,
}

fn read_sim(path: &Path) -> anyhow::Result<SimVerdict> {
    let text = basr::io::read_text(path)?;
    serde_json::from_str(&text).map_err(|e| {
        anyhow::anyhow!(
            "{}: not a `basr simulate --json` result ({e}); write one with \
             `basr simulate JOB --json > {}`",
            path.display(),
            path.display()
        )
    })
}

/// `sim` (read from `path`), when it is this job's: a result that names
/// another job (its `job_sha256`), or one written before results named
/// their job, is refused (exit 2): the sheet would give another job's
/// verdict as this one's.
fn sim_of_job(sim: SimVerdict, path: &Path, job: &basr::job::Job) -> anyhow::Result<SimVerdict> {
    let again = format!(
        "simulate this job again: `basr simulate JOB --json > {}`, or leave --sim out",
        path.display()
    );
    let short = |s: &str| s.chars().take(12).collect::<String>();
    match &sim.job_sha256 {
        Some(sha) if *sha == job.sha256 => Ok(sim),
        Some(sha) => anyhow::bail!(
            "{}: the simulate result is of another job (sha256 {}…), not this one ({}…); {again}",
            path.display(),
            short(sha),
            short(&job.sha256)
        ),
        None => anyhow::bail!(
            "{}: the simulate result does not name the job it simulated (written before \
             results did); {again}",
            path.display()
        ),
    }
}

fn simulate(job: &basr::job::Job, show: bool) -> anyhow::Result<SimVerdict> {
    use basr::sim;
    let Some(robot) = job.robot.basr() else {
        // An electric kind: its servo plant, at its description's accuracy.
        let r = sim::servo_job::simulate_job(job, job.robot.control().accuracy_m)?;
        return Ok(SimVerdict::from_servo(&r));
    };
    let model = sim::SimModel::from_robot(robot)
        .map_err(|e| anyhow::anyhow!("the job's robot cannot be simulated: {e} (use --no-sim)"))?;
    let opts = sim::Options {
        controller: sim::ControllerKind::Sjct,
        tolerance_m: robot.control.accuracy_m,
        keep_trace: false,
        substeps: None,
        stop_over_m: None,
        waviness: true,
    };
    let bar = super::progress_bar(show, "simulating the arm");
    let outcome = sim::simulate(job, &model, &opts, &mut |done, total| {
        bar.set_length(total);
        bar.set_position(done);
    })?;
    bar.finish_and_clear();
    Ok(SimVerdict::from_report(&outcome.report))
}

/// What the job's signature proves, for the sheet: under `--trust` the
/// reader has verified it; else the key its id names in the key folder
/// verifies it, or it is said to be unverified. A signature malformed or
/// refused by the key at hand is refused here (exit 2), as `check` lists it.
fn seal(job: &basr::job::Job, args: &Args) -> anyhow::Result<Seal> {
    if let (Some(key), Some(path)) = (args.trust.key()?, &args.trust.trust) {
        return Ok(Seal::Verified {
            key_id: key.id(),
            key: path.clone(),
        });
    }
    if job.signature.is_none() {
        return Ok(Seal::Unsigned);
    }
    let bytes = basr::io::read_bytes(&args.job)?;
    basr::job::trust::examine(
        job.signature.as_ref(),
        basr::job::signed_bytes(&bytes).as_deref(),
        basr::job::trust::key_folder().as_deref(),
    )
    .map_err(|e| anyhow::anyhow!("{}: {e}", args.job.display()))
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| super::named_after_job(&args.job, "sheet.html"));
    let mut outputs: Vec<(&str, &Path)> = vec![("the page (-o)", &out)];
    if let Some(t) = &args.tip_tally {
        outputs.push(("the tip tally (--tip-tally)", t));
    }
    let mut inputs: Vec<(&str, &Path)> = vec![("the job", &args.job)];
    if let Some(s) = &args.sim {
        inputs.push(("the simulate result (--sim)", s));
    }
    super::refuse_clashes(&outputs, &inputs)?;
    super::outputs::check("-o", &out, &["html", "htm"])?;
    if let Some(t) = &args.tip_tally {
        super::outputs::check("--tip-tally", t, &["toml"])?;
    }
    basr::io::check_writable(&out)?;
    let job = super::read_job(&args.job, &args.trust)?;
    // The content checks preview and simulate run first (exit 2): a
    // re-sealed job with every z_m = 1e6 once took 30 s and 619 MB here and
    // came out "simulate PASS" (issue 31, R6).
    super::simulate::content_checks(&job, &args.job)?;
    let origin = args.job.display().to_string();
    let seal = seal(&job, &args)?;
    let sim = match (&args.sim, args.no_sim) {
        (Some(p), _) => Some(sim_of_job(read_sim(p)?, p, &job)?),
        (None, true) => None,
        (None, false) => Some(simulate(&job, !global.quiet)?),
    };
    // A tally counts one tip: a job planned for another is refused here,
    // before anything is written.
    let tally = match &args.tip_tally {
        Some(p) => {
            let origin = p.display().to_string();
            let read = if p.exists() {
                Tally::parse(&basr::io::read_text(p)?, &origin)?
            } else {
                Tally::default()
            };
            Some(read.for_tip(job.paint.tip.as_deref(), &origin)?)
        }
        None => None,
    };

    // The film stage at preview's defaults: what compile recorded in
    // `summary.film` and what `basr preview JOB` prints.
    let bar = super::progress_bar(!global.quiet, "painting");
    let JobFilm {
        preview: film,
        verdict: film_verdict,
    } = basr::paint::film::film(&job, &FilmOptions::preview_defaults(), &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    })
    .with_context(|| format!("{origin}: preview"))?;
    bar.finish_and_clear();
    let panel = Panel {
        job: &job,
        preview: &film,
        verdict: &film_verdict,
        from_sim: false,
        replanned: None,
    };
    let film_svg = preview::render_svg(
        &[panel],
        &format!("film of {}", job.message.replace('\n', " / ")),
    );

    let sheet = report::build(&report::Input {
        job_name: &origin,
        job: &job,
        film: &film.metrics,
        film_verdict: &film_verdict,
        film_svg: &film_svg,
        sim: sim.as_ref(),
        tip_used_before_m3: tally.as_ref().map(|t| t.used_m3_without(&job.sha256)),
        signature: &seal.describe(),
        units: args.units.into(),
    });
    basr::io::write_atomic(&out, report::html::render(&sheet).as_bytes())?;
    if let (Some(p), Some(t)) = (&args.tip_tally, tally) {
        let t = t.with_job(&job.sha256, &job.message, job.summary.paint_volume_m3);
        basr::io::write_atomic(p, t.to_toml().as_bytes())?;
        super::outputs::after_commit(format!(
            "tip tally {}: {:.2} L through this tip with this job",
            p.display(),
            t.used_m3_without("") * 1e3
        ));
    }
    // The verdict first: it is what the reader acts on.
    super::outputs::after_commit(format!(
        "{}: wrote {} (the job sheet{})",
        sheet.overall.to_uppercase(),
        out.display(),
        if sheet.overall == "not ready" {
            "; it says why: do not paint this job"
        } else {
            ""
        }
    ));
    // NOT READY is a negative verdict (exit 1), as compile's; the page is
    // written all the same.
    Ok(if sheet.overall == "not ready" {
        Outcome::Negative
    } else {
        Outcome::Success
    })
}
