//! End-to-end tests of `basr pose`.

mod common;
use common::json_of;

use assert_cmd::Command;
use predicates::prelude::*;

fn basr() -> Command {
    Command::cargo_bin("basr").unwrap()
}

#[test]
fn pose_json_keyed_by_csv_columns() {
    let v = json_of(
        basr()
            .args(["pose", "0", "3", "--tilt-deg", "10", "--json"])
            .output()
            .unwrap(),
    );
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
            predicate::str::contains("extension_m").and(predicate::str::contains("by 0.6946 m")),
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

#[test]
fn zero_tilt_keeps_the_fan_as_asked_and_prints_no_negative_zero() {
    // At β = 0 both fan branches have tilt 0 (and −0.0 == 0.0); the one
    // shown must point where asked: θ1 + yaw joint = ψ, not ψ + π.
    for yaw in ["0", "30", "-150", "180"] {
        let out = basr()
            .args(["pose", "0", "3", "--yaw-deg", yaw, "--json"])
            .output()
            .unwrap();
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(
            !text.contains("-0.0,") && !text.contains("-0.0\n"),
            "{text}"
        );
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let j = &v["joints"];
        let psi = j["base_rot_rad"].as_f64().unwrap() + j["ee_yaw_rad"].as_f64().unwrap();
        let want = yaw.parse::<f64>().unwrap().to_radians();
        let d = basr::robot::kinematics::wrap_pi(psi - want);
        assert!(d.abs() < 1e-9, "yaw {yaw}: fan at {psi} rad");
    }
    // A tilt given as -0 is still printed as 0.
    basr()
        .args(["pose", "0", "3", "--tilt-deg", "-0", "--json"])
        .assert()
        .success()
        .stdout(predicate::str::contains("-0.0").not());
    basr()
        .args(["pose", "0", "3", "--tilt-deg", "-0"])
        .assert()
        .success()
        .stderr(predicate::str::contains("-0.0").not());
}

#[test]
fn non_finite_numbers_reach_our_validation() {
    // `-inf` is no number to clap's negative-number test: it used to fail
    // with "unexpected argument '-i'".
    for (args, what) in [
        (["pose", "0", "-inf"], "Y is not a finite number"),
        (["pose", "-inf", "3"], "X is not a finite number"),
        (["pose", "nan", "3"], "X is not a finite number"),
    ] {
        basr()
            .args(args)
            .assert()
            .code(2)
            .stdout("")
            .stderr(predicate::str::contains(what).and(predicate::str::contains("'-i'").not()));
    }
    basr()
        .args(["pose", "0", "3", "--height", "-inf"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--height is not a finite number"));
    basr().args(["pose", "-1", "3"]).assert().success();
    basr()
        .args(["pose", "-1", "3", "--json"])
        .assert()
        .success();
    basr()
        .args(["pose", "--json", "-1", "3"])
        .assert()
        .success();
}

#[test]
fn a_tiny_excess_is_shown_with_significant_digits() {
    // 15.0000001° is 1.7e-9 rad over the limit: not "by 0.0000 rad (0.00°)".
    basr()
        .args(["pose", "0", "3", "--tilt-deg", "15.0000001"])
        .assert()
        .code(2)
        .stderr(
            predicate::str::contains("by 0.0000000017 rad (0.00000010°)")
                .and(predicate::str::contains("0.00°)\n").not()),
        );
}

#[test]
fn yaw_is_wrapped_to_one_turn() {
    for (given, shown) in [
        ("1e300", 0.0f64),
        ("540", 180.0),
        ("-190", 170.0),
        ("1e20", -80.0),
    ] {
        let out = basr()
            .args(["pose", "0", "3", "--yaw-deg", given, "--json"])
            .output()
            .unwrap();
        assert!(out.status.success(), "{given}");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let yaw = v["pose"]["yaw_rad"].as_f64().unwrap();
        assert!((yaw - shown.to_radians()).abs() < 1e-12, "{given}: {yaw}");
        let out = basr()
            .args(["pose", "0", "3", "--yaw-deg", given])
            .output()
            .unwrap();
        let first = String::from_utf8(out.stderr).unwrap();
        let first = first.lines().next().unwrap().to_string();
        assert!(first.contains(&format!("yaw {shown:.2}°")), "{first}");
        assert!(first.len() < 120, "{first}");
    }
    // Far beyond reach: a short message, not 300 digits or "not finite".
    let out = basr().args(["pose", "1e300", "3"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("extension_m would be 1.0000e300 m"), "{err}");
    assert!(err.len() < 300, "{err}");
}

/// Lengths take units, as every length option does: 10ft is 3.048 m, 6in
/// of height 0.1524 m; a unit basr does not know is refused naming it.
#[test]
fn pose_lengths_take_units() {
    let v = json_of(
        basr()
            .args(["pose", "0", "10ft", "--height", "6in", "--json"])
            .output()
            .unwrap(),
    );
    let m = json_of(
        basr()
            .args(["pose", "0", "3.048", "--height", "0.1524", "--json"])
            .output()
            .unwrap(),
    );
    for (k, a) in v["joints"].as_object().unwrap() {
        let b = m["joints"][k].as_f64().unwrap();
        assert!(
            (a.as_f64().unwrap() - b).abs() < 1e-12,
            "{k}: {a} against {b}"
        );
    }
    basr()
        .args(["pose", "0", "3x"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("unknown unit \"x\""));
}
