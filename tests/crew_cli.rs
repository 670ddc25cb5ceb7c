//! Issue 15: lengths with units, hints for the usual slips, output paths
//! refused before any work.

mod common;
use common::{basr, stderr};

#[test]
fn letter_height_in_feet_and_a_bare_feet_number_hinted() {
    let dir = tempfile::tempdir().unwrap();
    let out = basr(
        dir.path(),
        &["compile", "STOP", "--letter-height", "8ft", "-q"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let job: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("STOP.job.json")).unwrap()).unwrap();
    assert_eq!(job["layout"]["letter_height_m"], 2.4384);

    let out = basr(dir.path(), &["compile", "STOP", "--letter-height", "8"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.contains("hint: --letter-height 8 is read as 8 m"),
        "{err}"
    );
    assert!(err.contains("--letter-height 8ft (2.4384 m)"), "{err}");
}

#[test]
fn slips_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = basr(dir.path(), &["compile", "STOP", "AHEAD"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("quote it: basr compile \"STOP AHEAD\""),
        "{}",
        stderr(&out)
    );

    let out = basr(dir.path(), &["compile", "ST\u{041E}P"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("U+041E") && err.contains("Latin O"), "{err}");

    std::fs::write(dir.path().join("STOP.csv"), "t_s,station,stroke\n0,0,-1\n").unwrap();
    let out = basr(dir.path(), &["preview", "STOP.csv"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("a setpoint CSV"), "{}", stderr(&out));
}

#[test]
fn a_folder_as_output_is_refused_before_work_and_earlier_files_stay() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("adir")).unwrap();
    std::fs::write(dir.path().join("old.csv"), "earlier run").unwrap();
    let out = basr(
        dir.path(),
        &["compile", "STOP", "-o", "adir", "--csv", "old.csv"],
    );
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("-o adir is a folder"), "{err}");
    // Nothing was planned or announced, and the earlier file is as it was.
    assert!(!err.contains("station"), "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("old.csv")).unwrap(),
        "earlier run"
    );
    assert_eq!(
        std::fs::read_dir(dir.path().join("adir")).unwrap().count(),
        0
    );

    let out = basr(dir.path(), &["compile", "STOP", "-q"]);
    assert!(out.status.success());
    for args in [
        &["preview", "STOP.job.json", "-o", "adir"][..],
        &["preview", "STOP.job.json", "-o", "film.png"],
        &["simulate", "STOP.job.json", "--svg", "adir/"],
    ] {
        let out = basr(dir.path(), args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            !stderr(&out).contains("wrote"),
            "{args:?}: {}",
            stderr(&out)
        );
    }
}

/// Issue 15: compile's default text is a short block with a verdict and at
/// most the problems; --verbose lists every warning; JSON keeps them all,
/// each with a severity.
#[test]
fn compile_says_what_where_how_long_and_whether_to_go() {
    let dir = tempfile::tempdir().unwrap();
    let out = basr(dir.path(), &["compile", "STOP"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stderr(&out);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines.len() <= 12, "{} lines:\n{text}", lines.len());
    assert!(
        lines[0].contains("min on site") && lines[0].contains(" L of paint"),
        "{text}"
    );
    assert!(
        text.contains("stop 1: arm axis 4.57 m past the near edge of STOP"),
        "{text}"
    );
    // The spray tip to mount, the film as `basr preview` measures it, how
    // closely the simulated arm followed it, then the verdict.
    assert!(
        lines[2].starts_with("  spray tip: seed-63.5 (63.5° fan, 0.40 L/min, uniform flux)"),
        "{text}"
    );
    assert!(
        lines[3].starts_with("  film (as `basr preview` measures it): cv "),
        "{text}"
    );
    assert!(
        lines[4].starts_with("  arm (closed loop): nozzle within ")
            && lines[4].contains("on 6 plants drawn around it (bound 4.76 mm)"),
        "{text}"
    );
    assert!(lines[5].starts_with("  verdict: "), "{text}");
    for l in &lines[6..] {
        assert!(l.starts_with("  problem: ") || l.starts_with("  … "), "{l}");
    }

    let out = basr(dir.path(), &["compile", "STOP", "--json", "-q"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let warnings = v["summary"]["warnings"].as_array().unwrap();
    assert!(!warnings.is_empty());
    for w in warnings {
        let sev = w["severity"].as_str().unwrap_or("");
        assert!(["info", "notice", "problem"].contains(&sev), "{w}");
    }

    let out = basr(dir.path(), &["compile", "STOP", "--verbose"]);
    let listed = stderr(&out)
        .lines()
        .filter(|l| {
            ["  info: ", "  notice: ", "  problem: "]
                .iter()
                .any(|p| l.starts_with(p))
        })
        .count();
    assert_eq!(listed, warnings.len());
}
