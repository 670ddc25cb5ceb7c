//! `basr check FILE...`: validate font, robot, marking, job and CSV files,
//! reporting every problem found (exit 1 when any file has problems, 2 when
//! any could not be read; the others are still checked).

use std::path::PathBuf;

use super::{Global, Outcome};

/// Validate job, setpoint CSV, font, robot and marking files, listing every
/// problem.
///
/// Fonts (.toml), robot descriptions (.toml), marking files (.toml), jobs
/// (.json) and the setpoint CSVs `compile --csv` writes; the kind is
/// recognised from the content. `-` reads standard input.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  basr check STOP.job.json STOP.csv     # a job and its setpoint CSV\n  basr check fonts/basr.toml markings/*.toml\n  basr robot --toml | basr check -\n\nExit codes: 0 all valid, 1 problems found (all listed), 2 a file could not be read\n(the others are still checked)."
)]
pub struct Args {
    /// Files to check (`-` for standard input).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
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
}

fn kind_of(text: &str) -> Option<Kind> {
    let trimmed = text.trim_start();
    if trimmed.starts_with('{') {
        return Some(Kind::Job);
    }
    if basr::job::csv::looks_like_csv(text) {
        return Some(Kind::Csv);
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

/// Problems in one file's text (empty when valid).
fn problems(text: &str, origin: &str) -> Vec<String> {
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
        Some(Kind::Marking) => basr::layout::check_marking_source(text, origin),
        Some(Kind::Csv) => basr::job::csv::check_source(text, origin),
        None if basr::layout::looks_like_marking(text) => {
            basr::layout::check_marking_source(text, origin)
        }
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
    // Every file is checked, an unreadable one included: the README promises
    // all problems at once. Unreadable files decide the exit code (2) at the
    // end, ahead of problems found (1).
    let (mut bad, mut unreadable) = (0usize, 0usize);
    for path in &args.files {
        let origin = path.display().to_string();
        let text = match basr::io::read_text(path) {
            Ok(t) => t,
            Err(e) => {
                unreadable += 1;
                note!("{e:#}");
                continue;
            }
        };
        let found = problems(&text, &origin);
        if found.is_empty() {
            if !global.quiet {
                note!("{origin}: ok");
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
