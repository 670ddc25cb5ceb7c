//! The `basr` command line: parse arguments, call the library, print results.
//!
//! Each subcommand lives in `src/cmd/<name>.rs` with its own `Args` and `run`.
//! Exit codes (README.md): 0 success, 1 negative verdict, 2 bad input or usage,
//! 128 + signal interrupted (130 Ctrl-C, 143 SIGTERM, 129 SIGHUP, 131 SIGQUIT).

// println!/eprintln! panic when the reader has gone (`| head`): machine
// output goes through basr::io::print_stdout, human text through note!.
#![deny(clippy::print_stdout, clippy::print_stderr)]

/// `eprintln!` for human text that never panics: `basr … 2>&1 | head` closes
/// stderr as well, and a note nobody reads is no reason to stop (exit 101)
/// in the middle of writing a job. Defined before `mod cmd` so every
/// subcommand sees it.
macro_rules! note {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

/// `eprint!` of a ready-made text, under the same rule as `note!`.
fn note_text(text: &str) {
    use std::io::Write as _;
    let _ = std::io::stderr().write_all(text.as_bytes());
}

mod cmd;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

const EXAMPLES: &str = "\
Examples:
  basr compile STOP                      # writes STOP.job.json in this folder
  basr compile \"STOP AHEAD\" --csv sa.csv # two lines, setpoints as CSV too
  basr preview STOP.job.json -o stop.svg # simulated paint film
  basr simulate STOP.job.json            # closed-loop check against 6.35 mm
  basr report STOP.job.json -o STOP.html # the job sheet for the crew
  basr glyphs --svg alphabet.svg         # the embedded font, drawn
  basr symbols --svg symbols.svg         # the symbol library, drawn
  basr compile --symbol arrow-left       # one symbol alone
  basr compile --shape logo.svg --shape-height-m 2   # any filled outline
  basr pose 0 3 --tilt-deg 10            # one nozzle pose to joints and encoders
  basr keygen -o crew.key                # a key pair; then compile --sign crew.key
  basr completions bash > basr.bash      # shell completions

Exit codes: 0 success, 1 verdict negative (simulate over tolerance, check found
problems), 2 bad input or usage, 130 interrupted by Ctrl-C (128 + the signal:
143 SIGTERM, 129 SIGHUP, 131 SIGQUIT); an interrupted run leaves no output file.
A reader that stops early (`basr glyphs --json | head`) is not an error.";

/// Offline trajectory-planning compiler for the Big Articulated Stenciling Robot.
///
/// basr turns a roadway message ("STOP", "SCHOOL XING") into a job file of
/// timed setpoints for every actuator of the BASR truck-mounted arm, previews
/// the paint film it will lay, and simulates the arm in closed loop.
#[derive(Parser)]
#[command(name = "basr", version, about, long_about, after_help = EXAMPLES)]
struct Cli {
    /// Print nothing but errors on stderr.
    #[arg(long, short, global = true)]
    quiet: bool,

    #[command(subcommand)]
    command: Command,
}

// Parsed once per run; boxing the larger argument structs would buy nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Subcommand)]
enum Command {
    Compile(cmd::compile::Args),
    Glyphs(cmd::glyphs::Args),
    /// List the symbol library (arrows, lines, crosswalks, RXR …); draw its sheet
    Symbols(cmd::symbols::Args),
    Import(cmd::import::Args),
    Preview(cmd::preview::Args),
    Report(cmd::report::Args),
    Simulate(cmd::simulate::Args),
    Robot(cmd::robot::Args),
    Calibrate(cmd::calibrate::Args),
    Workspace(cmd::workspace::Args),
    Pose(cmd::pose::Args),
    Fit(cmd::fit::Args),
    Check(cmd::check::Args),
    Keygen(cmd::keygen::Args),
    Design(cmd::design::Args),
    Export(cmd::export::Args),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    #[command(after_help = "Examples:
  basr completions bash > ~/.local/share/bash-completion/completions/basr
  basr completions zsh > ~/.zfunc/_basr        # with fpath+=(~/.zfunc) in ~/.zshrc
  basr completions fish > ~/.config/fish/completions/basr.fish")]
    Completions {
        /// The shell to complete for.
        shell: clap_complete::Shell,
    },
}

/// Print clap's error (or help) as clap would, with a hint for the usual
/// slips: `basr compile STOP AHEAD`, a message of several words unquoted,
/// and `--letter-height 8 ft`, a number and its unit apart. A misspelt
/// option's value is never taken for message text (`--lane-widht 12ft`
/// must not become `compile "STOP 12ft"`, which paints 12FT): clap's own
/// tip names the option meant.
fn usage_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    let args: Vec<String> = std::env::args().skip(1).collect();
    let compiling = args.first().is_some_and(|a| a == "compile");
    if e.kind() != ErrorKind::UnknownArgument || !compiling {
        e.exit();
    }
    let (words, units) = message_words(&args[1..]);
    let text = e.render().to_string();
    note_text(&text);
    if !units.is_empty() {
        for u in units {
            note!("hint: write the number and its unit as one: {u}");
        }
    } else if words.len() > 1 {
        note!(
            "hint: a message of several words is one argument; quote it: basr compile \"{}\"",
            words.join(" ")
        );
    }
    ExitCode::from(2)
}

/// Unit words a length may be followed by when typed apart (`8 ft`).
const UNIT_WORDS: [&str; 10] = [
    "ft", "feet", "foot", "in", "inch", "inches", "m", "mm", "cm", "'",
];

/// From `compile`'s arguments: the words that stand where the message
/// does (not an option, not an option's value, not a unit that follows
/// one), and `OPTION VALUEunit` for each length typed apart from its unit.
/// An unknown option is taken to have a value when the next argument is
/// not an option: it is never message text.
fn message_words(args: &[String]) -> (Vec<String>, Vec<String>) {
    use clap::CommandFactory;
    let cmd = Cli::command();
    let compile = cmd.find_subcommand("compile");
    let takes_value = |name: &str| -> Option<bool> {
        let a = compile?.get_arguments().find(|a| {
            name.strip_prefix("--")
                .is_some_and(|l| a.get_long() == Some(l))
                || (name.len() == 2
                    && name.starts_with('-')
                    && a.get_short() == name.chars().nth(1))
        })?;
        Some(a.get_action().takes_values())
    };
    let (mut words, mut units) = (vec![], vec![]);
    let mut i = 0;
    while i < args.len() {
        let a = &args[i];
        let next_is_value = args.get(i + 1).is_some_and(|n| !n.starts_with('-'));
        if a.starts_with('-') && a.len() > 1 && !a.contains('=') {
            match takes_value(a) {
                Some(false) => i += 1,
                Some(true) => {
                    let unit = args.get(i + 2).filter(|u| {
                        UNIT_WORDS.contains(&u.to_ascii_lowercase().as_str())
                            && args[i + 1].parse::<f64>().is_ok()
                    });
                    if let Some(u) = unit {
                        units.push(format!("{a} {}{u}", args[i + 1]));
                        i += 1;
                    }
                    i += 2;
                }
                None => i += if next_is_value { 2 } else { 1 },
            }
            continue;
        }
        if !a.starts_with('-') && !a.is_empty() && a.chars().all(|c| c.is_alphanumeric()) {
            words.push(a.clone());
        }
        i += 1;
    }
    (words, units)
}

fn main() -> ExitCode {
    // An empty BASR_TRUST is no trusted key (docs/signed-jobs.md); clap
    // reads a set but empty variable as `--trust` with no value and refused
    // every command (issue 31, R9). First, while the process has one thread.
    if std::env::var_os(basr::job::trust::TRUST_ENV).is_some_and(|v| v.is_empty()) {
        std::env::remove_var(basr::job::trust::TRUST_ENV);
    }
    basr::io::install_interrupt_cleanup();
    basr::io::stage_outputs();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(e),
    };
    let global = cmd::Global { quiet: cli.quiet };
    let result = match cli.command {
        Command::Compile(a) => cmd::compile::run(a, &global),
        Command::Glyphs(a) => cmd::glyphs::run(a, &global),
        Command::Symbols(a) => cmd::symbols::run(a, &global),
        Command::Import(a) => cmd::import::run(a, &global),
        Command::Preview(a) => cmd::preview::run(a, &global),
        Command::Fit(a) => cmd::fit::run(a, &global),
        Command::Report(a) => cmd::report::run(a, &global),
        Command::Simulate(a) => cmd::simulate::run(a, &global),
        Command::Robot(a) => cmd::robot::run(a, &global),
        Command::Calibrate(a) => cmd::calibrate::run(a, &global),
        Command::Workspace(a) => cmd::workspace::run(a, &global),
        Command::Pose(a) => cmd::pose::run(a, &global),
        Command::Check(a) => cmd::check::run(a, &global),
        Command::Keygen(a) => cmd::keygen::run(a, &global),
        Command::Design(a) => cmd::design::run(a, &global),
        Command::Export(a) => cmd::export::run(a, &global),
        Command::Completions { shell } => {
            use clap::CommandFactory;
            // Generated into memory: clap_complete panics on a failed write,
            // print_stdout treats a closed pipe as the reader being done.
            let mut script = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "basr", &mut script);
            basr::io::print_stdout(&String::from_utf8_lossy(&script))
                .map(|()| cmd::Outcome::Success)
                .map_err(Into::into)
        }
    };
    // Every output of the run is renamed into place together, or none is.
    let result = match result {
        Ok(outcome) => basr::io::commit_outputs()
            .map(|()| {
                if !global.quiet {
                    for text in cmd::outputs::take_after_commit() {
                        note!("{text}");
                    }
                }
                outcome
            })
            .map_err(Into::into),
        Err(e) => {
            basr::io::discard_outputs();
            Err(e)
        }
    };
    match result {
        Ok(cmd::Outcome::Success) => ExitCode::SUCCESS,
        Ok(cmd::Outcome::Negative) => ExitCode::from(1),
        Err(e) => {
            note!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}
