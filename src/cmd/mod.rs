//! One module per subcommand. Each has `Args` (clap) and
//! `run(Args, &Global) -> anyhow::Result<Outcome>`; an `Err` exits with 2.

pub mod check;
pub mod compile;
pub mod glyphs;
pub mod keygen;
pub mod pose;
pub mod preview;
pub mod robot;
pub mod simulate;
pub mod workspace;

use std::path::Path;

/// Options every subcommand sees.
pub struct Global {
    /// `--quiet`: no human text on stderr except errors.
    pub quiet: bool,
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
        let what = if outputs.iter().any(|(n, _)| *n == b) {
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
