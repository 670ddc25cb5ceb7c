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
            "STOP",
            "--letter-height",
            height,
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
    // STOP at 6 ft (MUTCD's minimum) is NOT READY on the default robot.
    let (code, v) = compile_json(d, "6ft", "a.job.json");
    assert_eq!(code, Some(1), "{v}");
    let sizes = &v["sizes"];
    let asked = sizes["asked_m"].as_f64().expect("asked_m");
    assert!((asked - 1.8288).abs() < 1e-9, "{asked}");
    // Nothing below MUTCD's 6 ft is offered.
    assert!(sizes["nearest_ready_smaller_m"].is_null(), "{sizes}");
    let larger = sizes["nearest_ready_larger_m"]
        .as_f64()
        .unwrap_or_else(|| panic!("a larger size paints: {sizes}"));
    assert!(
        larger > 1.8288 && larger <= 1.8288 + 8.0 * 0.0762 + 1e-9,
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
