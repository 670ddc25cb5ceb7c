//! Progress on stderr for the commands that take seconds (a scene's or a
//! shape's compile, `simulate --plants`, a long preview): shown on a
//! terminal, never when stderr is a pipe or a file, under `--quiet` or
//! under `--json`. The terminal is util-linux's `script`, which runs the
//! command on a pseudo-terminal; without it those checks are skipped.

use std::path::{Path, PathBuf};
use std::process::Command as Std;

use assert_cmd::cargo::cargo_bin;

fn marking(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("markings")
        .join(name)
}

/// Everything `basr ARGS` writes to its terminal (stdout and stderr, run
/// under `script` in `dir`), escapes and all; `None` without `script`.
fn on_a_terminal(dir: &Path, args: &[&str]) -> Option<String> {
    let script = ["/usr/bin/script", "/bin/script"]
        .into_iter()
        .find(|p| Path::new(p).exists())?;
    // The shell line script runs: every argument quoted.
    let line: Vec<String> = std::iter::once(cargo_bin("basr").display().to_string())
        .chain(args.iter().map(|a| a.to_string()))
        .map(|a| format!("'{}'", a.replace('\'', "'\\''")))
        .collect();
    let log = dir.join("terminal.log");
    let out = Std::new(script)
        .current_dir(dir)
        .args(["-qec", &line.join(" ")])
        .arg(&log)
        .output()
        .unwrap();
    assert!(
        out.status.code().is_some(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(String::from_utf8_lossy(&std::fs::read(&log).unwrap()).into_owned())
}

#[test]
fn a_scene_compile_shows_progress_on_a_terminal_only() {
    let dir = tempfile::tempdir().unwrap();
    let m = marking("stop_line.toml");
    let m = m.to_str().unwrap();
    // Piped: no progress, no control characters.
    let out = Std::new(cargo_bin("basr"))
        .current_dir(dir.path())
        .args(["compile", "--marking", m, "-o", "piped.job.json"])
        .output()
        .unwrap();
    assert!(dir.path().join("piped.job.json").exists());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("compiling stop_line.toml"), "{err}");
    assert!(!err.contains('\u{1b}') && !err.contains('\r'), "{err:?}");

    let Some(shown) = on_a_terminal(
        dir.path(),
        &["compile", "--marking", m, "-o", "tty.job.json"],
    ) else {
        eprintln!("no `script` here: the terminal checks are skipped");
        return;
    };
    assert!(dir.path().join("tty.job.json").exists(), "{shown}");
    assert!(shown.contains("compiling stop_line.toml"), "{shown}");
    for quiet in ["--quiet", "--json"] {
        let name = format!("tty{quiet}.job.json");
        let shown =
            on_a_terminal(dir.path(), &["compile", "--marking", m, quiet, "-o", &name]).unwrap();
        assert!(dir.path().join(&name).exists(), "{shown}");
        assert!(
            !shown.contains("compiling stop_line.toml"),
            "{quiet}: {shown}"
        );
    }
    // simulate --plants counts its plants.
    let shown = on_a_terminal(
        dir.path(),
        &["simulate", "tty.job.json", "--plants", "3", "--seed", "1"],
    )
    .unwrap();
    assert!(shown.contains("simulating 3 plants"), "{shown}");
    let shown = on_a_terminal(
        dir.path(),
        &["simulate", "tty.job.json", "--plants", "3", "--json"],
    )
    .unwrap();
    assert!(!shown.contains("simulating 3 plants"), "{shown}");
}
