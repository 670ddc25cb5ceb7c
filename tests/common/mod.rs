//! What the end-to-end tests share: running the built `basr` binary in a
//! folder and reading what it said. Each test file that needs it declares
//! `mod common;` (not every file uses every helper).
#![allow(dead_code)]

use std::path::Path;
use std::process::Output;

/// Runs `basr args` in `dir` and returns what it did.
pub fn basr(dir: &Path, args: &[&str]) -> Output {
    assert_cmd::Command::cargo_bin("basr")
        .expect("the basr binary is built")
        .current_dir(dir)
        .args(args)
        .output()
        .expect("basr runs")
}

/// What a run wrote to stderr, as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// What a run wrote to stdout, as text.
pub fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Asserts a run succeeded (showing its stderr if not) and returns it.
pub fn succeeded(out: Output) -> Output {
    assert!(out.status.success(), "{}", stderr(&out));
    out
}

/// Asserts a run succeeded and parses its stdout as JSON.
pub fn json_of(out: Output) -> serde_json::Value {
    let out = succeeded(out);
    serde_json::from_slice(&out.stdout).expect("stdout is JSON")
}
