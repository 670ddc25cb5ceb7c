//! Compact canonical bytes of a JSON value, the form description hashes are
//! taken over (`robot_sha256`; a job's own `sha256` and signature cover the
//! job's file form, `job::canonical`, docs/job-canonical-form.md): compact JSON of a
//! `serde_json::Value`, object keys in byte order (serde_json's default
//! sorted map), numbers in serde_json's shortest round-trip form. A module of
//! its own so `robot` and `job` both use it without importing each other.

/// Canonical bytes of a JSON value (see the module docs).
pub fn canonical_json(v: &serde_json::Value) -> Vec<u8> {
    serde_json::to_vec(v).expect("a serde_json::Value always serialises")
}
