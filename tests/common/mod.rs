//! What the end-to-end tests share: running the built `basr` binary in a
//! folder and reading what it said. Each test file that needs it declares
//! `mod common;` (not every file uses every helper).
#![allow(dead_code)]

pub mod noise;

use std::path::{Path, PathBuf};
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

/// A Chromium to render pages with: `BASR_CHROMIUM`, else the first of
/// the usual names on `PATH` (`.ci/run` installs Debian's `chromium`).
/// `None` when there is none: the browser tests then skip, saying so.
pub fn browser() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("BASR_CHROMIUM") {
        return Some(PathBuf::from(p));
    }
    let path = std::env::var_os("PATH")?;
    ["chromium", "chromium-browser", "google-chrome", "chrome"]
        .iter()
        .flat_map(|name| std::env::split_paths(&path).map(move |d| d.join(name)))
        .find(|p| p.is_file())
}

/// `toml` with its first line that starts with `key =` (after trimming)
/// replaced by `key = value`; the key must be there.
pub fn set_key(toml: &str, key: &str, value: &str) -> String {
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
    assert!(done, "key {key} not found in the description");
    lines.join("\n")
}
