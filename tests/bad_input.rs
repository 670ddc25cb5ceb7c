//! The bad-input battery (issue 7): every case runs the binary as a user
//! would and asserts exit code 2, a message that names the problem and the
//! fix, and that no output file is left behind.

use std::path::{Path, PathBuf};

use assert_cmd::Command;

/// A scratch folder holding only the inputs a case writes.
struct Scratch {
    dir: tempfile::TempDir,
    inputs: Vec<PathBuf>,
}

impl Scratch {
    fn new() -> Scratch {
        Scratch {
            dir: tempfile::tempdir().unwrap(),
            inputs: vec![],
        }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// Write an input file the case needs.
    fn input(&mut self, name: &str, bytes: &[u8]) -> PathBuf {
        let p = self.path(name);
        std::fs::write(&p, bytes).unwrap();
        self.inputs.push(p.clone());
        p
    }

    /// Run `basr args…` in the folder; assert exit 2, that stderr holds every
    /// `needles` (case-insensitive), and that no file besides the inputs exists.
    fn refuses(&self, args: &[&str], needles: &[&str]) -> String {
        let out = Command::cargo_bin("basr")
            .unwrap()
            .current_dir(self.dir.path())
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        assert_eq!(
            out.status.code(),
            Some(2),
            "basr {args:?} should exit 2; stderr:\n{stderr}"
        );
        assert!(out.stdout.is_empty(), "nothing on stdout for an error");
        let lower = stderr.to_lowercase();
        for n in needles {
            assert!(
                lower.contains(&n.to_lowercase()),
                "stderr of basr {args:?} should mention {n:?}:\n{stderr}"
            );
        }
        self.assert_only_inputs();
        stderr
    }

    fn assert_only_inputs(&self) {
        let mut extra = vec![];
        for e in std::fs::read_dir(self.dir.path()).unwrap() {
            let p = e.unwrap().path();
            if !self.inputs.contains(&p) {
                extra.push(p);
            }
        }
        assert!(extra.is_empty(), "files left behind: {extra:?}");
    }
}

fn basr_toml() -> String {
    let out = Command::cargo_bin("basr")
        .unwrap()
        .args(["robot", "--toml"])
        .output()
        .unwrap();
    assert!(out.status.success());
    String::from_utf8(out.stdout).unwrap()
}

/// Replace the first line starting with `key =` (after trimming) by `key = value`.
fn set_key(toml: &str, key: &str, value: &str) -> String {
    let mut done = false;
    let lines: Vec<String> = toml
        .lines()
        .map(|l| {
            let t = l.trim_start();
            if !done && t.starts_with(key) && t[key.len()..].trim_start().starts_with('=') {
                done = true;
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect();
    assert!(done, "key {key} not found in the robot description");
    lines.join("\n")
}

#[test]
fn unsupported_character_is_named_with_its_position() {
    Scratch::new().refuses(&["compile", "ST@P"], &["'@'", "position 3", "A–Z"]);
}

#[test]
fn empty_message_is_refused() {
    Scratch::new().refuses(&["compile", ""], &["empty"]);
    Scratch::new().refuses(&["compile", "   "], &["empty"]);
}

#[test]
fn no_message_and_no_marking_is_refused() {
    Scratch::new().refuses(&["compile"], &["message"]);
}

#[test]
fn message_wider_than_the_lane_names_both_widths() {
    Scratch::new().refuses(
        &["compile", "STOPSTOPSTOP"],
        &["wide", "lane", "--lane-width"],
    );
}

/// 10 000 characters, as one word or as 2 000 lines that each fit the lane,
/// are refused at once (the letter cap) rather than planned for hours in
/// gigabytes of memory; so is a marking file of hundreds of lines.
#[test]
fn enormous_message_is_refused_quickly() {
    let long = "A".repeat(10_000);
    Scratch::new().refuses(&["compile", &long], &["10000 letters", "at most 200"]);
    let many_lines = vec!["STOP"; 2_000].join(" ");
    assert_eq!(many_lines.len(), 9_999);
    Scratch::new().refuses(
        &["compile", &many_lines],
        &["8000 letters", "split it into several jobs"],
    );
    let mut s = Scratch::new();
    let lines = vec!["\"STOP\""; 500].join(", ");
    s.input(
        "long.toml",
        format!("[marking]\nlines = [{lines}]\n").as_bytes(),
    );
    s.refuses(
        &["compile", "--marking", "long.toml"],
        &["long.toml", "2000 letters"],
    );
}

#[test]
fn missing_marking_file_is_named() {
    Scratch::new().refuses(
        &["compile", "--marking", "nowhere.toml"],
        &["nowhere.toml", "cannot read"],
    );
}

#[test]
fn empty_marking_file_is_refused() {
    let mut s = Scratch::new();
    s.input("empty.toml", b"");
    s.refuses(&["compile", "--marking", "empty.toml"], &["empty.toml"]);
}

#[test]
fn malformed_marking_toml_gives_line_and_column() {
    let mut s = Scratch::new();
    s.input("bad.toml", b"[marking]\nlines = [\"STOP\"\nname = 3\n");
    s.refuses(&["compile", "--marking", "bad.toml"], &["bad.toml", "line"]);
}

#[test]
fn unknown_marking_key_is_named_with_line() {
    let mut s = Scratch::new();
    s.input(
        "m.toml",
        b"[marking]\nlines = [\"STOP\"]\ncolour = \"red\"\n",
    );
    s.refuses(
        &["compile", "--marking", "m.toml"],
        &["m.toml", "line 3", "colour"],
    );
}

#[test]
fn non_utf8_marking_is_refused() {
    let mut s = Scratch::new();
    s.input("latin1.toml", b"[marking]\nlines = [\"STRA\xdfE\"]\n");
    s.refuses(&["compile", "--marking", "latin1.toml"], &["utf-8"]);
}

#[cfg(unix)]
#[test]
fn non_utf8_message_argument_is_refused() {
    use std::os::unix::ffi::OsStrExt;
    let s = Scratch::new();
    let out = Command::cargo_bin("basr")
        .unwrap()
        .current_dir(s.dir.path())
        .arg("compile")
        .arg(std::ffi::OsStr::from_bytes(b"ST\xffP"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr)
        .to_lowercase()
        .contains("utf-8"));
    s.assert_only_inputs();
}

#[test]
fn unknown_option_is_a_usage_error() {
    Scratch::new().refuses(&["compile", "STOP", "--colour", "red"], &["--colour"]);
}

#[test]
fn negative_and_nan_letter_height_are_refused() {
    Scratch::new().refuses(&["compile", "STOP", "--letter-height=-2"], &["letter"]);
    Scratch::new().refuses(&["compile", "STOP", "--letter-height", "NaN"], &["letter"]);
    Scratch::new().refuses(&["compile", "STOP", "--lane-width", "inf"], &["lane"]);
}

/// A number given as its own argument (`--letter-height -2`, not `=-2`)
/// reaches our validation instead of clap's "use '-- -2'" tip.
#[test]
fn negative_and_non_finite_numbers_as_separate_arguments_reach_validation() {
    let cases: [(&[&str], &[&str]); 7] = [
        (
            &["compile", "STOP", "--letter-height", "-2"],
            &["letter height", "above zero", "got -2 m"],
        ),
        (
            &["compile", "STOP", "--letter-height", "-inf"],
            &["letter height", "got -inf"],
        ),
        (
            &["compile", "STOP", "--lane-width", "NaN"],
            &["lane width", "got NaN"],
        ),
        (
            &["compile", "STOP", "--period-s", "-1e-3"],
            &["--period-s", "above zero"],
        ),
        (
            &["compile", "STOP", "--gun-lag-s", "-0.1"],
            &["--gun-lag-s", "zero or more"],
        ),
        (
            &["workspace", "--yaw-deg", "inf"],
            &["--yaw-deg", "finite", "got inf"],
        ),
        (
            &["pose", "0", "3", "--tilt-deg", "-inf"],
            &["tilt", "not a finite number"],
        ),
    ];
    for (args, needles) in cases {
        let err = Scratch::new().refuses(args, needles);
        assert!(!err.contains("tip:"), "clap's tip, not our message:\n{err}");
    }
    // A line gap or anchor far beyond one site (10³⁰⁰ m overflowed the planner).
    Scratch::new().refuses(
        &["compile", "A B", "--line-gap", "1e300"],
        &["line gap", "more than 1000 m"],
    );
    // Positive but so fine that the work would not fit in memory.
    Scratch::new().refuses(
        &["compile", "STOP", "--rung-spacing-mm", "1e-6"],
        &["--rung-spacing-mm", "1 mm minimum"],
    );
    Scratch::new().refuses(
        &["compile", "STOP", "--period-s", "1e-7"],
        &["--period-s", "at least 0.005"],
    );
    let mut s = Scratch::new();
    write_job(&mut s, "j.job.json", |_| {});
    s.refuses(
        &["preview", "j.job.json", "--resolution-mm", "-2"],
        &["--resolution-mm", "above zero"],
    );
    s.refuses(
        &["simulate", "j.job.json", "--tolerance-mm", "-1"],
        &["--tolerance-mm", "positive"],
    );
    s.refuses(
        &["simulate", "j.job.json", "--tolerance-mm", "inf"],
        &["--tolerance-mm", "positive"],
    );
}

/// Cells kilometres wide once made the SVG's axes loop for ever over tick
/// labels; a vast cell size now draws a coarse plot and ends.
#[test]
fn preview_at_a_vast_cell_size_ends() {
    let mut s = Scratch::new();
    write_job(&mut s, "j.job.json", |_| {});
    let out = Command::cargo_bin("basr")
        .unwrap()
        .current_dir(s.dir.path())
        .args([
            "preview",
            "j.job.json",
            "-o",
            "j.svg",
            "--resolution-mm",
            "1e300",
            "-q",
        ])
        .output()
        .unwrap();
    assert!(
        matches!(out.status.code(), Some(0 | 2)),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn missing_robot_file_is_named() {
    Scratch::new().refuses(
        &["compile", "STOP", "--robot", "nobot.toml"],
        &["nobot.toml"],
    );
}

#[test]
fn robot_with_nan_names_the_field_and_line() {
    let mut s = Scratch::new();
    let bad = set_key(&basr_toml(), "film_m", "nan");
    s.input("nan.toml", bad.as_bytes());
    s.refuses(&["robot", "--robot", "nan.toml"], &["nan.toml", "film_m"]);
    s.refuses(
        &["compile", "STOP", "--robot", "nan.toml"],
        &["nan.toml", "film_m"],
    );
}

#[test]
fn robot_with_negative_flow_names_the_field() {
    let mut s = Scratch::new();
    let bad = set_key(&basr_toml(), "flow_m3ps", "-1e-6");
    s.input("neg.toml", bad.as_bytes());
    s.refuses(
        &["robot", "--robot", "neg.toml"],
        &["neg.toml", "flow_m3ps"],
    );
}

#[test]
fn robot_with_a_reversed_range_says_swap() {
    let mut s = Scratch::new();
    let bad = set_key(&basr_toml(), "tip_life_min_m3", "0.3");
    s.input("rev.toml", bad.as_bytes());
    s.refuses(
        &["compile", "STOP", "--robot", "rev.toml"],
        &["rev.toml", "tip_life_min_m3", "reversed range", "swap"],
    );
}

#[test]
fn letters_out_of_reach_name_the_stroke_and_the_fix() {
    Scratch::new().refuses(
        &[
            "compile",
            "I",
            "--letter-height",
            "4.5",
            "--lane-width",
            "6",
        ],
        &[
            "cannot be reached",
            "outside the arm's reach",
            "--letter-height",
        ],
    );
}

#[test]
fn robot_toml_syntax_error_gives_line() {
    let mut s = Scratch::new();
    let bad = format!("[arm\n{}", basr_toml());
    s.input("syntax.toml", bad.as_bytes());
    s.refuses(
        &["robot", "--robot", "syntax.toml"],
        &["syntax.toml:1:", "syntax"],
    );
}

#[test]
fn missing_job_file_is_named() {
    let s = Scratch::new();
    s.refuses(&["preview", "nojob.json"], &["nojob.json"]);
    s.refuses(&["simulate", "nojob.json"], &["nojob.json"]);
}

#[test]
fn truncated_job_is_refused_by_readers() {
    let mut s = Scratch::new();
    s.input(
        "t.job.json",
        b"{\"format\": \"basr-job\", \"version\": 1, \"samp",
    );
    s.refuses(&["preview", "t.job.json"], &["t.job.json", "truncated"]);
    s.refuses(&["simulate", "t.job.json"], &["t.job.json", "truncated"]);
}

#[test]
fn empty_job_file_is_refused() {
    let mut s = Scratch::new();
    s.input("e.job.json", b"");
    s.refuses(&["preview", "e.job.json"], &["e.job.json"]);
    s.refuses(&["simulate", "e.job.json"], &["e.job.json"]);
}

/// A small, valid, sealed job built through the library, written to `dir`.
fn write_job(s: &mut Scratch, name: &str, edit: impl FnOnce(&mut basr::job::Job)) -> PathBuf {
    let job = small_job(edit);
    let p = s.path(name);
    std::fs::write(&p, job.to_bytes()).unwrap();
    s.inputs.push(p.clone());
    p
}

/// A small valid job: the simulator's synthetic letter, sealed, then `edit`ed.
fn small_job(edit: impl FnOnce(&mut basr::job::Job)) -> basr::job::Job {
    let mut job = basr::sim::synthetic::letter_job();
    edit(&mut job);
    job
}

fn read_back(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap()
}

#[test]
fn hand_edited_job_fails_the_hash_everywhere() {
    let mut s = Scratch::new();
    let p = write_job(&mut s, "j.job.json", |_| {});
    let mut v: serde_json::Value = serde_json::from_str(&read_back(&p)).unwrap();
    v["message"] = serde_json::Value::String("EDITED".into());
    std::fs::write(&p, serde_json::to_vec_pretty(&v).unwrap()).unwrap();
    s.refuses(
        &["preview", "j.job.json"],
        &["integrity", "compile it again"],
    );
    s.refuses(
        &["simulate", "j.job.json"],
        &["integrity", "compile it again"],
    );
}

#[test]
fn unknown_job_version_is_refused() {
    let mut s = Scratch::new();
    write_job(&mut s, "v.job.json", |j| {
        j.version = 99;
        j.seal();
    });
    s.refuses(&["preview", "v.job.json"], &["version 99"]);
    s.refuses(&["simulate", "v.job.json"], &["version 99"]);
}

#[test]
fn job_for_another_robot_is_refused_by_simulate() {
    let mut s = Scratch::new();
    write_job(&mut s, "other.job.json", |j| {
        j.robot.name = "BASR-2".into();
        j.seal();
    });
    s.refuses(&["simulate", "other.job.json"], &["robot"]);
}
