//! Strokes narrower than the fan at its lowest height: the planner turns
//! the fan off the rung so its footprint covers the stroke, instead of
//! laying the extra band beside it (docs/planner.md, `narrow`). Through the
//! binary, at 7 ft where the one-unit strokes (85 mm) are narrower than
//! BASR's narrowest fan (97 mm).

mod common;

use basr::job::Job;
use common::{basr, stderr};

/// The default robot with the seed's 63.5° tip alone (a crew that carries
/// no other): the one whose fan is wider than a 7 ft letter's stroke. With
/// its other tips the narrower 511 paints an I at 7 ft untouched.
fn seed_tip_robot(dir: &std::path::Path) -> std::path::PathBuf {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("robots/basr.toml"),
    )
    .unwrap();
    // Drop every `[[paint.tip]]` table but the seed's (a table runs to the
    // next table's header; comments before that header go with it).
    let mut out = String::new();
    let mut block: Option<String> = None;
    let flush = |block: &mut Option<String>, out: &mut String| {
        if let Some(b) = block.take() {
            if b.contains("name = \"seed-63.5\"") {
                out.push_str(&b);
            }
        }
    };
    for line in text.lines() {
        if line.starts_with('[') {
            flush(&mut block, &mut out);
            if line == "[[paint.tip]]" {
                block = Some(String::new());
            }
        }
        match block.as_mut() {
            Some(b) => b.push_str(line),
            None => out.push_str(line),
        }
        match block.as_mut() {
            Some(b) => b.push('\n'),
            None => out.push('\n'),
        }
    }
    flush(&mut block, &mut out);
    assert_eq!(out.matches("[[paint.tip]]").count(), 1, "{out}");
    let path = dir.join("seed-tip.toml");
    std::fs::write(&path, out).unwrap();
    path
}

/// Compile `what` at `height` with the seed's tip alone (exit 0 or 1:
/// both write the job) and read the job back.
fn job(dir: &std::path::Path, what: &str, height: &str) -> Job {
    let robot = seed_tip_robot(dir);
    let out = basr(
        dir,
        &[
            "compile",
            what,
            "--letter-height",
            height,
            "--robot",
            robot.to_str().unwrap(),
            "-o",
            "j.job.json",
            "-q",
            "--no-size-search",
        ],
    );
    assert!(
        matches!(out.status.code(), Some(0 | 1)),
        "{what} {height}: {}",
        stderr(&out)
    );
    Job::read(&dir.join("j.job.json")).unwrap()
}

#[test]
fn a_stem_narrower_than_the_fan_is_painted_with_the_fan_turned() {
    let dir = tempfile::tempdir().unwrap();
    let j = job(dir.path(), "I", "7ft");
    let s = &j.samples;
    // The painting rows' fan direction: an I's stem runs along the road's
    // y, its rungs across it (ψ = 0 or π); a turned fan is neither.
    let turned = (0..s.len())
        .filter(|&i| s.paint[i] == 1)
        .filter(|&i| {
            let off = s.yaw_rad[i].sin().abs();
            off > 0.3
        })
        .count();
    let painting = s.paint.iter().filter(|&&p| p == 1).count();
    assert!(
        turned * 2 > painting,
        "{turned} of {painting} painting rows turned off the rung"
    );
    // What that buys, measured by the film check: the fan beside an
    // untouched stem laid 11.7 % of the paint outside the letter.
    let film = j.summary.film.as_ref().expect("the film is measured");
    let (overspray, coverage, cv) = (
        film.overspray.expect("overspray"),
        film.coverage.expect("coverage"),
        film.cv.expect("cv"),
    );
    assert!(overspray < 0.06, "overspray {overspray}");
    assert!(coverage >= 0.98, "coverage {coverage}");
    assert!(cv <= 0.05, "cv {cv}");
}
