//! Small synthetic jobs for the simulator's tests and benchmark: strokes
//! drawn in a station's base frame, timed with smooth speed ramps, turned
//! into joint setpoints by the arm's closed-form inverse kinematics.

use basr_job::{FontRef, Job, Layout, SampleRow, Samples, Station, Summary};
use basr_robot::Robot;

/// A stroke in the base frame: `point(u)` for u ∈ [0, 1].
pub struct Stroke {
    pub point: Box<dyn Fn(f64) -> [f64; 2]>,
    /// Painting speed (m/s).
    pub speed: f64,
}

impl Stroke {
    /// Straight stroke from `a` to `b`.
    pub fn line(a: [f64; 2], b: [f64; 2], speed: f64) -> Stroke {
        Stroke {
            point: Box::new(move |u| [a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])]),
            speed,
        }
    }
    /// Arc about `c` of radius `r` from angle `a0` to `a1` (rad).
    pub fn arc(c: [f64; 2], r: f64, a0: f64, a1: f64, speed: f64) -> Stroke {
        Stroke {
            point: Box::new(move |u| {
                let a = a0 + u * (a1 - a0);
                [c[0] + r * a.cos(), c[1] + r * a.sin()]
            }),
            speed,
        }
    }
    fn length(&self) -> f64 {
        let n = 400;
        (0..n)
            .map(|i| {
                let p = (self.point)(i as f64 / n as f64);
                let q = (self.point)((i + 1) as f64 / n as f64);
                (q[0] - p[0]).hypot(q[1] - p[1])
            })
            .sum()
    }
    /// u at arc length `s` (by bisection on the sampled length).
    fn at_length(&self, s: f64, total: f64) -> [f64; 2] {
        // strokes here are lines and arcs: arc length is linear in u
        (self.point)((s / total).clamp(0.0, 1.0))
    }
}

/// Distance travelled after `t` s of a move of length `l` at cruise `v` with
/// acceleration ramps of `ta` s (cosine-smoothed); and its total time.
fn profile(l: f64, v: f64, ta: f64) -> (f64, Box<dyn Fn(f64) -> f64>) {
    // a raised-cosine speed ramp covers v·ta/2 in ta seconds
    let (v, ta) = if l < v * ta {
        let v2 = l / ta;
        (v2, ta)
    } else {
        (v, ta)
    };
    let cruise = (l - v * ta) / v;
    let total = 2.0 * ta + cruise;
    let f = move |t: f64| -> f64 {
        let ramp = |t: f64| {
            v * (0.5 * t
                - ta / (2.0 * std::f64::consts::PI) * (std::f64::consts::PI * t / ta).sin())
        };
        if t <= 0.0 {
            0.0
        } else if t < ta {
            ramp(t)
        } else if t < ta + cruise {
            ramp(ta) + v * (t - ta)
        } else if t < total {
            l - ramp(total - t)
        } else {
            l
        }
    };
    (total, Box::new(f))
}

/// Joints for a base-frame nozzle point: (θ1, R) with W = R·(c, s) + a2·(s, −c) (SPEC §2).
pub fn ik(p: [f64; 2], a2: f64) -> (f64, f64) {
    let r = (p[0] * p[0] + p[1] * p[1] - a2 * a2).max(0.0).sqrt();
    (p[1].atan2(p[0]) + a2.atan2(r), r)
}

/// Speed ramps of every move (s): slow enough that the rows keep the base's
/// 0.3 rad/s² at 2 m of reach (robots/basr.toml `limits.base_rot_rad`).
const RAMP_S: f64 = 0.8;

/// A sealed job painting `strokes` from one station at (0, `station_y`),
/// heading −π/2, with air moves at `air_speed` between them and 0.5 s holds
/// at start and end. Setpoints every `period` s.
pub fn job(strokes: &[Stroke], air_speed: f64, period: f64) -> Job {
    let robot = Robot::basr();
    let station = Station {
        x_m: 0.0,
        y_m: 6.0,
        heading_rad: -std::f64::consts::FRAC_PI_2,
    };
    // timeline of (duration, position(t), paint, stroke index)
    type Seg = (f64, Box<dyn Fn(f64) -> [f64; 2]>, bool, i64);
    let mut segs: Vec<Seg> = Vec::new();
    let first = (strokes[0].point)(0.0);
    segs.push((0.5, Box::new(move |_| first), false, -1));
    let mut prev_end = first;
    for (i, st) in strokes.iter().enumerate() {
        let start = (st.point)(0.0);
        let gap = (start[0] - prev_end[0]).hypot(start[1] - prev_end[1]);
        if gap > 1e-9 {
            let (t, f) = profile(gap, air_speed, RAMP_S);
            let a = prev_end;
            segs.push((
                t,
                Box::new(move |tt| {
                    let s = f(tt) / gap;
                    [a[0] + s * (start[0] - a[0]), a[1] + s * (start[1] - a[1])]
                }),
                false,
                -1,
            ));
        }
        let l = st.length();
        let (t, f) = profile(l, st.speed, RAMP_S);
        let pt: &Stroke = st;
        let pts: Vec<[f64; 2]> = (0..=2000)
            .map(|j| pt.at_length(j as f64 / 2000.0 * l, l))
            .collect();
        segs.push((
            t,
            Box::new(move |tt| {
                let u = (f(tt) / l * 2000.0).clamp(0.0, 2000.0);
                let j = (u.floor() as usize).min(1999);
                let w = u - j as f64;
                [
                    pts[j][0] + w * (pts[j + 1][0] - pts[j][0]),
                    pts[j][1] + w * (pts[j + 1][1] - pts[j][1]),
                ]
            }),
            true,
            i as i64,
        ));
        prev_end = (st.point)(1.0);
    }
    let last = prev_end;
    segs.push((0.5, Box::new(move |_| last), false, -1));

    let total: f64 = segs.iter().map(|s| s.0).sum();
    let n = (total / period).ceil() as usize + 1;
    let (mut seg, mut seg_t0) = (0usize, 0.0);
    let mut rows = Vec::with_capacity(n);
    for i in 0..n {
        let t = i as f64 * period;
        while seg + 1 < segs.len() && t > seg_t0 + segs[seg].0 {
            seg_t0 += segs[seg].0;
            seg += 1;
        }
        let (_, f, paint, stroke) = &segs[seg];
        rows.push((f(t - seg_t0), *paint, *stroke));
    }
    sealed(robot, station, &rows, strokes.len(), period)
}

/// A setpoint row at `t` whose every column follows from the joints by the
/// robot's kinematics seen from `station`, as compile writes them, so
/// `basr check` finds nothing to say about it. The gun is on where `width`
/// is above 0; the speed is left 0 for [`set_speeds`].
pub fn row_from_joints(
    robot: &Robot,
    station: &Station,
    j: &basr_robot::Joints,
    t: f64,
    stroke: i64,
    width: f64,
) -> SampleRow {
    let (s, c) = (station.heading_rad - std::f64::consts::FRAC_PI_2).sin_cos();
    let pose = robot.fk(j);
    SampleRow {
        t_s: t,
        station: 0,
        stroke,
        paint: u8::from(width > 0.0),
        x_m: station.x_m + c * pose.x_m - s * pose.y_m,
        y_m: station.y_m + s * pose.x_m + c * pose.y_m,
        z_m: pose.z_m,
        yaw_rad: basr_robot::kinematics::wrap_pi(
            pose.yaw_rad + station.heading_rad - std::f64::consts::FRAC_PI_2,
        ),
        speed_mps: 0.0,
        width_m: width,
        ..SampleRow::default()
    }
    .with_basr_joints(robot, j)
}

/// Nozzle speed as compile writes it: central difference of the road
/// columns, one-sided at the ends.
pub fn set_speeds(samples: &mut Samples, period: f64) {
    let n = samples.len();
    for i in 0..n {
        let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
        samples.speed_mps[i] = if b > a {
            (samples.x_m[b] - samples.x_m[a]).hypot(samples.y_m[b] - samples.y_m[a])
                / ((b - a) as f64 * period)
        } else {
            0.0
        };
    }
}

/// A sealed job whose nozzle visits the base-frame points `rows` (point,
/// gun on, stroke index), one per `period`, from `station`.
fn sealed(
    robot: Robot,
    station: Station,
    rows: &[([f64; 2], bool, i64)],
    strokes: usize,
    period: f64,
) -> Job {
    let a2 = robot.arm.a2_m;
    let n = rows.len();
    let mut samples = Samples::default();
    let mut paint_time = 0.0;
    for (i, (p, paint, stroke)) in rows.iter().enumerate() {
        let t = i as f64 * period;
        let (th, r) = ik(*p, a2);
        if *paint {
            paint_time += period;
        }
        let joints = basr_robot::Joints {
            base_rot_rad: th,
            extension_m: r,
            vertical_m: 0.0,
            ee_yaw_rad: 0.0,
            tilt_rad: 0.0,
        };
        let width = if *paint { 0.15 } else { 0.0 };
        samples.push(&row_from_joints(
            &robot, &station, &joints, t, *stroke, width,
        ));
    }
    set_speeds(&mut samples, period);
    let paint = basr_job::Paint::of(&robot.paint);
    let paint_volume_m3 = robot.paint.flow_m3ps * paint_time;
    let mut job = Job {
        format: basr_job::FORMAT.into(),
        version: basr_job::VERSION,
        message: "synthetic".into(),
        font: FontRef {
            name: "none".into(),
            sha256: String::new(),
        },
        robot: robot.into(),
        robot_sha256: String::new(),
        paint,
        control_period_s: period,
        layout: Layout {
            letter_height_m: 2.44,
            lane_width_m: 3.66,
            tilt_method: "none".into(),
            // one glyph holding the strokes (their edges are not drawn)
            glyphs: vec![basr_job::PlacedGlyph {
                char: "S".into(),
                line: 0,
                strokes: (0..strokes)
                    .map(|_| basr_job::PlacedStroke {
                        left: vec![],
                        right: vec![],
                    })
                    .collect(),
            }],
            options: None,
            low_speed: false,
        },
        stations: vec![station],
        road: Default::default(),
        samples,
        summary: Summary::timed(
            (n - 1) as f64 * period,
            paint_time,
            strokes,
            paint_volume_m3,
        ),
        outputs: Default::default(),
        sha256: String::new(),
        signature: None,
    };
    job.seal();
    job
}

/// A letter-sized workout: an S-like pair of arcs at mid reach, a long
/// straight stroke near full reach and one near full retraction.
pub fn letter_job() -> Job {
    let v = 0.16; // SPEC §4: ≈ 6 in/s painting
    job(
        &[
            Stroke::arc([0.0, 3.4], 0.3, 0.0, std::f64::consts::PI * 1.5, v),
            Stroke::arc(
                [0.0, 2.8],
                0.3,
                std::f64::consts::FRAC_PI_2,
                -std::f64::consts::PI,
                v,
            ),
            Stroke::line([-0.6, 5.0], [0.6, 5.0], v),
            Stroke::line([0.5, 2.0], [-0.5, 2.0], v),
        ],
        0.25,
        0.032,
    )
}

/// `letter_job` with a deliberate 20 mm step in every setpoint halfway
/// through the first stroke (a job the arm cannot follow).
pub fn step_job() -> Job {
    let model = crate::SimModel::basr();
    let mut j = letter_job();
    let s = &mut j.samples;
    let first = s.stroke.iter().position(|&k| k == 0).unwrap_or(0);
    let len = s.stroke.iter().filter(|&&k| k == 0).count();
    for i in first + len / 2..s.len() {
        s.y_m[i] += 0.02;
        // the station heading is −π/2: road +y is base −y
        let w = crate::nozzle_base(&model, s.base_rot_rad[i], s.extension_m[i]);
        let (th, r) = ik([w[0], w[1] - 0.02], model.arm.a2_m);
        s.base_rot_rad[i] = th;
        s.extension_m[i] = r;
    }
    j.seal();
    j
}

/// The arm held fully retracted (every extension setpoint exactly at the
/// reach's lower limit) for 0.5 s, then extended by 0.5 m at the robot's
/// extension acceleration limit (speeding up, then slowing down) and held:
/// a setpoint series that a curve through the rows overshoots below the
/// limit at the corner.
pub fn retracted_then_extending_job() -> Job {
    let robot = Robot::basr();
    let period = robot.control.period_s;
    let a2 = robot.arm.a2_m;
    let r_min = robot.limits.extension_m.min;
    let acc = robot.limits.extension_m.max_acc;
    let theta = std::f64::consts::FRAC_PI_2; // the arm's symmetry axis (SPEC §2)
    let (sn, cs) = theta.sin_cos();
    let hold = (0.5 / period).round() as usize;
    // 0.25 m speeding up, 0.25 m slowing down at `acc`
    let half = (0.25 * 2.0 / acc).sqrt();
    let moving = (2.0 * half / period).ceil() as usize;
    let rows: Vec<([f64; 2], bool, i64)> = (0..2 * hold + moving)
        .map(|i| {
            let t = (i.saturating_sub(hold) as f64 * period).min(2.0 * half);
            let d = if t <= half {
                0.5 * acc * t * t
            } else {
                0.5 - 0.5 * acc * (2.0 * half - t).powi(2)
            };
            let r = r_min + d;
            // W = R·(cos θ1, sin θ1) + a2·(sin θ1, −cos θ1) (SPEC §2)
            ([r * cs + a2 * sn, r * sn - a2 * cs], false, -1)
        })
        .collect();
    let station = Station {
        x_m: 0.0,
        y_m: 6.0,
        heading_rad: -std::f64::consts::FRAC_PI_2,
    };
    sealed(robot, station, &rows, 0, period)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ik_inverts_the_forward_formula() {
        let m = crate::SimModel::basr();
        for p in [[0.3, 3.0], [-1.0, 4.5], [0.0, 1.6]] {
            let (th, r) = ik(p, m.arm.a2_m);
            let w = crate::nozzle_base(&m, th, r);
            assert!((w[0] - p[0]).abs() < 1e-12 && (w[1] - p[1]).abs() < 1e-12);
        }
    }

    #[test]
    fn letter_job_is_valid_and_paints() {
        let j = letter_job();
        let text = String::from_utf8(j.to_bytes()).unwrap();
        let back = Job::from_str_verified(&text, "t").unwrap();
        // and `basr check` finds nothing wrong with it
        let problems = basr_job::verify::problems(&back, "t");
        assert!(problems.is_empty(), "{problems:#?}");
        let r = retracted_then_extending_job();
        let problems = basr_job::verify::problems(&r, "r");
        assert!(problems.is_empty(), "{problems:#?}");
        assert!(back.summary.paint_time_s > 10.0);
        assert!(back.samples.paint.contains(&1));
    }

    /// The CSV `basr compile --csv` writes for `job`.
    fn csv_of(job: &Job) -> String {
        let mut text = basr_job::COLUMNS.join(",") + "\n";
        for i in 0..job.samples.len() {
            text += &(job.samples.csv_fields(i).join(",") + "\n");
        }
        text
    }

    /// (The CSV check's test lives here: it needs a job, and the job
    /// crate cannot build one without the arm.)
    #[test]
    fn written_csv_checks_and_a_cut_one_does_not() {
        let job = letter_job();
        let text = csv_of(&job);
        assert!(basr_job::csv::looks_like_csv(&text));
        assert_eq!(
            basr_job::csv::check_source(&text, "s.csv"),
            Vec::<String>::new()
        );
        // Cut in the middle of a row.
        let cut = &text[..text.len() - 40];
        let p = basr_job::csv::check_source(cut, "s.csv");
        assert!(p.iter().any(|m| m.contains("truncated")), "{p:?}");
        assert!(
            p.iter().any(|m| m.contains("fields but the header has 22")),
            "{p:?}"
        );
        // A time out of step and a word where a count belongs.
        let bad = text
            .replacen("\n0.064,", "\n0.065,", 1)
            .replacen(",0\n", ",x\n", 1);
        let p = basr_job::csv::check_source(&bad, "s.csv");
        assert!(
            p.iter().any(|m| m.contains("s.csv:4: t_s is 0.065")),
            "{p:?}"
        );
        assert!(p.iter().any(|m| m.contains("not a finite number")), "{p:?}");
        assert!(!basr_job::csv::check_source("x,y\n1,2\n", "s.csv")[0].contains("truncated"));
    }
}
