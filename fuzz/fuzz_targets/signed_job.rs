//! A signed job's bytes, edited by the fuzzer (replace, insert, delete or
//! flip bytes anywhere, the signature and the hash included): nothing that
//! differs from the original is accepted under the signing key's trust, and
//! the original always is (SPEC §7).
#![no_main]
use std::sync::OnceLock;

use basr_job::trust::{PublicKey, SecretKey};
use basr_job::Job;
use libfuzzer_sys::fuzz_target;

fn signed() -> &'static (Vec<u8>, PublicKey) {
    static JOB: OnceLock<(Vec<u8>, PublicKey)> = OnceLock::new();
    JOB.get_or_init(|| {
        let key = SecretKey::from_seed([7; 32]);
        let mut job = basr_sim::synthetic::letter_job();
        // A short job keeps each run fast; the edits reach every byte.
        let keep = 8.min(job.samples.len());
        let mut s = basr_job::Samples::default();
        for i in 0..keep {
            s.push(&job.samples.row(i).expect("row in range"));
        }
        job.samples = s;
        job.seal();
        job.sign(&key);
        (job.to_bytes(), key.public())
    })
}

fuzz_target!(|data: &[u8]| {
    let (original, key) = signed();
    let mut bytes = original.clone();
    for edit in data.chunks(4) {
        let [op, a, b, v] = [0, 1, 2, 3].map(|k| edit.get(k).copied().unwrap_or(0));
        if bytes.is_empty() {
            bytes.push(v);
            continue;
        }
        let at = (usize::from(a) << 8 | usize::from(b)) * bytes.len() / 65536;
        match op % 4 {
            0 => bytes[at] = v,
            1 => bytes.insert(at, v),
            2 => {
                bytes.remove(at);
            }
            _ => bytes[at] ^= 1 << (v % 8),
        }
    }
    let accepted = Job::from_bytes(bytes.clone(), "fuzz", Some(key)).is_ok();
    assert_eq!(
        accepted,
        bytes == *original,
        "accepted a changed job, or refused the original"
    );
});
