//! One module per subcommand. Each has `Args` (clap) and
//! `run(Args, &Global) -> anyhow::Result<Outcome>`; an `Err` exits with 2.

pub mod check;
pub mod compile;
pub mod glyphs;
pub mod pose;
pub mod preview;
pub mod robot;
pub mod simulate;
pub mod workspace;

/// Options every subcommand sees.
#[allow(dead_code)] // read once every subcommand is implemented
pub struct Global {
    /// `--quiet`: no human text on stderr except errors.
    pub quiet: bool,
}

/// How a command that ran to the end turned out.
#[allow(dead_code)] // constructed once every subcommand is implemented
pub enum Outcome {
    /// Exit 0.
    Success,
    /// Exit 1: the work ran but its verdict is negative.
    Negative,
}
