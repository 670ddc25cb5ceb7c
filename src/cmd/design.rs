//! `basr design`: synthesise a telescopic arm that reaches prescribed points
//! (seed 002), by Newton–Raphson on the workspace equations.

use std::path::PathBuf;

use anyhow::Context;
use basr::robot::design::{design, parse_points};
use basr::robot::kind::TELESCOPIC_TOML;
use basr::robot::{AnyRobot, Kind};
use serde_json::json;

use super::{Global, Outcome};

/// Design a robot whose workspace holds the given points with a margin.
///
/// Starts from a template arm (the shipped robots/telescopic.toml unless
/// --template) and solves for the telescopic stroke range [d_min, d_max] so
/// that every point is reachable by the tip at zero tilt and at either tilt
/// limit, `--margin-m` inside the workspace boundary (seed 002's cover tori,
/// eq. 1). Prints the Newton–Raphson iterations (residual, Jacobian
/// condition), checks each point with the designed arm's inverse kinematics
/// and writes the description. Point sets that no arm of the kind can reach
/// (below the road, spread round the base beyond its window, needing a boom
/// over 12 m or extending over 4× its retracted length) exit 2 saying why.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  basr design --kind telescopic --points lane.toml -o arm.toml\n  basr pose 1.83 3 --height 0.15 --robot arm.toml   # each point is reachable\n  basr design --kind telescopic --points lane.toml -o arm.toml --margin-m 0.2 --json\n\nA points file holds, in metres in the base frame (docs/robot-kinds.md):\n  points_m = [[-1.83, 3.0, 0.15], [-0.61, 3.0, 0.15], [0.61, 3.0, 0.15], [1.83, 3.0, 0.15]]\n\nExit codes: 0 designed and written, 2 bad input or no arm of the kind reaches the points."
)]
pub struct Args {
    /// Robot kind to design; `telescopic` (seed 002) is the one with a design method.
    #[arg(long, value_name = "KIND")]
    pub kind: String,
    /// Points file (TOML): `points_m = [[x, y, z], ...]`, base frame, metres.
    #[arg(long, value_name = "FILE")]
    pub points: PathBuf,
    /// Write the designed robot description (TOML) here.
    #[arg(short, long, value_name = "ROBOT.toml")]
    pub output: PathBuf,
    /// Distance every point keeps from the workspace boundary (m).
    #[arg(long, default_value_t = 0.1, value_name = "M")]
    pub margin_m: f64,
    /// Template arm (a telescopic description) whose stroke is designed.
    #[arg(long, value_name = "FILE")]
    pub template: Option<PathBuf>,
    /// Print the design report as JSON on stdout.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    match Kind::parse(&args.kind) {
        Some(Kind::Telescopic) => {}
        Some(k) => anyhow::bail!(
            "--kind {}: design has a method for the telescopic kind only (seed 002); \
             write a {} description by hand from robots/{}.toml",
            k.name(),
            k.name(),
            k.name()
        ),
        None => anyhow::bail!(
            "--kind {:?} is not a robot kind; give one of {}",
            args.kind,
            Kind::NAMES.join(", ")
        ),
    }
    anyhow::ensure!(
        args.margin_m.is_finite() && (0.0..=1.0).contains(&args.margin_m),
        "--margin-m must be between 0 and 1 m (got {})",
        basr::io::show_num(args.margin_m)
    );
    let mut inputs = vec![("the points file (--points)", args.points.as_path())];
    if let Some(t) = &args.template {
        inputs.push(("the template (--template)", t.as_path()));
    }
    super::refuse_clashes(&[("-o", args.output.as_path())], &inputs)?;
    let template = match &args.template {
        Some(p) => AnyRobot::load(p)?,
        None => AnyRobot::from_toml_str(TELESCOPIC_TOML, "robots/telescopic.toml (shipped)")?,
    };
    let AnyRobot::Telescopic(template) = template else {
        anyhow::bail!(
            "--template must be a telescopic description (kind = \"telescopic\"); this one is {}",
            template.kind().name()
        );
    };
    let origin = args.points.display().to_string();
    let text = basr::io::read_text(&args.points)?;
    let points = parse_points(&text, &origin)?;
    let d = design(&template, &points, args.margin_m)
        .with_context(|| format!("cannot design a telescopic arm for {origin}"))?;
    let mut robot = d.robot.clone();
    robot.name = format!("{} designed for {origin}", template.name);
    let body = toml::to_string(&robot).context("serialising the designed robot")?;
    let header = format!(
        "# Telescopic arm designed by `basr design` (seed 002, Newton–Raphson on eq. 1) for the\n\
         # points of {origin} with a {} m margin; every other value is the template's\n\
         # (robots/telescopic.toml in the basr sources says where each comes from).\n\
         # joints.stroke_m.min/max are the designed values.\n",
        args.margin_m
    );
    basr::io::write_atomic(&args.output, (header + &body).as_bytes())?;
    if args.json {
        let out = json!({
            "robot": robot.name,
            "output": args.output.display().to_string(),
            "stroke_m": [robot.joints.stroke_m.min, robot.joints.stroke_m.max],
            "margin_m": d.margin_m,
            "iterations": d.iterations,
            "points": d.points,
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&out)? + "\n"))?;
    } else if !global.quiet {
        note!("Newton–Raphson on 002 eq. 1 for the stroke range (residual: eq. 1 / A²):");
        note!("  iter       d_min (m)       d_max (m)     residual   cond(J)");
        for it in &d.iterations {
            note!(
                "  {:>4}  {:>14.9}  {:>14.9}  {:>11.3e}  {:>8.3}",
                it.iteration,
                it.d_min_m,
                it.d_max_m,
                it.residual,
                it.jacobian_condition
            );
        }
        note!("points (inverse kinematics of the designed arm, zero tilt):");
        for p in &d.points {
            note!(
                "  ({:>7.3}, {:>7.3}, {:>6.3}) m  stroke {:.4} m  margin on the road {:.3} m",
                p.point_m[0],
                p.point_m[1],
                p.point_m[2],
                p.stroke_m,
                p.reach_margin_m
            );
        }
        note!(
            "wrote {} (stroke {:.4} .. {:.4} m)",
            args.output.display(),
            robot.joints.stroke_m.min,
            robot.joints.stroke_m.max
        );
    }
    Ok(Outcome::Success)
}
