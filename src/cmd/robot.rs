//! `basr robot`: print the effective robot description.

use std::path::PathBuf;

use super::{Global, Outcome};

/// Print the effective robot description (TOML or JSON).
///
/// The description is the embedded BASR (docs/robot.md) or the file given with --robot, after validation. The TOML form reads back to an
/// identical robot, so it is a starting point for a customised description.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  basr robot                       # embedded BASR as TOML\n  basr robot --toml > my.toml      # edit, then: basr robot --robot my.toml\n  basr robot --json | jq .limits\n  basr robot --toml | basr check -"
)]
pub struct Args {
    /// Robot description file (TOML); default: the embedded BASR.
    #[arg(long, value_name = "FILE")]
    pub robot: Option<PathBuf>,
    /// Print JSON (the form embedded in job files) instead of TOML.
    #[arg(long, conflicts_with = "toml")]
    pub json: bool,
    /// Print TOML (the default): the embedded file with its sources when the
    /// robot is the default (also when read from a file), else the effective
    /// values of --robot FILE; either reads back to the same text.
    #[arg(long)]
    pub toml: bool,
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    let robot = basr::robot::AnyRobot::load_or_default(args.robot.as_deref())?;
    if args.json {
        let mut v = robot.to_json();
        if let Some(o) = v.as_object_mut() {
            o.insert("sha256".into(), robot.sha256().into());
        }
        basr::io::print_stdout(&(serde_json::to_string_pretty(&v)? + "\n"))?;
    } else {
        // The default robot prints as shipped, with every value's source,
        // also when read back from a file: `robot --toml > f` then
        // `robot --robot f --toml` gives the same text.
        basr::io::print_stdout(&robot.to_toml_text())?;
        if !global.quiet {
            note!("robot {} sha256 {}", robot.arm().name(), robot.sha256());
        }
    }
    Ok(Outcome::Success)
}
