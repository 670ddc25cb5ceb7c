//! End-to-end tests of `basr preview` on synthetic jobs: the film of a
//! straight stroke, volume conservation, a ring and a tilted pass, the SVG
//! (rendered with resvg), and refusal of damaged jobs.

mod preview_common;

use std::path::Path;

use assert_cmd::Command;
use basr::paint::preview::{self, Options, Panel};
use preview_common::*;
use serde_json::Value;

fn write_job(dir: &Path, name: &str, job: &basr::job::Job) -> std::path::PathBuf {
    let p = dir.join(name);
    job.write(&p).unwrap();
    p
}

fn preview_json(job: &Path, svg: &Path, extra: &[&str]) -> Value {
    let out = Command::cargo_bin("basr")
        .unwrap()
        .args([
            "preview",
            job.to_str().unwrap(),
            "--json",
            "-o",
            svg.to_str().unwrap(),
        ])
        .args(extra)
        .output()
        .unwrap();
    preview_common::assert_ran_to_a_verdict(&out);
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn straight_stroke_at_k_over_w_gives_target_film_and_clean_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(dir.path(), "I.job.json", &straight_job(0.2, 1.0));
    let m = preview_json(&job, &dir.path().join("i.svg"), &[]);
    for key in [
        "coverage",
        "cv",
        "overspray",
        "u_min",
        "u_max",
        "mean_film_m",
    ] {
        assert!(m[key].is_number(), "{key} missing in {m}");
    }
    let mean = m["mean_film_m"].as_f64().unwrap();
    assert!((mean / FILM - 1.0).abs() < 0.02, "mean film {mean}");
    assert!(m["coverage"].as_f64().unwrap() > 0.97, "{m}");
    assert!(m["cv"].as_f64().unwrap() < 0.05, "{m}");
    assert!(m["overspray"].as_f64().unwrap() < 0.05, "{m}");
    // A straight stroke has equal tiles: U = 50 % everywhere.
    assert!((m["u_min"].as_f64().unwrap() - 0.5).abs() < 1e-6, "{m}");
    assert!((m["u_max"].as_f64().unwrap() - 0.5).abs() < 1e-6, "{m}");
    assert_eq!(m["glyphs"][0]["char"], "I");
}

#[test]
fn film_in_the_middle_of_a_straight_stroke_is_the_target() {
    let job = straight_job(0.25, 1.0);
    let p = preview::preview_job(&job, &Options::default()).unwrap();
    for x in [-0.08, -0.03, 0.0, 0.04, 0.09] {
        let v = p.film.as_ref().unwrap().grid.sample([x, 0.5]);
        assert!((v / FILM - 1.0).abs() < 0.02, "film {v} at x = {x}");
    }
}

#[test]
fn deposited_volume_is_flow_times_efficiency_times_gun_on_time() {
    for profile in [
        "uniform",
        "uniform-angle",
        "beta:2,3",
        "gauss:1,-0.4,0.3;2,0.3,0.5",
    ] {
        let dir = tempfile::tempdir().unwrap();
        let job = ring_job(0.3, 0.5, 0.0, "none");
        let gun_on: f64 = job
            .samples
            .paint
            .windows(2)
            .zip(job.samples.t_s.windows(2))
            .filter(|(p, _)| p[0] == 1)
            .map(|(_, t)| t[1] - t[0])
            .sum();
        let path = write_job(dir.path(), "o.json", &job);
        let m = preview_json(&path, &dir.path().join("o.svg"), &["--profile", profile]);
        let vol = m["volume_on_road_m3"].as_f64().unwrap();
        let want = FLOW * EFF * gun_on;
        assert!(
            (vol / want - 1.0).abs() < 0.005,
            "{profile}: {vol} vs {want}"
        );
        assert!((m["gun_on_s"].as_f64().unwrap() - gun_on).abs() < 1e-9);
    }
}

/// The divider's (nozzle axis) shift from the rung midpoint towards +ψ for
/// a rung of length `l` painted with tilt `b` (SPEC sign).
fn divider_shift(l: f64, b: f64) -> f64 {
    let (x, _, z, _) = basr::paint::planned_tip([0.0, 0.0], [l, 0.0], b, ALPHA);
    x + z * b.tan() - l / 2.0
}

#[test]
fn ring_inner_half_is_heavy_untilted_and_evened_by_tilt() {
    let (r0, r1) = (0.3, 0.5);
    let flat = preview::preview_job(&ring_job(r0, r1, 0.0, "none"), &Options::default()).unwrap();
    // Untilted: the inner half-tiles are smaller (001 fig. 2.10: 42/58).
    let (umin, umax) = (flat.metrics.u_min.unwrap(), flat.metrics.u_max.unwrap());
    assert!(umin < 0.45 && umax > 0.55, "{umin} {umax}");
    // Film: inner half heavier than outer half.
    let inner = flat.film.as_ref().unwrap().grid.sample([0.0, 1.0 + 0.34]);
    let outer = flat.film.as_ref().unwrap().grid.sample([0.0, 1.0 + 0.46]);
    assert!(inner > outer * 1.2, "inner {inner} outer {outer}");

    // Tilt so the axis meets the road at the radius halving the annulus
    // area: sqrt((r0² + r1²)/2). β < 0 moves it towards +ψ (outwards).
    let want = ((r0 * r0 + r1 * r1) / 2.0).sqrt() - (r0 + r1) / 2.0;
    let (mut lo, mut hi) = (-0.4, 0.0);
    for _ in 0..60 {
        let mid = (lo + hi) / 2.0;
        if divider_shift(r1 - r0, mid) > want {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let beta = (lo + hi) / 2.0;
    assert!(beta < 0.0);
    let tilted =
        preview::preview_job(&ring_job(r0, r1, beta, "trapezoid"), &Options::default()).unwrap();
    let (tmin, tmax) = (tilted.metrics.u_min.unwrap(), tilted.metrics.u_max.unwrap());
    assert!(
        tmax - tmin < 0.2 * (umax - umin),
        "{tmin}–{tmax} vs {umin}–{umax}"
    );
    // The film is more even too.
    assert!(tilted.metrics.cv.unwrap() < flat.metrics.cv.unwrap(), "cv");
}

#[test]
fn tilted_pass_lays_its_rungs_and_throws_the_far_half_thinner() {
    let beta = 0.2;
    let p = preview::preview_job(&tilted_job(0.3, 1.0, beta), &Options::default()).unwrap();
    let m = &p.metrics;
    assert!(m.coverage.unwrap() > 0.95, "{m:?}");
    assert!(m.overspray.unwrap() < 0.05, "{m:?}");
    // β > 0: the +ψ (+x) half lands farther and shallower (SPEC §2), so the
    // same half of the paint covers more road there.
    let near = p.film.as_ref().unwrap().grid.sample([-0.1, 0.5]);
    let far = p.film.as_ref().unwrap().grid.sample([0.1, 0.5]);
    assert!(far < near * 0.95, "near {near} far {far}");
    // Across the whole bar the film still averages the target.
    let mean: f64 = (0..=20)
        .map(|k| {
            p.film
                .as_ref()
                .unwrap()
                .grid
                .sample([-0.14 + 0.28 * k as f64 / 20.0, 0.5])
        })
        .sum::<f64>()
        / 21.0;
    assert!((mean / FILM - 1.0).abs() < 0.03, "{mean}");
}

fn render(svg: &str) -> resvg::tiny_skia::Pixmap {
    let tree = resvg::usvg::Tree::from_str(svg, &resvg::usvg::Options::default()).unwrap();
    let size = tree.size().to_int_size();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height()).unwrap();
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    pixmap
}

#[test]
fn svg_renders_with_resvg_and_the_letter_is_coloured() {
    let job = straight_job(0.2, 1.0);
    let p = preview::preview_job(&job, &Options::default()).unwrap();
    let verdict = basr::paint::verdict::judge(&p.metrics, &Default::default());
    let panels = [Panel {
        job: &job,
        preview: &p,
        verdict: &verdict,
        from_sim: false,
        replanned: None,
    }];
    let svg = preview::render_svg(&panels, "test");
    let frame = preview::panel_frames(&panels)[0];
    let pix = render(&svg);
    let at = |road: [f64; 2]| {
        let (x, y) = frame.px(road);
        pix.pixel(x.round() as u32, y.round() as u32).unwrap()
    };
    // Inside the letter: the film scale's on-target band (not grey).
    let c = at([0.05, 0.5]);
    let want = basr::plot::colour::film(1.0);
    let diff = (c.red() as i32 - want[0] as i32).abs()
        + (c.green() as i32 - want[1] as i32).abs()
        + (c.blue() as i32 - want[2] as i32).abs();
    assert!(diff < 30, "pixel {c:?} vs {want:?}");
    // Bare road beside it stays grey.
    let r = at([0.17, 0.5]);
    assert_eq!((r.red(), r.green(), r.blue()), (0xe6, 0xe6, 0xe6));
}

#[test]
fn cli_writes_an_svg_resvg_can_render_and_defaults_its_name() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(dir.path(), "BAR.job.json", &straight_job(0.2, 1.0));
    Command::cargo_bin("basr")
        .unwrap()
        .current_dir(dir.path())
        .args(["preview", "BAR.job.json", "--quiet"])
        .assert()
        .success()
        .stdout("");
    let svg = std::fs::read_to_string(dir.path().join("BAR.preview.svg")).unwrap();
    assert!(svg.starts_with("<svg"));
    let pix = render(&svg);
    assert!(pix.width() > 500);
    let _ = job;
}

#[test]
fn damaged_jobs_exit_2_and_leave_no_svg() {
    let dir = tempfile::tempdir().unwrap();
    let text = String::from_utf8(straight_job(0.2, 0.5).to_bytes()).unwrap();
    let cases = [
        (
            "truncated.json",
            text[..text.len() / 2].to_string(),
            "truncated",
        ),
        (
            "edited.json",
            text.replacen("\"message\": \"I\"", "\"message\": \"L\"", 1),
            "integrity",
        ),
        (
            "future.json",
            text.replacen("\"version\": 1", "\"version\": 99", 1),
            "version",
        ),
    ];
    for (name, body, needle) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, body).unwrap();
        let svg = dir.path().join(format!("{name}.svg"));
        let out = Command::cargo_bin("basr")
            .unwrap()
            .args([
                "preview",
                path.to_str().unwrap(),
                "-o",
                svg.to_str().unwrap(),
            ])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle) && err.contains(name), "{name}: {err}");
        assert!(!svg.exists(), "{name}: svg left behind");
    }
}

#[test]
fn cell_sizes_and_fan_depths_out_of_range_exit_2_saying_the_range() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(dir.path(), "I.json", &straight_job(0.2, 0.5));
    for (args, says) in [
        (["--resolution-mm", "1e9"], "20 mm maximum"),
        (["--resolution-mm", "20.5"], "20 mm maximum"),
        (["--resolution-mm", "0.01"], "1 mm minimum"),
        (["--resolution-mm", "-2"], "above zero"),
        (["--fan-depth", "tophat:1e9"], "reaches at most 200 mm"),
        (["--fan-depth", "gauss:70"], "210 mm either side"),
    ] {
        let out = Command::cargo_bin("basr")
            .unwrap()
            .current_dir(dir.path())
            .arg("preview")
            .arg(&job)
            .args(["-o", "x.svg"])
            .args(args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!err.contains("coarser --resolution-mm"), "{args:?}: {err}");
        assert!(!dir.path().join("x.svg").exists());
    }
    // The ends of the range are accepted.
    for r in ["1", "20"] {
        let v = preview_json(&job, &dir.path().join("x.svg"), &["--resolution-mm", r]);
        assert!(v["coverage"].as_f64().is_some(), "{r}: {v}");
    }
}

#[test]
fn bad_options_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(dir.path(), "I.json", &straight_job(0.2, 0.5));
    for args in [
        vec!["--resolution-mm", "0"],
        vec!["--profile", "cone"],
        vec!["--fan-depth", "gauss"],
        vec!["--compare", "none,sideways"],
    ] {
        Command::cargo_bin("basr")
            .unwrap()
            .current_dir(dir.path())
            .arg("preview")
            .arg(&job)
            .args(&args)
            .assert()
            .code(2);
    }
}
