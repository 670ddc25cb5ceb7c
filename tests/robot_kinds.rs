//! End-to-end tests of the telescopic and articulated robot kinds (SPEC §8):
//! check, robot, pose, workspace and design through the binary.

use assert_cmd::Command;
use predicates::prelude::*;

fn basr() -> Command {
    Command::cargo_bin("basr").unwrap()
}

const KINDS: [&str; 2] = ["robots/telescopic.toml", "robots/articulated.toml"];

#[test]
fn shipped_descriptions_check_ok_and_print_as_shipped() {
    for f in KINDS {
        basr().args(["check", f]).assert().success();
        let out = basr()
            .args(["robot", "--toml", "--robot", f])
            .output()
            .unwrap();
        assert!(out.status.success());
        assert_eq!(
            String::from_utf8(out.stdout).unwrap(),
            std::fs::read_to_string(f).unwrap()
        );
    }
}

#[test]
fn check_names_a_bad_kind_field_with_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("t.toml");
    let text = std::fs::read_to_string(KINDS[0]).unwrap().replacen(
        "max_effort = 2500.0",
        "max_effort = 1.0",
        1,
    );
    std::fs::write(&f, &text).unwrap();
    let line = text
        .lines()
        .position(|l| l.starts_with("max_acc = 0.5"))
        .unwrap()
        + 1;
    basr()
        .arg("check")
        .arg(&f)
        .assert()
        .code(1)
        .stderr(predicate::str::contains(format!(
            ":{line}: field `joints.base_rot_rad.max_acc`"
        )));
}

#[test]
fn pose_json_is_keyed_by_the_kinds_columns() {
    for (f, joint, enc) in [
        (KINDS[0], "stroke_m", "enc_stroke"),
        (KINDS[1], "elbow_rad", "enc_elbow"),
    ] {
        let out = basr()
            .args([
                "pose", "0.5", "2.5", "--height", "0.15", "--json", "--robot", f,
            ])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(v["joints"][joint].is_f64(), "{v}");
        assert!(v["encoders"][enc].is_i64(), "{v}");
        assert!(v["solutions"].as_u64().unwrap() >= 2);
        assert!(v["reach_margin_m"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn pose_out_of_reach_exits_2_naming_the_limit() {
    basr()
        .args(["pose", "0", "20", "--robot", KINDS[0]])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("stroke_m would be"));
    basr()
        .args(["pose", "0", "20", "--robot", KINDS[1]])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("reach_m would be"));
}

#[test]
fn workspace_svg_for_every_kind_parses_and_says_ring_and_voids() {
    let dir = tempfile::tempdir().unwrap();
    for f in KINDS {
        let svg = dir.path().join("ws.svg");
        let out = basr()
            .args(["workspace", "--json", "--robot", f, "--svg"])
            .arg(&svg)
            .output()
            .unwrap();
        assert!(out.status.success());
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        // Both arms keep off the base axis (the telescopic by h2, the
        // articulated by the shoulder offset): rings, without voids.
        assert_eq!(v["section"]["ring"], true);
        assert_eq!(v["section"]["voids"], 0);
        // The lane: 3.66 m across, 2.44 m along, behind the base.
        let road = v["road"]["area_m2"].as_f64().unwrap();
        assert!(road > 3.66 * 2.44, "{road}");
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(resvg::usvg::Tree::from_str(&text, &resvg::usvg::Options::default()).is_ok());
        assert!(text.contains("ring yes"));
    }
}

/// `basr design --kind telescopic --points POINTS -o OUT`, more arguments to add.
fn design(points: &std::path::Path, out: &std::path::Path) -> Command {
    let mut c = basr();
    c.args(["design", "--kind", "telescopic", "--points"])
        .arg(points)
        .arg("-o")
        .arg(out);
    c
}

/// The lane of the acceptance: four points across 12 ft, 3 m back.
const LANE: &str =
    "points_m = [[-1.83, 3.0, 0.15], [-0.61, 3.0, 0.15], [0.61, 3.0, 0.15], [1.83, 3.0, 0.15]]\n";

#[test]
fn design_across_a_lane_then_every_point_is_reachable() {
    let dir = tempfile::tempdir().unwrap();
    let points = dir.path().join("lane.toml");
    std::fs::write(&points, LANE).unwrap();
    let arm = dir.path().join("arm.toml");
    let out = design(&points, &arm).arg("--json").output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let its = v["iterations"].as_array().unwrap();
    assert!(its.last().unwrap()["residual"].as_f64().unwrap() < 1e-12);
    basr().arg("check").arg(&arm).assert().success();
    for x in ["-1.83", "-0.61", "0.61", "1.83"] {
        let out = basr()
            .args(["pose", x, "3", "--height", "0.15", "--json", "--robot"])
            .arg(&arm)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{x}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let p: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        // The 0.1 m margin holds on the road.
        assert!(p["reach_margin_m"].as_f64().unwrap() >= 0.1 - 1e-3, "{p}");
    }
}

#[test]
fn design_refuses_unreachable_sets_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let arm = dir.path().join("arm.toml");
    for (points, why) in [
        ("points_m = [[0.0, 3.0, -0.5]]", "below the road"),
        ("points_m = [[0.0, 3.0, 0.1], [0.0, -3.0, 0.1]]", "azimuth"),
        (
            "points_m = [[0.0, 1.0, 0.1], [0.0, 11.0, 0.1]]",
            "retracted length",
        ),
        ("points_m = [[0.0, 3.0]]", "points_m[0]"),
    ] {
        let f = dir.path().join("p.toml");
        std::fs::write(&f, points).unwrap();
        design(&f, &arm)
            .assert()
            .code(2)
            .stderr(predicate::str::contains(why));
        assert!(!arm.exists());
    }
    basr()
        .args(["design", "--kind", "articulated", "--points", "x", "-o"])
        .arg(&arm)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("telescopic kind only"));
}
