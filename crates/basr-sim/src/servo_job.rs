//! `basr simulate` for the electric kinds (telescopic, articulated): the
//! job's own joint columns played through the servo plant (`servo`: each
//! joint a rigid inertia under a PID + feed-forward loop with its drive's
//! torque and speed limits, sampled at the description's controller
//! period), and the verdict on the tip's distance from where the setpoints
//! put it while the gun is on, as the hydraulic simulation judges BASR.

use serde::Serialize;

use super::report::{Place, Verdict};
use super::servo::{self, Tick};
use super::SimError;
use basr_job::Job;
use basr_robot::{AnyRobot, ServoJoint, Q};

/// How one joint's drive was used.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct JointUse {
    pub joint: String,
    /// Largest |effort| asked / max_effort (over 1: the drive saturated).
    pub effort_fraction: f64,
    /// Time the drive spent saturated (s).
    pub saturated_s: f64,
    /// Largest |speed| / max_vel.
    pub speed_fraction: f64,
    /// Farthest the followed joint went outside its range (rad or m; 0 inside).
    pub range_excess: f64,
}

/// What the servo simulation of a job found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ServoJobReport {
    /// The robot kind's name (`telescopic`, `articulated`).
    pub kind: &'static str,
    pub controller: String,
    pub tolerance_m: f64,
    pub verdict: Verdict,
    pub reasons: Vec<String>,
    /// Tip error while painting (the whole job if it never paints).
    pub max_error_m: f64,
    pub rms_error_m: f64,
    pub worst: Place,
    pub max_error_all_m: f64,
    pub joints: Vec<JointUse>,
    pub duration_s: f64,
    pub painting_s: f64,
    pub controller_sample_s: f64,
}

/// Range overshoot tolerated before a joint counts as leaving its range
/// (rad or m). assumed: 1 mrad or 1 mm, the planner's own clamp
/// (plan/samples.rs `CLAMP_MAX`).
const RANGE_SLACK: f64 = 1e-3;

impl ServoJobReport {
    pub fn passed(&self) -> bool {
        self.verdict == Verdict::Pass
    }

    /// Whether a joint left its range (a limit the plan must not break).
    pub fn broken_limits(&self) -> Vec<String> {
        self.joints
            .iter()
            .filter(|j| j.range_excess > RANGE_SLACK)
            .map(|j| {
                format!(
                    "{} leaves its range by {:.4} in the simulation",
                    j.joint, j.range_excess
                )
            })
            .collect()
    }

    /// A few lines for a person.
    pub fn human(&self) -> String {
        let mm = |m: f64| m * 1e3;
        let mut s = format!(
            "simulate ({}, {} kind): {} — max error {:.3} mm, RMS {:.3} mm while painting \
             (tolerance {:.3} mm)\n",
            self.controller,
            self.kind,
            self.verdict.name().to_uppercase(),
            mm(self.max_error_m),
            mm(self.rms_error_m),
            mm(self.tolerance_m)
        );
        s += &format!("  worst at {}\n", self.worst.describe());
        s += &format!(
            "  whole job: max {:.3} mm over {:.1} s ({:.1} s painting)\n",
            mm(self.max_error_all_m),
            self.duration_s,
            self.painting_s
        );
        for j in &self.joints {
            s += &format!(
                "  {}: drive up to {:.0} % of its effort ({:.2} s saturated), speed up to {:.0} % \
                 of its limit\n",
                j.joint,
                100.0 * j.effort_fraction,
                j.saturated_s,
                100.0 * j.speed_fraction
            );
        }
        for r in &self.reasons {
            s += &format!("  FAIL: {r}\n");
        }
        s
    }
}

/// The servo joints of an electric kind (`None` for BASR).
pub fn servo_joints(robot: &AnyRobot) -> Option<[ServoJoint; 5]> {
    match robot {
        AnyRobot::Telescopic(t) => Some(t.joints.all().map(|j| *j)),
        AnyRobot::Articulated(a) => Some(a.joints.all().map(|j| *j)),
        AnyRobot::Basr(_) => None,
    }
}

/// An electric kind's servo joints and controller sample, once the job's
/// samples hold its joints (one row each, at least two) and its periods
/// are positive.
fn setup(job: &Job) -> Result<([ServoJoint; 5], f64), SimError> {
    let robot = &job.robot;
    let Some(joints) = servo_joints(robot) else {
        return Err(SimError::Job(
            "a BASR job is simulated by the hydraulic plant (sim::simulate)".into(),
        ));
    };
    let s = &job.samples;
    let n = s
        .check_lengths()
        .map_err(|e| SimError::Job(e.to_string()))?;
    if n < 2 || s.kind_joints.len() != n {
        return Err(SimError::Job(format!(
            "it has {n} setpoint rows and {} rows of the {} kind's joints; at least 2 of each, \
             one per row, are needed",
            s.kind_joints.len(),
            robot.kind().name()
        )));
    }
    let period = job.control_period_s;
    let sample = robot.control().controller_sample_s;
    if !(period.is_finite() && period > 0.0 && sample.is_finite() && sample > 0.0) {
        return Err(SimError::Job(format!(
            "control_period_s {period} and the controller sample {sample} s must be positive"
        )));
    }
    Ok((joints, sample))
}

/// Simulate an electric kind's job and judge it against `tolerance_m`.
pub fn simulate_job(job: &Job, tolerance_m: f64) -> Result<ServoJobReport, SimError> {
    let robot = &job.robot;
    let (joints, sample) = setup(job)?;
    let s = &job.samples;
    let n = s.len();
    if !(tolerance_m.is_finite() && tolerance_m > 0.0) {
        return Err(SimError::Option(format!(
            "tolerance {tolerance_m} m must be positive"
        )));
    }
    let period = job.control_period_s;
    let setpoints: &[Q] = &s.kind_joints;
    let limits = robot.limits();
    let mut paint = Stats::default();
    let mut all = Stats::default();
    let mut uses: Vec<JointUse> = robot
        .joint_names()
        .iter()
        .map(|n| JointUse {
            joint: n.to_string(),
            effort_fraction: 0.0,
            saturated_s: 0.0,
            speed_fraction: 0.0,
            range_excess: 0.0,
        })
        .collect();
    let speeds = servo::follow(
        robot.arm(),
        &joints,
        setpoints,
        period,
        sample,
        &mut |t: &Tick| {
            all.add(t);
            if s.paint[t.index] == 1 {
                paint.add(t);
            }
            for (k, u) in uses.iter_mut().enumerate() {
                u.effort_fraction = u.effort_fraction.max(t.effort_fraction[k]);
                if t.effort_fraction[k] > 1.0 {
                    u.saturated_s += sample;
                }
                u.range_excess = u.range_excess.max(limits[k].excess(t.q[k]));
            }
        },
    );
    for (u, v) in uses.iter_mut().zip(speeds) {
        u.speed_fraction = v;
    }
    let judged = if paint.n > 0 { &paint } else { &all };
    let i = judged.worst_index;
    let worst = Place {
        t_s: s.t_s[i],
        stroke: s.stroke[i],
        station: s.station[i],
        x_m: s.x_m[i],
        y_m: s.y_m[i],
    };
    let mut report = ServoJobReport {
        kind: robot.kind().name(),
        controller: "servo PID + feed-forward".into(),
        tolerance_m,
        // Judged below, once every reason is in.
        verdict: Verdict::Pass,
        reasons: vec![],
        max_error_m: judged.max,
        rms_error_m: judged.rms(),
        worst,
        max_error_all_m: all.max,
        joints: uses,
        duration_s: (n - 1) as f64 * period,
        painting_s: s.paint.iter().filter(|&&p| p == 1).count() as f64 * period,
        controller_sample_s: sample,
    };
    if report.max_error_m > tolerance_m {
        report.reasons.push(format!(
            "nozzle error {:.3} mm while painting exceeds the tolerance {:.3} mm at {}",
            report.max_error_m * 1e3,
            tolerance_m * 1e3,
            report.worst.describe()
        ));
    }
    report.reasons.extend(report.broken_limits());
    report.verdict = Verdict::of(&report.reasons);
    Ok(report)
}

/// One controller tick of the servo simulation of a job: where the
/// followed joints and the reference put the nozzle (base frame of the
/// tick's station), for the film of the simulated arm (`preview --from-sim`).
#[derive(Clone, Copy, Debug)]
pub struct TrackTick {
    pub t_s: f64,
    /// The setpoint nearest in time.
    pub index: usize,
    pub actual: basr_robot::NozzlePose,
    pub wanted: basr_robot::NozzlePose,
}

/// The servo simulation of an electric kind's job, tick by tick.
pub fn track(job: &Job) -> Result<Vec<TrackTick>, SimError> {
    let robot = &job.robot;
    let (joints, sample) = setup(job)?;
    let s = &job.samples;
    let mut out = Vec::new();
    servo::follow(
        robot.arm(),
        &joints,
        &s.kind_joints,
        job.control_period_s,
        sample,
        &mut |t: &Tick| {
            out.push(TrackTick {
                t_s: t.t_s,
                index: t.index,
                actual: robot.fk(&t.q),
                wanted: robot.fk(&t.want),
            })
        },
    );
    Ok(out)
}

#[derive(Default)]
struct Stats {
    max: f64,
    worst_index: usize,
    sum2: f64,
    n: usize,
}

impl Stats {
    fn add(&mut self, t: &Tick) {
        self.sum2 += t.tip_error_m * t.tip_error_m;
        self.n += 1;
        if t.tip_error_m > self.max {
            self.max = t.tip_error_m;
            self.worst_index = t.index;
        }
    }

    fn rms(&self) -> f64 {
        if self.n == 0 {
            0.0
        } else {
            (self.sum2 / self.n as f64).sqrt()
        }
    }
}
