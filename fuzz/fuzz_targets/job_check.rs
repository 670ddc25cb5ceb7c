//! Job contents past the integrity check: any JSON that deserialises into a
//! job is sealed (as compile would), read back and checked by `basr check`'s
//! validator, which must report problems, never panic.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(mut job) = serde_json::from_slice::<basr_job::Job>(data) {
        job.seal();
        let bytes = job.to_bytes();
        if let Ok(text) = std::str::from_utf8(&bytes) {
            if let Ok(job) = basr_job::Job::from_str_verified(text, "fuzz") {
                let _ = basr_job::verify::problems(&job, "fuzz");
            }
        }
    }
});
