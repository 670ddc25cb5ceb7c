//! `basr pose`: inverse kinematics of one nozzle pose, to joints, actuators
//! and encoder counts.

use std::path::PathBuf;

use anyhow::Context;
use basr::robot::kinematics::{show_number, wrap_pi};
use basr::robot::{AnyRobot, ArmKind, Joints, NozzlePose, Robot};
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
    /// Tip x in the base frame (m unless a unit is written: 4ft, 120cm).
    #[arg(allow_hyphen_values = true, value_parser = basr::units::metres_value)]
    pub x: f64,
    /// Tip y in the base frame (m unless a unit is written).
    #[arg(allow_hyphen_values = true, value_parser = basr::units::metres_value)]
    pub y: f64,
    /// Tip height over the road (m unless a unit is written); default: the
    /// middle of the vertical stroke.
    #[arg(long, allow_hyphen_values = true, value_parser = basr::units::metres_value)]
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

/// Zero without its sign: `--tilt-deg 0` flipped is −0.0, which says
/// nothing a reader can use and must not be printed.
fn unsigned_zero(v: f64) -> f64 {
    v + 0.0
}

/// A fixed-point number for the table, right-aligned, never `-0.000000`.
fn cell(v: f64, width: usize, decimals: usize) -> String {
    format!("{:>width$}", show_number(v, decimals))
}

/// Degrees wrapped to (−180°, 180°]. `%` on floats is exact, so even
/// `--yaw-deg 1e300` wraps to the direction it names, not to a 300-digit yaw.
fn wrap_deg(d: f64) -> f64 {
    let w = d.rem_euclid(360.0);
    unsigned_zero(if w > 180.0 { w - 360.0 } else { w })
}

/// The pose as given, `x … m{sep}y … m{sep}height … m{sep}yaw …°{sep}tilt …°`,
/// for the error and the human report alike.
fn pose_text(pose: &NozzlePose, yaw_deg: f64, tilt_deg: f64, sep: &str) -> String {
    [
        format!("x {} m", show_number(pose.x_m, 4)),
        format!("y {} m", show_number(pose.y_m, 4)),
        format!("height {} m", show_number(pose.z_m, 4)),
        format!("yaw {}°", show_number(yaw_deg, 2)),
        format!("tilt {}°", show_number(tilt_deg, 2)),
    ]
    .join(sep)
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    for (what, v, unit) in [
        ("X", Some(args.x), "metres"),
        ("Y", Some(args.y), "metres"),
        ("--height", args.height, "metres"),
        ("--yaw-deg", Some(args.yaw_deg), "degrees"),
        ("--tilt-deg", Some(args.tilt_deg), "degrees"),
    ] {
        if let Some(v) = v {
            anyhow::ensure!(
                v.is_finite(),
                "{what} is not a finite number of {unit} (got {v}); give a finite number"
            );
        }
    }
    let robot = match AnyRobot::load_or_default(args.robot.as_deref())? {
        AnyRobot::Basr(r) => r,
        other => return run_kind(&args, other.arm(), global),
    };
    let top = robot.end_effector.tip_height_top_m;
    let lv = &robot.limits.vertical_m;
    let yaw_deg = wrap_deg(args.yaw_deg);
    let tilt_deg = unsigned_zero(args.tilt_deg);
    let pose = NozzlePose {
        x_m: unsigned_zero(args.x),
        y_m: unsigned_zero(args.y),
        z_m: unsigned_zero(args.height.unwrap_or(top - 0.5 * (lv.min + lv.max))),
        yaw_rad: yaw_deg.to_radians(),
        tilt_rad: tilt_deg.to_radians(),
    };
    let all = robot.ik(&pose).with_context(|| {
        format!(
            "pose {} cannot be reached",
            pose_text(&pose, yaw_deg, tilt_deg, ", ")
        )
    })?;
    // Nearest the rest position, keeping the fan as asked (its direction ψ,
    // so its tilt β) when a solution does; the flipped fan (ψ+π, −β) paints
    // the same. Compared by direction: at zero tilt β = −β.
    let as_asked: Vec<_> = all
        .iter()
        .filter(|j| wrap_pi(j.base_rot_rad + j.ee_yaw_rad - pose.yaw_rad).abs() < 1e-9)
        .copied()
        .collect();
    let pool = if as_asked.is_empty() { &all } else { &as_asked };
    let j = robot
        .nearest_of(pool, &rest(&robot))
        .context("inverse kinematics returned no solution")?;
    let j = Joints {
        base_rot_rad: unsigned_zero(j.base_rot_rad),
        extension_m: unsigned_zero(j.extension_m),
        vertical_m: unsigned_zero(j.vertical_m),
        ee_yaw_rad: unsigned_zero(j.ee_yaw_rad),
        tilt_rad: unsigned_zero(j.tilt_rad),
    };
    let a = robot.actuators(&j);
    let e = robot.encoders(&j);
    // Distance to the edge of the region reachable with this yaw and tilt.
    let margin = robot
        .region_for(pose.yaw_rad, pose.tilt_rad)
        .map(|r| r.margin(pose.x_m, pose.y_m))?;
    let z = unsigned_zero;
    if args.json {
        let out = json!({
            "pose": pose,
            "joints": j,
            "actuators": {
                "base_motor_rad": z(a.base_motor_rad),
                "cylinder_m": z(a.cylinder_m),
                "vertical_m": z(a.vertical_m),
                "yaw_motor_rad": z(a.yaw_motor_rad),
                "tilt_nut_m": z(a.tilt_nut_m),
                "tilt_motor_rad": z(a.tilt_motor_rad),
            },
            "encoders": e,
            "solutions": all.len(),
            "reach_margin_m": z(margin),
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&out)? + "\n"))?;
    } else if !global.quiet {
        let deg = |r: f64| show_number(r.to_degrees(), 3);
        note!(
            "pose (base frame): {}",
            pose_text(&pose, yaw_deg, tilt_deg, "  ")
        );
        note!(
            "joints ({} solutions; nearest the rest position shown):",
            all.len()
        );
        note!(
            "  base_rot_rad  {}  ({}°)",
            cell(j.base_rot_rad, 12, 6),
            deg(j.base_rot_rad)
        );
        note!("  extension_m   {}", cell(j.extension_m, 12, 6));
        note!("  vertical_m    {}", cell(j.vertical_m, 12, 6));
        note!(
            "  ee_yaw_rad    {}  ({}°)",
            cell(j.ee_yaw_rad, 12, 6),
            deg(j.ee_yaw_rad)
        );
        note!(
            "  tilt_rad      {}  ({}°)",
            cell(j.tilt_rad, 12, 6),
            deg(j.tilt_rad)
        );
        note!("actuators:");
        note!("  base_motor_rad {}", cell(a.base_motor_rad, 12, 6));
        note!("  cylinder_m     {}", cell(a.cylinder_m, 12, 6));
        note!("  vertical_m     {}", cell(a.vertical_m, 12, 6));
        note!("  yaw_motor_rad  {}", cell(a.yaw_motor_rad, 12, 6));
        note!("  tilt_nut_m     {}", cell(a.tilt_nut_m, 12, 6));
        note!("  tilt_motor_rad {}", cell(a.tilt_motor_rad, 12, 6));
        note!("encoders:");
        note!("  enc_base      {:>10}", e.base);
        note!("  enc_extension {:>10}", e.extension);
        note!("  enc_yaw       {:>10}", e.yaw);
        note!("  enc_tilt      {:>10}", e.tilt);
        note!("  enc_vertical  {:>10}", e.vertical);
        note!(
            "reach margin: {} m inside the workspace boundary",
            show_number(margin, 3)
        );
    }
    Ok(Outcome::Success)
}

/// Encoder column names of a kind's joints: `enc_` and the joint's name
/// without its unit (`boom_rad` → `enc_boom`).
pub fn encoder_names(arm: &dyn ArmKind) -> [String; 5] {
    arm.joint_names().map(|n| {
        let stem = n
            .strip_suffix("_rad")
            .or_else(|| n.strip_suffix("_m"))
            .unwrap_or(n);
        format!("enc_{stem}")
    })
}

/// `pose` for the telescopic and articulated kinds: the joints of the
/// solution with the shortest travel from the rest position, their encoder
/// counts, how many solutions there are and the margin on the road.
fn run_kind(args: &Args, arm: &dyn ArmKind, global: &Global) -> anyhow::Result<Outcome> {
    let [lo, hi] = arm.tip_heights_m();
    let yaw_deg = wrap_deg(args.yaw_deg);
    let tilt_deg = unsigned_zero(args.tilt_deg);
    let pose = NozzlePose {
        x_m: unsigned_zero(args.x),
        y_m: unsigned_zero(args.y),
        z_m: unsigned_zero(args.height.unwrap_or(0.5 * (lo + hi))),
        yaw_rad: yaw_deg.to_radians(),
        tilt_rad: tilt_deg.to_radians(),
    };
    let all = arm.ik(&pose).with_context(|| {
        format!(
            "pose {} cannot be reached by {} ({} arm)",
            pose_text(&pose, yaw_deg, tilt_deg, ", "),
            arm.name(),
            arm.kind().name()
        )
    })?;
    let q = arm
        .nearest(&all, &arm.rest())
        .context("inverse kinematics returned no solution")?
        .map(unsigned_zero);
    let enc = arm.encoders(&q);
    let names = arm.joint_names();
    let enc_names = encoder_names(arm);
    let margin = basr::robot::section::reach_margin(arm, pose.x_m, pose.y_m, pose.z_m);
    if args.json {
        let joints: serde_json::Map<_, _> = names
            .iter()
            .zip(q)
            .map(|(n, v)| (n.to_string(), json!(v)))
            .collect();
        let encoders: serde_json::Map<_, _> = enc_names
            .iter()
            .zip(enc)
            .map(|(n, v)| (n.clone(), json!(v)))
            .collect();
        let out = json!({
            "kind": arm.kind().name(),
            "pose": pose,
            "joints": joints,
            "encoders": encoders,
            "solutions": all.len(),
            "reach_margin_m": unsigned_zero(margin),
        });
        basr::io::print_stdout(&(serde_json::to_string_pretty(&out)? + "\n"))?;
    } else if !global.quiet {
        note!(
            "pose (base frame): {}",
            pose_text(&pose, yaw_deg, tilt_deg, "  ")
        );
        note!(
            "{} ({} arm): {} solutions; the shortest travel from the rest position shown:",
            arm.name(),
            arm.kind().name(),
            all.len()
        );
        for ((n, v), (e, c)) in names.iter().zip(q).zip(enc_names.iter().zip(enc)) {
            let deg = if n.ends_with("_rad") {
                format!("  ({}°)", show_number(v.to_degrees(), 3))
            } else {
                String::new()
            };
            note!("  {n:<14}{}{deg}", cell(v, 12, 6));
            note!("    {e:<16}{c:>10}");
        }
        note!(
            "reach margin: {} m on the road at this height (zero tilt)",
            show_number(margin, 3)
        );
    }
    Ok(Outcome::Success)
}
