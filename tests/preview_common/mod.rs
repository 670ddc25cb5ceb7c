//! Synthetic jobs for the preview tests, built in code and sealed, until
//! `basr compile` writes real ones: a straight stroke, a ring and a tilted
//! pass, each with its true outline in `layout.glyphs`.

#![allow(dead_code)] // each test file uses some of these

use std::f64::consts::PI;

use basr::job::{
    FontRef, Job, Layout, Paint, PlacedGlyph, PlacedStroke, Samples, Station, Summary, FORMAT,
    VERSION,
};
use basr::paint::planned_tip;
use basr::robot::Robot;
use basr::sim::synthetic;

pub const ALPHA: f64 = 63.5 * PI / 180.0; // SPEC §4 fan angle
pub const FLOW: f64 = 0.4e-3 / 60.0; // SPEC §4 example: 0.4 L/min
pub const EFF: f64 = 0.9;
pub const FILM: f64 = 3.8e-4;
pub const PERIOD: f64 = 0.032;

pub fn k() -> f64 {
    FLOW * EFF / FILM // 001 eq. 2.6
}

/// One rung: its −ψ and +ψ ends and the tilt to paint it with.
pub struct Rung {
    pub a: [f64; 2],
    pub b: [f64; 2],
    pub tilt: f64,
}

/// The station every synthetic job paints from: 4 m up the road from the
/// letters, facing down it, so they lie within the arm's reach and its
/// base-rotation window.
pub const STATION: Station = Station {
    x_m: 0.0,
    y_m: 4.0,
    heading_rad: -PI / 2.0,
};

/// Seconds of each speed ramp before and after the painting pass: slow
/// enough for every joint's acceleration limit (robots/basr.toml).
const RAMP_S: f64 = 1.0;

/// Road-frame tip poses (x, y, z, yaw), tilt, gun and width of one row.
type Row = ((f64, f64, f64, f64), f64, bool, f64);

/// Samples that paint `rungs` in order at v = k/w (speed of the rung's
/// midpoint), run up to from rest along the first rung's direction of
/// travel with a raised-cosine speed ramp and run out the same way, with
/// every joint column from the robot's inverse kinematics so `basr check`
/// (and preview's content checks) find nothing to say.
pub fn samples_for(rungs: &[Rung]) -> Samples {
    // Dense path along the rung midpoints, resampled in time at v = k/w.
    let mid = |r: &Rung| [(r.a[0] + r.b[0]) / 2.0, (r.a[1] + r.b[1]) / 2.0];
    let width = |r: &Rung| (r.b[0] - r.a[0]).hypot(r.b[1] - r.a[1]);
    let mut paint: Vec<Row> = Vec::new();
    let mut u = 0.0; // position along the rung sequence, in rungs
    let last = (rungs.len() - 1) as f64;
    while u < last {
        let k0 = (u.floor() as usize).min(rungs.len() - 2);
        let f = u - k0 as f64;
        let (r0, r1) = (&rungs[k0], &rungs[k0 + 1]);
        let lerp = |p: [f64; 2], q: [f64; 2]| [p[0] + f * (q[0] - p[0]), p[1] + f * (q[1] - p[1])];
        let r = Rung {
            a: lerp(r0.a, r1.a),
            b: lerp(r0.b, r1.b),
            tilt: r0.tilt + f * (r1.tilt - r0.tilt),
        };
        let tip = planned_tip(r.a, r.b, r.tilt, ALPHA);
        paint.push((tip, r.tilt, true, width(&r)));
        // Advance the midpoint by v·dt.
        let step_len = {
            let (m0, m1) = (mid(r0), mid(r1));
            (m1[0] - m0[0]).hypot(m1[1] - m0[1]).max(1e-9)
        };
        u += k() / width(&r) * PERIOD / step_len;
    }
    // run-up and run-out: straight on from the pass' ends at its speed,
    // slowing to rest over RAMP_S (a raised-cosine speed profile covers
    // v·RAMP_S/2)
    let ramp = |end: &Row, next: &Row, ahead: bool| -> Vec<Row> {
        let (p, q) = (end.0, next.0);
        let (dx, dy) = (p.0 - q.0, p.1 - q.1);
        let v = dx.hypot(dy) / PERIOD;
        let (ux, uy) = (dx / dx.hypot(dy), dy / dx.hypot(dy));
        let n = (RAMP_S / PERIOD).round() as usize;
        let mut out: Vec<Row> = (1..=n + 10)
            .map(|i| {
                let t = (i as f64 * PERIOD).min(RAMP_S);
                // distance covered slowing from v to rest over RAMP_S at
                // the speed v·(1 + cos(πt/T))/2
                let d = 0.5 * v * (t + RAMP_S / PI * (PI * t / RAMP_S).sin());
                // the fan keeps turning as it did per metre (a ring's)
                let turn = (p.3 - q.3) / dx.hypot(dy) * d;
                (
                    (p.0 + ux * d, p.1 + uy * d, p.2, p.3 + turn),
                    end.1,
                    false,
                    0.0,
                )
            })
            .collect();
        if !ahead {
            out.reverse();
        }
        out
    };
    let before = ramp(&paint[0], &paint[1], false);
    let after = ramp(&paint[paint.len() - 1], &paint[paint.len() - 2], true);
    let rows: Vec<Row> = before.into_iter().chain(paint).chain(after).collect();
    rows_to_samples(&rows)
}

/// The samples of `rows` from the station, every column from the robot's
/// kinematics (joints by IK nearest the previous row's).
fn rows_to_samples(rows: &[Row]) -> Samples {
    use basr::robot::{kinematics::wrap_pi, Joints, NozzlePose};
    let robot = Robot::basr();
    let (s0, c0) = (STATION.heading_rad - PI / 2.0).sin_cos();
    let to_base = |x: f64, y: f64| {
        let (dx, dy) = (x - STATION.x_m, y - STATION.y_m);
        [c0 * dx + s0 * dy, -s0 * dx + c0 * dy]
    };
    let mut s = Samples::default();
    let mut prev: Option<Joints> = None;
    for (i, ((x, y, z, yaw), tilt, on, w)) in rows.iter().enumerate() {
        let b = to_base(*x, *y);
        let pose = NozzlePose {
            x_m: b[0],
            y_m: b[1],
            z_m: *z,
            yaw_rad: wrap_pi(yaw - (STATION.heading_rad - PI / 2.0)),
            tilt_rad: *tilt,
        };
        let j = match prev {
            Some(p) => robot.ik_nearest(&pose, &p),
            None => robot.ik(&pose).map(|all| all[0]),
        }
        .unwrap_or_else(|e| panic!("row {i} out of reach: {e:?}"));
        prev = Some(j);
        let t = i as f64 * PERIOD;
        let width = if *on { *w } else { 0.0 };
        s.push(&synthetic::row_from_joints(
            &robot,
            &STATION,
            &j,
            t,
            if *on { 0 } else { -1 },
            width,
        ));
    }
    synthetic::set_speeds(&mut s, PERIOD);
    s
}

/// A sealed job painting `rungs`, with `glyph` as its true outline.
pub fn job_with(message: &str, tilt_method: &str, rungs: &[Rung], glyph: PlacedGlyph) -> Job {
    let samples = samples_for(rungs);
    let duration = *samples.t_s.last().unwrap();
    let on = samples.paint.iter().filter(|&&p| p == 1).count() as f64 * PERIOD;
    let mut job = Job {
        format: FORMAT.into(),
        version: VERSION,
        message: message.into(),
        font: FontRef {
            name: "synthetic".into(),
            sha256: String::new(),
        },
        robot: Robot::basr().into(),
        robot_sha256: String::new(),
        paint: Paint {
            fan_angle_rad: ALPHA,
            flow_m3ps: FLOW,
            transfer_efficiency: EFF,
            film_m: FILM,
            k_m2ps: k(),
            tip: None,
        },
        control_period_s: PERIOD,
        layout: Layout {
            letter_height_m: 1.0,
            lane_width_m: 3.66,
            tilt_method: tilt_method.into(),
            glyphs: vec![glyph],
            options: None,
            low_speed: false,
        },
        stations: vec![STATION],
        road: Default::default(),
        samples,
        summary: Summary::timed(duration, on, 1, on * FLOW),
        outputs: Default::default(),
        sha256: String::new(),
        signature: None,
    };
    job.seal();
    job
}

/// A straight bar `w` wide from y = 0 to y = `len`, painted along +y with the
/// fan across it.
pub fn straight_job(w: f64, len: f64) -> Job {
    let n = 50;
    let rungs: Vec<Rung> = (0..=n)
        .map(|i| {
            let y = len * i as f64 / n as f64;
            Rung {
                a: [-w / 2.0, y],
                b: [w / 2.0, y],
                tilt: 0.0,
            }
        })
        .collect();
    let glyph = PlacedGlyph {
        char: "I".into(),
        line: 0,
        strokes: vec![PlacedStroke {
            left: rungs.iter().map(|r| r.a).collect(),
            right: rungs.iter().map(|r| r.b).collect(),
        }],
    };
    job_with("I", "none", &rungs, glyph)
}

/// A ring (inner radius `r0`, outer `r1`) round (0, 1), painted once round
/// with the fan along the radius; `tilt` = 0 or the tilt that evens it
/// (a constant trapezoid-style tilt given by the caller).
pub fn ring_job(r0: f64, r1: f64, tilt: f64, method: &str) -> Job {
    let n = 240;
    let c = [0.0, 1.0];
    let rungs: Vec<Rung> = (0..=n)
        .map(|i| {
            let phi = 2.0 * PI * i as f64 / n as f64;
            let (cs, sn) = (phi.cos(), phi.sin());
            Rung {
                a: [c[0] + r0 * cs, c[1] + r0 * sn],
                b: [c[0] + r1 * cs, c[1] + r1 * sn],
                tilt,
            }
        })
        .collect();
    let glyph = PlacedGlyph {
        char: "O".into(),
        line: 0,
        strokes: vec![PlacedStroke {
            left: rungs.iter().map(|r| r.b).collect(),
            right: rungs.iter().map(|r| r.a).collect(),
        }],
    };
    job_with("O", method, &rungs, glyph)
}

/// The straight bar painted with a constant tilt `beta` (tip placed by
/// 001 eq. 2.21–2.24 so the fan still lays the bar's width).
pub fn tilted_job(w: f64, len: f64, beta: f64) -> Job {
    let n = 50;
    let rungs: Vec<Rung> = (0..=n)
        .map(|i| {
            let y = len * i as f64 / n as f64;
            Rung {
                a: [-w / 2.0, y],
                b: [w / 2.0, y],
                tilt: beta,
            }
        })
        .collect();
    let glyph = PlacedGlyph {
        char: "I".into(),
        line: 0,
        strokes: vec![PlacedStroke {
            left: rungs.iter().map(|r| r.a).collect(),
            right: rungs.iter().map(|r| r.b).collect(),
        }],
    };
    job_with("I", "trapezoid", &rungs, glyph)
}

/// Asserts [`ran_to_a_verdict`], showing the run's stderr if not.
pub fn assert_ran_to_a_verdict(out: &std::process::Output) {
    assert!(
        ran_to_a_verdict(out),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `basr preview` ran to its verdict: exit 0 when the film passes, 1 when
/// it fails (the metrics are printed either way); 2 would be bad input.
pub fn ran_to_a_verdict(out: &std::process::Output) -> bool {
    let code = out.status.code();
    match serde_json::from_slice::<serde_json::Value>(&out.stdout) {
        Ok(v) if v.is_object() => match v["verdict"].as_str() {
            Some("pass") => code == Some(0),
            Some("fail") => code == Some(1),
            _ => false,
        },
        _ => matches!(code, Some(0 | 1)),
    }
}

/// A compile that ran to its verdict and wrote `job`: exit 0, or exit 1
/// exactly when the job is NOT READY (a problem among its warnings).
#[allow(dead_code)] // not every test binary that includes this compiles
pub fn compiled(out: &std::process::Output, job: &std::path::Path) -> bool {
    let Ok(bytes) = std::fs::read(job) else {
        return false;
    };
    let v: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
    let problem = v["summary"]["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| w["severity"] == "problem");
    out.status.code() == Some(if problem { 1 } else { 0 })
}
