//! `basr preview --from-sim`: the film of the simulated arm, end to end.

use assert_cmd::Command;

fn basr(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    Command::cargo_bin("basr")
        .unwrap()
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn from_sim_previews_the_film_the_arm_lays() {
    let dir = tempfile::tempdir().unwrap();
    let out = basr(dir.path(), &["compile", "L", "-q"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = basr(
        dir.path(),
        &[
            "preview",
            "L.job.json",
            "--from-sim",
            "--json",
            "-o",
            "sim.svg",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let coverage = v["coverage"].as_f64().unwrap();
    let laid = v["volume_laid_m3"].as_f64().unwrap();
    // The arm tracks within millimetres, so the letter is still covered and
    // paint was laid; a broken pose conversion (wrong frame, gun never on)
    // would drop coverage to near zero.
    assert!(coverage > 0.9, "coverage {coverage}");
    assert!(laid > 0.0);
    assert!(dir.path().join("sim.svg").exists());
}

#[test]
fn from_sim_and_compare_do_not_combine() {
    let dir = tempfile::tempdir().unwrap();
    let out = basr(
        dir.path(),
        &["preview", "x.job.json", "--from-sim", "--compare", "none"],
    );
    assert_eq!(out.status.code(), Some(2));
}
