//! End-to-end tests of `basr robot` and robot-file validation through the binary.

use assert_cmd::Command;
use predicates::prelude::*;

fn basr() -> Command {
    Command::cargo_bin("basr").unwrap()
}

fn default_toml() -> String {
    let out = basr().args(["robot", "--toml"]).output().unwrap();
    assert!(out.status.success());
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn toml_output_checks_and_reads_back() {
    let text = default_toml();
    basr()
        .args(["check", "-"])
        .write_stdin(text.clone())
        .assert()
        .success()
        .stderr(predicate::str::contains("-: ok"));
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("r.toml");
    std::fs::write(&f, &text).unwrap();
    let again = basr()
        .args(["robot", "--toml", "--robot"])
        .arg(&f)
        .output()
        .unwrap();
    assert!(again.status.success());
    let again = String::from_utf8(again.stdout).unwrap();
    // The default prints the embedded file with its sources, also when it
    // is read back from a file.
    assert!(text.contains("# Safety window of the controller"));
    let parse = |t: &str| basr::robot::Robot::from_toml_str(t, "t").unwrap();
    assert_eq!(parse(&again), basr::robot::Robot::basr());
    assert_eq!(again, text);
}

#[test]
#[allow(clippy::approx_constant)] // 0.7854 is the seed's base window, not π/4
fn json_has_sections_and_hash() {
    let out = basr().args(["robot", "--json"]).output().unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "arm",
        "end_effector",
        "paint",
        "control",
        "encoders",
        "limits",
        "hydraulics",
    ] {
        assert!(v.get(key).is_some(), "{key}");
    }
    assert_eq!(v["limits"]["base_rot_rad"]["min"], 0.7854);
    assert_eq!(v["sha256"].as_str().unwrap().len(), 64);
    assert_eq!(v["sha256"], basr::robot::Robot::basr().sha256());
}

/// Write the default description with one edit; return the file and the
/// 1-based line of the edit.
fn bad_file(dir: &tempfile::TempDir, find: &str, replace: &str) -> (std::path::PathBuf, usize) {
    let text = default_toml();
    let (before, _) = text.split_once(find).expect("field present");
    let line = before.matches('\n').count() + 1;
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, text.replacen(find, replace, 1)).unwrap();
    (path, line)
}

fn assert_rejected(find: &str, replace: &str, field: &str) {
    let dir = tempfile::tempdir().unwrap();
    let (path, line) = bad_file(&dir, find, replace);
    let shown = format!("{}:{line}", path.display());
    basr()
        .args(["robot", "--robot"])
        .arg(&path)
        .assert()
        .code(2)
        .stdout("")
        .stderr(predicate::str::contains(shown.clone()).and(predicate::str::contains(field)));
    basr()
        .arg("check")
        .arg(&path)
        .assert()
        .code(1)
        .stderr(predicate::str::contains(shown).and(predicate::str::contains(field)));
}

#[test]
fn syntax_error_exits_2_with_line() {
    assert_rejected("a2_m = 0.01", "a2_m = 0.01 0.02", "a2_m");
}

#[test]
fn nan_exits_2_naming_field() {
    assert_rejected(
        "fan_angle_rad = ",
        "fan_angle_rad = nan #",
        "paint.fan_angle_rad",
    );
}

#[test]
fn negative_mass_exits_2_naming_field() {
    assert_rejected("mass_kg = 35.0", "mass_kg = -35.0", "end_effector.mass_kg");
}

#[test]
fn reversed_range_exits_2_naming_field() {
    assert_rejected(
        "min = -0.2617993877991494\nmax = 0.2617993877991494",
        "min = 0.2617993877991494\nmax = -0.2617993877991494",
        "limits.tilt_rad.min",
    );
}

#[test]
fn missing_file_exits_2() {
    basr()
        .args(["robot", "--robot", "no/such/robot.toml"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("no/such/robot.toml"));
}

#[test]
fn missing_field_has_its_dotted_name_and_line() {
    // Line of the [end_effector] header: serde points at the table.
    let text = default_toml();
    let header = text.lines().position(|l| l == "[end_effector]").unwrap() + 1;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, text.replacen("mass_kg = 35.0\n", "", 1)).unwrap();
    let want = format!(
        "{}:{header}:1: missing field `end_effector.mass_kg`",
        path.display()
    );
    basr()
        .args(["robot", "--robot"])
        .arg(&path)
        .assert()
        .code(2)
        .stdout("")
        .stderr(predicate::str::contains(want.clone()));
    basr()
        .arg("check")
        .arg(&path)
        .assert()
        .code(1)
        .stderr(predicate::str::contains(want));
}

#[test]
fn nan_in_an_array_names_its_line() {
    assert_rejected(
        "joint_f_deflection_extension_m = [1.470",
        "joint_f_deflection_extension_m = [nan",
        "end_effector.joint_f_deflection_extension_m[0]",
    );
}

#[test]
fn non_utf8_file_is_refused_at_line_and_column() {
    let text = default_toml();
    let line = text.lines().position(|l| l.starts_with("mass_kg")).unwrap() + 1;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("latin1.toml");
    // A Latin-1 'ß' (0xdf) in a comment, column 18 of the mass_kg line.
    let mut bytes = text
        .replacen("mass_kg = 35.0", "mass_kg = 35.0 # X", 1)
        .into_bytes();
    let x = bytes.windows(3).position(|w| w == b"# X").unwrap() + 2;
    bytes[x] = 0xdf;
    std::fs::write(&path, bytes).unwrap();
    let want = format!("{}:{line}:18: not UTF-8", path.display());
    basr()
        .args(["robot", "--robot"])
        .arg(&path)
        .assert()
        .code(2)
        .stderr(
            predicate::str::contains(want.clone()).and(predicate::str::contains("offset").not()),
        );
    basr()
        .arg("check")
        .arg(&path)
        .assert()
        .code(2)
        .stderr(predicate::str::contains(want));
}

#[test]
fn multi_line_syntax_message_is_joined() {
    let dir = tempfile::tempdir().unwrap();
    let (path, _) = bad_file(&dir, "a2_m = 0.01", "a2_m = [1,");
    let out = basr().arg("check").arg(&path).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("invalid array; expected `]`"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

/// `basr robot --robot FILE --toml` of a file.
fn toml_of(path: &std::path::Path) -> String {
    let out = basr()
        .args(["robot", "--toml", "--robot"])
        .arg(path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn toml_output_reads_back_byte_identically() {
    let dir = tempfile::tempdir().unwrap();
    // The default: printed, read back, printed again: the shipped text with
    // its source comments both times (it used to lose them the second time).
    let first = default_toml();
    let f = dir.path().join("f.toml");
    std::fs::write(&f, &first).unwrap();
    assert_eq!(toml_of(&f), first);
    // A different description: the canonical form is a fixed point.
    let custom = first
        .replacen("mass_kg = 35.0", "mass_kg = 3.65e1", 1)
        .replacen("supply_pa = 2.069e7", "supply_pa = 2.1e7", 1);
    let c = dir.path().join("c.toml");
    std::fs::write(&c, custom).unwrap();
    let once = toml_of(&c);
    assert!(once.contains("mass_kg = 36.5"), "{once}");
    let c1 = dir.path().join("c1.toml");
    std::fs::write(&c1, &once).unwrap();
    assert_eq!(toml_of(&c1), once);
}

#[test]
fn check_carries_on_past_an_unreadable_file() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("good.toml");
    std::fs::write(&good, default_toml()).unwrap();
    let (bad, line) = bad_file(&dir, "mass_kg = 35.0", "mass_kg = -35.0");
    let missing = dir.path().join("nosuch.toml");
    // The file after the unreadable one is checked too; exit 2 at the end.
    let out = basr()
        .arg("check")
        .args([&good, &missing, &bad])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains(&format!("{}: ok", good.display())), "{err}");
    assert!(
        err.contains(&format!("cannot read {}", missing.display())),
        "{err}"
    );
    assert!(
        err.contains(&format!(
            "{}:{line}: field `end_effector.mass_kg`",
            bad.display()
        )),
        "{err}"
    );
    assert!(
        err.contains("1 of 3 files could not be read, 1 with problems"),
        "{err}"
    );
    // Without the unreadable one: problems found, exit 1.
    basr()
        .arg("check")
        .args([&good, &bad])
        .assert()
        .code(1)
        .stderr(predicate::str::contains("could not be read").not());
    basr().arg("check").arg(&good).assert().success();
}
