//! End-to-end tests of `basr simulate` through the binary, on synthetic jobs.

use assert_cmd::Command;
use basr::sim::synthetic;
use predicates::prelude::*;

fn write_job(dir: &tempfile::TempDir, name: &str, job: &basr::job::Job) -> std::path::PathBuf {
    let p = dir.path().join(name);
    job.write(&p).unwrap();
    p
}

fn basr() -> Command {
    Command::cargo_bin("basr").unwrap()
}

#[test]
fn letter_job_passes_with_json_report() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(&dir, "letter.job.json", &synthetic::letter_job());
    let out = basr()
        .arg("simulate")
        .arg(&job)
        .arg("--json")
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["verdict"], "pass");
    let max = v["max_error_m"].as_f64().unwrap();
    let rms = v["rms_error_m"].as_f64().unwrap();
    assert!(max > 0.0 && max < 6.35e-3, "{max}");
    assert!(rms > 0.0 && rms <= max);
    assert_eq!(v["strokes"].as_array().unwrap().len(), 4);
    assert!(out.stderr.is_empty(), "--json keeps stderr quiet");
}

#[test]
fn tiny_tolerance_fails_with_exit_1_and_says_where() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(&dir, "letter.job.json", &synthetic::letter_job());
    basr()
        .arg("simulate")
        .arg(&job)
        .args(["--tolerance-mm", "0.001"])
        .assert()
        .code(1)
        .stderr(predicate::str::contains("FAIL").and(predicate::str::contains("stroke")));
}

#[test]
fn a_step_in_the_setpoints_is_refused_by_simulate_and_fails_in_the_library() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(&dir, "step.job.json", &synthetic::step_job());
    // the binary runs `check`'s content checks first: a 20 mm step breaks
    // the joints' acceleration limits, and simulate says so (exit 2)
    basr()
        .arg("simulate")
        .arg(&job)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("acceleration limit"));
    // simulated anyway (the library does not check), it fails and says where
    let stepped = synthetic::step_job();
    let r = basr::sim::simulate(
        &stepped,
        &basr::sim::SimModel::basr(),
        &basr::sim::Options::default(),
        &mut |_, _| {},
    )
    .unwrap()
    .report;
    assert_eq!(r.verdict, basr::sim::report::Verdict::Fail);
    // the step is halfway through stroke 0
    assert_eq!(r.worst.stroke, 0);
    assert!(r.max_error_m > 0.01);
    // and the worst moment is the arm catching up with it: within a fraction
    // of a second after the first stepped row (the reference starts to move
    // towards it one row, 32 ms, earlier)
    let plain = synthetic::letter_job();
    let first = (0..plain.samples.len())
        .find(|&i| plain.samples.y_m[i] != stepped.samples.y_m[i])
        .unwrap();
    let t_step = stepped.samples.t_s[first];
    let t_worst = r.worst.t_s;
    assert!(
        t_worst >= t_step - stepped.control_period_s && t_worst <= t_step + 0.3,
        "worst at {t_worst} s, step at {t_step} s"
    );
}

#[test]
fn setpoints_at_a_limit_are_not_failed_by_the_interpolation_between_them() {
    // Every extension setpoint is within reach, the first ones exactly at its
    // lower limit; the reference between rows must not dip below it, and the
    // setpoint limit is judged on the rows themselves.
    let dir = tempfile::tempdir().unwrap();
    let job = synthetic::retracted_then_extending_job();
    let r_min = job.robot.basr().unwrap().limits.extension_m.min;
    assert!(job.samples.extension_m.iter().all(|&r| r >= r_min - 1e-12));
    let p = write_job(&dir, "retracted.job.json", &job);
    let csv = dir.path().join("tr.csv");
    let out = basr()
        .arg("simulate")
        .arg(&p)
        .arg("--json")
        .arg("--trace")
        .arg(&csv)
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let kinds: Vec<&str> = v["limits"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["kind"].as_str().unwrap())
        .collect();
    assert!(
        !kinds.contains(&"setpoint_extension"),
        "{kinds:?}: {}",
        v["reasons"]
    );
    let mut rd = csv::Reader::from_path(&csv).unwrap();
    let col = rd
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == "extension_desired_m")
        .unwrap();
    let lowest = rd
        .records()
        .map(|r| r.unwrap()[col].parse::<f64>().unwrap())
        .fold(f64::INFINITY, f64::min);
    assert!(
        lowest >= r_min - 1e-9,
        "reference dipped to {lowest} below {r_min}"
    );
}

#[test]
fn an_empty_or_cut_job_is_named_once_and_as_what_it_is() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.job.json");
    std::fs::write(&empty, "").unwrap();
    let cut = dir.path().join("cut.job.json");
    std::fs::write(&cut, "{\"format\": \"basr-job\", \"samp").unwrap();
    for (job, says) in [(&empty, "is empty"), (&cut, "truncated")] {
        let out = basr().arg("simulate").arg(job).output().unwrap();
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{err}");
        assert!(
            !err.contains("is empty") || !err.contains("truncated"),
            "{err}"
        );
        assert!(
            err.matches("EOF while parsing").count() <= 1,
            "said twice: {err}"
        );
    }
}

#[test]
fn hand_edited_job_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(&dir, "letter.job.json", &synthetic::letter_job());
    let text = std::fs::read_to_string(&job).unwrap();
    let edited = text.replacen(
        "\"control_period_s\": 0.032",
        "\"control_period_s\": 0.033",
        1,
    );
    assert_ne!(edited, text);
    std::fs::write(&job, edited).unwrap();
    basr()
        .arg("simulate")
        .arg(&job)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("integrity"));
}

#[test]
fn job_for_another_robot_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let mut job = synthetic::letter_job();
    // change one value of the embedded robot description and reseal: a job
    // that is internally consistent but for a different robot
    let mut v = serde_json::to_value(&job.robot).unwrap();
    fn bump(v: &mut serde_json::Value) -> bool {
        match v {
            serde_json::Value::String(s) => {
                s.push('X');
                true
            }
            serde_json::Value::Number(n) => {
                *v = serde_json::json!(n.as_f64().unwrap() * 1.5 + 1.0);
                true
            }
            serde_json::Value::Object(m) => m.values_mut().any(bump),
            serde_json::Value::Array(a) => a.iter_mut().any(bump),
            _ => false,
        }
    }
    assert!(bump(&mut v));
    job.robot = serde_json::from_value(v).unwrap();
    job.seal();
    let p = write_job(&dir, "other.job.json", &job);
    basr()
        .arg("simulate")
        .arg(&p)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("another robot"));
}

#[test]
fn trace_and_svg_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(&dir, "letter.job.json", &synthetic::letter_job());
    let csv = dir.path().join("t.csv");
    let svg = dir.path().join("t.svg");
    basr()
        .arg("simulate")
        .arg(&job)
        .arg("--quiet")
        .arg("--trace")
        .arg(&csv)
        .arg("--svg")
        .arg(&svg)
        .assert()
        .code(0)
        .stderr(predicate::str::is_empty());
    let text = std::fs::read_to_string(&csv).unwrap();
    let header = text.lines().next().unwrap();
    assert!(header.starts_with("t_s,station,stroke,paint,x_desired_m,y_desired_m,x_m,y_m,error_m"));
    assert!(text.lines().count() > 1000);
    let s = std::fs::read_to_string(&svg).unwrap();
    let tree = resvg::usvg::Tree::from_str(&s, &Default::default()).unwrap();
    assert!(tree.size().width() > 100.0);
    // Axes with units on both plots, the worst point marked on both, and the
    // desired path drawn before (under) the actual one, so both show.
    for label in [
        "x (m)",
        "y (m)",
        "time (s)",
        "nozzle error (mm)",
        "tolerance 6.35 mm",
    ] {
        assert!(s.contains(label), "no {label:?}");
    }
    assert!(
        s.matches("<circle").count() >= 3,
        "worst marked on both plots and in the legend"
    );
    assert_eq!(
        s.matches("worst while painting: ").count(),
        2,
        "in the legend and on the error plot"
    );
    let (desired, actual) = (s.find("#1f77b4").unwrap(), s.find("#d62728").unwrap());
    assert!(
        desired < actual,
        "the desired path must not be drawn over by the actual"
    );
}

#[test]
fn failed_output_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("t.csv");
    basr()
        .arg("simulate")
        .arg(dir.path().join("missing.job.json"))
        .arg("--trace")
        .arg(&csv)
        .assert()
        .code(2);
    assert!(!csv.exists());
}

#[test]
fn a_failed_svg_removes_the_trace_written_before_it() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(&dir, "letter.job.json", &synthetic::letter_job());
    let csv = dir.path().join("tr.csv");
    basr()
        .current_dir(dir.path())
        .arg("simulate")
        .arg(&job)
        .arg("--trace")
        .arg(&csv)
        .arg("--svg")
        .arg(dir.path().join("no-such-folder").join("x.svg"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("x.svg"));
    let mut left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["letter.job.json"], "no trace, no temporary file");
}

#[test]
fn robot_with_impossible_dynamics_exits_2_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let job = write_job(&dir, "letter.job.json", &synthetic::letter_job());
    let text = basr::robot::BASR_TOML.replace("cylinder_rod_m = 0.034925", "cylinder_rod_m = 0.09");
    assert_ne!(text, basr::robot::BASR_TOML);
    let robot = dir.path().join("bad.toml");
    std::fs::write(&robot, text).unwrap();
    basr()
        .arg("simulate")
        .arg(&job)
        .arg("--robot")
        .arg(&robot)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("dynamics.cylinder_rod_m"));
}
