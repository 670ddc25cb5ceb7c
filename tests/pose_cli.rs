//! End-to-end tests of `basr pose`.

use assert_cmd::Command;
use predicates::prelude::*;

fn basr() -> Command {
    Command::cargo_bin("basr").unwrap()
}

#[test]
fn pose_json_keyed_by_csv_columns() {
    let out = basr()
        .args(["pose", "0", "3", "--tilt-deg", "10", "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for k in [
        "base_rot_rad",
        "extension_m",
        "vertical_m",
        "ee_yaw_rad",
        "tilt_rad",
    ] {
        assert!(v["joints"][k].is_f64(), "{k}");
    }
    for k in ["cylinder_m", "tilt_nut_m", "vertical_m"] {
        assert!(v["actuators"][k].is_f64(), "{k}");
    }
    for k in [
        "enc_base",
        "enc_extension",
        "enc_yaw",
        "enc_tilt",
        "enc_vertical",
    ] {
        assert!(v["encoders"][k].is_i64(), "{k}");
    }
    // The fan as asked: tilt +10°; base straight back (≈ 90°).
    let tilt = v["joints"]["tilt_rad"].as_f64().unwrap();
    assert!((tilt - 10f64.to_radians()).abs() < 1e-12);
    let th = v["joints"]["base_rot_rad"].as_f64().unwrap();
    assert!((th.to_degrees() - 90.21).abs() < 0.01, "{th}");
    // Encoders agree with the library for these joints.
    let r = basr::robot::Robot::basr();
    let j: basr::robot::Joints = serde_json::from_value(v["joints"].clone()).unwrap();
    let e: basr::robot::Encoders = serde_json::from_value(v["encoders"].clone()).unwrap();
    assert_eq!(r.encoders(&j), e);
}

#[test]
fn negative_coordinates_are_accepted() {
    basr()
        .args([
            "pose",
            "-1.2",
            "4",
            "--yaw-deg",
            "-30",
            "--height",
            "0.15",
            "--json",
        ])
        .assert()
        .success();
}

#[test]
fn unreachable_pose_exits_2_naming_limit_and_excess() {
    basr()
        .args(["pose", "0", "6"])
        .assert()
        .code(2)
        .stdout("")
        .stderr(
            predicate::str::contains("extension_m").and(predicate::str::contains("by 0.6417 m")),
        );
    basr()
        .args(["pose", "0", "3", "--tilt-deg", "20"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("tilt_rad").and(predicate::str::contains("by ")));
    basr()
        .args(["pose", "0", "3", "--height", "0.5"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("vertical_m"));
}

#[test]
fn human_table_goes_to_stderr() {
    basr()
        .args(["pose", "0", "3"])
        .assert()
        .success()
        .stdout("")
        .stderr(predicate::str::contains("enc_base"));
}

#[test]
fn tip_on_the_base_axis_names_the_extension_it_would_need() {
    // Within a2 = 0.01 m of the rotation axis no arm pose exists; the
    // message gives R ≈ |W| and its real shortfall, not "not finite".
    basr()
        .args(["pose", "0", "0"])
        .assert()
        .code(2)
        .stdout("")
        .stderr(
            predicate::str::contains("extension_m would be 0.0000 m")
                .and(predicate::str::contains("by 1.5500 m"))
                .and(predicate::str::contains("finite").not()),
        );
}
