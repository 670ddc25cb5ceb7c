//! `basr preview` on jobs written by `basr compile`: tilt evens the seed's
//! U on the letter O, `--compare` re-plans side by side, and a compiled job
//! that was damaged is refused with exit 2.

use std::path::Path;

use assert_cmd::Command;
use serde_json::Value;

fn compile(dir: &Path, message: &str, tilt: &str, out: &str) -> std::path::PathBuf {
    let path = dir.join(out);
    Command::cargo_bin("basr")
        .unwrap()
        .args(["compile", message, "--tilt", tilt, "--quiet", "-o"])
        .arg(&path)
        .assert()
        .success();
    path
}

fn preview(job: &Path, extra: &[&str]) -> Value {
    let out = Command::cargo_bin("basr")
        .unwrap()
        .arg("preview")
        .arg(job)
        .args(["--json", "--quiet", "-o"])
        .arg(job.with_extension("svg"))
        .args(extra)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn u_span(m: &Value) -> f64 {
    m["u_max"].as_f64().unwrap() - m["u_min"].as_f64().unwrap()
}

#[test]
fn quadrilateral_tilt_narrows_u_on_the_letter_o() {
    let dir = tempfile::tempdir().unwrap();
    let none = preview(&compile(dir.path(), "O", "none", "none.json"), &[]);
    let quad = preview(&compile(dir.path(), "O", "quadrilateral", "quad.json"), &[]);
    assert!(u_span(&quad) < u_span(&none), "quad {quad} none {none}");
    // Every letter cell is painted and little paint leaves the letter.
    for m in [&none, &quad] {
        assert!(m["coverage"].as_f64().unwrap() > 0.95, "{m}");
        assert!(m["overspray"].as_f64().unwrap() < 0.05, "{m}");
        let vol = m["volume_on_road_m3"].as_f64().unwrap();
        let laid = m["volume_laid_m3"].as_f64().unwrap();
        assert!((vol / laid - 1.0).abs() < 0.005, "{m}");
    }
}

#[test]
fn compare_replans_each_tilt_method() {
    let dir = tempfile::tempdir().unwrap();
    let job = compile(dir.path(), "O", "quadrilateral", "o.json");
    let m = preview(&job, &["--compare", "trapezoid,quadrilateral"]);
    let runs = m.as_array().expect("one report per method");
    assert_eq!(runs.len(), 2);
    assert_eq!(runs[0]["tilt_method"], "trapezoid");
    assert_eq!(runs[1]["tilt_method"], "quadrilateral");
    // Both tilt methods keep the seed's U near 50 % (001 fig. 2.14: 47–52).
    for r in runs {
        assert!(u_span(r) < 0.25, "{r}");
    }
    let svg = std::fs::read_to_string(job.with_extension("svg")).unwrap();
    assert_eq!(svg.matches("tilt: ").count(), 2);
}

#[test]
fn damaged_compiled_job_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let job = compile(dir.path(), "O", "quadrilateral", "o.json");
    let text = std::fs::read_to_string(&job).unwrap();
    let cases = [
        (
            "cut.json",
            text[..text.len() * 2 / 3].to_string(),
            "truncated",
        ),
        ("edit.json", text.replacen("\"O\"", "\"Q\"", 1), "integrity"),
        (
            "v9.json",
            text.replacen("\"version\": 1", "\"version\": 9", 1),
            "version",
        ),
    ];
    for (name, body, needle) in cases {
        assert_ne!(body, text, "{name}: the edit did not apply");
        let path = dir.path().join(name);
        std::fs::write(&path, body).unwrap();
        let out = Command::cargo_bin("basr")
            .unwrap()
            .arg("preview")
            .arg(&path)
            .arg("-o")
            .arg(dir.path().join("x.svg"))
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{name}: {err}");
        assert!(!dir.path().join("x.svg").exists());
    }
}
