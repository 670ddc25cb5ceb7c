//! The jobs basr writes are pinned by their SHA-256: STOP, SCHOOL XING,
//! every shipped marking file, every library symbol, an imported shape and
//! each robot kind, as recorded in `tests/data/output_hashes.txt`.
//!
//! The table was recorded on main ee239cc, before the code was split into a
//! workspace, so a refactor that moves code cannot change a job unnoticed.
//! A change that alters a job on purpose updates its line and says why.

use std::path::Path;
use std::process::Command;

struct Case {
    name: String,
    args: Vec<String>,
    sha256: String,
}

fn cases() -> Vec<Case> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("tests/data/output_hashes.txt"))
        .expect("tests/data/output_hashes.txt is part of the repository");
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let parts: Vec<&str> = l.split('|').collect();
            assert_eq!(parts.len(), 3, "bad line in output_hashes.txt: {l}");
            Case {
                name: parts[0].to_string(),
                args: parts[1].split(';').map(str::to_string).collect(),
                sha256: parts[2].to_string(),
            }
        })
        .collect()
}

/// Compiles one case into `dir` and returns the job's SHA-256, or why not.
fn job_sha256(case: &Case, dir: &Path) -> Result<String, String> {
    use sha2::{Digest, Sha256};
    let job = dir.join(format!("{}.job.json", case.name));
    let out = Command::new(env!("CARGO_BIN_EXE_basr"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(&case.args)
        .arg("-o")
        .arg(&job)
        .arg("--quiet")
        .output()
        .map_err(|e| format!("cannot run basr: {e}"))?;
    let bytes = std::fs::read(&job).map_err(|e| {
        format!(
            "{}: no job written (exit {:?}): {e}\n{}",
            case.name,
            out.status.code(),
            String::from_utf8_lossy(&out.stderr)
        )
    })?;
    Ok(Sha256::digest(&bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect())
}

#[test]
fn every_pinned_job_is_byte_identical() {
    let cases = cases();
    // Every kind of input the pipeline takes is pinned (the table cannot
    // quietly shrink to the cheap cases).
    for prefix in ["word-", "words-", "marking-", "symbol-", "shape-", "kind-"] {
        assert!(
            cases.iter().any(|c| c.name.starts_with(prefix)),
            "no {prefix} case in output_hashes.txt"
        );
    }
    let dir = tempfile::tempdir().expect("temporary folder");
    // Two workers: the cases are independent processes.
    let half = cases.len().div_ceil(2);
    let (a, b) = cases.split_at(half);
    let run = |part: &[Case]| -> Vec<String> {
        part.iter()
            .filter_map(|c| match job_sha256(c, dir.path()) {
                Ok(h) if h == c.sha256 => None,
                Ok(h) => Some(format!("{}: sha256 {h}, pinned {}", c.name, c.sha256)),
                Err(e) => Some(e),
            })
            .collect()
    };
    let mut differ = std::thread::scope(|s| {
        let other = s.spawn(|| run(b));
        let mut mine = run(a);
        mine.extend(other.join().expect("worker thread"));
        mine
    });
    differ.sort();
    assert!(
        differ.is_empty(),
        "{} of {} jobs differ from tests/data/output_hashes.txt:\n{}",
        differ.len(),
        cases.len(),
        differ.join("\n")
    );
}
