//! `basr fit` end to end: a compiled job, a truck that stopped off its
//! planned place on a sloped road, three reference points measured from
//! that truth with ±2 mm of noise; the fitted job must put the paint on the
//! marking when the arm runs it from the true pose, keep the nozzle's
//! height over the true road, pass preview, simulate and check, and be the
//! same bytes twice. And the refusals: an outlier named, a truck too far
//! off told where to move, bad point files refused with nothing written.

mod common;

use std::path::Path;

use basr::job::{Job, Road, Station, StopPlane};
use common::{basr, stderr, succeeded};

use common::noise::Noise;

/// Where the truck really stood and the road the arm saw there: a plane
/// in the arm's base frame.
struct Truth {
    station: Station,
    plane: StopPlane,
}

/// The job's stop `stop` (from 1) moved by (dx, dy, dθ).
fn moved(job: &Job, stop: usize, d: [f64; 3], plane: StopPlane) -> Truth {
    let s = &job.stations[stop - 1];
    Truth {
        station: Station {
            x_m: s.x_m + d[0],
            y_m: s.y_m + d[1],
            heading_rad: s.heading_rad + d[2].to_radians(),
        },
        plane,
    }
}

/// The job's own reference points for the stop, measured by the arm at the
/// truth with ±`noise_m` on every coordinate, as a points file.
fn points_file(job: &Job, stop: usize, truth: &Truth, noise_m: f64, seed: u64) -> String {
    let refs = basr::job::reference::reference_points(job, stop - 1);
    assert!(
        refs.len() >= 3,
        "three or four reference points for stop {stop}"
    );
    let mut n = Noise(seed);
    let mut out = format!("stop = {stop}\n");
    for r in refs {
        let b = truth.station.road_to_base(r.road_m);
        let z = truth.plane.z_at(b);
        out += &format!(
            "[[point]]\nname = \"{}\"\nroad_m = [{:?}, {:?}]\nbase_m = [{:?}, {:?}, {:?}]\n",
            r.name,
            r.road_m[0],
            r.road_m[1],
            b[0] + noise_m * n.next(),
            b[1] + noise_m * n.next(),
            z + noise_m * n.next()
        );
    }
    out
}

/// What the fitted job does when the arm runs it from the true pose over
/// the true road: the largest distance (m) between where the nozzle goes
/// and where the job means it to go, over the fitted stop's painting rows,
/// and the largest difference between its height over the true road and
/// its planned height over the fitted one.
fn run_from_truth(fitted: &Job, stop: usize, truth: &Truth) -> (f64, f64) {
    let si = stop - 1;
    let s = &fitted.samples;
    let true_road = Road {
        planes: vec![StopPlane {
            stop,
            ..truth.plane.clone()
        }],
        ..Road::default()
    };
    let (mut off, mut dh) = (0.0f64, 0.0f64);
    let mut rows = 0;
    for i in 0..s.len() {
        if s.station[i] as usize != si || s.paint[i] != 1 {
            continue;
        }
        rows += 1;
        let q = basr::job::verify::q_at(fitted, i);
        let pose = fitted.robot.fk(&q);
        let at = truth.station.base_to_road([pose.x_m, pose.y_m]);
        off = off.max((at[0] - s.x_m[i]).hypot(at[1] - s.y_m[i]));
        // Heights over the surface, each road as its own stop sees it.
        let yaw = pose.yaw_rad + truth.station.heading_rad - std::f64::consts::FRAC_PI_2;
        let real = true_road.relative(si, &truth.station, at, pose.z_m, yaw, pose.tilt_rad);
        let planned = fitted.road.relative(
            si,
            &fitted.stations[si],
            [s.x_m[i], s.y_m[i]],
            s.z_m[i],
            s.yaw_rad[i],
            s.tilt_rad[i],
        );
        let d = (real.height_m - planned.height_m).abs();
        if d > dh && d > 0.003 {
            eprintln!(
                "row {i}: real {:.4} planned {:.4} at {:?} z {:.4} tilt {:.4} planned tilt {:.4}",
                real.height_m, planned.height_m, at, pose.z_m, pose.tilt_rad, s.tilt_rad[i]
            );
        }
        dh = dh.max(d);
    }
    assert!(rows > 100, "the stop paints ({rows} rows)");
    (off, dh)
}

/// Writes `points` as p.toml and runs `basr fit j.job.json --points
/// p.toml -o f.job.json` with `extra` arguments.
fn fit(dir: &Path, points: &str, extra: &[&str]) -> std::process::Output {
    std::fs::write(dir.join("p.toml"), points).unwrap();
    let mut args = vec![
        "fit",
        "j.job.json",
        "--points",
        "p.toml",
        "-o",
        "f.job.json",
    ];
    args.extend(extra);
    basr(dir, &args)
}

/// Station `si` of `a` paints the runs of `b`: the same strokes in the
/// same order, each starting and ending where `b`'s does (within the gun's
/// lead and lag, 5 cm) and a quarter of the way in within 5 cm too (a
/// wheel turned round moves it by its diameter).
fn same_runs(a: &Job, b: &Job, si: usize) {
    use basr::plan::site::{painted_passes, PaintedPass};
    let n = a.stations.len();
    let (ra, rb) = (
        &painted_passes(&a.samples, n)[si],
        &painted_passes(&b.samples, n)[si],
    );
    let strokes = |r: &[PaintedPass]| r.iter().map(|p| p.stroke).collect::<Vec<_>>();
    assert_eq!(strokes(ra), strokes(rb), "stop {}: the job's order", si + 1);
    let d = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    for (k, (p, q)) in ra.iter().zip(rb).enumerate() {
        let off = d(p.from_m, q.from_m)
            .max(d(p.to_m, q.to_m))
            .max(d(p.quarter_m, q.quarter_m));
        assert!(
            off <= 0.05,
            "stop {}, run {k} (stroke {}): {:.0} mm off the job's",
            si + 1,
            p.stroke,
            off * 1e3
        );
    }
}

/// Compile, fit from the truth, and check every acceptance point.
fn fit_case(
    dir: &Path,
    compile: &[&str],
    marking: Option<&str>,
    stop: usize,
    truth_of: impl Fn(&Job) -> Truth,
) {
    succeeded(basr(dir, compile));
    let job = Job::read(&dir.join("j.job.json")).unwrap();
    let truth = truth_of(&job);
    let extra = match marking {
        Some(m) => vec!["--marking", m],
        None => vec![],
    };
    let points = points_file(&job, stop, &truth, 0.002, 7);
    succeeded(fit(dir, &points, &extra));
    let fitted = Job::read(&dir.join("f.job.json")).unwrap();
    let st = &fitted.stations[stop - 1];
    let (dx, dy) = (st.x_m - truth.station.x_m, st.y_m - truth.station.y_m);
    let dth = (st.heading_rad - truth.station.heading_rad).to_degrees();
    assert!(
        dx.hypot(dy) <= 0.005,
        "fitted axis {:.1} mm off",
        dx.hypot(dy) * 1e3
    );
    assert!(dth.abs() <= 0.1, "fitted heading {dth:.3}° off");
    // The other stops are the job's.
    for (k, (a, b)) in job.stations.iter().zip(&fitted.stations).enumerate() {
        if k != stop - 1 {
            assert_eq!(a, b, "stop {} moved", k + 1);
        }
    }
    // On a road level in the arm's frame the passes are the job's: the
    // fitted stop paints them in the order the job sheet gives, each the
    // way round the job does (a slope re-plans them: ordered afresh).
    if truth.plane.dz_dx == 0.0 && truth.plane.dz_dy == 0.0 {
        same_runs(&fitted, &job, stop - 1);
    }
    let (off, dh) = run_from_truth(&fitted, stop, &truth);
    assert!(off <= 0.005, "paint lands {:.1} mm off the plan", off * 1e3);
    assert!(dh <= 0.003, "nozzle height {:.1} mm off the plan", dh * 1e3);
    // preview and simulate pass, check accepts.
    succeeded(basr(dir, &["preview", "f.job.json", "-o", "f.svg"]));
    succeeded(basr(dir, &["simulate", "f.job.json"]));
    succeeded(basr(dir, &["check", "f.job.json"]));
    // The same bytes again.
    std::fs::rename(dir.join("f.job.json"), dir.join("g.job.json")).unwrap();
    succeeded(fit(dir, &points, &extra));
    assert_eq!(
        std::fs::read(dir.join("f.job.json")).unwrap(),
        std::fs::read(dir.join("g.job.json")).unwrap(),
        "fit is deterministic"
    );
}

/// The move: +0.25 m across, −0.30 m along, +2.5°.
const MOVE: [f64; 3] = [0.25, -0.30, 2.5];

/// A plane in the arm's frame falling 2 % across the lane (road x; base
/// −x at heading −90°) with the truck's axis 4 mm above it.
fn against_the_truck() -> StopPlane {
    StopPlane {
        stop: 1,
        z_m: -0.004,
        dz_dx: 0.02,
        dz_dy: 0.0,
    }
}

/// STOP at 8 ft uses the vertical joint's whole stroke, so its truck
/// stands on the sloped road it paints (the arm's frame leans with it: the
/// plane is level in that frame, through the base's origin).
#[test]
fn fit_a_word() {
    let dir = tempfile::tempdir().unwrap();
    fit_case(
        dir.path(),
        &["compile", "STOP", "-o", "j.job.json"],
        None,
        1,
        |j| {
            moved(
                j,
                1,
                MOVE,
                StopPlane {
                    stop: 1,
                    z_m: -0.003,
                    dz_dx: 0.0,
                    dz_dy: 0.0,
                },
            )
        },
    );
}

/// A gun that opens and closes 0.4 s early starts and ends each painted
/// run some 10 cm off its pass (the film is NOT READY for it, which fit
/// writes all the same, exit 1): the fitted stop still paints the job's
/// runs in the job's order.
#[test]
fn a_word_painted_with_a_long_gun_lead_is_fitted_in_its_order() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = basr(
        d,
        &[
            "compile",
            "ONLY",
            "--gun-lead-s",
            "0.4",
            "--gun-lag-s",
            "0.4",
            "-o",
            "j.job.json",
        ],
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let job = Job::read(&d.join("j.job.json")).unwrap();
    let truth = moved(&job, 1, MOVE, level(1));
    let out = fit(d, &points_file(&job, 1, &truth, 0.002, 5), &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    same_runs(&Job::read(&d.join("f.job.json")).unwrap(), &job, 0);
}

/// A symbol on a road sloped 2 % against the truck's own plane.
#[test]
fn fit_a_symbol_on_a_slope() {
    let dir = tempfile::tempdir().unwrap();
    fit_case(
        dir.path(),
        &["compile", "--symbol", "arrow-through", "-o", "j.job.json"],
        None,
        1,
        |j| moved(j, 1, MOVE, against_the_truck()),
    );
}

/// The third of a scene's four stops, sloped against the truck: the
/// others stay as they were.
#[test]
fn fit_a_scene_stop() {
    let dir = tempfile::tempdir().unwrap();
    let marking = Path::new(env!("CARGO_MANIFEST_DIR")).join("markings/rxr.toml");
    let m = marking.to_str().unwrap();
    fit_case(
        dir.path(),
        &["compile", "--marking", m, "-o", "j.job.json"],
        Some(m),
        3,
        |j| {
            moved(
                j,
                3,
                [0.10, 0.05, 1.0],
                StopPlane {
                    stop: 3,
                    ..against_the_truck()
                },
            )
        },
    );
}

/// The road under stop `stop` level in the arm's frame, 3 mm under its
/// base (the truck stands on the road it paints): its passes are the
/// job's.
fn level(stop: usize) -> StopPlane {
    StopPlane {
        stop,
        z_m: -0.003,
        dz_dx: 0.0,
        dz_dy: 0.0,
    }
}

/// A job compile planned with the gentle tilt (D at 6 ft: its first plan
/// slowed the bowl on the tilt's acceleration) records it, and fit plans
/// its stop gently again: the fitted job records it too and passes every
/// point of `fit_case`.
#[test]
fn a_gently_planned_job_is_fitted_gently() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fit_case(
        d,
        &["compile", "D", "--letter-height", "6ft", "-o", "j.job.json"],
        None,
        1,
        // on the truck's plane: a road 3 mm under it holds 6 ft's narrow
        // strokes at the bottom of the vertical stroke, 3 mm over the plan
        // (`tuning::Surface::clamp_free_m`)
        |job| {
            moved(
                job,
                1,
                MOVE,
                StopPlane {
                    z_m: 0.0,
                    ..level(1)
                },
            )
        },
    );
    let gentle = |name: &str| {
        Job::read(&d.join(name))
            .unwrap()
            .layout
            .options
            .is_some_and(|o| o.gentle_tilt)
    };
    assert!(gentle("j.job.json"), "compile planned D at 6 ft gently");
    assert!(gentle("f.job.json"), "fit planned it gently again");
}

/// The shipped railroad-crossing scene compiled in `d` as j.job.json, and
/// its marking file's path.
fn rxr_job(d: &Path) -> (Job, String) {
    let marking = Path::new(env!("CARGO_MANIFEST_DIR")).join("markings/rxr.toml");
    let m = marking.to_str().unwrap().to_string();
    succeeded(basr(d, &["compile", "--marking", &m, "-o", "j.job.json"]));
    (Job::read(&d.join("j.job.json")).unwrap(), m)
}

/// A crew fits each stop as it reaches it: the job fitted at one stop is
/// fitted again at the next; the stop fitted first keeps its motion, and
/// each paints its strokes in the job's order.
#[test]
fn a_fitted_job_is_fitted_again_at_its_next_stop() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (job, m) = rxr_job(d);
    let m = m.as_str();
    let first = moved(&job, 1, [0.15, -0.10, 1.5], level(1));
    succeeded(fit(
        d,
        &points_file(&job, 1, &first, 0.002, 3),
        &["--marking", m],
    ));
    let once = Job::read(&d.join("f.job.json")).unwrap();
    std::fs::rename(d.join("f.job.json"), d.join("j.job.json")).unwrap();
    let second = moved(&once, 2, [-0.05, 0.05, -0.5], level(2));
    succeeded(fit(
        d,
        &points_file(&once, 2, &second, 0.002, 4),
        &["--marking", m],
    ));
    let twice = Job::read(&d.join("f.job.json")).unwrap();
    assert_eq!(twice.stations[0], once.stations[0]);
    assert_eq!(
        station_rows(&twice, 0),
        station_rows(&once, 0),
        "the first fitted stop moves as it did"
    );
    for k in [0, 1] {
        same_runs(&twice, &job, k);
    }
}

/// Station `si`'s setpoint rows of `j`, without their clock.
fn station_rows(j: &Job, si: u32) -> Vec<Vec<String>> {
    let s = &j.samples;
    (0..s.len())
        .filter(|&i| s.station[i] == si)
        .map(|i| s.csv_fields(i).into_iter().skip(1).collect())
        .collect()
}

/// A crew fits a stop again (the truck moved, or a point was misread):
/// the fitted job's stop takes the points the crew chalked for it, though
/// as the job now places the stop, turned, one of its corners is past the
/// arm's reach (which stop a point belongs to is read from the marking).
#[test]
fn a_fitted_stop_is_fitted_again_from_its_own_points() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let job = word_job(d, "SCHOOL XING");
    let truth = moved(&job, 1, MOVE, level(1));
    let points = points_file(&job, 1, &truth, 0.002, 7);
    succeeded(fit(d, &points, &[]));
    std::fs::rename(d.join("f.job.json"), d.join("j.job.json")).unwrap();
    succeeded(fit(d, &points, &[]));
    let again = Job::read(&d.join("f.job.json")).unwrap();
    let st = &again.stations[0];
    let off = (st.x_m - truth.station.x_m).hypot(st.y_m - truth.station.y_m);
    assert!(off <= 0.005, "fitted again {:.1} mm off", off * 1e3);
}

/// A word's stops fitted one after the other, each on a road of its own:
/// stop 2's lies lower under the arm than stop 1's, so its strokes keep a
/// wider band of heights clear. Stop 1, fitted first, still moves as it
/// did: each stroke is planned with its own stop's band (with one band
/// for the job, stop 1's strokes were planned again with stop 2's and fit
/// refused the job as not its own).
#[test]
fn a_word_is_fitted_stop_by_stop_on_roads_of_their_own() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let job = word_job(d, "STOP AHEAD");
    assert_eq!(
        job.stations.len(),
        2,
        "STOP AHEAD is painted from two stops"
    );
    // both under the 3 mm the joints' clamp takes (`surface.clamp_free_m`)
    let low = StopPlane {
        z_m: -0.005,
        ..level(1)
    };
    let first = moved(&job, 1, MOVE, low);
    succeeded(fit(d, &points_file(&job, 1, &first, 0.002, 3), &[]));
    let once = Job::read(&d.join("f.job.json")).unwrap();
    std::fs::rename(d.join("f.job.json"), d.join("j.job.json")).unwrap();
    let lower = StopPlane {
        z_m: -0.008,
        ..level(2)
    };
    let second = moved(&once, 2, [-0.10, 0.20, -1.5], lower);
    succeeded(fit(d, &points_file(&once, 2, &second, 0.002, 4), &[]));
    let twice = Job::read(&d.join("f.job.json")).unwrap();
    assert_eq!(twice.stations[0], once.stations[0]);
    assert_eq!(
        station_rows(&twice, 0),
        station_rows(&once, 0),
        "the first fitted stop moves as it did"
    );
    let (off, dh) = run_from_truth(&twice, 2, &second);
    assert!(off <= 0.005, "paint lands {:.1} mm off the plan", off * 1e3);
    assert!(dh <= 0.003, "nozzle height {:.1} mm off the plan", dh * 1e3);
}

/// A stop beside a bicycle: the wheels are closed passes, whose runs start
/// and end at one point; the stop not fitted paints them the way round the
/// job does (fit refuses a job whose other stops it would change).
#[test]
fn fit_a_stop_beside_a_bicycle() {
    let dir = tempfile::tempdir().unwrap();
    let marking = dir.path().join("bike-lane.toml");
    std::fs::write(
        &marking,
        "[marking]\nname = \"bike lane\"\nlane_width_m = 3.66\n\n[[item]]\n\
         symbol = \"stop-line\"\nat_m = [0.0, 0.0]\n\n[[item]]\nsymbol = \"bike\"\n\
         at_m = [0.0, 3.0]\n",
    )
    .unwrap();
    let m = marking.to_str().unwrap();
    fit_case(
        dir.path(),
        &["compile", "--marking", m, "-o", "j.job.json"],
        Some(m),
        1,
        |j| moved(j, 1, [0.05, -0.05, 0.5], level(1)),
    );
}

fn stop_job(dir: &Path) -> Job {
    word_job(dir, "STOP")
}

/// `words` compiled at the defaults into `j.job.json`, read back.
fn word_job(dir: &Path, words: &str) -> Job {
    succeeded(basr(dir, &["compile", words, "-o", "j.job.json"]));
    Job::read(&dir.join("j.job.json")).unwrap()
}

/// Runs fit with `points` and asserts exit 2, no output, and that stderr
/// says each of `says`.
fn refused(dir: &Path, points: &str, says: &[&str]) {
    let out = fit(dir, points, &[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(!dir.join("f.job.json").exists(), "no file left: {err}");
    for s in says {
        assert!(err.contains(s), "{s:?} not in: {err}");
    }
}

#[test]
fn an_outlier_is_named_with_its_residual() {
    let dir = tempfile::tempdir().unwrap();
    let job = stop_job(dir.path());
    let truth = moved(&job, 1, MOVE, against_the_truck());
    let mut text = points_file(&job, 1, &truth, 0.0, 1);
    // Move the last point 0.15 m along the base frame's x.
    let name = basr::job::reference::reference_points(&job, 0)[2]
        .name
        .clone();
    let at = text.find(&format!("name = \"{name}\"")).unwrap();
    let base = at + text[at..].find("base_m = [").unwrap() + "base_m = [".len();
    let end = base + text[base..].find(',').unwrap();
    let x: f64 = text[base..end].parse().unwrap();
    text.replace_range(base..end, &format!("{:?}", x + 0.15));
    refused(
        dir.path(),
        &text,
        &[&format!(
            "point \"{name}\" is 150.0 mm from where the other points put it"
        )],
    );
}

#[test]
fn a_truck_far_off_is_told_where_to_move() {
    let dir = tempfile::tempdir().unwrap();
    let job = stop_job(dir.path());
    // 2.5 m further along the lane than planned.
    let truth = moved(&job, 1, [0.0, 2.5, 0.0], against_the_truck());
    refused(
        dir.path(),
        &points_file(&job, 1, &truth, 0.0, 1),
        &[
            "cannot reach the marking from where the truck stopped",
            "m back",
            "then chalk",
        ],
    );
    // the stop is named once
    let out = fit(dir.path(), &points_file(&job, 1, &truth, 0.0, 1), &[]);
    let err = stderr(&out);
    assert!(
        err.contains("re-planning: stop 1: the arm cannot reach"),
        "{err}"
    );

    // Just past the edge of reach (0.68 m short of the planned place):
    // the leaned nozzle of the O's knots is what falls short, and the crew
    // is told where to move, not compile's advice on letter sizes.
    for back in [-0.68, -0.685] {
        let truth = moved(&job, 1, [0.0, back, 0.0], level(1));
        refused(
            dir.path(),
            &points_file(&job, 1, &truth, 0.002, 3),
            &[
                "cannot reach the marking from where the truck stopped",
                "forward",
            ],
        );
        let out = fit(dir.path(), &points_file(&job, 1, &truth, 0.002, 3), &[]);
        assert!(!stderr(&out).contains("letter-height"), "{}", stderr(&out));
    }
}

#[test]
fn bad_point_files_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let job = stop_job(d);
    let truth = moved(&job, 1, MOVE, against_the_truck());
    let good = points_file(&job, 1, &truth, 0.0, 1);
    // One point only.
    let one = good
        .split("[[point]]")
        .take(2)
        .collect::<Vec<_>>()
        .join("[[point]]");
    refused(d, &one, &["1 point(s) given", "at least two"]);
    // Not a number.
    let at = good.find("base_m = [").unwrap() + "base_m = [".len();
    let comma = at + good[at..].find(',').unwrap();
    let mut nan = good.clone();
    nan.replace_range(at..comma, "nan");
    refused(d, &nan, &["not a number"]);
    // Another stop of a one-stop job.
    refused(
        d,
        &good.replace("stop = 1", "stop = 2"),
        &["stop 2 is not one of the job's stops (1 to 1)"],
    );
    // No stop.
    refused(d, &good.replace("stop = 1\n", ""), &["which stop"]);
    // A name with a terminal's escape in it, and one far too long.
    refused(
        d,
        &good.replacen("name = \"A\"", "name = \"A\\u001b[31m\"", 1),
        &["control characters"],
    );
    refused(
        d,
        &good.replacen(
            "name = \"A\"",
            &format!("name = \"{}\"", "A".repeat(500)),
            1,
        ),
        &["over 40 characters"],
    );
    // Not a points file.
    refused(d, "[[point]]\nroad = [0, 0]\n", &["points file"]);
    // A setpoint CSV or a job given as the points: said what it reads as.
    refused(
        d,
        "t_s,station,stroke,paint\n0.000,0,-1,0\n",
        &["reads as CSV", "a points file is TOML"],
    );
    // a points file opening with a comment that has commas in it is still
    // read as one: its own mistake named with its line
    let at = good.find("road_m = [").unwrap();
    let close = at + good[at..].find(']').unwrap();
    let mut typo = good.clone();
    typo.remove(close);
    refused(
        d,
        &format!("# measured 2026-12-06, stop 1, truck 12\n{typo}"),
        &["line ", "expected `]`"],
    );
    let job_text = std::fs::read_to_string(d.join("j.job.json")).unwrap();
    refused(
        d,
        &job_text,
        &["reads as JSON (a job?)", "a points file is TOML"],
    );
    // The job given as the points: named as such, nothing written.
    let out = basr(
        d,
        &[
            "fit",
            "j.job.json",
            "--points",
            "j.job.json",
            "-o",
            "f.job.json",
        ],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the job and the points name one file") && err.contains("path of the points"),
        "{err}"
    );
    assert!(!d.join("f.job.json").exists());
}

/// Points chalked on another stop's part of a scene are named as such.
#[test]
fn points_of_another_stop_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (job, m) = rxr_job(d);
    let m = m.as_str();
    let truth = moved(
        &job,
        4,
        [0.0; 3],
        StopPlane {
            stop: 4,
            z_m: 0.0,
            dz_dx: 0.0,
            dz_dy: 0.0,
        },
    );
    let text = points_file(&job, 4, &truth, 0.0, 1).replace("stop = 4", "stop = 1");
    let out = fit(d, &text, &["--marking", m]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("is on stop 4's part of the marking, not stop 1's"),
        "{}",
        stderr(&out)
    );
    assert!(!d.join("f.job.json").exists());
}

/// The crew may give the arm's encoder counts instead of its base-frame
/// reading: the nozzle held 0.1 m over each point (`basr pose` gives the
/// counts of that pose), the gap written with them.
#[test]
fn points_may_be_encoder_counts() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let job = stop_job(d);
    // STOP at 8 ft uses the whole stroke: its truck stands on the road it
    // paints (a level plane in the arm's frame, through the base's origin).
    let level = StopPlane {
        stop: 1,
        z_m: 0.0,
        dz_dx: 0.0,
        dz_dy: 0.0,
    };
    let truth = moved(&job, 1, MOVE, level);
    let mut text = String::from("stop = 1\n");
    for r in basr::job::reference::reference_points(&job, 0) {
        let b = truth.station.road_to_base(r.road_m);
        let z = truth.plane.z_at(b) + 0.1;
        let (x, y, h) = (
            format!("{:.6}", b[0]),
            format!("{:.6}", b[1]),
            format!("{z:.6}"),
        );
        let pose = common::json_of(basr(d, &["pose", &x, &y, "--height", &h, "--json"]));
        let enc: Vec<String> = pose["encoders"]
            .as_object()
            .unwrap()
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        text += &format!(
            "[[point]]\nname = \"{}\"\nroad_m = [{:?}, {:?}]\nencoders = {{ {} }}\ntip_gap_m = 0.1\n",
            r.name,
            r.road_m[0],
            r.road_m[1],
            enc.join(", ")
        );
    }
    let out = common::json_of(fit(d, &text, &["--json"]));
    let st = &out["station"];
    let dx = st["x_m"].as_f64().unwrap() - truth.station.x_m;
    let dy = st["y_m"].as_f64().unwrap() - truth.station.y_m;
    assert!(
        dx.hypot(dy) < 0.002,
        "{:.2} mm off\n{text}",
        dx.hypot(dy) * 1e3
    );
    let plane = &out["plane"];
    assert!(plane["dz_dx"].as_f64().unwrap().abs() < 0.002, "{plane}");
    assert!(plane["z_m"].as_f64().unwrap().abs() < 0.002, "{plane}");
    // A count that is not one of the robot's, and a missing one.
    std::fs::remove_file(d.join("f.job.json")).unwrap();
    let bad = text.replacen("enc_base", "enc_basse", 1);
    refused(d, &bad, &["encoders lacks enc_base"]);
    // Counts without the tip's height over the road: the road is not
    // taken to be at the tip.
    let bad = text.replacen("tip_gap_m = 0.1\n", "", 1);
    refused(
        d,
        &bad,
        &["encoders need tip_gap_m", "measure it with a rule"],
    );
    // A count the joint cannot reach: named, with the joint's range.
    let at = text.find("enc_extension = ").unwrap() + "enc_extension = ".len();
    let end = at + text[at..].find([',', ' ', '}']).unwrap();
    let mut far = text.clone();
    far.replace_range(at..end, "-900000");
    refused(
        d,
        &far,
        &[
            "enc_extension = -900000 puts extension_m at",
            "outside its range",
            "check the count",
        ],
    );
}

/// A job compiled with its own options is fitted with them (the job
/// records them), and a point 13 mm off where the others put it is refused
/// at the 10 mm tolerance even when it drags the fit its way.
#[test]
fn fit_keeps_the_jobs_options_and_its_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    succeeded(basr(
        d,
        &[
            "compile",
            "--symbol",
            "arrow-through",
            "--gun-lead-s",
            "0.1",
            "-o",
            "j.job.json",
        ],
    ));
    let job = Job::read(&d.join("j.job.json")).unwrap();
    let options = job
        .layout
        .options
        .clone()
        .expect("the job records its gun lead");
    assert_eq!(options.gun_lead_s, 0.1);
    let truth = moved(&job, 1, [0.1, -0.1, 1.0], against_the_truck());
    let text = points_file(&job, 1, &truth, 0.0, 1);
    succeeded(fit(d, &text, &[]));
    let fitted = Job::read(&d.join("f.job.json")).unwrap();
    assert_eq!(fitted.layout.options, Some(options));
    std::fs::remove_file(d.join("f.job.json")).unwrap();
    // The last point 13 mm along the base frame's y.
    let name = basr::job::reference::reference_points(&job, 0)
        .last()
        .unwrap()
        .name
        .clone();
    let at = text.find(&format!("name = \"{name}\"")).unwrap();
    let base = at + text[at..].find("base_m = [").unwrap() + "base_m = [".len();
    let comma = base + text[base..].find(", ").unwrap() + 2;
    let end = comma + text[comma..].find(',').unwrap();
    let y: f64 = text[comma..end].parse().unwrap();
    let mut off = text.clone();
    off.replace_range(comma..end, &format!("{:?}", y + 0.013));
    refused(d, &off, &[&format!("point \"{name}\" is 13.")]);
}

/// A job laid out for a road below 25 mph (`--low-speed`: a symbol at
/// three quarters of its size without a notice) records it, and fit lays
/// the marking out the same way: no notice the job did not have.
#[test]
fn fit_keeps_a_low_speed_layout() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("arrow.toml"),
        "[[item]]\nsymbol = \"arrow-through\"\nat_m = [0.0, 0.0]\nscale = 0.75\n",
    )
    .unwrap();
    succeeded(basr(
        d,
        &[
            "compile",
            "--marking",
            "arrow.toml",
            "--low-speed",
            "-o",
            "j.job.json",
        ],
    ));
    let job = Job::read(&d.join("j.job.json")).unwrap();
    assert!(job.layout.low_speed, "the job records --low-speed");
    let layout_notes = |j: &Job| {
        j.summary
            .warnings
            .iter()
            .filter(|w| w.kind == basr::job::WarningKind::Layout)
            .count()
    };
    assert_eq!(layout_notes(&job), 0, "{:?}", job.summary.warnings);
    let truth = moved(&job, 1, [0.1, -0.1, 1.0], against_the_truck());
    let text = points_file(&job, 1, &truth, 0.0, 1);
    succeeded(fit(d, &text, &["--marking", "arrow.toml"]));
    let fitted = Job::read(&d.join("f.job.json")).unwrap();
    assert!(fitted.layout.low_speed);
    assert_eq!(layout_notes(&fitted), 0, "{:?}", fitted.summary.warnings);
}

/// A fitted job keeps the job's other stops as the job timed and verified
/// them (`summary.stops`): they are not simulated again, so a figure put
/// in the record comes back as it was given, while the fitted stop is
/// verified afresh; every stop moves as the job's did.
#[test]
fn the_other_stops_keep_their_timing_and_are_not_simulated_again() {
    use basr::pipeline::compile::{compile_job, CompileRequest, Source};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("markings/rxr.toml");
    let req = CompileRequest {
        source: Source::Marking {
            text: std::fs::read_to_string(&path).unwrap(),
            origin: path.display().to_string(),
        },
        ..CompileRequest::message("")
    };
    let job = compile_job(&req).unwrap();
    let n = job.stations.len();
    assert!(n >= 3, "a scene of several stops ({n})");
    assert_eq!(job.summary.stops.len(), n, "one record per stop");
    let mut kept = job.summary.stops.clone();
    // a figure no simulation gives: it must come back as given
    kept[0].max_error_m = 0.001234;
    let fitted = 2;
    let again = compile_job(&CompileRequest {
        site: Some(basr::plan::site::Site {
            stations: job.stations.clone(),
            fitted,
            road: job.road.clone(),
            kept,
            painted: basr::plan::site::painted_passes(&job.samples, n),
        }),
        ..req.clone()
    })
    .unwrap();
    assert_eq!(again.summary.stops[0].max_error_m, 0.001234);
    // the fitted stop was simulated: its figures are the job's own
    assert_eq!(again.summary.stops[fitted], job.summary.stops[fitted]);
    for k in 1..n {
        assert_eq!(
            again.summary.stops[k],
            job.summary.stops[k],
            "stop {}",
            k + 1
        );
    }
    assert_eq!(
        again.samples, job.samples,
        "every stop moves as the job's did"
    );
    // records that do not fit the plan (one missing) are not trusted
    let mut short = job.summary.stops.clone();
    short.pop();
    short[0].max_error_m = 0.001234;
    let all = compile_job(&CompileRequest {
        site: Some(basr::plan::site::Site {
            stations: job.stations.clone(),
            fitted,
            road: job.road.clone(),
            kept: short,
            painted: vec![],
        }),
        ..req
    })
    .unwrap();
    assert_eq!(
        all.summary.stops, job.summary.stops,
        "every stop verified again"
    );
}

/// A scene fitted with another marking file is told to pass its own: not
/// to write its items as `lines = [...]`, which a marking file refuses
/// (`[` is no letter).
#[test]
fn a_scene_fitted_with_another_marking_file_is_told_to_pass_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (job, _) = rxr_job(d);
    let truth = moved(&job, 1, [0.0, 0.0, 0.0], level(1));
    let other = Path::new(env!("CARGO_MANIFEST_DIR")).join("markings/turn_lane.toml");
    let out = fit(
        d,
        &points_file(&job, 1, &truth, 0.0, 1),
        &["--marking", other.to_str().unwrap()],
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the job is a scene")
            && err.contains("only the marking file it was compiled from"),
        "{err}"
    );
    assert!(!err.contains("lines = ["), "{err}");
    assert!(!d.join("f.job.json").exists());
}

/// A fit that comes out NOT READY says why, as compile does, and what the
/// crew can do at the site (the notes' remedies are the planner's: letter
/// sizes and tips). STOP on a plane 4 mm under the base, sloped 1 % and
/// −0.5 % against the truck: the lowest nozzle height over it rises to
/// 109 mm and the fan outgrows the narrow strokes (overspray 0.066).
#[test]
fn a_fit_that_is_not_ready_says_why_and_what_to_do_at_the_site() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let job = stop_job(d);
    let truth = moved(
        &job,
        1,
        [0.0, 0.0, 0.0],
        StopPlane {
            stop: 1,
            z_m: -0.004,
            dz_dx: 0.01,
            dz_dy: -0.005,
        },
    );
    let out = fit(d, &points_file(&job, 1, &truth, 0.0, 1), &[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "NOT READY: {err}");
    assert!(err.contains("(NOT READY:"), "{err}");
    assert!(err.contains("  problem: "), "the problems are said: {err}");
    assert!(
        err.contains("at the site: do not paint this stop as fitted. Check the points"),
        "{err}"
    );
    assert!(
        d.join("f.job.json").exists(),
        "written, for the report to say why"
    );
}

/// Fitting again over a fitted job whose CSV was bound to it says that
/// CSV stays beside the new job and is not its own; fitting again with
/// --csv writes the pair anew and says nothing of it.
#[test]
fn fitting_over_a_fitted_job_says_its_csv_is_left_behind() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let job = stop_job(d);
    let truth = moved(&job, 1, [0.05, -0.05, 0.5], level(1));
    let points = points_file(&job, 1, &truth, 0.0, 1);
    let first = fit(d, &points, &["--csv", "f.csv"]);
    assert!(
        first.status.code().is_some_and(|c| c <= 1),
        "{}",
        stderr(&first)
    );
    // replacing it with its CSV written again: the pair is new, nothing left
    let with_csv = fit(d, &points, &["--csv", "f.csv"]);
    let err = stderr(&with_csv);
    assert!(with_csv.status.code().is_some_and(|c| c <= 1), "{err}");
    assert!(!err.contains("stays beside it"), "{err}");
    // replacing it without: its CSV is left behind
    let again = fit(d, &points, &[]);
    let err = stderr(&again);
    assert!(again.status.code().is_some_and(|c| c <= 1), "{err}");
    assert!(
        err.contains("replaced a job whose csv file f.csv stays beside it"),
        "{err}"
    );
}

/// What fit cannot check, it says: two points cannot check each other,
/// and a plane measured under a stop replaces the job's crown line
/// through its marking, which one plane cannot follow.
#[test]
fn fit_says_what_its_points_cannot_check() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let job = stop_job(d);
    let truth = moved(&job, 1, MOVE, level(1));
    let points = points_file(&job, 1, &truth, 0.002, 7);
    // the file's first two points
    let two: String = points
        .split("[[point]]")
        .take(3)
        .collect::<Vec<_>>()
        .join("[[point]]");
    let out = fit(d, &two, &[]);
    succeeded(out.clone());
    assert!(stderr(&out).contains("two points fix the stop but cannot check each other"));
    let out = fit(d, &points, &[]);
    assert!(!stderr(&out).contains("two points"), "{}", stderr(&out));
    // STOP with a crown line 0.3 m right of its centre
    std::fs::write(
        d.join("m.toml"),
        "[[item]]\nword = \"STOP\"\nat_m = [0.0, 0.0]\n[road]\ncross_slope_pct = 2.0\ncrown_x_m = 0.3\n",
    )
    .unwrap();
    succeeded(basr(
        d,
        &["compile", "--marking", "m.toml", "-o", "j.job.json"],
    ));
    let job = Job::read(&d.join("j.job.json")).unwrap();
    let truth = moved(&job, 1, MOVE, level(1));
    let out = fit(
        d,
        &points_file(&job, 1, &truth, 0.002, 7),
        &["--marking", "m.toml"],
    );
    assert!(
        stderr(&out).contains("crown line at x = 0.30 m through this stop's marking"),
        "{}",
        stderr(&out)
    );
}
