//! Canonical bytes of a JSON value, the form every document and description
//! hash is taken over (job `sha256`, `robot_sha256`): compact JSON of a
//! `serde_json::Value`, object keys in byte order (serde_json's default
//! sorted map), numbers in serde_json's shortest round-trip form. A module of
//! its own so `robot` and `job` both use it without importing each other.

/// Canonical bytes of a JSON value (see the module docs).
pub fn canonical_json(v: &serde_json::Value) -> Vec<u8> {
    serde_json::to_vec(v).expect("a serde_json::Value always serialises")
}
