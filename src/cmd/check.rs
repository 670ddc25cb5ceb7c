//! `basr check FILE...`: validate font, robot, marking, job and CSV files,
//! reporting every problem found (exit 1 when any file has problems, 2 when
//! any could not be read; the others are still checked). A CSV given with
//! its job is checked to be the one written with it (docs/signed-jobs.md).

use std::path::PathBuf;

use basr::job::trust::Seal;

use super::{Global, Outcome};

/// Validate job, setpoint CSV, font, robot and marking files, listing every
/// problem.
///
/// Fonts (.toml), robot descriptions (.toml), marking files (.toml), jobs
/// (.json) and the setpoint CSVs `compile --csv` writes; the kind is
/// recognised from the content. `-` reads standard input. A CSV given with
/// a job must be the one written with it: its SHA-256 is the one the job
/// records, else the first row and column that differ are named. Under
/// `--trust`, a job not signed by that key is a problem.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  basr check STOP.job.json STOP.csv     # a job and the CSV written with it\n  basr check --trust crew.key.pub STOP.job.json\n  basr check fonts/basr.toml markings/*.toml\n  basr robot --toml | basr check -\n\nA sound job's verdict is said beside it (READY, READY WITH NOTES, NOT READY);\na NOT READY job is a problem (exit 1): it is not to be loaded on the truck.\n`--validate-only` checks the files alone.\n\nExit codes: 0 all valid, 1 problems found (all listed) or a job NOT READY, 2 a\nfile could not be read (the others are still checked)."
)]
pub struct Args {
    /// Files to check (`-` for standard input).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,

    #[command(flatten)]
    pub trust: basr::job::trust::TrustOptions,

    /// Only validate the files: a sound job whose verdict is NOT READY is
    /// then `ok` (exit 0) instead of a problem (exit 1).
    #[arg(long)]
    pub validate_only: bool,
}

/// What kind of basr file a text is.
#[derive(Debug, PartialEq)]
enum Kind {
    Job,
    Font,
    Robot,
    Marking,
    Csv,
    Symbols,
    Adept,
}

fn kind_of(text: &str) -> Option<Kind> {
    let trimmed = text.trim_start();
    if trimmed.starts_with('{') {
        return Some(Kind::Job);
    }
    if basr::job::csv::looks_like_csv(text) {
        return Some(Kind::Csv);
    }
    if basr::job::adept::looks_like_program(text) {
        return Some(Kind::Adept);
    }
    let table: toml::Table = toml::from_str(text).ok()?;
    if table.contains_key("symbols") {
        Some(Kind::Symbols)
    } else if table.contains_key("glyphs") || table.contains_key("primitives") {
        Some(Kind::Font)
    } else if table.contains_key("arm") {
        Some(Kind::Robot)
    } else if table.contains_key("marking")
        || table.contains_key("lines")
        || table.contains_key("item")
    {
        Some(Kind::Marking)
    } else {
        None
    }
}

/// A checked file kept for pairing a CSV with its job.
enum Kept {
    /// A job and what its signature proves.
    Job(Box<basr::job::Job>, Seal),
    Csv(String),
    Adept(String),
    Other,
}

/// Problems in one file's bytes (empty when valid), and what to keep of it.
fn problems(
    bytes: Vec<u8>,
    origin: &str,
    trusted: Option<&basr::job::trust::PublicKey>,
    trusted_path: Option<&std::path::Path>,
) -> (Vec<String>, Kept) {
    if bytes.trim_ascii_start().first() == Some(&b'{') {
        // Without --trust the signature is checked with the key its id names
        // in the key folder, when there is one (issue 31, R1: a forged
        // signature was reported "signed by key …").
        let signed = match trusted {
            None => basr::job::signed_bytes(&bytes),
            Some(_) => None,
        };
        return match basr::job::Job::from_bytes(bytes, origin, trusted) {
            Ok(job) => {
                let mut found = basr::job::verify::problems(&job, origin);
                let seal = match trusted {
                    Some(key) => Ok(Seal::Verified {
                        key_id: key.id(),
                        key: trusted_path.map(Into::into).unwrap_or_default(),
                    }),
                    None => basr::job::trust::examine(
                        job.signature.as_ref(),
                        signed.as_deref(),
                        basr::job::trust::key_folder().as_deref(),
                    ),
                };
                let seal = seal.unwrap_or_else(|e| {
                    found.push(format!("{origin}: {e}"));
                    Seal::Unsigned
                });
                (found, Kept::Job(Box::new(job), seal))
            }
            Err(e) => (vec![e.to_string()], Kept::Other),
        };
    }
    match basr::io::utf8_text(bytes, origin) {
        Ok(text) => {
            let found = text_problems(&text, origin);
            let kept = match kind_of(&text) {
                Some(Kind::Csv) => Kept::Csv(text),
                Some(Kind::Adept) => Kept::Adept(text),
                _ => Kept::Other,
            };
            (found, kept)
        }
        Err(e) => (vec![format!("{e:#}")], Kept::Other),
    }
}

/// The job a CSV or program (`kind`) is checked against: the one that
/// recorded its bytes, else the one that recorded its file name, else the
/// only job given.
fn job_for<'a>(
    text: &str,
    origin: &str,
    kind: &str,
    jobs: &'a [(String, Box<basr::job::Job>)],
) -> Option<&'a (String, Box<basr::job::Job>)> {
    let sha = basr::io::sha256_hex(text.as_bytes());
    let name = std::path::Path::new(origin)
        .file_name()
        .map(|n| n.to_string_lossy().into_owned());
    let recorded = |j: &basr::job::Job| j.outputs.get(kind).cloned();
    jobs.iter()
        .find(|(_, j)| recorded(j).is_some_and(|b| b.sha256 == sha))
        .or_else(|| {
            jobs.iter()
                .find(|(_, j)| recorded(j).map(|b| b.file) == name)
        })
        .or(if jobs.len() == 1 { jobs.first() } else { None })
}

/// Problems of a marking file; a scene's shape items are imported for the
/// embedded robot (the one `compile` paints with unless `--robot` says).
fn marking_problems(text: &str, origin: &str) -> Vec<String> {
    let robot = match basr::robot::AnyRobot::load_or_default(None) {
        Ok(r) => r,
        Err(e) => return vec![e.to_string()],
    };
    let shapes = |p: &std::path::Path, s| {
        basr::pipeline::shapes::import_item(&robot, origin, p, s).map(|(strokes, _)| strokes)
    };
    basr::layout::check_marking_source_with(text, origin, &shapes)
}

/// `check`'s line for a sound job whose verdict is NOT READY: the verdict,
/// how many problems and the first, and what to do.
fn not_ready_line(origin: &str, job: Option<&basr::job::Job>) -> String {
    let problems: Vec<&str> = job
        .map(|j| {
            j.summary
                .warnings
                .iter()
                .filter(|w| w.severity == Some(basr::job::Severity::Problem))
                .map(|w| w.message.as_str())
                .collect()
        })
        .unwrap_or_default();
    format!(
        "{origin}: verdict NOT READY ({} problem{}): do not load it on the truck; \
         `basr report {origin}` says what to change (--validate-only checks the file alone){}",
        problems.len(),
        if problems.len() == 1 { "" } else { "s" },
        problems
            .first()
            .map(|p| format!("\n  first problem: {p}"))
            .unwrap_or_default()
    )
}

/// Problems in one file's text (empty when valid).
fn text_problems(text: &str, origin: &str) -> Vec<String> {
    if text.trim().is_empty() {
        return vec![format!(
            "{origin}: the file is empty: give a job, setpoint CSV, font, robot or marking file"
        )];
    }
    match kind_of(text) {
        Some(Kind::Job) => match basr::job::Job::from_str_verified(text, origin) {
            Ok(job) => basr::job::verify::problems(&job, origin),
            Err(e) => vec![e.to_string()],
        },
        Some(Kind::Marking) => marking_problems(text, origin),
        Some(Kind::Csv) => basr::job::csv::check_source(text, origin),
        // Checked against its job when one is given.
        Some(Kind::Adept) => vec![],
        None if basr::layout::looks_like_marking(text) => marking_problems(text, origin),
        Some(Kind::Robot) => basr::robot::check_source(text, origin),
        // A robot file with a TOML syntax error: report where, not "unknown".
        None if basr::robot::looks_like_robot(text) => basr::robot::check_source(text, origin),
        Some(Kind::Symbols) => basr::font::check_library_source(text, origin),
        None if basr::font::looks_like_library(text) => {
            basr::font::check_library_source(text, origin)
        }
        Some(Kind::Font) => basr::font::check_source(text, origin),
        None if basr::font::looks_like_font(text) => basr::font::check_source(text, origin),
        None => vec![format!(
            "{origin}: not a basr file: expected a job (JSON), a setpoint CSV or a font, robot \
             or marking description (TOML with a [glyphs], [arm] or [marking] table) or a \
             symbol library ([symbols.NAME] tables)"
        )],
    }
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    let trusted = args.trust.key()?;
    // Every file is checked, an unreadable one included: the README promises
    // all problems at once. Unreadable files decide the exit code (2) at the
    // end, ahead of problems found (1).
    let (mut bad, mut unreadable) = (0usize, 0usize);
    let mut jobs: Vec<(String, Box<basr::job::Job>)> = vec![];
    let mut csvs: Vec<(String, String, bool)> = vec![];
    let mut programs: Vec<(String, String)> = vec![];
    let mut report: Vec<(String, Vec<String>)> = vec![];
    let mut seals: Vec<(String, Seal)> = vec![];
    for path in &args.files {
        let origin = path.display().to_string();
        let bytes = match basr::io::read_bytes(path) {
            Ok(t) => t,
            Err(e) => {
                unreadable += 1;
                note!("{e:#}");
                continue;
            }
        };
        // Text that is not UTF-8 cannot be read as any of basr's formats:
        // unreadable (exit 2), as every other command says of it.
        if let Some(e) = basr::io::utf8_problem(&bytes, &origin) {
            unreadable += 1;
            note!("{e}");
            continue;
        }
        let (found, kept) = problems(
            bytes,
            &origin,
            trusted.as_ref(),
            args.trust.trust.as_deref(),
        );
        match kept {
            Kept::Job(j, seal) => {
                seals.push((origin.clone(), seal));
                jobs.push((origin.clone(), j));
            }
            Kept::Csv(text) => csvs.push((origin.clone(), text, found.is_empty())),
            Kept::Adept(text) => programs.push((origin.clone(), text)),
            Kept::Other => {}
        }
        report.push((origin, found));
    }
    // A CSV beside a job: it must be the job's own.
    for (origin, text, sound) in &csvs {
        if !sound {
            continue;
        }
        if let Some((job_origin, job)) = job_for(text, origin, "csv", &jobs) {
            let found = basr::job::csv::compare(job, text, origin, job_origin);
            if let Some((_, r)) = report.iter_mut().find(|(o, _)| o == origin) {
                r.extend(found);
            }
        }
    }
    // An Adept program beside a job: the same, by the program's hash.
    for (origin, text) in &programs {
        let found = match job_for(text, origin, "adept", &jobs) {
            Some((job_origin, job)) => basr::job::adept::compare(job, text, origin, job_origin),
            None => vec![],
        };
        if let Some((_, r)) = report.iter_mut().find(|(o, _)| o == origin) {
            r.extend(found);
        }
    }
    for (origin, found) in report {
        let job = jobs.iter().find(|(o, _)| *o == origin).map(|(_, j)| j);
        let verdict = job.map(|j| super::compile::verdict_of(j));
        if found.is_empty() && verdict == Some("not ready") && !args.validate_only {
            // A sound file, but not a job to paint: the step before the
            // truck must not pass it.
            bad += 1;
            note!("{}", not_ready_line(&origin, job.map(|j| &**j)));
        } else if found.is_empty() {
            if !global.quiet {
                let signed = match seals.iter().find(|(o, _)| *o == origin) {
                    Some((_, Seal::Unsigned)) | None => String::new(),
                    Some((_, seal)) => format!(", {}", seal.describe()),
                };
                let verdict = verdict
                    .map(|v| format!(" (verdict {}{signed})", v.to_uppercase()))
                    .unwrap_or_else(|| {
                        if signed.is_empty() {
                            String::new()
                        } else {
                            format!(" ({})", &signed[2..])
                        }
                    });
                note!("{origin}: ok{verdict}");
            }
        } else {
            bad += 1;
            for p in found {
                note!("{p}");
            }
        }
    }
    anyhow::ensure!(
        unreadable == 0,
        "{unreadable} of {} files could not be read{}",
        args.files.len(),
        if bad > 0 {
            format!(", {bad} with problems (see above)")
        } else {
            String::new()
        }
    );
    Ok(if bad == 0 {
        Outcome::Success
    } else {
        Outcome::Negative
    })
}
