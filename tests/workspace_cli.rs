//! End-to-end tests of `basr workspace`.

use assert_cmd::Command;
use predicates::prelude::*;

fn basr() -> Command {
    Command::cargo_bin("basr").unwrap()
}

#[test]
fn json_area_and_boundary() {
    let out = basr().args(["workspace", "--json"]).output().unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let area = v["area_m2"].as_f64().unwrap();
    // (2.3562 − 0.7854)·(5.3583² − 1.55²)/2 = 20.663 m².
    assert!((area - 20.663).abs() < 1e-3, "{area}");
    let pts = v["boundary"].as_array().unwrap();
    assert!(pts.len() > 100);
    let poly: Vec<[f64; 2]> = serde_json::from_value(v["boundary"].clone()).unwrap();
    let shoelace = basr::robot::workspace::polygon_area(&poly);
    assert!((shoelace - area).abs() < 1e-3, "{shoelace}");
    let z = v["z_range_m"].as_array().unwrap();
    assert!((z[0].as_f64().unwrap() - 0.078).abs() < 1e-9);
}

#[test]
fn svg_is_written_and_parses() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("ws.svg");
    basr()
        .args(["workspace", "--svg"])
        .arg(&f)
        .assert()
        .success();
    let text = std::fs::read_to_string(&f).unwrap();
    let tree = resvg::usvg::Tree::from_str(&text, &resvg::usvg::Options::default());
    assert!(tree.is_ok());
    assert!(text.contains("20.66 m²"));
}

#[test]
fn tilted_region_is_shifted_and_bad_tilt_refused() {
    let out = basr()
        .args(["workspace", "--tilt-deg", "15", "--yaw-deg", "0", "--json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let shift = v["shift_m"][0].as_f64().unwrap();
    assert!((shift - 0.0039).abs() < 1e-4, "{shift}");
    basr()
        .args(["workspace", "--tilt-deg", "30"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("tilt_rad"));
}
