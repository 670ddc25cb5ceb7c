//! `[road]` in a marking file, end to end: a plain cross slope, or a crown
//! beside the marking, is the plane the truck stands on and leaves the job
//! as on a flat road; a crown through the marking is followed (the film
//! passes, with a narrower tip where the seed's has no room left in the
//! arm's vertical stroke).

mod common;

use std::path::Path;

use basr::job::Job;
use common::{basr, stderr, succeeded};

fn compile(dir: &Path, name: &str, text: &str) -> Job {
    std::fs::write(dir.join(format!("{name}.toml")), text).unwrap();
    let marking = format!("{name}.toml");
    let job = format!("{name}.job.json");
    succeeded(basr(
        dir,
        &["compile", "--marking", &marking, "-o", &job, "-q"],
    ));
    Job::read(&dir.join(job)).unwrap()
}

const STOP: &str = "[marking]\nlines = [\"STOP\"]\n";

#[test]
fn a_plain_slope_and_a_crown_beside_are_the_flat_job() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let flat = compile(d, "flat", STOP);
    for (name, road) in [
        ("slope", "cross_slope_pct = 2.0"),
        ("beside", "cross_slope_pct = 2.0\ncrown_x_m = -1.83"),
        ("rising", "cross_slope_pct = -3.0\ncrown_x_m = 1.5"),
    ] {
        let job = compile(d, name, &format!("{STOP}[road]\n{road}\n"));
        assert!(!job.road.is_flat(), "{name}: the job records its road");
        assert_eq!(
            job.samples, flat.samples,
            "{name}: the arm moves as on a flat road"
        );
        assert_eq!(job.summary.film, flat.summary.film, "{name}");
    }
}

#[test]
fn a_crown_through_an_arrow_keeps_its_film() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (name, crown) in [("left", -0.2), ("right", 0.2)] {
        let text = format!(
            "[[item]]\nsymbol = \"arrow-through\"\nat_m = [0.0, 0.0]\n[road]\n\
             cross_slope_pct = 2.0\ncrown_x_m = {crown}\n"
        );
        let job = compile(d, name, &text);
        let film = job
            .summary
            .film
            .as_ref()
            .expect("compile measures the film");
        assert!(film.failed.is_empty(), "{name}: {:?}", film.failed);
        assert!(
            job.summary
                .warnings
                .iter()
                .any(|w| w.kind == basr::job::WarningKind::Surface),
            "{name}: the job says what the crown does"
        );
        let file = format!("{name}.job.json");
        succeeded(basr(d, &["preview", &file, "-o", "p.svg"]));
        succeeded(basr(d, &["simulate", &file]));
        succeeded(basr(d, &["check", &file]));
    }
}

/// STOP at 8 ft uses the seed tip's whole vertical stroke: with the road
/// past a crown falling away from the truck's plane (33 mm under it at
/// the far letters), the seed's fan at the lowest nozzle is wider than the
/// one-unit strokes. A 45° tip lays them from the height the arm still
/// reaches over that road, its wide bowls cut across into stretches of
/// side-by-side sweeps (`passes::split_passes`): the job paints, its film
/// within the bounds, and the nozzle's height over the crowned road is the
/// height its fan's width asks for.
#[test]
fn a_crown_through_stop_is_painted_with_a_narrower_tip() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("crown.toml"),
        format!("{STOP}[road]\ncross_slope_pct = 2.0\ncrown_x_m = 0.3\n"),
    )
    .unwrap();
    let out = basr(
        d,
        &[
            "compile",
            "--marking",
            "crown.toml",
            "-o",
            "crown.job.json",
            "--no-size-search",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stderr(&out).contains("verdict: READY"), "{}", stderr(&out));
    let job = Job::read(&d.join("crown.job.json")).unwrap();
    let surface = job
        .summary
        .warnings
        .iter()
        .find(|w| w.kind == basr::job::WarningKind::Surface)
        .expect("a surface note");
    assert!(surface.message.contains("below"), "{}", surface.message);
    let film = job.summary.film.as_ref().unwrap();
    assert!(film.failed.is_empty(), "{:?}", film.failed);
    let alpha = job.paint.fan_angle_rad;
    assert!(
        alpha < 63.0f64.to_radians(),
        "a narrower tip than the seed's"
    );
    // The joints lay the nozzle at its planned height over the crowned
    // road: through the robot's forward kinematics from each painting
    // row's joints, against the row's planned pose, both measured square
    // to the road under them (the height the fan's width follows).
    let s = &job.samples;
    let (mut worst, mut rows, mut beyond) = (0.0f64, 0, 0);
    for i in 0..s.len() {
        if s.paint[i] != 1 {
            continue;
        }
        let si = s.station[i] as usize;
        let st = &job.stations[si];
        let pose = job.robot.fk(&basr::job::verify::q_at(&job, i));
        let yaw = pose.yaw_rad + st.heading_rad - std::f64::consts::FRAC_PI_2;
        let at = st.base_to_road([pose.x_m, pose.y_m]);
        let real = job.road.relative(si, st, at, pose.z_m, yaw, pose.tilt_rad);
        let xy = [s.x_m[i], s.y_m[i]];
        let planned = job
            .road
            .relative(si, st, xy, s.z_m[i], s.yaw_rad[i], s.tilt_rad[i]);
        worst = worst.max((real.height_m - planned.height_m).abs());
        rows += 1;
        // past the crown the road falls away below the truck's plane: the
        // nozzle's height over it is more than its height over that plane
        if s.x_m[i] > 0.5 && planned.height_m > s.z_m[i] + 0.004 {
            beyond += 1;
        }
    }
    assert!(rows > 1000, "the marking is painted: {rows} rows");
    assert!(beyond > 100, "rows past the crown followed: {beyond}");
    assert!(
        worst <= 0.003,
        "nozzle {:.1} mm off its height",
        worst * 1e3
    );
    for cmd in [
        &["preview", "crown.job.json", "-o", "p.svg"][..],
        &["simulate", "crown.job.json"],
        &["check", "crown.job.json"],
    ] {
        succeeded(basr(d, cmd));
    }
}

#[test]
fn bad_road_tables_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (road, says) in [
        ("crown_x_m = 0.3", "needs cross_slope_pct"),
        ("cross_slope_pct = 20", "cross slope 20 % is outside ±12 %"),
        ("cross_slope_pct = nan", "cross slope is not a number"),
        ("cross_slope_pct = 2\nbanking = 1", "banking"),
        ("cross_slope_pct = 2\ncrown_x_m = 40", "crown line x 40 m"),
    ] {
        std::fs::write(d.join("bad.toml"), format!("{STOP}[road]\n{road}\n")).unwrap();
        let out = basr(
            d,
            &["compile", "--marking", "bad.toml", "-o", "bad.job.json"],
        );
        assert_eq!(out.status.code(), Some(2), "{road}: {}", stderr(&out));
        assert!(stderr(&out).contains(says), "{road}: {}", stderr(&out));
        assert!(!d.join("bad.job.json").exists());
    }
}
