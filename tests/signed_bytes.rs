//! The property the `signed_job` fuzz target runs, as a proptest on the
//! stable toolchain: a signed job whose bytes are edited anywhere (bytes
//! replaced, inserted, deleted or flipped; a key repeated; spacing or
//! number spelling changed) is refused under the signing key's trust
//! unless the edits left the bytes as they were (SPEC §7).

use basr::job::trust::{PublicKey, SecretKey};
use basr::job::{Job, Samples};
use proptest::prelude::*;

fn signed() -> &'static (Vec<u8>, PublicKey) {
    static JOB: std::sync::OnceLock<(Vec<u8>, PublicKey)> = std::sync::OnceLock::new();
    JOB.get_or_init(|| {
        let key = SecretKey::from_seed([7; 32]);
        let mut job = basr::sim::synthetic::letter_job();
        let mut s = Samples::default();
        for i in 0..8.min(job.samples.len()) {
            s.push(&job.samples.row(i).unwrap());
        }
        job.samples = s;
        job.seal();
        job.sign(&key);
        (job.to_bytes(), key.public())
    })
}

#[derive(Clone, Debug)]
enum Edit {
    Set(prop::sample::Index, u8),
    Insert(prop::sample::Index, u8),
    Delete(prop::sample::Index),
    Flip(prop::sample::Index, u8),
    /// Repeat the line at the index (a key given twice, an array value
    /// doubled).
    RepeatLine(prop::sample::Index),
    /// Swap the line at the index with the next (key order).
    SwapLines(prop::sample::Index),
    /// One `e` of an exponent upper-cased, or `: ` made `:`.
    Respell(prop::sample::Index, bool),
}

fn edit() -> impl Strategy<Value = Edit> {
    let i = any::<prop::sample::Index>;
    prop_oneof![
        (i(), any::<u8>()).prop_map(|(a, b)| Edit::Set(a, b)),
        (i(), any::<u8>()).prop_map(|(a, b)| Edit::Insert(a, b)),
        i().prop_map(Edit::Delete),
        (i(), 0u8..8).prop_map(|(a, b)| Edit::Flip(a, b)),
        i().prop_map(Edit::RepeatLine),
        i().prop_map(Edit::SwapLines),
        (i(), any::<bool>()).prop_map(|(a, b)| Edit::Respell(a, b)),
    ]
}

fn apply(bytes: &mut Vec<u8>, e: &Edit) {
    if bytes.is_empty() {
        return;
    }
    let line_at = |bytes: &[u8], k: usize| {
        let start = bytes[..k]
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |p| p + 1);
        let end = bytes[k..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |p| k + p + 1);
        start..end
    };
    match e {
        Edit::Set(i, v) => {
            let k = i.index(bytes.len());
            bytes[k] = *v;
        }
        Edit::Insert(i, v) => {
            let k = i.index(bytes.len() + 1);
            bytes.insert(k, *v);
        }
        Edit::Delete(i) => {
            bytes.remove(i.index(bytes.len()));
        }
        Edit::Flip(i, bit) => {
            let k = i.index(bytes.len());
            bytes[k] ^= 1 << bit;
        }
        Edit::RepeatLine(i) => {
            let r = line_at(bytes, i.index(bytes.len()));
            let line = bytes[r.clone()].to_vec();
            bytes.splice(r.start..r.start, line);
        }
        Edit::SwapLines(i) => {
            let a = line_at(bytes, i.index(bytes.len()));
            if a.end < bytes.len() {
                let b = line_at(bytes, a.end);
                let (la, lb) = (bytes[a.clone()].to_vec(), bytes[b.clone()].to_vec());
                bytes.splice(a.start..b.end, lb.into_iter().chain(la));
            }
        }
        Edit::Respell(i, exponent) => {
            let pat: &[u8] = if *exponent { b"e-" } else { b": " };
            let hits: Vec<usize> = bytes
                .windows(2)
                .enumerate()
                .filter(|(_, w)| *w == pat)
                .map(|(k, _)| k)
                .collect();
            if !hits.is_empty() {
                let k = hits[i.index(hits.len())];
                if *exponent {
                    bytes[k] = b'E';
                } else {
                    bytes.remove(k + 1);
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(3000),
        ..ProptestConfig::default()
    })]

    #[test]
    fn no_edited_signed_job_is_trusted(edits in prop::collection::vec(edit(), 1..6)) {
        let (original, key) = signed();
        let mut bytes = original.clone();
        for e in &edits {
            apply(&mut bytes, e);
        }
        let accepted = Job::from_bytes(bytes.clone(), "edited", Some(key)).is_ok();
        prop_assert_eq!(accepted, bytes == *original);
    }
}

#[test]
fn the_original_is_trusted_and_only_under_its_key() {
    let (original, key) = signed();
    assert!(Job::from_bytes(original.clone(), "j", Some(key)).is_ok());
    let other = SecretKey::from_seed([8; 32]).public();
    let e = Job::from_bytes(original.clone(), "j", Some(&other)).unwrap_err();
    assert!(e.to_string().contains(&key.id()), "{e}");
}
