//! A reader that stops early (`basr glyphs --json | head`) closes the pipe
//! before basr has written everything. That must end quietly with the
//! command's own exit code, never a panic ("failed printing to stdout",
//! exit 101), whether stdout or stderr is the closed one.

use std::path::Path;
use std::process::{Command, Stdio};

fn basr() -> Command {
    Command::new(assert_cmd::cargo::cargo_bin("basr"))
}

/// Run `basr args` in `dir` with stdout a pipe whose reading end is closed
/// before the child can write (so every write meets a broken pipe); return
/// the exit code and stderr.
fn with_stdout_closed(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let mut child = basr()
        .current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

#[test]
fn machine_output_into_a_closed_pipe_ends_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let job = dir.path().join("I.job.json");
    let made = basr()
        .current_dir(dir.path())
        .args(["compile", "I", "-q"])
        .status()
        .unwrap();
    assert!(made.success());
    let job = job.to_str().unwrap();
    let svg = dir.path().join("i.svg");
    let svg = svg.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec!["glyphs", "--json"],
        vec!["robot"],
        vec!["robot", "--json"],
        vec!["workspace", "--json"],
        vec!["pose", "0", "3", "--json"],
        vec!["completions", "bash"],
        vec!["--help"],
        vec!["compile", "--help"],
        vec!["compile", "I", "-o", "again.job.json", "--json"],
        vec!["preview", job, "-o", svg, "--json", "--resolution-mm", "10"],
    ];
    for args in cases {
        let (code, stderr) = with_stdout_closed(dir.path(), &args);
        assert!(
            !stderr.contains("panicked") && !stderr.contains("Broken pipe"),
            "basr {args:?} complained about the closed pipe:\n{stderr}"
        );
        // preview's own film verdict (exit 1 on a failed film) is not what
        // this test is about; a closed pipe must not turn into any other code.
        let ok: &[i32] = if args[0] == "preview" { &[0, 1] } else { &[0] };
        assert!(
            code.is_some_and(|c| ok.contains(&c)),
            "basr {args:?} exited {code:?}; stderr:\n{stderr}"
        );
    }
    // The job was still written: the closed pipe only drops the summary.
    assert!(dir.path().join("again.job.json").is_file());
}

#[test]
fn human_text_into_a_closed_stderr_ends_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let mut child = basr()
        .current_dir(dir.path())
        .args(["compile", "STOP"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    let status = child.wait().unwrap();
    assert_eq!(
        status.code(),
        Some(0),
        "exit 101 is a panic on the closed stderr"
    );
    assert!(dir.path().join("STOP.job.json").is_file());

    // A failing command still reports failure, even with nobody to tell.
    let mut child = basr()
        .current_dir(dir.path())
        .args(["compile", "ST@P"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    assert_eq!(child.wait().unwrap().code(), Some(2));
}
