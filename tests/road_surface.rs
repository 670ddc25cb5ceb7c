//! `[road]` in a marking file, end to end: a plain cross slope, or a crown
//! beside the marking, is the plane the truck stands on and leaves the job
//! as on a flat road; a crown through the marking is followed (the film
//! passes where the arm's stroke has room) or, where it has none, the job
//! says why it is NOT READY.

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

/// STOP at 8 ft uses the vertical joint's whole stroke: with the road past
/// a crown falling away from the truck's plane, the narrow strokes' fans
/// are wider than the strokes. The job is written NOT READY and says why.
#[test]
fn a_crown_through_stop_says_what_it_costs() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("crown.toml"),
        format!("{STOP}[road]\ncross_slope_pct = 2.0\ncrown_x_m = 0.3\n"),
    )
    .unwrap();
    // Exit 1: the job is written, its verdict NOT READY.
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
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("NOT READY"), "{}", stderr(&out));
    // --no-size-search: the verdict without the search for sizes that paint
    assert!(!stderr(&out).contains("sizes:"), "{}", stderr(&out));
    let job = Job::read(&d.join("crown.job.json")).unwrap();
    let surface = job
        .summary
        .warnings
        .iter()
        .find(|w| w.kind == basr::job::WarningKind::Surface)
        .expect("a surface note");
    assert!(
        surface.message.contains("below") && surface.message.contains("instead of 78 to"),
        "{}",
        surface.message
    );
    let film = job.summary.film.as_ref().unwrap();
    assert!(
        !film.failed.is_empty(),
        "the far letters' fans are too wide"
    );
}

#[test]
fn bad_road_tables_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (road, says) in [
        ("crown_x_m = 0.3", "needs cross_slope_pct"),
        ("cross_slope_pct = 20", "cross slope 20 % is outside ±12 %"),
        ("cross_slope_pct = nan", "cross slope NaN %"),
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
