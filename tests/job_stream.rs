//! A job is written and hashed as it is printed (`basr-job`'s `stream`:
//! the job without its samples and glyphs as a value, those streamed into
//! their places): the bytes must be the canonical bytes of the whole
//! value, and the seal's hash the hash of those without `sha256`, for a
//! job with letters on two lines and one of an electric kind (its own
//! sample columns).

use basr::job::{canonical, Job};
use basr::pipeline::compile::{compile_job, CompileRequest};

fn planned(message: &str, robot: Option<&str>) -> Job {
    let mut req = CompileRequest::message(message);
    req.verify = false;
    req.film = false;
    req.robot = robot.map(|r| std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(r));
    compile_job(&req).expect("it plans")
}

#[test]
fn streamed_bytes_and_hash_are_the_whole_values() {
    for job in [
        planned("STOP AHEAD", None),
        planned("ON", Some("robots/telescopic.toml")),
    ] {
        assert!(!job.layout.glyphs.is_empty());
        let value = serde_json::to_value(&job).unwrap();
        let bytes = job.to_bytes();
        assert_eq!(bytes, canonical::to_canonical(&value), "{}", job.message);
        assert_eq!(
            job.sha256,
            basr::job::document_sha256(value),
            "{}",
            job.message
        );
        // and what is read back verifies and writes the same bytes
        let back = Job::from_str_verified(std::str::from_utf8(&bytes).unwrap(), "t").unwrap();
        assert_eq!(back.to_bytes(), bytes);
    }
    assert!(!planned("ON", Some("robots/telescopic.toml"))
        .samples
        .kind_columns
        .is_empty());
}
