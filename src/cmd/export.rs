//! `basr export JOB --format F`: the job for another controller.

use std::path::PathBuf;

use super::{Global, Outcome};

/// The export formats.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum Format {
    /// ROS 2: one trajectory_msgs/msg/JointTrajectory per stop as YAML, with
    /// velocities, accelerations and the gun's on/off times.
    Ros2,
    /// Universal Robots URScript for the articulated kind: servoj at the
    /// control period, digital output 0 for the gun.
    Urscript,
}

/// Write the job's joint trajectories for another controller.
///
/// Reads the sealed job (as every command does: `--trust` to accept only a
/// signed one) and writes each stop's joint trajectory in the format an
/// integrator loads. Stops are numbered from 1, as the job sheet numbers
/// them. Nothing is planned again.
#[derive(clap::Args)]
#[command(after_help = "\
Examples:
  basr export STOP.job.json --format ros2 -o stop.yaml
  basr export STOP.job.json --format ros2            # writes STOP.ros2.yaml
  basr compile STOP --robot robots/articulated.toml -o arm.job.json
  basr export arm.job.json --format urscript         # writes arm.urscript.script

A NOT READY job (its verdict as `basr check` and the job sheet give it) is
written for the integrator to inspect, with a first line saying so, and
exits 1: do not run it on the truck.

Exit 0 written, 1 written but the job is NOT READY, 2 bad input (nothing
is written).")]
pub struct Args {
    /// The job file written by `basr compile`.
    pub job: PathBuf,

    #[command(flatten)]
    pub trust: basr::job::trust::TrustOptions,

    /// The format to write.
    #[arg(long, value_enum)]
    pub format: Format,

    /// The file to write [default: the job's name with .ros2.yaml or
    /// .urscript.script, in the current folder].
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
}

pub fn run(args: Args, _global: &Global) -> anyhow::Result<Outcome> {
    let (ext, exts): (&str, &[&str]) = match args.format {
        Format::Ros2 => ("ros2.yaml", &["yaml", "yml"]),
        Format::Urscript => ("urscript.script", &["script", "urscript"]),
    };
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| super::named_after_job(&args.job, ext));
    super::refuse_clashes(&[("the export (-o)", &out)], &[("the job", &args.job)])?;
    super::outputs::check("-o", &out, exts)?;
    basr::io::check_writable(&out)?;
    let job = super::read_job(&args.job, &args.trust)?;
    super::simulate::content_checks(&job, &args.job)?;
    let name = args.job.display().to_string();
    let text = match args.format {
        Format::Ros2 => basr::export::ros2::document(&job, &name),
        Format::Urscript => basr::export::urscript::program(&job, &name)?,
    };
    // Both formats take `#` comments: the job's path on one line.
    let not_ready = super::compile::verdict_of(&job) == "not ready";
    let name = name.replace(|c: char| c.is_control(), " ");
    let text = if not_ready {
        format!(
            "# NOT READY: the job has problems (`basr report {name}` says which); this export \
             is for inspection, do not run it on the truck\n{text}"
        )
    } else {
        text
    };
    basr::io::write_atomic(&out, text.as_bytes())?;
    super::outputs::after_commit(format!(
        "{}wrote {} ({} stop{}){}",
        if not_ready { "NOT READY: " } else { "" },
        out.display(),
        job.stations.len(),
        if job.stations.len() == 1 { "" } else { "s" },
        if not_ready {
            format!(
                ": the job has problems (`basr report {name}` says which); inspect it, do \
                 not run it on the truck"
            )
        } else {
            String::new()
        }
    ));
    Ok(if not_ready {
        Outcome::Negative
    } else {
        Outcome::Success
    })
}
