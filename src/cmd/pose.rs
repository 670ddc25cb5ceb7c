//! `basr pose`: inverse kinematics of one nozzle pose, to joints, actuators
//! and encoder counts.

use std::path::PathBuf;

use anyhow::Context;
use basr::robot::{Joints, NozzlePose, Robot};
use serde_json::json;

use super::{Global, Outcome};

/// Joints, actuators and encoder counts of one nozzle pose (inverse kinematics).
///
/// The pose is given in the base frame (origin on the base rotation axis at road level, +y straight back along the arm's symmetry
/// axis): prints the joints, actuator positions and encoder counts of the
/// solution nearest the arm's rest position. An unreachable pose exits 2
/// naming the binding limit and by how much it is exceeded. The engineer's
/// tool for calibration and manual moves.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  basr pose 0 3 --tilt-deg 10          # 3 m straight back, tilted 10°\n  basr pose -1.2 4 --height 0.15 --yaw-deg 30 --json\n\nJSON: {\"pose\", \"joints\", \"actuators\", \"encoders\", \"solutions\"}; joints,\nactuators and encoders are keyed by the setpoint CSV's column names."
)]
pub struct Args {
    /// Tip x in the base frame (m).
    #[arg(allow_negative_numbers = true)]
    pub x: f64,
    /// Tip y in the base frame (m).
    #[arg(allow_negative_numbers = true)]
    pub y: f64,
    /// Tip height over the road (m); default: the middle of the vertical stroke.
    #[arg(long, allow_hyphen_values = true)]
    pub height: Option<f64>,
    /// Fan direction in the base frame, degrees from +x counter-clockwise.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub yaw_deg: f64,
    /// Tilt in degrees (> 0 leans the nozzle towards the fan direction).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub tilt_deg: f64,
    /// Robot description file (TOML); default: the embedded BASR.
    #[arg(long, value_name = "FILE")]
    pub robot: Option<PathBuf>,
    /// Print JSON on stdout instead of a table on stderr.
    #[arg(long)]
    pub json: bool,
}

/// The joint set IK is measured from when there is no previous state: the
/// middle of every range (arm on its axis, yaw and tilt centred).
fn rest(robot: &Robot) -> Joints {
    let mid = |l: &basr::robot::JointLimit| 0.5 * (l.min + l.max);
    let l = &robot.limits;
    Joints {
        base_rot_rad: mid(&l.base_rot_rad),
        extension_m: mid(&l.extension_m),
        vertical_m: mid(&l.vertical_m),
        ee_yaw_rad: mid(&l.ee_yaw_rad),
        tilt_rad: mid(&l.tilt_rad),
    }
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    let robot = Robot::load_or_default(args.robot.as_deref())?;
    let top = robot.end_effector.tip_height_top_m;
    let lv = &robot.limits.vertical_m;
    let pose = NozzlePose {
        x_m: args.x,
        y_m: args.y,
        z_m: args.height.unwrap_or(top - 0.5 * (lv.min + lv.max)),
        yaw_rad: args.yaw_deg.to_radians(),
        tilt_rad: args.tilt_deg.to_radians(),
    };
    let all = robot.ik(&pose).with_context(|| {
        format!(
            "pose x {:.4} m, y {:.4} m, height {:.4} m, yaw {}°, tilt {}° cannot be reached",
            pose.x_m, pose.y_m, pose.z_m, args.yaw_deg, args.tilt_deg
        )
    })?;
    // Nearest the rest position, keeping the fan as asked (ψ, β) when a
    // solution does; the flipped fan (ψ+π, −β) paints the same.
    let as_asked: Vec<_> = all
        .iter()
        .filter(|j| (j.tilt_rad - pose.tilt_rad).abs() < 1e-12)
        .copied()
        .collect();
    let pool = if as_asked.is_empty() { &all } else { &as_asked };
    let j = robot
        .nearest_of(pool, &rest(&robot))
        .context("inverse kinematics returned no solution")?;
    let a = robot.actuators(&j);
    let e = robot.encoders(&j);
    // Distance to the edge of the region reachable with this yaw and tilt.
    let margin = robot
        .region_for(pose.yaw_rad, pose.tilt_rad)
        .map(|r| r.margin(pose.x_m, pose.y_m))?;
    if args.json {
        let out = json!({
            "pose": pose,
            "joints": j,
            "actuators": {
                "base_motor_rad": a.base_motor_rad,
                "cylinder_m": a.cylinder_m,
                "vertical_m": a.vertical_m,
                "yaw_motor_rad": a.yaw_motor_rad,
                "tilt_nut_m": a.tilt_nut_m,
                "tilt_motor_rad": a.tilt_motor_rad,
            },
            "encoders": e,
            "solutions": all.len(),
            "reach_margin_m": margin,
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&out)? + "\n"))?;
    } else if !global.quiet {
        let deg = |r: f64| r.to_degrees();
        note!(
            "pose (base frame): x {:.4} m  y {:.4} m  height {:.4} m  yaw {:.2}°  tilt {:.2}°",
            pose.x_m,
            pose.y_m,
            pose.z_m,
            deg(pose.yaw_rad),
            deg(pose.tilt_rad)
        );
        note!(
            "joints ({} solutions; nearest the rest position shown):",
            all.len()
        );
        note!(
            "  base_rot_rad  {:>12.6}  ({:.3}°)",
            j.base_rot_rad,
            deg(j.base_rot_rad)
        );
        note!("  extension_m   {:>12.6}", j.extension_m);
        note!("  vertical_m    {:>12.6}", j.vertical_m);
        note!(
            "  ee_yaw_rad    {:>12.6}  ({:.3}°)",
            j.ee_yaw_rad,
            deg(j.ee_yaw_rad)
        );
        note!(
            "  tilt_rad      {:>12.6}  ({:.3}°)",
            j.tilt_rad,
            deg(j.tilt_rad)
        );
        note!("actuators:");
        note!("  base_motor_rad {:>12.6}", a.base_motor_rad);
        note!("  cylinder_m     {:>12.6}", a.cylinder_m);
        note!("  vertical_m     {:>12.6}", a.vertical_m);
        note!("  yaw_motor_rad  {:>12.6}", a.yaw_motor_rad);
        note!("  tilt_nut_m     {:>12.6}", a.tilt_nut_m);
        note!("  tilt_motor_rad {:>12.6}", a.tilt_motor_rad);
        note!("encoders:");
        note!("  enc_base      {:>10}", e.base);
        note!("  enc_extension {:>10}", e.extension);
        note!("  enc_yaw       {:>10}", e.yaw);
        note!("  enc_tilt      {:>10}", e.tilt);
        note!("  enc_vertical  {:>10}", e.vertical);
        note!("reach margin: {margin:.3} m inside the workspace boundary");
    }
    Ok(Outcome::Success)
}
