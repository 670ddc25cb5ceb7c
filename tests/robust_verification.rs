//! Issue 28's guarantee through the binary: the job `basr compile STOP`
//! writes records what it was verified on beyond the robot description
//! (`summary.verified`: six plants, spread 0.1, seed 1, each within
//! 0.75 × 6.35 mm), and passes `basr simulate --plants 40 --spread 0.1`
//! for other seeds than the one compile drew; an electric kind's job,
//! whose servo plant has no drawn numbers, records none.
//!
//! The sweep over every shipped marking, symbol and seeds 1–10 costs half
//! an hour of simulation: `scripts/robust-sweep.sh` runs it (release
//! build); its figures are in docs/simulate.md.

use assert_cmd::Command;

fn basr() -> Command {
    Command::cargo_bin("basr").unwrap()
}

/// The agency's tolerance (1/4 in) and compile's share of it.
const TOLERANCE_M: f64 = 6.35e-3;
const SHARE: f64 = 0.75;

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

#[test]
fn stop_is_verified_on_the_spread_and_passes_forty_plants_of_other_seeds() {
    let dir = tempfile::tempdir().unwrap();
    basr()
        .current_dir(dir.path())
        .args(["compile", "STOP", "-q"])
        .assert()
        .code(0);
    let job = dir.path().join("STOP.job.json");
    let v = json(&job)["summary"]["verified"].clone();
    assert_eq!(v["plants"], 6, "{v}");
    assert_eq!(v["spread"], 0.1, "{v}");
    assert_eq!(v["seed"], 1, "{v}");
    let (p95, max) = (
        v["p95_max_error_m"].as_f64().unwrap(),
        v["max_error_m"].as_f64().unwrap(),
    );
    assert!(p95 <= max && max <= SHARE * TOLERANCE_M, "{v}");
    // the description's own figure is kept beside it
    let nominal = json(&job)["summary"]["verified_max_error_m"]
        .as_f64()
        .unwrap();
    assert!(nominal > 0.0 && nominal <= SHARE * TOLERANCE_M);
    for seed in ["2", "7"] {
        let out = basr()
            .current_dir(dir.path())
            .args([
                "simulate",
                "STOP.job.json",
                "--plants",
                "40",
                "--spread",
                "0.1",
            ])
            .args(["--seed", seed, "--json"])
            .output()
            .unwrap();
        let r: serde_json::Value = serde_json::from_slice(&out.stdout)
            .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
        let p = &r["plants"];
        assert_eq!(r["verdict_on"], "plants_p95", "{r}");
        assert!(
            p["p95_max_error_m"].as_f64().unwrap() <= TOLERANCE_M,
            "seed {seed}: {p}"
        );
        assert_eq!(out.status.code(), Some(0), "seed {seed}: {p}");
    }
}

#[test]
fn an_electric_kinds_job_records_no_plant_set() {
    let dir = tempfile::tempdir().unwrap();
    let robot = std::fs::canonicalize("robots/telescopic.toml").unwrap();
    let out = basr()
        .current_dir(dir.path())
        .args(["compile", "STOP", "-q", "--robot"])
        .arg(&robot)
        .output()
        .unwrap();
    assert!(
        matches!(out.status.code(), Some(0 | 1)),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s = &json(&dir.path().join("STOP.job.json"))["summary"];
    assert!(s["verified_max_error_m"].as_f64().is_some(), "{s}");
    assert!(s.get("verified").is_none(), "{s}");
}

/// A station compile keeps with a plant of the set over the bound (only a
/// slower path for the whole station would help: glyph C at 3.5 m, its
/// join into stroke 0 already at the slowest re-timing) says so
/// where the crew reads: an `arm` notice naming the stop and the plant,
/// beside `summary.verified.over`.
#[test]
fn a_plant_kept_over_the_bound_is_a_notice() {
    use basr::pipeline::compile::{compile_job, CompileRequest};
    let job = compile_job(&CompileRequest {
        overrides: basr::layout::Overrides {
            letter_height_m: Some(3.5),
            ..Default::default()
        },
        ..CompileRequest::message("C")
    })
    .unwrap();
    let over = job
        .summary
        .verified
        .as_ref()
        .and_then(|v| v.over.clone())
        .expect("C at 3.5 m is kept with a plant over the bound");
    let arm: Vec<&basr::job::Warning> = job
        .summary
        .warnings
        .iter()
        .filter(|w| w.kind == basr::job::WarningKind::Arm)
        .collect();
    assert_eq!(arm.len(), 1, "{:?}", job.summary.warnings);
    assert_eq!(arm[0].graded(), basr::job::Severity::Notice);
    assert!(arm[0].message.starts_with("stop 1: "), "{}", arm[0].message);
    assert!(arm[0].message.contains(&over), "{}", arm[0].message);
    assert!(arm[0].message.contains("--plants 40"), "{}", arm[0].message);
    // STOP keeps every plant within: no such notice
    let stop = compile_job(&CompileRequest::message("STOP")).unwrap();
    assert!(stop
        .summary
        .warnings
        .iter()
        .all(|w| w.kind != basr::job::WarningKind::Arm));
}

/// D at 12 ft once needed a re-timing that the robot's own check refused:
/// every join into its stroke 1 slowed to 8 % of the accelerations
/// carried the tilt's ball nut past its speed, and compile kept the last
/// pace (`not_taken` in `pipeline::planned_job`, which stays for such a
/// case). Now the verification slows only the join into the pass the arm
/// arrived late at (stroke 1's third here), and no slowed motion breaks a
/// limit: the job is written with the join paces naming their passes, and
/// a plant of the set still over the bound is kept for what only a slower
/// path for the whole station would help.
#[test]
fn a_late_arrival_slows_the_join_into_that_pass() {
    use basr::pipeline::compile::{compile_job, CompileRequest};
    let job = compile_job(&CompileRequest {
        overrides: basr::layout::Overrides {
            letter_height_m: Some(12.0 * 0.3048),
            ..Default::default()
        },
        ..CompileRequest::message("D")
    })
    .expect("D at 12 ft compiles");
    let stop = &job.summary.stops[0];
    assert!(
        stop.join_paces
            .iter()
            .any(|j| j.stroke == 1 && j.pass == Some(2) && j.share < 0.1),
        "{:?}",
        stop.join_paces
    );
    let over = job
        .summary
        .verified
        .as_ref()
        .and_then(|v| v.over.clone())
        .expect("D at 12 ft is kept with a plant over the bound");
    assert!(
        !over.contains("breaks a limit")
            && over.contains("only a slower path for the whole station would help"),
        "{over}"
    );
    // the description itself is within the bound
    assert!(job.summary.verified_max_error_m.unwrap() <= SHARE * TOLERANCE_M);
}
