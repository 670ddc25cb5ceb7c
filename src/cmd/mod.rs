//! One module per subcommand. Each has `Args` (clap) and
//! `run(Args, &Global) -> anyhow::Result<Outcome>`; an `Err` exits with 2.

pub mod calibrate;
pub mod check;
pub mod compile;
pub mod design;
pub mod export;
pub mod fit;
pub mod glyphs;
pub mod import;
pub mod keygen;
pub mod outputs;
pub mod pose;
pub mod preview;
pub mod replan;
pub mod report;
pub mod robot;
pub mod simulate;
pub mod sizes;
pub mod symbols;
pub mod workspace;
pub mod workspace_kinds;

use std::path::Path;

/// Options every subcommand sees.
pub struct Global {
    /// `--quiet`: no human text on stderr except errors.
    pub quiet: bool,
}

/// `--units`: the crew's units for truck positions and sizes.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum UnitsArg {
    /// Metres (4.60 m).
    Metric,
    /// Feet and inches, to the inch (15 ft 1 in).
    Us,
}

impl From<UnitsArg> for basr::units::System {
    fn from(u: UnitsArg) -> Self {
        match u {
            UnitsArg::Metric => basr::units::System::Metric,
            UnitsArg::Us => basr::units::System::Us,
        }
    }
}

/// How a command that ran to the end turned out.
pub enum Outcome {
    /// Exit 0.
    Success,
    /// Exit 1: the work ran but its verdict is negative.
    Negative,
}

/// Refuse a run whose outputs name one file twice or name one of its
/// inputs: the later write would replace the other file (`compile -o
/// STOP.csv --csv STOP.csv`, `preview STOP.job.json -o STOP.job.json`).
/// Each entry is (what it is for, path); `-` never clashes.
pub fn refuse_clashes(outputs: &[(&str, &Path)], inputs: &[(&str, &Path)]) -> anyhow::Result<()> {
    let all: Vec<(&str, &Path)> = outputs.iter().chain(inputs).copied().collect();
    if let Some(((a, path), (b, _))) = basr::io::same_file_pair(&all) {
        let written = |x: &str| outputs.iter().any(|(n, _)| *n == x);
        if !written(a) && !written(b) {
            // two inputs named by one path: one of them is not what it
            // should be (`fit JOB --points JOB`)
            anyhow::bail!(
                "{a} and {b} name one file, {}: each is a file of its own; give the path of \
                 {b}",
                path.display()
            );
        }
        let what = if written(b) {
            "each would be written over the other"
        } else {
            "writing it would destroy the input"
        };
        anyhow::bail!(
            "{a} and {b} are the same file, {}: {what}; give a different path for {a}",
            path.display()
        );
    }
    Ok(())
}

/// Whether a command shows progress on stderr: only on a terminal, and
/// never under `--quiet` or `--json` (a script reading either wants no
/// control characters on its streams).
pub fn shows_progress(quiet: bool, json: bool, stderr_is_terminal: bool) -> bool {
    !quiet && !json && stderr_is_terminal
}

/// A spinner on stderr saying `what` and the time it has taken, for work
/// that cannot count its steps (a compile: layout, planning, the verifying
/// simulation of each stop, the film); hidden unless `show` and stderr is
/// a terminal. Its own thread redraws it, so it moves while the work runs.
pub fn spinner(show: bool, what: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !(show && std::io::stderr().is_terminal()) {
        return indicatif::ProgressBar::hidden();
    }
    let b = indicatif::ProgressBar::new_spinner();
    b.set_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    b.set_message(what.to_string());
    // assumed: 8 redraws a second reads as moving and costs nothing.
    b.enable_steady_tick(std::time::Duration::from_millis(125));
    b
}

/// A progress bar on stderr when `show` and stderr is a terminal (hidden
/// otherwise, so logs and pipes get no control characters).
pub fn progress_bar(show: bool, what: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !(show && std::io::stderr().is_terminal()) {
        return indicatif::ProgressBar::hidden();
    }
    let b = indicatif::ProgressBar::new(1);
    b.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{what} {{bar:40}} {{percent:>3}}%, {{eta}} left"
        ))
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    b
}

/// Read a job, saying what the file is when it is a setpoint CSV or
/// another of basr's outputs rather than a job; under `--trust` (the
/// command's flattened [`basr::job::trust::TrustOptions`]) only a job the
/// trusted key signed.
pub fn read_job(
    path: &Path,
    trust: &basr::job::trust::TrustOptions,
) -> anyhow::Result<basr::job::Job> {
    if let Some(what) = not_a_job(path) {
        anyhow::bail!(
            "{}: this is {what}, not a job file; give the job that `basr compile` wrote \
             (STOP.job.json for `basr compile STOP`)",
            path.display()
        );
    }
    trust.read_job(path)
}

/// What a file given as a job is instead, from its name or first bytes.
fn not_a_job(path: &Path) -> Option<&'static str> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let mut head = [0u8; 64];
    // An unreadable file is the job reader's to report.
    let n = std::fs::File::open(path)
        .and_then(|mut f| std::io::Read::read(&mut f, &mut head))
        .ok()?;
    let head = String::from_utf8_lossy(&head[..n]);
    let head = head.trim_start();
    if head.starts_with("t_s,") || ext.as_deref() == Some("csv") && !head.starts_with('{') {
        Some("a setpoint CSV (`compile --csv` writes it beside the job)")
    } else if head.starts_with("<svg") || head.starts_with("<?xml") {
        Some("an SVG picture")
    } else if head.starts_with("<!DOCTYPE html") || head.starts_with("<html") {
        Some("an HTML page (a job sheet from `basr report`)")
    } else if ext.as_deref() == Some("toml") {
        Some("a TOML file (a font, robot or marking: `basr check` reads those)")
    } else {
        None
    }
}

/// An output named after the job, in the current folder:
/// `a/STOP.job.json` → `STOP.EXT`.
pub fn named_after_job(job: &Path, ext: &str) -> std::path::PathBuf {
    let name = job
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "job".into());
    let stem = name.strip_suffix(".json").unwrap_or(&name);
    let stem = stem.strip_suffix(".job").unwrap_or(stem);
    std::path::PathBuf::from(format!("{stem}.{ext}"))
}
