//! Ctrl-C (SIGINT) in the middle of a run: exit 130 and no file left in the
//! output folder, neither a finished output nor a `.basr-*.part` temporary,
//! whether the signal lands while basr computes or while it writes; and
//! files an earlier run left under the same names keep their contents.
//!
//! Nothing here depends on how fast the machine is: the signal is sent once
//! the handler is seen installed (/proc/PID/status) and, for the writing
//! phase, once a temporary file is seen in the folder; a run that finishes
//! before it could be interrupted is retried with a larger message.
#![cfg(target_os = "linux")]

use std::path::Path;
use std::process::{Child, Command, Stdio};

mod process_common;
use process_common::entries;

/// Messages of growing size: one word per line, so each one adds a line of
/// letters (and seconds of computing, and megabytes of job to write).
const MESSAGES: [&str; 4] = [
    "STOP",
    "STOP AHEAD",
    "STOP AHEAD STOP AHEAD",
    "STOP AHEAD STOP AHEAD STOP AHEAD STOP AHEAD",
];

fn spawn_compile(dir: &Path, message: &str) -> Child {
    Command::new(assert_cmd::cargo::cargo_bin("basr"))
        .current_dir(dir)
        // --force: the earlier files a test lays under the default names
        // are no jobs, which compile otherwise refuses to replace.
        .args([
            "compile",
            message,
            "--csv",
            "setpoints.csv",
            "--quiet",
            "--force",
        ])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// Whether process `pid` catches SIGINT yet.
fn catches_sigint(pid: u32) -> bool {
    process_common::catches(pid, 2)
}

fn send_sigint(pid: u32) {
    let sent = Command::new("kill")
        .args(["-INT", &pid.to_string()])
        .status()
        .unwrap();
    assert!(sent.success(), "kill -INT {pid}");
}

fn has_temp(dir: &Path) -> bool {
    entries(dir).iter().any(|n| n.starts_with(".basr-"))
}

/// Wait until the child catches SIGINT; None if it exited first.
fn wait_for_handler(child: &mut Child) -> Option<()> {
    loop {
        if child.try_wait().unwrap().is_some() {
            return None;
        }
        if catches_sigint(child.id()) {
            return Some(());
        }
        std::thread::sleep(std::time::Duration::from_micros(200));
    }
}

/// Interrupt the run once `ready(dir)` holds; Some(exit code) if the signal
/// was sent, None if the run finished first (the caller retries bigger).
fn interrupt_when(message: &str, ready: impl Fn(&Path) -> bool) -> Option<(i32, Vec<String>)> {
    let dir = tempfile::tempdir().unwrap();
    let mut child = spawn_compile(dir.path(), message);
    wait_for_handler(&mut child)?;
    loop {
        if child.try_wait().unwrap().is_some() {
            return None;
        }
        if ready(dir.path()) {
            break;
        }
        std::thread::sleep(std::time::Duration::from_micros(200));
    }
    send_sigint(child.id());
    let status = child.wait().unwrap();
    if status.code() == Some(0) {
        // It finished between our look and the signal.
        return None;
    }
    Some((status.code().unwrap_or(-1), entries(dir.path())))
}

fn assert_interrupted_cleanly(phase: &str, ready: impl Fn(&Path) -> bool) {
    for message in MESSAGES {
        if let Some((code, left)) = interrupt_when(message, &ready) {
            eprintln!("{phase}: interrupted compile {message:?}");
            assert_eq!(code, 130, "{phase}: compile {message:?} interrupted");
            assert!(left.is_empty(), "{phase}: left behind {left:?}");
            return;
        }
    }
    panic!("{phase}: every run finished before it could be interrupted");
}

#[test]
fn interrupted_while_computing_leaves_nothing() {
    // Ready as soon as the handler is in: compile is then planning, and
    // nothing exists in the folder yet.
    assert_interrupted_cleanly("computing", |dir| entries(dir).is_empty());
}

#[test]
fn interrupted_while_writing_leaves_nothing() {
    // Ready when a temporary file appears: the CSV or the job is being
    // written (and for the job, the finished CSV must go too).
    assert_interrupted_cleanly("writing", has_temp);
}

/// Temporary files in the folder.
fn temps(dir: &Path) -> usize {
    entries(dir)
        .iter()
        .filter(|n| n.starts_with(".basr-") && n.ends_with(".part"))
        .count()
}

#[test]
fn interrupted_between_outputs_keeps_the_earlier_files() {
    // The CSV is complete (staged) and the job is being written: the run
    // stops with 130, no temporary is left, and the files of an earlier run
    // under the same names keep their contents (the outputs are renamed into
    // place together, or not at all).
    for message in MESSAGES {
        let dir = tempfile::tempdir().unwrap();
        let job_name = format!("{}.job.json", message.replace(' ', "_"));
        std::fs::write(dir.path().join("setpoints.csv"), "earlier csv\n").unwrap();
        std::fs::write(dir.path().join(&job_name), "earlier job\n").unwrap();
        let mut child = spawn_compile(dir.path(), message);
        if wait_for_handler(&mut child).is_none() {
            continue;
        }
        let mut finished = false;
        while temps(dir.path()) < 2 {
            if child.try_wait().unwrap().is_some() {
                finished = true;
                break;
            }
            std::thread::sleep(std::time::Duration::from_micros(200));
        }
        if finished {
            continue;
        }
        send_sigint(child.id());
        let code = child.wait().unwrap().code();
        if code == Some(0) {
            continue; // it committed between our look and the signal
        }
        assert_eq!(code, Some(130), "compile {message:?} interrupted");
        let mut want = vec!["setpoints.csv".to_string(), job_name.clone()];
        want.sort();
        assert_eq!(entries(dir.path()), want, "only the earlier files");
        let read = |n: &str| std::fs::read_to_string(dir.path().join(n)).unwrap();
        assert_eq!(read("setpoints.csv"), "earlier csv\n");
        assert_eq!(read(&job_name), "earlier job\n");
        return;
    }
    panic!("every run finished before it could be interrupted");
}
