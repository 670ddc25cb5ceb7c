//! Issue 17's acceptance through the binary: for every shipped robot kind
//! the description checks ok, `compile STOP --robot F` writes its job (exit
//! 0, or 1 when its film makes it NOT READY), and the job passes `check
//! --validate-only` and `simulate --robot F` with the planner's verified
//! error within 0.75 × 6.35 mm; a sweep of words per kind; the electric
//! kinds' CSV columns; the articulated arm's tilt.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::prelude::*;

fn basr() -> Command {
    Command::cargo_bin("basr").unwrap()
}

const ROBOTS: [&str; 3] = [
    "robots/basr.toml",
    "robots/telescopic.toml",
    "robots/articulated.toml",
];

/// issue 11's verify bound: 0.75 × 1/4 in.
const BOUND_M: f64 = 0.75 * 6.35e-3;

fn robot(f: &str) -> PathBuf {
    std::fs::canonicalize(f).unwrap()
}

/// Compile `word` for `robot` into `dir`; the job's path. These tests are
/// about each kind's kinematics, not the film: a job NOT READY for its
/// film (the articulated arm's STOP, cv 0.12) exits 1 and is written all
/// the same, and is checked as any other (without searching the sizes
/// near it that paint: tests/size_advice.rs).
fn compile(dir: &Path, word: &str, robot: &Path, extra: &[&str]) -> PathBuf {
    let job = dir.join(format!("{word}.job.json"));
    let mut cmd = basr();
    cmd.args(["compile", word, "--no-size-search", "--robot"])
        .arg(robot)
        .arg("-o")
        .arg(&job)
        .args(extra);
    ran_to_verdict(&mut cmd, &job);
    job
}

/// Run a compile: exit 0, or exit 1 exactly when the job it wrote is NOT
/// READY (a problem among its warnings).
fn ran_to_verdict(cmd: &mut assert_cmd::Command, job: &Path) {
    let out = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(job.exists(), "no job written: {err}");
    let problem = json(job)["summary"]["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| w["severity"] == "problem");
    assert_eq!(out.status.code(), Some(i32::from(problem)), "{err}");
}

fn json(p: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(p).unwrap()).unwrap()
}

/// The job passes `check` and `simulate --robot F`, and compile verified it
/// within the bound; its verified error.
fn passes_check_and_simulate(job: &Path, robot: &Path) -> f64 {
    // The file alone: a NOT READY film is the film's verdict, not the
    // kinematics' (compile's exit says it).
    basr()
        .args(["check", "--validate-only"])
        .arg(job)
        .assert()
        .success()
        .stderr(predicate::str::contains(": ok"));
    let out = basr()
        .arg("simulate")
        .arg(job)
        .arg("--robot")
        .arg(robot)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}: {}",
        job.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let rep: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(rep["verdict"], "pass", "{rep}");
    let v = verified(job);
    assert!(v <= BOUND_M, "{}: verified {v} m", job.display());
    v
}

#[test]
fn every_shipped_kind_checks_compiles_stop_and_its_job_passes_check_and_simulate() {
    let dir = tempfile::tempdir().unwrap();
    for f in ROBOTS {
        basr().args(["check", f]).assert().success();
        let r = robot(f);
        let sub = dir.path().join(r.file_stem().unwrap());
        std::fs::create_dir(&sub).unwrap();
        let job = compile(&sub, "STOP", &r, &[]);
        let v = passes_check_and_simulate(&job, &r);
        eprintln!("{f}: STOP verified within {:.3} mm", v * 1e3);
    }
}

// Each electric kind its own test, and symbols apart from markings: the
// harness runs tests side by side, where one test holding every kind kept
// one core idle for a minute of CI.
#[test]
fn a_sweep_of_words_compiles_and_simulates_for_the_telescopic_kind() {
    sweep_of_words(ROBOTS[1]);
}

#[test]
fn a_sweep_of_words_compiles_and_simulates_for_the_articulated_kind() {
    sweep_of_words(ROBOTS[2]);
}

fn sweep_of_words(f: &str) {
    let dir = tempfile::tempdir().unwrap();
    let r = robot(f);
    for (i, word) in ["XING", "SCHOOL", "BUS", "AHEAD", "8"].iter().enumerate() {
        let sub = dir.path().join(format!("{i}"));
        std::fs::create_dir(&sub).unwrap();
        let job = compile(&sub, word, &r, &[]);
        passes_check_and_simulate(&job, &r);
    }
    // The ends of the letter-height range an 8 ft lane word uses.
    for h in ["1.2", "2.44"] {
        let sub = dir.path().join(format!("h{h}"));
        std::fs::create_dir(&sub).unwrap();
        let job = compile(&sub, "ONLY", &r, &["--letter-height", h]);
        passes_check_and_simulate(&job, &r);
    }
}

#[test]
fn an_electric_kinds_csv_has_its_own_joint_and_encoder_columns_and_checks_with_its_job() {
    let dir = tempfile::tempdir().unwrap();
    for (f, cols) in [
        (
            ROBOTS[1],
            "base_rot_rad,boom_rad,stroke_m,ee_yaw_rad,tilt_rad,enc_base_rot,enc_boom,enc_stroke,enc_ee_yaw,enc_tilt",
        ),
        (
            ROBOTS[2],
            "waist_rad,shoulder_rad,elbow_rad,pitch_rad,gun_tilt_rad,enc_waist,enc_shoulder,enc_elbow,enc_pitch,enc_gun_tilt",
        ),
    ] {
        let r = robot(f);
        let csv = dir.path().join("STOP.csv");
        let job = compile(dir.path(), "STOP", &r, &["--csv", csv.to_str().unwrap()]);
        let text = std::fs::read_to_string(&csv).unwrap();
        let header = text.lines().next().unwrap();
        assert!(
            header.starts_with("t_s,station,stroke,paint,") && header.ends_with(cols),
            "{header}"
        );
        // BASR's joint columns are 0 (not applicable), the kind's are not.
        let names: Vec<&str> = header.split(',').collect();
        let at = |n: &str| names.iter().position(|c| *c == n).unwrap();
        let rows: Vec<Vec<&str>> = text.lines().skip(1).map(|l| l.split(',').collect()).collect();
        assert!(rows.iter().all(|r| r[at("extension_m")] == "0"));
        assert!(rows.iter().any(|r| r[names.len() - 1] != "0"));
        basr().args(["check", "--validate-only"]).arg(&job).arg(&csv).assert().success();
        basr().arg("check").arg(&csv).assert().success();
        // An edited kind column is found.
        let edited = text.replacen(&format!("\n{}", rows[5].join(",")), &{
            let mut r = rows[5].clone();
            let last = names.len() - 2;
            r[last] = "12345";
            format!("\n{}", r.join(","))
        }, 1);
        let bad = dir.path().join("bad.csv");
        std::fs::write(&bad, edited).unwrap();
        basr()
            .arg("check")
            .arg(&job)
            .arg(&bad)
            .assert()
            .failure()
            .stderr(predicate::str::contains("row 5"));
    }
}

#[test]
fn the_articulated_arm_paints_untilted_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let r = robot(ROBOTS[2]);
    let job = compile(dir.path(), "STOP", &r, &["--tilt", "quadrilateral"]);
    let j = json(&job);
    assert_eq!(j["layout"]["tilt_method"], "none");
    // Untilted while painting (joint curves between knots lean the gun by
    // a fraction of a milliradian).
    let s = &j["samples"];
    let tilts = s["tilt_rad"].as_array().unwrap();
    let gun = s["paint"].as_array().unwrap();
    assert!(tilts
        .iter()
        .zip(gun)
        .filter(|(_, g)| g.as_u64() == Some(1))
        .all(|(t, _)| t.as_f64().unwrap().abs() < 1e-3));
    let says = j["summary"]["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| {
            w["message"]
                .as_str()
                .unwrap()
                .contains("--tilt quadrilateral is painted as --tilt none")
        });
    assert!(says, "{}", j["summary"]["warnings"]);
    // The telescopic head tilts as BASR's does.
    let t = compile(dir.path(), "STOP", &robot(ROBOTS[1]), &[]);
    let tilts = json(&t)["samples"]["tilt_rad"].clone();
    assert!(tilts
        .as_array()
        .unwrap()
        .iter()
        .any(|t| t.as_f64().unwrap().abs() > 0.01));
}

#[test]
fn a_job_checked_or_simulated_against_another_kind_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let job = compile(dir.path(), "IT", &robot(ROBOTS[1]), &[]);
    basr()
        .arg("simulate")
        .arg(&job)
        .arg("--robot")
        .arg(robot(ROBOTS[2]))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("another robot description"));
    // The hydraulic-only options are refused for an electric kind.
    basr()
        .arg("simulate")
        .arg(&job)
        .arg("--robot")
        .arg(robot(ROBOTS[1]))
        .arg("--plants")
        .arg("5")
        .assert()
        .code(2)
        .stderr(predicate::str::contains("telescopic kind"));
}

/// The verified error compile recorded for a job (issue 11's guarantee).
fn verified(job: &Path) -> f64 {
    json(job)["summary"]["verified_max_error_m"]
        .as_f64()
        .expect("compile verified the job")
}

#[test]
fn every_library_symbol_compiles_verified_for_the_telescopic_kind() {
    symbols_compile_verified(ROBOTS[1]);
}

#[test]
fn every_library_symbol_compiles_verified_for_the_articulated_kind() {
    symbols_compile_verified(ROBOTS[2]);
}

#[test]
fn every_shipped_marking_compiles_verified_for_the_telescopic_kind() {
    markings_compile_verified(ROBOTS[1]);
}

#[test]
fn every_shipped_marking_compiles_verified_for_the_articulated_kind() {
    markings_compile_verified(ROBOTS[2]);
}

fn symbols_compile_verified(f: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = basr().arg("symbols").output().unwrap();
    let list = String::from_utf8(out.stdout).unwrap() + &String::from_utf8(out.stderr).unwrap();
    let symbols: Vec<&str> = list
        .lines()
        .skip(1)
        .filter(|l| l.starts_with(|c: char| c.is_ascii_lowercase()))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert!(symbols.len() >= 15, "{symbols:?}");
    let r = robot(f);
    for s in &symbols {
        let job = dir.path().join(format!("{s}.job.json"));
        ran_to_verdict(
            basr()
                .args(["compile", "--symbol", s, "--robot"])
                .arg(&r)
                .arg("-o")
                .arg(&job),
            &job,
        );
        assert!(verified(&job) <= BOUND_M, "{f} {s}");
    }
}

fn markings_compile_verified(f: &str) {
    let dir = tempfile::tempdir().unwrap();
    let markings: Vec<PathBuf> = std::fs::read_dir("markings")
        .unwrap()
        .map(|e| std::fs::canonicalize(e.unwrap().path()).unwrap())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    assert!(markings.len() >= 5, "{markings:?}");
    let r = robot(f);
    for m in &markings {
        let job = dir
            .path()
            .join(m.file_stem().unwrap())
            .with_extension("job.json");
        ran_to_verdict(
            basr()
                .args(["compile", "--no-size-search", "--marking"])
                .arg(m)
                .arg("--robot")
                .arg(&r)
                .arg("-o")
                .arg(&job),
            &job,
        );
        assert!(verified(&job) <= BOUND_M, "{f} {}", m.display());
    }
}

#[test]
fn preview_and_preview_from_sim_draw_every_electric_kinds_job() {
    let dir = tempfile::tempdir().unwrap();
    for f in &ROBOTS[1..] {
        let job = compile(dir.path(), "STOP", &robot(f), &[]);
        for from_sim in [false, true] {
            let svg = dir.path().join("p.svg");
            let mut cmd = basr();
            cmd.arg("preview")
                .arg(&job)
                .arg("-o")
                .arg(&svg)
                .arg("--json");
            if from_sim {
                cmd.arg("--from-sim");
            }
            let out = cmd.output().unwrap();
            // 0 or 1 (the film verdict), never bad input.
            assert!(
                matches!(out.status.code(), Some(0 | 1)),
                "{f}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            let p: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            assert_eq!(p["from_sim"], from_sim);
            // The arm follows its job closely: the simulated film covers the
            // letters as the planned one does.
            assert!(p["coverage"].as_f64().unwrap() > 0.97, "{f}: {p}");
            assert!(std::fs::metadata(&svg).unwrap().len() > 1000);
        }
    }
}

/// `check`'s content checks of an electric kind's job (library call, as
/// `basr check` makes it): a compiled job has none; a joint that jumps, a
/// BASR column written in, a renamed column and a wrong encoder count are
/// each found.
#[test]
fn check_finds_what_is_wrong_with_an_electric_kinds_setpoints() {
    use basr::pipeline::compile::{compile_job, CompileRequest};
    let robot = basr::robot::AnyRobot::load(Path::new(ROBOTS[2])).unwrap();
    let mut req = CompileRequest::message("IT");
    req.robot_description = Some(robot);
    let job = compile_job(&req).unwrap();
    assert_eq!(basr::job::verify::problems(&job, "j"), Vec::<String>::new());
    let k = job.samples.len() / 2;
    let damaged = |edit: &dyn Fn(&mut basr::job::Job)| {
        let mut j = job.clone();
        edit(&mut j);
        basr::job::verify::problems(&j, "j").join("\n")
    };
    let p = damaged(&|j| j.samples.kind_joints[k][1] += 0.05);
    assert!(p.contains("shoulder_rad moves at"), "{p}");
    assert!(
        p.contains("away from where the joints put the nozzle"),
        "{p}"
    );
    let p = damaged(&|j| j.samples.extension_m[k] = 1.0);
    assert!(
        p.contains("extension_m is 1 but it is BASR's column"),
        "{p}"
    );
    let p = damaged(&|j| j.samples.kind_columns[0] = "base_rot_rad".into());
    assert!(p.contains("samples.kind_columns"), "{p}");
    let p = damaged(&|j| j.samples.kind_encoders[k][4] += 1);
    assert!(p.contains(&format!("row {k}: encoder counts")), "{p}");
}

/// An electric kind's station verified alone reports its worst error at a
/// time within the station's own rows: its servo plant reads the rows'
/// own job times (the verification once added the station's start to them
/// again, placing a later station's worst error past its end).
#[test]
fn an_electric_station_verified_alone_reports_job_time() {
    use basr::pipeline::compile::{compile_job, CompileRequest};
    let job = compile_job(&CompileRequest {
        robot: Some(robot("robots/telescopic.toml")),
        ..CompileRequest::message("SCHOOL XING")
    })
    .expect("compiles");
    let s = &job.samples;
    let first = s
        .station
        .iter()
        .position(|&st| st == 1)
        .expect("a second station");
    let last = s.station.iter().rposition(|&st| st == 1).unwrap();
    let mut alone = job.clone();
    alone.samples = s.rows(first..last + 1);
    let t0 = first as f64 * job.control_period_s;
    let v = basr::pipeline::verify::simulated(&alone, t0).expect("simulates");
    assert!(
        (s.t_s[first] - 1e-9..=s.t_s[last] + 1e-9).contains(&v.worst_t_s),
        "worst at {} s, the station's rows run {}–{} s",
        v.worst_t_s,
        s.t_s[first],
        s.t_s[last]
    );
}
