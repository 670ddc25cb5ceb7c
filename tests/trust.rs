//! Jobs no one can tamper with and no interruption can half-write (SPEC §7,
//! issue 16), through the binary: bytes other than the canonical form,
//! unsigned and foreign-key jobs under `--trust`, a CSV edited beside its
//! job, signals at random moments, a run whose outputs cannot all be
//! written, and the modes of replaced files.

use std::path::{Path, PathBuf};
use std::process::{Command as StdCommand, Output};

use assert_cmd::Command;

mod process_common;
use process_common::{catches, entries};

fn basr_in(dir: &Path) -> Command {
    let mut c = Command::cargo_bin("basr").unwrap();
    c.current_dir(dir).env_remove("BASR_TRUST");
    c
}

fn run(dir: &Path, args: &[&str]) -> Output {
    basr_in(dir).args(args).output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit code `code` and every `needle` in stderr.
fn expect(o: &Output, code: i32, needles: &[&str], what: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(code), "{what}: {err}");
    for n in needles {
        assert!(err.contains(n), "{what}: stderr lacks {n:?}:\n{err}");
    }
}

/// A folder with STOP compiled (job, CSV and Adept program), keys `a` and
/// `b`, and the job signed by `a` as `signed.job.json`.
struct Site {
    dir: tempfile::TempDir,
}

impl Site {
    fn new() -> Site {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        for k in ["a.key", "b.key"] {
            expect(&run(d, &["keygen", "-o", k, "-q"]), 0, &[], "keygen");
        }
        let o = run(
            d,
            &[
                "compile", "STOP", "-q", "--csv", "STOP.csv", "--adept", "STOP.v2",
            ],
        );
        expect(&o, 0, &[], "compile");
        let o = run(
            d,
            &[
                "compile",
                "STOP",
                "-q",
                "--sign",
                "a.key",
                "-o",
                "signed.job.json",
            ],
        );
        expect(&o, 0, &[], "compile --sign");
        Site { dir }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn read(&self, name: &str) -> String {
        std::fs::read_to_string(self.path(name)).unwrap()
    }

    fn write(&self, name: &str, text: &str) {
        std::fs::write(self.path(name), text).unwrap();
    }

    fn run(&self, args: &[&str]) -> Output {
        run(self.dir.path(), args)
    }

    /// `args` then `job`.
    fn run_owned(&self, args: &[String], job: &str) -> Output {
        basr_in(self.dir.path())
            .args(args)
            .arg(job)
            .output()
            .unwrap()
    }

    /// Key `a`'s id, as the job it signed names it.
    fn key_id_a(&self) -> String {
        let job = self.read("signed.job.json");
        let at = job.find("\"key_id\": \"").unwrap() + 11;
        job[at..at + 16].to_string()
    }

    /// `edited` written as `name` is refused by check (1), preview and
    /// simulate (2), each saying every needle.
    fn refused_everywhere(&self, name: &str, edited: &str, trust: &[&str], needles: &[&str]) {
        self.write(name, edited);
        let with = |cmd: &[&'static str]| -> Vec<String> {
            cmd.iter().chain(trust).map(|a| a.to_string()).collect()
        };
        let check = self.run_owned(&with(&["check"]), name);
        expect(&check, 1, needles, "check");
        let svg = format!("{name}.svg");
        let mut args = with(&["preview"]);
        args.extend(["-o".to_string(), svg.clone()]);
        let o = self.run_owned(&args, name);
        expect(&o, 2, needles, "preview");
        assert!(!self.path(&svg).exists(), "preview wrote an SVG of {name}");
        let sim = self.run_owned(&with(&["simulate"]), name);
        expect(&sim, 2, needles, "simulate");
    }
}

#[test]
fn a_duplicate_key_is_refused_by_every_reader() {
    let site = Site::new();
    let job = site.read("STOP.job.json");
    // serde_json keeps the last of two keys, another reader the first:
    // an earlier message or x_m column would show one and paint the other.
    let message = job.replacen(
        "\n  \"message\": ",
        "\n  \"message\": \"EVIL MESSAGE\",\n  \"message\": ",
        1,
    );
    let x_m = job.replacen(
        "\n    \"x_m\": [\n",
        "\n    \"x_m\": [\n      999.0\n    ],\n    \"x_m\": [\n",
        1,
    );
    for (edited, key) in [(message, "\"message\""), (x_m, "\"x_m\"")] {
        assert_ne!(edited, job);
        let needles = ["dup.job.json", "integrity", "appears twice", key];
        site.refused_everywhere("dup.job.json", &edited, &[], &needles);
    }
}

#[test]
fn other_number_spelling_and_spacing_are_refused() {
    let site = Site::new();
    let job = site.read("STOP.job.json");
    let upper_e = job.replace("e-", "E-");
    assert_ne!(upper_e, job);
    site.refused_everywhere("e.job.json", &upper_e, &[], &["e.job.json", "number"]);
    let spaced = job.replace(": ", " : ");
    site.refused_everywhere("s.job.json", &spaced, &[], &["s.job.json", "canonical"]);
}

#[test]
fn a_re_indented_signed_job_is_refused_under_trust() {
    let site = Site::new();
    let job = site.read("signed.job.json");
    // The same value, indented by four spaces: every hash of the value
    // still matches, only the bytes differ.
    let v: serde_json::Value = serde_json::from_str(&job).unwrap();
    let mut four = Vec::new();
    let fmt = serde_json::ser::PrettyFormatter::with_indent(b"    ");
    serde::Serialize::serialize(
        &v,
        &mut serde_json::Serializer::with_formatter(&mut four, fmt),
    )
    .unwrap();
    four.push(b'\n');
    let four = String::from_utf8(four).unwrap();
    assert_ne!(four, job);
    let trust = ["--trust", "a.key.pub"];
    site.refused_everywhere("r.job.json", &four, &trust, &["r.job.json", "canonical"]);
    // The original passes under the same trust.
    let o = site.run(&["check", "--trust", "a.key.pub", "signed.job.json"]);
    expect(&o, 0, &["signed by key"], "check of the signed job");
}

#[test]
fn unsigned_and_foreign_key_jobs_are_refused_under_trust() {
    let site = Site::new();
    let a = site.key_id_a();
    let unsigned = site.read("STOP.job.json");
    let trust = ["--trust", "a.key.pub"];
    site.refused_everywhere("u.job.json", &unsigned, &trust, &["not signed", &a]);
    let signed = site.read("signed.job.json");
    let trust_b = ["--trust", "b.key.pub"];
    site.refused_everywhere("f.job.json", &signed, &trust_b, &["signed by key", &a]);
    // BASR_TRUST sets the key once for every command.
    let o = basr_in(site.dir.path())
        .env("BASR_TRUST", "b.key.pub")
        .args(["simulate", "signed.job.json"])
        .output()
        .unwrap();
    expect(&o, 2, &["not by the trusted key", &a], "BASR_TRUST");
    let o = basr_in(site.dir.path())
        .env("BASR_TRUST", "a.key.pub")
        .args(["check", "signed.job.json", "STOP.job.json"])
        .output()
        .unwrap();
    expect(
        &o,
        1,
        &["STOP.job.json: the job is not signed"],
        "check lists it",
    );
    assert!(stderr(&o).contains("signed.job.json: ok"), "{}", stderr(&o));
}

/// The CSV with field `column` of data row `row` changed by `edit`.
fn edit_csv(csv: &str, row: usize, column: &str, edit: impl Fn(&str) -> String) -> String {
    let mut lines: Vec<String> = csv.lines().map(str::to_string).collect();
    let c = lines[0].split(',').position(|n| n == column).unwrap();
    let mut fields: Vec<String> = lines[row + 1].split(',').map(str::to_string).collect();
    fields[c] = edit(&fields[c]);
    lines[row + 1] = fields.join(",");
    lines.join("\n") + "\n"
}

#[test]
fn an_edited_csv_row_is_named_beside_its_job() {
    let site = Site::new();
    let o = site.run(&["check", "STOP.job.json", "STOP.csv"]);
    expect(&o, 0, &["STOP.csv: ok"], "the pair as written");
    let csv = site.read("STOP.csv");
    // A row where the gun is on, so the flag flips to off.
    let painting = csv
        .lines()
        .skip(1)
        .position(|l| l.split(',').nth(3) == Some("1"))
        .unwrap();
    let cases = [
        (
            "x_m",
            100,
            edit_csv(&csv, 100, "x_m", |f| {
                (f.parse::<f64>().unwrap() + 1.0).to_string()
            }),
        ),
        (
            "enc_base",
            200,
            edit_csv(&csv, 200, "enc_base", |f| {
                (f.parse::<i64>().unwrap() + 1).to_string()
            }),
        ),
        (
            "paint",
            painting,
            edit_csv(&csv, painting, "paint", |_| "0".into()),
        ),
    ];
    for (column, row, edited) in cases {
        assert_ne!(edited, csv);
        site.write("edited.csv", &edited);
        let o = site.run(&["check", "STOP.job.json", "edited.csv"]);
        let at = format!("edited.csv:{}: row {row}, column {column}", row + 2);
        expect(
            &o,
            1,
            &["not the CSV written with STOP.job.json", &at],
            column,
        );
    }
    // The Adept program is bound the same way.
    let o = site.run(&["check", "STOP.job.json", "STOP.v2"]);
    expect(&o, 0, &["STOP.v2: ok"], "the program as written");
    let program = site.read("STOP.v2");
    let line = program
        .lines()
        .position(|l| l.starts_with("move "))
        .unwrap();
    let edited: Vec<String> = program
        .lines()
        .enumerate()
        .map(|(k, l)| {
            if k == line {
                l.replacen("move trans(", "move trans(1", 1)
            } else {
                l.into()
            }
        })
        .collect();
    site.write("edited.v2", &(edited.join("\n") + "\n"));
    let o = site.run(&["check", "STOP.job.json", "edited.v2"]);
    let at = format!("edited.v2:{}: the program has", line + 1);
    expect(
        &o,
        1,
        &["not the Adept program written with STOP.job.json", &at],
        "adept",
    );
    // The CSV of another job (the signed one's is the same; a 3-letter
    // job's is not) is not this job's either.
    expect(
        &site.run(&[
            "compile",
            "SO",
            "-q",
            "--csv",
            "so.csv",
            "-o",
            "so.job.json",
        ]),
        0,
        &[],
        "compile SO",
    );
    let o = site.run(&["check", "STOP.job.json", "so.csv"]);
    expect(&o, 1, &["so.csv", "row 0"], "another job's CSV");
}

#[test]
fn a_folder_as_output_leaves_the_earlier_files() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("f.csv"), "EARLIER\n").unwrap();
    std::fs::create_dir(d.join("d")).unwrap();
    let o = run(d, &["compile", "STOP", "-o", "d", "--csv", "f.csv"]);
    expect(&o, 2, &["d", "is a folder"], "-o a folder");
    assert_eq!(
        std::fs::read_to_string(d.join("f.csv")).unwrap(),
        "EARLIER\n"
    );
    assert_eq!(entries(d), ["d", "f.csv"]);
    // The same for a CSV path that is a folder, with an earlier job.
    std::fs::write(d.join("j.json"), "EARLIER JOB\n").unwrap();
    let o = run(d, &["compile", "STOP", "-o", "j.json", "--csv", "d"]);
    expect(&o, 2, &["is a folder"], "--csv a folder");
    assert_eq!(
        std::fs::read_to_string(d.join("j.json")).unwrap(),
        "EARLIER JOB\n"
    );
    assert_eq!(entries(d), ["d", "f.csv", "j.json"]);
}

#[cfg(unix)]
#[test]
fn replaced_files_keep_their_mode() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mode = |n: &str| std::fs::metadata(d.join(n)).unwrap().permissions().mode() & 0o777;
    for (n, m) in [("j.json", 0o600), ("s.csv", 0o640), ("p.v2", 0o664)] {
        std::fs::write(d.join(n), "earlier\n").unwrap();
        std::fs::set_permissions(d.join(n), std::fs::Permissions::from_mode(m)).unwrap();
    }
    let o = run(
        d,
        &[
            "compile", "I", "-q", "-o", "j.json", "--csv", "s.csv", "--adept", "p.v2",
        ],
    );
    expect(&o, 0, &[], "compile over earlier files");
    assert_eq!(
        [mode("j.json"), mode("s.csv"), mode("p.v2")],
        [0o600, 0o640, 0o664]
    );
    assert!(std::fs::read_to_string(d.join("j.json"))
        .unwrap()
        .contains("basr-job"));
    // A new file is an ordinary document; a secret key is the owner's alone.
    expect(&run(d, &["keygen", "-o", "k", "-q"]), 0, &[], "keygen");
    assert_eq!([mode("k"), mode("k.pub")], [0o600, 0o644]);
    let o = run(d, &["keygen", "-o", "k"]);
    expect(&o, 2, &["k exists", "never replaces"], "keygen over a key");
    std::fs::set_permissions(d.join("k"), std::fs::Permissions::from_mode(0o644)).unwrap();
    let o = run(d, &["compile", "I", "--sign", "k"]);
    expect(&o, 2, &["readable by others"], "a shared secret key");
}

#[cfg(target_os = "linux")]
#[test]
fn signals_at_random_moments_leave_no_temporary_and_the_earlier_files() {
    // (name, number): SIGTERM and SIGHUP most, SIGQUIT and SIGINT too.
    let signals: [(&str, i32); 6] = [
        ("TERM", 15),
        ("HUP", 1),
        ("TERM", 15),
        ("HUP", 1),
        ("QUIT", 3),
        ("INT", 2),
    ];
    // A fixed seed: the moments are spread, the runs repeatable.
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    // One run undisturbed sets the span the moments are drawn from (a
    // little past its end, so some signals land after the commit).
    let span = {
        let dir = tempfile::tempdir().unwrap();
        let start = std::time::Instant::now();
        let o = run(
            dir.path(),
            &["compile", "STOP", "-q", "-o", "j.json", "--csv", "s.csv"],
        );
        expect(&o, 0, &[], "the undisturbed run");
        (start.elapsed().as_micros() as u64 * 6 / 5).max(1)
    };
    let (mut interrupted, mut finished) = (0, 0);
    for run_no in 0..50 {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::write(d.join("s.csv"), "EARLIER\n").unwrap();
        std::fs::write(d.join("j.json"), "EARLIER\n").unwrap();
        let mut child = StdCommand::new(assert_cmd::cargo::cargo_bin("basr"))
            .current_dir(d)
            .args(["compile", "STOP", "-q", "-o", "j.json", "--csv", "s.csv"])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        let (name, number) = signals[run_no % signals.len()];
        while !catches(child.id(), number) && child.try_wait().unwrap().is_none() {
            std::thread::sleep(std::time::Duration::from_micros(100));
        }
        // Somewhere in the run: computing, writing, committing or done.
        std::thread::sleep(std::time::Duration::from_micros(next() % span));
        let sent = StdCommand::new("kill")
            .args([format!("-{name}"), child.id().to_string()])
            .status()
            .unwrap();
        let code = child.wait().unwrap().code();
        let left = entries(d);
        assert_eq!(
            left,
            ["j.json", "s.csv"],
            "run {run_no} (SIG{name}): {left:?}"
        );
        let read = |n: &str| std::fs::read_to_string(d.join(n)).unwrap();
        if code == Some(0) {
            // Done before the signal (or it came after the commit): both new.
            finished += 1;
            assert!(read("j.json").contains("basr-job") && read("s.csv").starts_with("t_s,"));
        } else {
            assert!(sent.success());
            interrupted += 1;
            assert_eq!(code, Some(128 + number), "run {run_no}: SIG{name}");
            assert_eq!(
                (read("j.json"), read("s.csv")),
                ("EARLIER\n".into(), "EARLIER\n".into())
            );
        }
    }
    eprintln!("{interrupted} runs interrupted, {finished} finished first");
    assert!(
        interrupted >= 10,
        "only {interrupted} of 50 runs were interrupted"
    );
}
