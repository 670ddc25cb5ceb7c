//! The bad-input battery (issue 7): every case runs the binary as a user
//! would and asserts exit code 2, a message that names the problem and the
//! fix, and that no output file is left behind.

use std::path::{Path, PathBuf};

use assert_cmd::Command;

mod common;
use common::set_key;

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

#[test]
fn unsupported_character_is_named_with_its_position() {
    Scratch::new().refuses(&["compile", "ST@P"], &["'@'", "position 3", "A–Z"]);
}

#[test]
fn empty_message_is_refused() {
    Scratch::new().refuses(&["compile", ""], &["empty", "basr compile STOP"]);
    Scratch::new().refuses(&["compile", "   "], &["empty", "at least one letter"]);
}

#[test]
fn no_message_and_no_marking_is_refused() {
    Scratch::new().refuses(
        &["compile"],
        &[
            "message",
            "basr compile STOP",
            "--marking markings/stop.toml",
        ],
    );
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
        &["nowhere.toml", "cannot read", "check the path"],
    );
}

#[test]
fn empty_marking_file_is_refused() {
    let mut s = Scratch::new();
    s.input("empty.toml", b"");
    s.refuses(
        &["compile", "--marking", "empty.toml"],
        &["empty.toml", "is empty", "lines = [\"STOP\"]"],
    );
}

/// `--letter-height` sizes words: given for a symbol, or a scene of
/// symbols without a word, it would do nothing (but print feet). Refused,
/// saying what sizes a symbol.
#[test]
fn a_letter_height_for_a_marking_without_letters_is_refused() {
    let mut s = Scratch::new();
    s.refuses(
        &["compile", "--symbol", "bike", "--letter-height", "6ft"],
        &["--letter-height", "the symbol bike has none", "scale = 1.5"],
    );
    s.input(
        "bikes.toml",
        b"[[item]]\nsymbol = \"bike\"\nat_m = [0.0, 0.0]\nscale = 0.75\n",
    );
    s.refuses(
        &["compile", "--marking", "bikes.toml", "--letter-height", "2"],
        &["bikes.toml", "no word", "leave --letter-height out"],
    );
}

#[test]
fn malformed_marking_toml_gives_line_and_column() {
    let mut s = Scratch::new();
    s.input("bad.toml", b"[marking]\nlines = [\"STOP\"\nname = 3\n");
    s.refuses(
        &["compile", "--marking", "bad.toml"],
        &["bad.toml", "line 3, column 1", "expected `]`"],
    );
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
    s.refuses(
        &["compile", "--marking", "latin1.toml"],
        &["latin1.toml", "not utf-8", "save the file as utf-8"],
    );
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
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("not UTF-8"), "{stderr}");
    assert!(stderr.contains("the letters A–Z"), "{stderr}");
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
        &["nobot.toml", "check the path"],
    );
}

#[test]
fn robot_with_nan_names_the_field_and_line() {
    let mut s = Scratch::new();
    let bad = set_key(&basr_toml(), "film_m", "nan");
    s.input("nan.toml", bad.as_bytes());
    let line = bad
        .lines()
        .position(|l| l.starts_with("film_m"))
        .expect("the robot file has film_m")
        + 1;
    let place = format!("nan.toml:{line}:");
    let needles = [place.as_str(), "paint.film_m", "must be a finite number"];
    s.refuses(&["robot", "--robot", "nan.toml"], &needles);
    s.refuses(&["compile", "STOP", "--robot", "nan.toml"], &needles);
}

#[test]
fn robot_with_negative_flow_names_the_field() {
    let mut s = Scratch::new();
    let bad = set_key(&basr_toml(), "flow_m3ps", "-1e-6");
    s.input("neg.toml", bad.as_bytes());
    s.refuses(
        &["robot", "--robot", "neg.toml"],
        &["neg.toml", "paint.flow_m3ps", "must be positive"],
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
    s.refuses(
        &["preview", "nojob.json"],
        &["nojob.json", "check the path"],
    );
    s.refuses(
        &["simulate", "nojob.json"],
        &["nojob.json", "check the path"],
    );
}

#[test]
fn truncated_job_is_refused_by_readers() {
    let mut s = Scratch::new();
    s.input(
        "t.job.json",
        b"{\"format\": \"basr-job\", \"version\": 1, \"samp",
    );
    let needles = [
        "t.job.json",
        "truncated",
        "line 1 column 42",
        "compile it again",
    ];
    s.refuses(&["preview", "t.job.json"], &needles);
    s.refuses(&["simulate", "t.job.json"], &needles);
}

#[test]
fn empty_job_file_is_refused() {
    let mut s = Scratch::new();
    s.input("e.job.json", b"");
    s.refuses(
        &["preview", "e.job.json"],
        &["e.job.json", "compile it again"],
    );
    s.refuses(
        &["simulate", "e.job.json"],
        &["e.job.json", "compile it again"],
    );
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
    let needles = ["version 99", "reads version 1", "compile it again"];
    s.refuses(&["preview", "v.job.json"], &needles);
    s.refuses(&["simulate", "v.job.json"], &needles);
}

#[test]
fn job_for_another_robot_is_refused_by_simulate() {
    let mut s = Scratch::new();
    write_job(&mut s, "other.job.json", |j| {
        j.robot.basr_mut().unwrap().name = "BASR-2".into();
        j.seal();
    });
    s.refuses(&["simulate", "other.job.json"], &["robot"]);
}

#[test]
fn job_for_another_robot_says_which_description_to_use() {
    let mut s = Scratch::new();
    write_job(&mut s, "other.job.json", |j| {
        j.robot.basr_mut().unwrap().name = "BASR-2".into();
        j.seal();
    });
    let stderr = s.refuses(&["simulate", "other.job.json"], &["robot", "--robot"]);
    assert!(stderr.contains("other.job.json"), "{stderr}");
}

#[test]
fn job_with_a_stale_robot_hash_is_refused_everywhere() {
    let mut s = Scratch::new();
    write_job(&mut s, "stale.job.json", |j| {
        // The robot changes after sealing; the document hash is made to
        // match again, so only robot_sha256 tells.
        j.robot.basr_mut().unwrap().name = "BASR-edited".into();
        j.sha256 = basr::job::document_sha256(serde_json::to_value(&*j).unwrap());
    });
    let needles = ["stale.job.json", "robot_sha256", "compile the job again"];
    s.refuses(&["preview", "stale.job.json"], &needles);
    s.refuses(&["simulate", "stale.job.json"], &needles);
    let out = Command::cargo_bin("basr")
        .unwrap()
        .current_dir(s.dir.path())
        .args(["check", "stale.job.json"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "check: problems found");
    assert!(String::from_utf8_lossy(&out.stderr).contains("robot_sha256"));
}

/// Layout and timing numbers far outside anything a road or the arm takes
/// are refused with their range before any work (a lane of 1e9 m grew the
/// station search to 14 GB; a gun lag of 1e300 s painted nothing, exit 0).
#[test]
fn absurd_layout_and_timing_numbers_are_refused_with_their_range() {
    let cases: [(&[&str], &[&str]); 6] = [
        (&["--lane-width", "1e9"], &["lane width 1e9 m", "0..30 m"]),
        (
            &["--letter-height", "1e300"],
            &["letter height 1e300 m", "0.3..10 m", "--letter-height 2.44"],
        ),
        (&["--letter-height", "244"], &["outside 0.3..10 m"]),
        (&["--period-s", "10"], &["--period-s", "at most 0.1 s"]),
        (&["--gun-lag-s", "1e300"], &["--gun-lag-s", "at most 1 s"]),
        (
            &["--rung-spacing-mm", "1e9"],
            &["--rung-spacing-mm", "at most 100 mm"],
        ),
    ];
    for (extra, needles) in cases {
        let mut args = vec!["compile", "STOP", "--csv", "s.csv"];
        args.extend_from_slice(extra);
        Scratch::new().refuses(&args, needles);
    }
    let mut s = Scratch::new();
    s.input(
        "wide.toml",
        b"[marking]\nlines = [\"STOP\"]\nlane_width_m = 1e300\n",
    );
    s.refuses(
        &["compile", "--marking", "wide.toml"],
        &["wide.toml", "lane width 1e300 m", "0..30 m"],
    );
}

#[test]
fn robot_with_infinity_names_the_field() {
    let mut s = Scratch::new();
    let bad = set_key(&basr_toml(), "flow_m3ps", "inf");
    s.input("inf.toml", bad.as_bytes());
    s.refuses(
        &["compile", "STOP", "--robot", "inf.toml"],
        &["inf.toml:", "paint.flow_m3ps", "must be a finite number"],
    );
}

#[test]
fn empty_and_non_utf8_robot_files_are_refused() {
    let mut s = Scratch::new();
    s.input("empty.toml", b"");
    s.refuses(
        &["compile", "STOP", "--robot", "empty.toml"],
        &["empty.toml", "missing field"],
    );
    s.input("latin1.toml", b"name = \"BASR \xe9\"\n");
    s.refuses(
        &["pose", "0", "3", "--robot", "latin1.toml"],
        &["latin1.toml", "not utf-8", "save the file as utf-8"],
    );
}

#[test]
fn missing_empty_and_non_utf8_fonts_are_refused() {
    let mut s = Scratch::new();
    s.refuses(
        &["compile", "STOP", "--font", "nofont.toml"],
        &["nofont.toml"],
    );
    s.input("empty.toml", b"");
    s.refuses(&["glyphs", "--font", "empty.toml"], &["empty.toml"]);
    s.input("latin1.toml", b"name = \"caf\xe9\"\n");
    s.refuses(
        &["glyphs", "--font", "latin1.toml", "--svg", "a.svg"],
        &["latin1.toml", "utf-8"],
    );
}

#[test]
fn non_utf8_job_is_refused() {
    let mut s = Scratch::new();
    s.input("j.job.json", b"{\"format\": \"basr-j\xffob\"}");
    s.refuses(
        &["preview", "j.job.json"],
        &["j.job.json", "not utf-8", "save the file as utf-8"],
    );
}

#[test]
fn a_folder_given_as_an_input_file_is_named() {
    let s = Scratch::new();
    std::fs::create_dir(s.path("adir")).unwrap();
    let mut s = s;
    s.inputs.push(s.path("adir"));
    s.refuses(
        &["preview", "adir"],
        &["adir", "cannot read", "is a directory"],
    );
    s.refuses(
        &["compile", "--marking", "adir"],
        &["adir", "cannot read", "is a directory"],
    );
}

/// `basr check` on a setpoint CSV cut off mid-row (a copy that did not
/// finish): problems found (exit 1, SPEC §1: check's verdict), naming the
/// line and saying how to get a whole one.
#[test]
fn truncated_setpoint_csv_is_reported_by_check() {
    let mut s = Scratch::new();
    let job = small_job(|_| {});
    let mut text = basr::job::COLUMNS.join(",") + "\n";
    for i in 0..job.samples.len() {
        text += &(job.samples.csv_fields(i).join(",") + "\n");
    }
    let cut = &text[..text.len() * 2 / 3];
    let lines = cut.lines().count();
    s.input("cut.csv", cut.as_bytes());
    let out = Command::cargo_bin("basr")
        .unwrap()
        .current_dir(s.dir.path())
        .args(["check", "cut.csv"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!("cut.csv:{lines}: the last row has no line end")),
        "{stderr}"
    );
    assert!(stderr.contains("--csv FILE"), "{stderr}");
    s.assert_only_inputs();
}

/// An output named like an input would destroy it: refused before any
/// work, and the input is left as it was.
#[test]
fn an_output_over_an_input_is_refused() {
    let mut s = Scratch::new();
    let font = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/fonts/basr.toml")).unwrap();
    s.input("f.toml", &font);
    s.refuses(
        &["glyphs", "--font", "f.toml", "--svg", "./f.toml"],
        &[
            "same file",
            "would destroy the input",
            "different path for --svg",
        ],
    );
    assert!(std::fs::read(s.path("f.toml")).unwrap() == font);
    s.input("r.toml", basr_toml().as_bytes());
    s.refuses(
        &["workspace", "--robot", "r.toml", "--svg", "r.toml"],
        &["same file", "would destroy the input"],
    );
    assert_eq!(read_back(&s.path("r.toml")), basr_toml());
    let job = write_job(&mut s, "j.job.json", |_| {});
    let sealed = read_back(&job);
    s.refuses(
        &["preview", "j.job.json", "-o", "j.job.json"],
        &["same file", "would destroy the input", "-o"],
    );
    s.refuses(
        &["simulate", "j.job.json", "--svg", "./j.job.json"],
        &["same file", "would destroy the input", "--svg"],
    );
    s.refuses(
        &[
            "simulate",
            "j.job.json",
            "--trace",
            "t.csv",
            "--svg",
            "t.csv",
        ],
        &["same file", "each would be written over the other"],
    );
    assert_eq!(read_back(&job), sealed);
}
