//! The planner keeps the extension cylinder clear of its end stop: no
//! setpoint of a full-reach job asks for more than the stroke less
//! `arm.cylinder_stroke_margin_m` (robots/basr.toml), the simulated arm
//! stays short of the stop too, and a job that would need the margin is
//! refused with the reach named (issue 11).

use assert_cmd::Command;

fn basr() -> Command {
    Command::cargo_bin("basr").expect("the basr binary is built")
}

/// BASR's stroke and the margin (robots/basr.toml).
const STROKE_M: f64 = 0.457;
const MARGIN_M: f64 = 0.00635;

fn max_of(v: &serde_json::Value) -> f64 {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .fold(f64::MIN, f64::max)
}

#[test]
fn full_reach_jobs_stay_the_margin_short_of_the_end_stop() {
    for args in [
        ["I", "--letter-height", "3.6"],
        ["STOP", "--letter-height", "3.6"],
    ] {
        let dir = tempfile::tempdir().unwrap();
        let job = dir.path().join("j.job.json");
        basr()
            .arg("compile")
            .args(args)
            .arg("-o")
            .arg(&job)
            .arg("-q")
            .assert()
            .success();
        let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&job).unwrap()).unwrap();
        let cyl = max_of(&v["samples"]["cylinder_m"]);
        assert!(
            cyl <= STROKE_M - MARGIN_M + 1e-9,
            "{args:?}: setpoint {cyl} m of cylinder"
        );
        // Near full reach: the margin is what binds, not a smaller reach.
        assert!(cyl > STROKE_M - 4.0 * MARGIN_M, "{args:?}: only {cyl} m");
        // The simulated arm, lagging or overshooting, stays off the stop.
        let trace = dir.path().join("t.csv");
        basr()
            .arg("simulate")
            .arg(&job)
            .arg("--trace")
            .arg(&trace)
            .arg("-q")
            .assert()
            .success();
        let text = std::fs::read_to_string(&trace).unwrap();
        let mut lines = text.lines();
        let head: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = head.iter().position(|h| *h == "extension_m").unwrap();
        let peak = lines
            .map(|l| l.split(',').nth(col).unwrap().parse::<f64>().unwrap())
            .fold(f64::MIN, f64::max);
        let peak_cyl = (peak - 1.55) / (25.0 / 3.0);
        assert!(
            peak_cyl < STROKE_M - 0.5 * MARGIN_M,
            "{args:?}: simulated {peak_cyl} m"
        );
    }
}

#[test]
fn a_job_that_needs_the_margin_is_refused_with_the_reach_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = basr()
        .current_dir(dir.path())
        .args(["compile", "I", "--letter-height", "4", "-q"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("outside the arm's reach"), "{err}");
    assert!(
        std::fs::read_dir(dir.path()).unwrap().next().is_none(),
        "a job was left"
    );
}
