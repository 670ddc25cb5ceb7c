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
    // (2.3562 − 0.7854)·(5.3054² − 1.55²)/2 = 20.220 m²: the extension
    // stops the ¼ in stroke margin short of the cylinder's end stop.
    assert!((area - 20.220).abs() < 1e-3, "{area}");
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
    assert!(text.contains("20.22 m²"));
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

/// BASR with the yaw joint limited to ±1.6 rad and the tilt range made
/// asymmetric (−0.1 .. 0.2618 rad): a valid robot on which some fan
/// directions and tilts are painted by one fan branch only.
fn asymmetric_robot(dir: &tempfile::TempDir) -> std::path::PathBuf {
    let t = basr::robot::BASR_TOML
        .replacen(
            "min = -6.283185307179586\nmax = 6.283185307179586",
            "min = -1.6\nmax = 1.6",
            1,
        )
        .replacen("min = -0.2617993877991494\nmax", "min = -0.1\nmax", 1);
    let p = dir.path().join("asym.toml");
    std::fs::write(&p, t).unwrap();
    p
}

/// Even-odd point-in-polygon over all rings, and the distance to the
/// nearest edge.
fn inside_and_distance(rings: &[Vec<[f64; 2]>], x: f64, y: f64) -> (bool, f64) {
    let (mut inside, mut dist) = (false, f64::INFINITY);
    for ring in rings {
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            if (a[1] > y) != (b[1] > y) && x < a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) {
                inside = !inside;
            }
            let d = [b[0] - a[0], b[1] - a[1]];
            let t = (((x - a[0]) * d[0] + (y - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]))
                .clamp(0.0, 1.0);
            dist = dist.min((x - a[0] - t * d[0]).hypot(y - a[1] - t * d[1]));
        }
    }
    (inside, dist)
}

#[test]
fn one_branch_region_agrees_with_pose_on_a_grid() {
    let dir = tempfile::tempdir().unwrap();
    let robot = asymmetric_robot(&dir);
    // Fan 270° at 11.5°: as asked the yaw joint is out of range everywhere,
    // flipped the tilt would be −11.5°. The region used to be the full
    // 20.220 m² while pose refused.
    basr()
        .args([
            "workspace",
            "--yaw-deg",
            "270",
            "--tilt-deg",
            "11.5",
            "--robot",
        ])
        .arg(&robot)
        .assert()
        .code(2)
        .stdout("")
        .stderr(predicate::str::contains("no tip position is reachable"));
    basr()
        .args([
            "pose",
            "0",
            "3",
            "--yaw-deg",
            "270",
            "--tilt-deg",
            "11.5",
            "--robot",
        ])
        .arg(&robot)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("with the fan flipped (ψ+π").and(
            predicate::str::contains("tilt_rad would be -0.2007 rad (-11.50°)"),
        ));
    for (yaw, tilt) in [("180", "11.5"), ("0", "-10"), ("45", "3")] {
        let out = basr()
            .args([
                "workspace",
                "--json",
                "--yaw-deg",
                yaw,
                "--tilt-deg",
                tilt,
                "--robot",
            ])
            .arg(&robot)
            .output()
            .unwrap();
        assert!(out.status.success(), "{yaw} {tilt}");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let rings: Vec<Vec<[f64; 2]>> = serde_json::from_value(v["boundaries"].clone()).unwrap();
        let area = v["area_m2"].as_f64().unwrap();
        let shoelace: f64 = rings
            .iter()
            .map(|r| basr::robot::workspace::polygon_area(r))
            .sum();
        assert!(
            (shoelace - area).abs() < 1e-3,
            "{yaw} {tilt}: {shoelace} vs {area}"
        );
        if tilt != "3" {
            assert!(area < 15.0, "{yaw} {tilt}: {area} m² is not cut");
        }
        let (mut agreed, mut inside) = (0, 0);
        for i in 0..7 {
            for k in 0..7 {
                let x = -5.0 + 10.0 * i as f64 / 6.0;
                let y = 0.3 + 5.0 * k as f64 / 6.0;
                let (ins, d) = inside_and_distance(&rings, x, y);
                if d < 0.01 {
                    continue;
                }
                let (xs, ys) = (format!("{x}"), format!("{y}"));
                let code = basr()
                    .args([
                        "pose",
                        &xs,
                        &ys,
                        "--yaw-deg",
                        yaw,
                        "--tilt-deg",
                        tilt,
                        "--robot",
                    ])
                    .arg(&robot)
                    .output()
                    .unwrap()
                    .status
                    .code();
                assert_eq!(
                    code,
                    Some(if ins { 0 } else { 2 }),
                    "fan {yaw}° tilt {tilt}° at ({x}, {y}): workspace says inside = {ins}"
                );
                agreed += 1;
                inside += usize::from(ins);
            }
        }
        assert!(agreed > 30 && inside > 3, "{yaw} {tilt}: {agreed} {inside}");
    }
}
