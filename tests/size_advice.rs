//! A word marking compile finds NOT READY names the nearest letter heights
//! that paint READY, found by compiling them (src/cmd/sizes.rs), and each
//! height it names does paint READY; a READY job searches nothing.

mod common;

use common::{basr, stderr};

fn compile_json(
    dir: &std::path::Path,
    height: &str,
    out: &str,
) -> (Option<i32>, serde_json::Value) {
    let o = basr(
        dir,
        &[
            "compile",
            "BB",
            "--letter-height",
            height,
            "--low-speed",
            "-o",
            out,
            "--json",
        ],
    );
    let v = serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("{height}: {e}: {}", stderr(&o)));
    (o.status.code(), v)
}

#[test]
fn a_not_ready_size_names_the_nearest_that_paint_and_they_do() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // BB at 5 ft under 25 mph is NOT READY on the default robot (B's
    // one-unit strokes narrower than every tip's fan). At 6 ft, MUTCD's
    // minimum, it was until B's bars ran through its stem (docs/font.md);
    // every word tried there paints now.
    let (code, v) = compile_json(d, "5ft", "a.job.json");
    assert_eq!(code, Some(1), "{v}");
    let sizes = &v["sizes"];
    let asked = sizes["asked_m"].as_f64().expect("asked_m");
    assert!((asked - 1.524).abs() < 1e-9, "{asked}");
    // Nothing from MUTCD's low-speed 4.5 ft up to it paints.
    let searched = sizes["searched_m"][0].as_f64().expect("searched_m");
    assert!((searched - 4.5 * 0.3048).abs() < 1e-6, "{sizes}");
    assert!(sizes["nearest_ready_smaller_m"].is_null(), "{sizes}");
    let larger = sizes["nearest_ready_larger_m"]
        .as_f64()
        .unwrap_or_else(|| panic!("a larger size paints: {sizes}"));
    assert!(
        larger > 1.524 && larger <= 1.524 + 8.0 * 0.0762 + 1e-9,
        "{larger}"
    );
    // The named size paints READY (exit 0), and a quarter foot less does not.
    let (code, v) = compile_json(d, &format!("{larger}m"), "b.job.json");
    assert_eq!(code, Some(0), "{larger} m: {v}");
    assert!(v["sizes"].is_null(), "a READY job searches nothing");
    let (code, _) = compile_json(d, &format!("{}m", larger - 0.0762), "c.job.json");
    assert_eq!(
        code,
        Some(1),
        "the nearest: a quarter foot less is NOT READY"
    );
}

/// STOP at 4.5 ft under 25 mph (`--low-speed`, MUTCD's smallest word
/// letters) is NOT READY: the search names the nearest larger size that
/// paints (within the default 8 ft), and that size does paint while a
/// quarter foot less does not.
#[test]
fn low_speed_letters_are_told_the_nearest_larger_size() {
    let dir = tempfile::tempdir().unwrap();
    let o = basr(
        dir.path(),
        &[
            "compile",
            "STOP",
            "--letter-height",
            "4.5ft",
            "--low-speed",
            "-o",
            "a.job.json",
            "--json",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let larger = v["sizes"]["nearest_ready_larger_m"]
        .as_f64()
        .unwrap_or_else(|| panic!("a larger size is named: {}", v["sizes"]));
    assert!(
        larger > 4.5 * 0.3048 && larger <= 8.0 * 0.3048 + 1e-9,
        "{larger}"
    );
    let at = |h: f64, out: &str| {
        basr(
            dir.path(),
            &[
                "compile",
                "STOP",
                "--letter-height",
                &format!("{h}m"),
                "--low-speed",
                "--no-size-search",
                "-q",
                "-o",
                out,
            ],
        )
        .status
        .code()
    };
    assert_eq!(at(larger, "b.job.json"), Some(0), "{larger} m paints");
    assert_eq!(
        at(larger - 0.0762, "c.job.json"),
        Some(1),
        "the nearest: a quarter foot less is NOT READY"
    );
}

/// Letters asked under MUTCD's 6 ft (without --low-speed) are searched
/// from 6 ft up: the range the line and --json give starts there, not at
/// the asked height, whose neighbours under 6 ft were never tried.
#[test]
fn a_size_under_the_minimum_is_searched_from_the_minimum() {
    let dir = tempfile::tempdir().unwrap();
    let o = basr(
        dir.path(),
        &[
            "compile",
            "STOP",
            "--letter-height",
            "5ft",
            "-o",
            "a.job.json",
            "--json",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let searched = &v["sizes"]["searched_m"];
    let lo = searched[0].as_f64().unwrap_or_else(|| panic!("{searched}"));
    assert!((lo - 6.0 * 0.3048).abs() < 1e-6, "{searched}");
    assert!(
        v["sizes"]["nearest_ready_smaller_m"].is_null(),
        "{}",
        v["sizes"]
    );
    // the summary line on stderr, written beside --json's
    let err = stderr(&o);
    assert!(err.contains("searched 6ft (1.83 m) to"), "{err}");
}

/// The quarter-foot heights a `sizes:` line names (as `--letter-height`
/// takes them): "10.75ft (3.28 m) smaller" → ("10.75ft", "smaller").
fn named(line: &str) -> Vec<(String, String)> {
    let words: Vec<&str> = line.split_whitespace().collect();
    words
        .windows(4)
        .filter(|w| {
            w[0].ends_with("ft") && (w[3].starts_with("smaller") || w[3].starts_with("larger"))
        })
        .map(|w| {
            (
                w[0].to_string(),
                w[3].trim_end_matches([',', ' ']).to_string(),
            )
        })
        .collect()
}

/// A refusal for the word's size names the nearest sizes that paint, and
/// they do; a refusal no size mends searches nothing.
#[test]
fn a_size_refused_names_the_nearest_that_paint_and_they_do() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // ("6" at 12 ft was refused here too, a join carrying the extension
    // past full reach, until its bowl's wide stretches were split apart
    // from its narrow ones: it paints now, up to 18 ft.)
    for (what, args) in [
        // AHEAD at 9 ft is wider than a 3 m lane: searched from the
        // height it fits at
        (
            "wider",
            vec!["AHEAD", "--letter-height", "9ft", "--lane-width", "3"],
        ),
    ] {
        let mut a = vec!["compile"];
        a.extend(&args);
        a.extend(["-o", "refused.job.json"]);
        let o = basr(d, &a);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            !d.join("refused.job.json").exists(),
            "{args:?}: no job left"
        );
        let line = err
            .lines()
            .find(|l| l.trim_start().starts_with("sizes:"))
            .unwrap_or_else(|| panic!("{args:?} ({what}): no sizes line: {err}"));
        let found = named(line);
        assert!(!found.is_empty(), "{args:?}: a size paints: {line}");
        for (height, _) in &found {
            let mut a = vec!["compile", args[0]];
            a.extend(&args[3..]);
            a.extend([
                "--letter-height",
                height,
                "-o",
                "named.job.json",
                "--no-size-search",
            ]);
            let o = basr(d, &a);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{args:?} at {height}: {}",
                stderr(&o)
            );
        }
    }
    // A character no font has, and a lane that fits the word only below
    // MUTCD's 6 ft: refused, and no size searched.
    for args in [
        vec!["compile", "ST%P", "-o", "bad.job.json"],
        vec![
            "compile",
            "STOP",
            "--lane-width",
            "0.5",
            "-o",
            "bad.job.json",
        ],
    ] {
        let o = basr(d, &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(!stderr(&o).contains("sizes:"), "{args:?}: {}", stderr(&o));
    }
}

/// A robot the arm cannot follow with at any size (a supply pressure a
/// fifth of the seed's): the search stops at the first pair of heights
/// either way that are too fast to follow as well, and says the robot,
/// not the size, is the likely cause; nothing is written.
#[test]
fn a_robot_too_weak_to_follow_is_not_sent_searching_sizes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/basr.toml")).unwrap();
    assert!(robot.contains("\nsupply_pa = 2.069e7\n"));
    std::fs::write(
        d.join("weak.toml"),
        robot.replace("\nsupply_pa = 2.069e7\n", "\nsupply_pa = 4e6\n"),
    )
    .unwrap();
    let o = basr(
        d,
        &[
            "compile",
            "STOP",
            "--robot",
            "weak.toml",
            "-o",
            "w.job.json",
        ],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("cannot follow this job closely enough"),
        "{err}"
    );
    let line = err
        .lines()
        .find(|l| l.trim_start().starts_with("sizes:"))
        .unwrap_or_else(|| panic!("a sizes line: {err}"));
    assert!(
        line.contains("cannot follow the job at") && line.contains("robot description"),
        "{line}"
    );
    // the first pair each way: 7.75 and 7.5 ft below, 8.25 and 8.5 ft above
    // (2.44 m is 8 ft on the quarter-foot grid, not tried again)
    assert!(line.contains("7.5ft") && line.contains("8.5ft"), "{line}");
    assert!(!d.join("w.job.json").exists());
}

/// A word planned with settings other than compile's (a coarse rung
/// spacing that leaves STOP NOT READY) is not searched for sizes: the
/// line names the setting and sends the user to the default first.
#[test]
fn a_job_planned_with_other_settings_is_not_searched_for_sizes() {
    let dir = tempfile::tempdir().unwrap();
    let o = basr(
        dir.path(),
        &[
            "compile",
            "STOP",
            "--rung-spacing-mm",
            "100",
            "-o",
            "r.job.json",
        ],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "NOT READY: {err}");
    let line = err
        .lines()
        .find(|l| l.trim_start().starts_with("sizes:"))
        .unwrap_or_else(|| panic!("a sizes line: {err}"));
    assert!(
        line.contains("not searched") && line.contains("--rung-spacing-mm"),
        "{line}"
    );
}
