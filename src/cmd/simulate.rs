//! `basr simulate` (not yet implemented).

use super::{Global, Outcome};

/// Not yet implemented.
#[derive(clap::Args)]
pub struct Args {}

pub fn run(_args: Args, _global: &Global) -> anyhow::Result<Outcome> {
    anyhow::bail!("`basr simulate` is not implemented yet")
}
