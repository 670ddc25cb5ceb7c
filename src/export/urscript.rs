//! `basr export JOB --format urscript`: a post-processor for the
//! articulated kind (seed 003's waist, shoulder, elbow, pitch, gun tilt)
//! on a Universal Robots arm, whose shoulder, elbow and wrist 1 axes are
//! parallel as 003's shoulder, elbow and pitch are. The job's joints go to
//! UR joints 1–4 and 6 (wrist 2 held at 0 keeps the gun in the arm's
//! plane); `servoj` streams them at the job's control period, and standard
//! digital output 0 switches the gun. One program (`def basr_stop_N()`)
//! per stop, run after the truck is placed; `basr_job()` runs them all.

use std::fmt::Write as _;

use super::{joints, stop_rows};
use crate::job::Job;

/// Lookahead and gain of `servoj` (UR script manual: lookahead 0.03–0.2 s,
/// gain 100–2000). Assumed: the middle of the lookahead range smooths the
/// 32 ms setpoints without lagging the gun's switching by more than one
/// period; gain 300 is the manual's example.
const LOOKAHEAD_S: f64 = 0.1;
const GAIN: u32 = 300;
/// Speed and acceleration of the `movej` to each stop's first point
/// (rad/s, rad/s²). Assumed: slow, the arm starts from rest at the truck.
const APPROACH_V: f64 = 0.5;
const APPROACH_A: f64 = 0.5;

/// UR's six joints from the job's five (wrist 2 at 0).
pub fn ur_joints(q: [f64; 5]) -> [f64; 6] {
    [q[0], q[1], q[2], q[3], 0.0, q[4]]
}

fn list(q: &[f64]) -> String {
    let v: Vec<String> = q.iter().map(|x| format!("{x:.6}")).collect();
    format!("[{}]", v.join(", "))
}

/// A job for another robot kind than the articulated arm URScript drives.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{job_name}: --format urscript posts the articulated kind (robots/articulated.toml); this \
     job is for {robot:?}: compile it with --robot robots/articulated.toml, or use --format ros2"
)]
pub struct NotArticulated {
    pub job_name: String,
    pub robot: String,
}

/// The program, or why the job cannot be posted to this arm.
pub fn program(job: &Job, job_name: &str) -> Result<String, NotArticulated> {
    if job.samples.kind_joints.is_empty() || job.robot.joint_names()[0] != "waist_rad" {
        return Err(NotArticulated {
            job_name: job_name.into(),
            robot: job.robot.name().into(),
        });
    }
    let s = &job.samples;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# basr export --format urscript of {job_name} ({:?}), sha256 {}\n\
         # joints: {} -> UR base, shoulder, elbow, wrist 1, (wrist 2 = 0), wrist 3; rad\n\
         # servoj every {} s; standard digital output 0 drives the gun",
        job.message.replace('\n', " / "),
        job.sha256,
        job.robot.joint_names().join(", "),
        job.control_period_s
    );
    let stops = stop_rows(job);
    for (station, a, b) in &stops {
        let _ = writeln!(out, "def basr_stop_{}():", station + 1);
        if let Some(p) = job.stations.get(*station) {
            let _ = writeln!(
                out,
                "  # stop {}: the truck with the arm axis at x {:.3} m, y {:.3} m, heading {:.1} deg",
                station + 1,
                p.x_m,
                p.y_m,
                p.heading_rad.to_degrees()
            );
        }
        out.push_str("  set_standard_digital_out(0, False)\n");
        let _ = writeln!(
            out,
            "  movej({}, a={APPROACH_A}, v={APPROACH_V})",
            list(&ur_joints(joints(job, *a)))
        );
        let mut gun = false;
        for i in *a..*b {
            let on = s.paint[i] != 0;
            if on != gun {
                let _ = writeln!(
                    out,
                    "  set_standard_digital_out(0, {})",
                    if on { "True" } else { "False" }
                );
                gun = on;
            }
            let _ = writeln!(
                out,
                "  servoj({}, t={}, lookahead_time={LOOKAHEAD_S}, gain={GAIN})",
                list(&ur_joints(joints(job, i))),
                job.control_period_s
            );
        }
        out.push_str("  set_standard_digital_out(0, False)\n  stopj(2.0)\nend\n");
    }
    out.push_str("def basr_job():\n");
    for (station, _, _) in &stops {
        let _ = writeln!(
            out,
            "  popup(\"Place the truck for stop {n}, then continue\", blocking=True)\n  basr_stop_{n}()",
            n = station + 1
        );
    }
    out.push_str("end\n");
    Ok(out)
}
