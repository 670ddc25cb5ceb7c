//! A job's bytes do not depend on the machine's core count: the planner's
//! parallel work (each stroke's passes, each station's joint paths, each
//! station's verification, the film's bands and letters) is gathered in
//! its input's order, and a station runs its description beside the plant
//! set when it is the only one its round verifies, whatever the pool's
//! threads (its first failure in time re-timed, the description's or a
//! plant's; stations verified together re-time the description's first).
//! Compiled through the binary
//! with one, two and three worker threads (`RAYON_NUM_THREADS`): a word on
//! one stop, two lines on two stops, a scene of several stops, and two
//! lines where a plant of the set fails before the description does.

use std::path::Path;
use std::process::Command;

fn compile(args: &[&str], threads: usize, out: &Path) -> Vec<u8> {
    let status = Command::new(env!("CARGO_BIN_EXE_basr"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("RAYON_NUM_THREADS", threads.to_string())
        .arg("compile")
        .args(args)
        .arg("-q")
        .arg("-o")
        .arg(out)
        .status()
        .expect("runs basr");
    assert!(
        status.code().is_some_and(|c| c <= 1),
        "compile {args:?} with {threads} thread(s): {status}"
    );
    std::fs::read(out).expect("the job is written")
}

#[test]
fn every_core_count_writes_the_same_job() {
    let dir = tempfile::tempdir().expect("temporary folder");
    for (name, args) in [
        ("stop", vec!["STOP"]),
        ("school-xing", vec!["SCHOOL XING"]),
        ("stop-ahead", vec!["--marking", "markings/stop_ahead.toml"]),
        // a station where a plant strays before the description does: with
        // one thread, two or three, the same station is verified beside the
        // set in the same rounds
        ("bus-only", vec!["--marking", "markings/bus_only.toml"]),
    ] {
        let jobs: Vec<Vec<u8>> = [1, 2, 3]
            .iter()
            .map(|&n| compile(&args, n, &dir.path().join(format!("{name}-{n}.job.json"))))
            .collect();
        assert!(!jobs[0].is_empty());
        for (n, job) in [2, 3].iter().zip(&jobs[1..]) {
            assert!(
                job == &jobs[0],
                "{name}: the job compiled with {n} threads differs from the one compiled with 1"
            );
        }
    }
}
