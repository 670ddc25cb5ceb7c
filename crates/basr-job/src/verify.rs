//! Checks of a job's setpoints beyond its hashes: the time base, indices,
//! the robot's joint limits (position, velocity, acceleration) and the
//! agreement of the nozzle columns with the joints. Reports every problem.

use super::Job;
use basr_robot::{Joints, Q};

/// Relative slack on velocity and acceleration limits: finite differences of
/// a trajectory that keeps a limit stay within it; this only absorbs the
/// rounding of the JSON numbers.
const REL_TOL: f64 = 1e-6;
/// Absolute slack on positions (rad or m).
const POS_TOL: f64 = 1e-9;
/// Nozzle columns must match the joints' forward kinematics within this (m, rad).
const FK_TOL: f64 = 1e-6;
/// At most this many problems are listed per kind; the rest are counted.
const LIST_PER_KIND: usize = 5;

struct Collector {
    out: Vec<String>,
    counts: Vec<(String, usize)>,
}

impl Collector {
    fn add(&mut self, kind: &str, msg: String) {
        let n = match self.counts.iter_mut().find(|(k, _)| k == kind) {
            Some((_, n)) => {
                *n += 1;
                *n
            }
            None => {
                self.counts.push((kind.to_string(), 1));
                1
            }
        };
        if n <= LIST_PER_KIND {
            self.out.push(msg);
        }
    }

    fn finish(mut self, origin: &str) -> Vec<String> {
        for (kind, n) in &self.counts {
            if *n > LIST_PER_KIND {
                self.out.push(format!(
                    "{origin}: … and {} more {kind} problem(s)",
                    n - LIST_PER_KIND
                ));
            }
        }
        self.out
    }
}

fn joints_at(job: &Job, i: usize) -> Joints {
    let s = &job.samples;
    Joints {
        base_rot_rad: s.base_rot_rad[i],
        extension_m: s.extension_m[i],
        vertical_m: s.vertical_m[i],
        ee_yaw_rad: s.ee_yaw_rad[i],
        tilt_rad: s.tilt_rad[i],
    }
}

/// The joints of row `i` in the robot kind's order: BASR's SPEC §3
/// columns, or an electric kind's own (`kind_joints`; zeros when missing,
/// reported by `kind_columns`).
pub fn q_at(job: &Job, i: usize) -> Q {
    match job.robot.basr() {
        Some(_) => joints_at(job, i).values(),
        None => job.samples.kind_joints.get(i).copied().unwrap_or([0.0; 5]),
    }
}

/// An electric kind's job names its own columns and leaves BASR's joint,
/// actuator and encoder columns at 0 (docs/robot-kinds.md); a BASR job has
/// no kind columns.
fn kind_columns(job: &Job, origin: &str, c: &mut Collector) {
    let s = &job.samples;
    let r = &job.robot;
    if r.basr().is_some() {
        if !s.kind_columns.is_empty() || !s.kind_joints.is_empty() {
            c.add(
                "columns",
                format!("{origin}: a BASR job holds another kind's joint columns"),
            );
        }
        return;
    }
    let mut want: Vec<String> = r.joint_names().iter().map(|n| n.to_string()).collect();
    want.extend(r.encoder_names());
    if s.kind_columns != want || s.kind_joints.len() != s.len() {
        c.add(
            "columns",
            format!(
                "{origin}: samples.kind_columns are {:?} with {} rows, but the {} kind's are {want:?} \
                 with one per setpoint",
                s.kind_columns,
                s.kind_joints.len(),
                r.kind().name()
            ),
        );
    }
    let basr_only = [
        ("base_rot_rad", &s.base_rot_rad),
        ("extension_m", &s.extension_m),
        ("cylinder_m", &s.cylinder_m),
        ("vertical_m", &s.vertical_m),
        ("ee_yaw_rad", &s.ee_yaw_rad),
        ("tilt_nut_m", &s.tilt_nut_m),
    ];
    for (name, col) in basr_only {
        if let Some(i) = col.iter().position(|&v| v != 0.0) {
            c.add(
                "columns",
                format!(
                    "{origin}: row {i}: {name} is {} but it is BASR's column, 0 in a {} job",
                    col[i],
                    r.kind().name()
                ),
            );
        }
    }
    let encs = [
        &s.enc_base,
        &s.enc_extension,
        &s.enc_yaw,
        &s.enc_tilt,
        &s.enc_vertical,
    ];
    if let Some(i) = (0..s.len()).find(|&i| encs.iter().any(|e| e[i] != 0)) {
        c.add(
            "columns",
            format!(
                "{origin}: row {i}: BASR's encoder columns are not 0 in a {} job",
                r.kind().name()
            ),
        );
    }
}

/// Every problem of a verified job's setpoints (empty when it is sound).
/// `origin` names the job in the messages.
pub fn problems(job: &Job, origin: &str) -> Vec<String> {
    let mut c = Collector {
        out: vec![],
        counts: vec![],
    };
    let s = &job.samples;
    let n = s.len();
    let p = job.control_period_s;
    if !(p.is_finite() && p > 0.0) {
        c.add(
            "period",
            format!("{origin}: control_period_s is {p}, not a positive number"),
        );
        return c.finish(origin);
    }
    if n == 0 {
        c.add("empty", format!("{origin}: the job has no setpoints"));
        return c.finish(origin);
    }
    for i in 0..n {
        if !s.row_is_finite(i) {
            c.add(
                "not-finite",
                format!("{origin}: row {i} holds a value that is not a finite number"),
            );
        }
        let t = i as f64 * p;
        if (s.t_s[i] - t).abs() > 1e-9 * t.max(1.0) {
            c.add(
                "time",
                format!(
                    "{origin}: row {i}: t_s = {} but the period {p} s puts it at {t}",
                    s.t_s[i]
                ),
            );
        }
        if s.station[i] as usize >= job.stations.len() {
            c.add(
                "station",
                format!(
                    "{origin}: row {i}: station {} but the job has {} station(s)",
                    s.station[i],
                    job.stations.len()
                ),
            );
        }
        if s.paint[i] > 1 {
            c.add(
                "paint",
                format!("{origin}: row {i}: paint is {} (0 or 1)", s.paint[i]),
            );
        }
        if s.stroke[i] < -1 || s.stroke[i] >= job.summary.strokes as i64 {
            c.add(
                "stroke",
                format!(
                    "{origin}: row {i}: stroke {} outside −1..{}",
                    s.stroke[i], job.summary.strokes
                ),
            );
        }
        if s.paint[i] == 1 && s.stroke[i] < 0 {
            c.add(
                "paint",
                format!("{origin}: row {i}: the gun is on during an air move"),
            );
        }
    }
    kind_columns(job, origin, &mut c);
    // Joint limits, with velocity and acceleration by finite differences.
    let robot = &job.robot;
    let qs: Vec<Q> = (0..n).map(|i| q_at(job, i)).collect();
    for (j, (name, lim)) in robot
        .joint_names()
        .into_iter()
        .zip(robot.limits())
        .enumerate()
    {
        let col: Vec<f64> = qs.iter().map(|q| q[j]).collect();
        for (i, &v) in col.iter().enumerate() {
            if v < lim.min - POS_TOL || v > lim.max + POS_TOL {
                c.add(
                    name,
                    format!(
                        "{origin}: row {i} (t {:.3} s): {name} = {v:.6} outside its range [{}, {}]",
                        s.t_s[i], lim.min, lim.max
                    ),
                );
            }
        }
        for i in 1..n {
            let v = (col[i] - col[i - 1]) / p;
            if v.abs() > lim.max_vel * (1.0 + REL_TOL) + 1e-12 {
                c.add(
                    name,
                    format!(
                        "{origin}: row {i} (t {:.3} s): {name} moves at {:.6}/s, above its \
                         velocity limit {}",
                        s.t_s[i],
                        v.abs(),
                        lim.max_vel
                    ),
                );
            }
        }
        for i in 1..n.saturating_sub(1) {
            let a = (col[i + 1] - 2.0 * col[i] + col[i - 1]) / (p * p);
            if a.abs() > lim.max_acc * (1.0 + REL_TOL) + 1e-9 {
                c.add(
                    name,
                    format!(
                        "{origin}: row {i} (t {:.3} s): {name} accelerates at {:.6}/s², above \
                         its acceleration limit {}",
                        s.t_s[i],
                        a.abs(),
                        lim.max_acc
                    ),
                );
            }
        }
    }
    // Ball-nut speed of BASR's tilt drive (its own limit, SPEC §4).
    let nut_lim = robot
        .basr()
        .map_or(f64::INFINITY, |b| b.end_effector.tilt_nut_max_speed_mps);
    for i in 1..n {
        let v = (s.tilt_nut_m[i] - s.tilt_nut_m[i - 1]) / p;
        if v.abs() > nut_lim * (1.0 + REL_TOL) + 1e-12 {
            c.add(
                "tilt_nut_m",
                format!(
                    "{origin}: row {i} (t {:.3} s): the tilt ball nut moves at {:.6} m/s, above \
                     its limit {nut_lim} m/s",
                    s.t_s[i],
                    v.abs()
                ),
            );
        }
    }
    // Nozzle columns against the joints.
    for (i, q) in qs.iter().enumerate() {
        let Some(st) = job.stations.get(s.station[i] as usize) else {
            continue;
        };
        let pose = robot.fk(q);
        let r = st.base_to_road([pose.x_m, pose.y_m]);
        let yaw = basr_robot::kinematics::wrap_pi(
            pose.yaw_rad + st.heading_rad - std::f64::consts::FRAC_PI_2,
        );
        let dyaw = basr_robot::kinematics::wrap_pi(yaw - s.yaw_rad[i]);
        let dx = (r[0] - s.x_m[i]).hypot(r[1] - s.y_m[i]);
        let dz = (pose.z_m + job.road.origin_z(st) - s.z_m[i]).abs();
        if dx > FK_TOL || dz > FK_TOL || dyaw.abs() > FK_TOL {
            c.add(
                "nozzle",
                format!(
                    "{origin}: row {i}: the nozzle columns x_m/y_m, z_m and yaw_rad are {:.4} m, {:.4} m \
                     and {:.4} rad away from where the joints put the nozzle",
                    dx,
                    dz,
                    dyaw.abs()
                ),
            );
        }
    }
    derived_columns(job, origin, &mut c);
    summary_totals(job, origin, &mut c);
    settings(job, origin, &mut c);
    c.finish(origin)
}

/// The job's own settings: its robot description passes the checks a robot
/// file gets, the paint block is that robot's (k = flow·efficiency/film,
/// 001 eq. 2.6), and the stroke count is the layout's.
fn settings(job: &Job, origin: &str, c: &mut Collector) {
    if let Some(p) = job.road.problem(job.stations.len()) {
        c.add("road", format!("{origin}: the job's road: {p}"));
    }
    for (field, what) in job.robot.problems() {
        c.add(
            "robot",
            format!("{origin}: the job's robot description: field `robot.{field}`: {what}"),
        );
    }
    let want = super::Paint::of(job.robot.paint());
    let stated = &job.paint;
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-12);
    for (name, a, b) in [
        ("fan_angle_rad", stated.fan_angle_rad, want.fan_angle_rad),
        ("flow_m3ps", stated.flow_m3ps, want.flow_m3ps),
        (
            "transfer_efficiency",
            stated.transfer_efficiency,
            want.transfer_efficiency,
        ),
        ("film_m", stated.film_m, want.film_m),
        ("k_m2ps", stated.k_m2ps, want.k_m2ps),
    ] {
        if !close(a, b) {
            c.add(
                "paint",
                format!(
                    "{origin}: paint.{name} is {a} but the job's robot description gives {b} \
                     (k = flow × efficiency / film)"
                ),
            );
        }
    }
    if stated.tip != want.tip {
        c.add(
            "paint",
            format!(
                "{origin}: paint.tip is {:?} but the job's robot description mounts {:?} \
                 (robot.paint.mounted)",
                stated.tip, want.tip
            ),
        );
    }
    let laid: usize = job.layout.glyphs.iter().map(|g| g.strokes.len()).sum();
    if job.summary.strokes != laid {
        c.add(
            "summary",
            format!(
                "{origin}: summary.strokes is {} but the layout has {laid} strokes",
                job.summary.strokes
            ),
        );
    }
}

/// Columns the compiler derives from the joints and the nozzle path: the
/// actuator positions and encoder counts (robot model), the width (0 with
/// the gun off) and the nozzle speed (central difference within a station,
/// one-sided at its ends, as `plan::compile` writes it). An edit that keeps
/// the hashes but changes one of them would send the truck counts that do
/// not match the path.
fn derived_columns(job: &Job, origin: &str, c: &mut Collector) {
    let s = &job.samples;
    let n = s.len();
    let p = job.control_period_s;
    let robot = &job.robot;
    for i in 0..n {
        match robot.basr() {
            Some(b) => basr_derived(job, b, i, origin, c),
            None => {
                let want = robot.encoders(&q_at(job, i));
                let stated = s.kind_encoders.get(i).copied();
                if stated != Some(want) {
                    c.add(
                        "encoder",
                        format!(
                            "{origin}: row {i}: encoder counts {stated:?} ({}) are not the robot \
                             model's {want:?} for the joints",
                            robot.encoder_names().join(", ")
                        ),
                    );
                }
            }
        }
        if (s.paint[i] == 0) != (s.width_m[i] == 0.0) {
            c.add(
                "width",
                format!(
                    "{origin}: row {i}: width_m is {} with the gun {}; it is the stroke's \
                     width while painting and 0 otherwise",
                    s.width_m[i],
                    if s.paint[i] == 1 { "on" } else { "off" }
                ),
            );
        }
        let same = |k: usize| s.station[k] == s.station[i];
        let a = if i > 0 && same(i - 1) { i - 1 } else { i };
        let b = if i + 1 < n && same(i + 1) { i + 1 } else { i };
        let speed = if b > a {
            (s.x_m[b] - s.x_m[a]).hypot(s.y_m[b] - s.y_m[a]) / ((b - a) as f64 * p)
        } else {
            0.0
        };
        let dv = (speed - s.speed_mps[i]).abs();
        if dv.is_nan() || dv > FK_TOL {
            c.add(
                "speed",
                format!(
                    "{origin}: row {i} (t {:.3} s): speed_mps is {} but the nozzle columns \
                     move at {speed:.6} m/s there",
                    s.t_s[i], s.speed_mps[i]
                ),
            );
        }
    }
}

/// BASR's actuator and encoder columns of row `i` against its model.
fn basr_derived(job: &Job, robot: &basr_robot::Robot, i: usize, origin: &str, c: &mut Collector) {
    let s = &job.samples;
    let j = joints_at(job, i);
    let act = robot.actuators(&j);
    let enc = robot.encoders(&j);
    let off = (act.cylinder_m - s.cylinder_m[i])
        .abs()
        .max((act.tilt_nut_m - s.tilt_nut_m[i]).abs());
    if off.is_nan() || off > FK_TOL {
        c.add(
            "actuator",
            format!(
                "{origin}: row {i}: cylinder_m {} / tilt_nut_m {} are not what the robot \
                 model gives for the joints ({} / {})",
                s.cylinder_m[i], s.tilt_nut_m[i], act.cylinder_m, act.tilt_nut_m
            ),
        );
    }
    let stated = [
        s.enc_base[i],
        s.enc_extension[i],
        s.enc_yaw[i],
        s.enc_tilt[i],
        s.enc_vertical[i],
    ];
    let want = [enc.base, enc.extension, enc.yaw, enc.tilt, enc.vertical];
    if stated != want {
        c.add(
            "encoder",
            format!(
                "{origin}: row {i}: encoder counts {stated:?} (base, extension, yaw, tilt, \
                 vertical) are not the robot model's {want:?} for the joints"
            ),
        );
    }
}

/// The summary's totals against the samples (SPEC §3).
fn summary_totals(job: &Job, origin: &str, c: &mut Collector) {
    let s = &job.samples;
    let sum = &job.summary;
    let p = job.control_period_s;
    let gun_on = s.paint.iter().filter(|&&v| v == 1).count();
    let paint_time = gun_on as f64 * p;
    let duration = s.t_s.last().copied().unwrap_or(0.0);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
    let checks = [
        (
            "duration_s",
            sum.duration_s,
            duration,
            "the last setpoint's time",
        ),
        (
            "paint_time_s",
            sum.paint_time_s,
            paint_time,
            "the gun-on setpoints × the period",
        ),
        (
            "air_time_s",
            sum.air_time_s,
            (duration - paint_time).max(0.0),
            "the duration less the paint time",
        ),
        (
            "paint_volume_m3",
            sum.paint_volume_m3,
            job.robot.paint().flow_m3ps * paint_time,
            "the nozzle flow × the paint time",
        ),
    ];
    for (name, stated, want, why) in checks {
        if !close(stated, want) {
            c.add(
                "summary",
                format!("{origin}: summary.{name} is {stated} but {why} gives {want}"),
            );
        }
    }
}
