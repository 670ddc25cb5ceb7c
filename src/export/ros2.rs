//! `basr export JOB --format ros2`: one `trajectory_msgs/msg/JointTrajectory`
//! per stop as YAML (the message's own field names), with velocities and
//! accelerations (the ROS 2 joint trajectory controller interpolates
//! linearly between points given positions only), and beside each
//! trajectory the gun's on/off times (a JointTrajectory carries no
//! outputs). Written by hand: the document is a fixed, flat shape and a
//! YAML library would add a dependency for a few `writeln!`s.

use std::fmt::Write as _;

use super::{derivatives, gun_intervals, joints, stop_rows};
use crate::job::Job;

/// `{sec, nanosec}` of a duration in seconds (≥ 0), as
/// `builtin_interfaces/msg/Duration` holds it.
pub fn duration(t_s: f64) -> (i64, u32) {
    let ns = (t_s.max(0.0) * 1e9).round() as i64;
    (ns / 1_000_000_000, (ns % 1_000_000_000) as u32)
}

/// A float as YAML reads it back exactly (Rust's shortest round trip).
fn num(v: f64) -> String {
    if v.is_finite() {
        let s = format!("{v:?}");
        s
    } else {
        ".nan".into()
    }
}

fn list(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| num(*x)).collect();
    format!("[{}]", items.join(", "))
}

/// The YAML document: a header comment, then `stops:` with one entry per
/// stop (`stop`, 1-based as the job sheet counts; `station`, the job's
/// 0-based index; the truck's pose; `gun`; `trajectory`).
pub fn document(job: &Job, job_name: &str) -> String {
    let names = job.robot.joint_names();
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# basr export --format ros2 of {job_name} ({:?}), sha256 {}\n\
         # one trajectory_msgs/msg/JointTrajectory per stop, joints in the robot's \
         base frame at that stop\n\
         # units: rad and m (the joint names say which); times from the stop's start\n\
         # velocities and accelerations: finite differences of the job's setpoints",
        job.message.replace('\n', " / "),
        job.sha256
    );
    let _ = writeln!(out, "robot: {:?}", job.robot.name());
    let _ = writeln!(out, "control_period_s: {}", num(job.control_period_s));
    out.push_str("stops:\n");
    let s = &job.samples;
    for (station, a, b) in stop_rows(job) {
        let t: Vec<f64> = s.t_s[a..b].iter().map(|t| t - s.t_s[a]).collect();
        let q: Vec<[f64; 5]> = (a..b).map(|i| joints(job, i)).collect();
        let mut v = vec![[0.0; 5]; q.len()];
        let mut acc = vec![[0.0; 5]; q.len()];
        for j in 0..5 {
            let col: Vec<f64> = q.iter().map(|r| r[j]).collect();
            let (vj, aj) = derivatives(&t, &col);
            for i in 0..q.len() {
                v[i][j] = vj[i];
                acc[i][j] = aj[i];
            }
        }
        let pose = job.stations.get(station);
        let _ = writeln!(out, "  - stop: {}", station + 1);
        let _ = writeln!(out, "    station: {station}");
        if let Some(p) = pose {
            let _ = writeln!(
                out,
                "    truck: {{x_m: {}, y_m: {}, heading_rad: {}}}",
                num(p.x_m),
                num(p.y_m),
                num(p.heading_rad)
            );
        }
        out.push_str("    gun:\n");
        let gun = gun_intervals(job, a..b);
        if gun.is_empty() {
            out.push_str("      []\n");
        }
        for (on, off) in gun {
            let _ = writeln!(out, "      - {{on_s: {}, off_s: {}}}", num(on), num(off));
        }
        out.push_str("    trajectory:\n");
        let _ = writeln!(
            out,
            "      header: {{stamp: {{sec: 0, nanosec: 0}}, frame_id: \"basr_base_stop_{}\"}}",
            station + 1
        );
        let _ = writeln!(
            out,
            "      joint_names: [{}]",
            names
                .iter()
                .map(|n| format!("{n:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        out.push_str("      points:\n");
        for i in 0..q.len() {
            let (sec, nanosec) = duration(t[i]);
            let _ = writeln!(out, "        - positions: {}", list(&q[i]));
            let _ = writeln!(out, "          velocities: {}", list(&v[i]));
            let _ = writeln!(out, "          accelerations: {}", list(&acc[i]));
            out.push_str("          effort: []\n");
            let _ = writeln!(
                out,
                "          time_from_start: {{sec: {sec}, nanosec: {nanosec}}}"
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_split_into_seconds_and_nanoseconds() {
        assert_eq!(duration(0.0), (0, 0));
        assert_eq!(duration(1.5), (1, 500_000_000));
        assert_eq!(duration(0.032), (0, 32_000_000));
        assert_eq!(duration(12.000_000_001), (12, 1));
    }

    #[test]
    fn derivatives_are_exact_on_a_parabola() {
        let t: Vec<f64> = (0..20).map(|i| i as f64 * 0.1).collect();
        let q: Vec<f64> = t.iter().map(|t| 3.0 * t * t + t).collect();
        let (v, a) = derivatives(&t, &q);
        for i in 1..19 {
            assert!((v[i] - (6.0 * t[i] + 1.0)).abs() < 1e-9, "{i}: {}", v[i]);
        }
        for (i, a) in a.iter().enumerate().take(18).skip(2) {
            assert!((a - 6.0).abs() < 1e-9, "{i}: {a}");
        }
    }
}
