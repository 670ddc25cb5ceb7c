//! `basr preview --from-sim`: the film of the simulated arm, end to end.

mod common;
use common::{basr, succeeded};

#[path = "preview_common/mod.rs"]
mod preview_common;

#[test]
fn from_sim_previews_the_film_the_arm_lays() {
    let dir = tempfile::tempdir().unwrap();
    succeeded(basr(dir.path(), &["compile", "L", "-q"]));
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
    preview_common::assert_ran_to_a_verdict(&out);
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
fn from_sim_u_stays_near_the_compiled_jobs() {
    // The arm tracks STOP within millimetres, so the tile ratio of the film
    // it lays is close to the planned one (0.466–0.534); tiles between 5 ms
    // trace ticks spanned 0.00–1.00.
    let dir = tempfile::tempdir().unwrap();
    let out = basr(dir.path(), &["compile", "STOP", "-q"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let u = |extra: &[&str]| -> (f64, f64) {
        let mut args = vec!["preview", "STOP.job.json", "--json", "-o", "p.svg"];
        args.extend_from_slice(extra);
        let out = basr(dir.path(), &args);
        assert!(
            preview_common::ran_to_a_verdict(&out),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        (v["u_min"].as_f64().unwrap(), v["u_max"].as_f64().unwrap())
    };
    let planned = u(&[]);
    let simulated = u(&["--from-sim"]);
    assert!(
        (planned.0 - simulated.0).abs() <= 0.1 && (planned.1 - simulated.1).abs() <= 0.1,
        "U {planned:?} planned, {simulated:?} from the simulated arm"
    );
}

#[test]
fn from_sim_and_compare_do_not_combine() {
    let dir = tempfile::tempdir().unwrap();
    // A real job, so the refusal can only be the options' (a missing job
    // is refused with exit 2 too).
    succeeded(basr(dir.path(), &["compile", "L", "-q"]));
    let out = basr(
        dir.path(),
        &["preview", "L.job.json", "--from-sim", "--compare", "none"],
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--from-sim") && err.contains("--compare"),
        "the refusal names both options: {err}"
    );
    assert!(!dir.path().join("L.svg").exists(), "no preview written");
}
