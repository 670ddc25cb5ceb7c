//! Reading a job: the bytes are checked to be canonical, hashed and (under
//! `--trust`) their signature verified before one typed parse turns them
//! into a [`Job`]. The document is never built as a `serde_json::Value`
//! (that took 4.7× the file in memory): the checks walk the bytes, and the
//! parse fills the sample columns directly.

use super::canonical::{self, Member};
use super::trust::{PublicKey, Signature};
use super::{Job, JobError, FORMAT, VERSION};

/// The top-level members a reader looks at before the typed parse.
#[derive(serde::Deserialize)]
struct Head {
    #[serde(default)]
    format: Option<serde_json::Value>,
    #[serde(default)]
    version: Option<serde_json::Value>,
}

fn check_head(head: Head, path: &str) -> Result<(), JobError> {
    let p = || path.to_string();
    let shown = |v: &Option<serde_json::Value>| {
        v.as_ref()
            .map_or_else(|| "missing".to_string(), |v| v.to_string())
    };
    if head.format.as_ref().and_then(|f| f.as_str()) != Some(FORMAT) {
        return Err(JobError::Format {
            path: p(),
            found: shown(&head.format),
        });
    }
    if head.version.as_ref().and_then(|v| v.as_u64()) != Some(VERSION as u64) {
        return Err(JobError::Version {
            path: p(),
            found: shown(&head.version),
        });
    }
    Ok(())
}

/// Why bytes that are not canonical were refused: not JSON at all (cut
/// short, or never a job), not a job of this version, or a job's JSON
/// spelled otherwise than basr writes it.
fn explain(bytes: &[u8], nc: canonical::NotCanonical, path: &str) -> JobError {
    match serde_json::from_slice::<Head>(bytes) {
        Err(detail) if detail.is_syntax() || detail.is_eof() => JobError::Syntax {
            path: path.to_string(),
            detail,
        },
        // JSON, but not an object: not a job at all.
        Err(_) if bytes.trim_ascii_start().first() != Some(&b'{') => JobError::Format {
            path: path.to_string(),
            found: "missing (the file is not a JSON object)".into(),
        },
        Ok(head) => match check_head(head, path) {
            Err(e) => e,
            Ok(()) => not_canonical(bytes, nc, path),
        },
        // A job's JSON spelled otherwise (a duplicate `format` is a serde
        // error here, and is said as the duplicate it is).
        Err(_) => not_canonical(bytes, nc, path),
    }
}

fn not_canonical(bytes: &[u8], nc: canonical::NotCanonical, path: &str) -> JobError {
    let (line, col) = nc.line_col(bytes);
    JobError::NotCanonical {
        path: path.to_string(),
        line,
        col,
        what: nc.what,
    }
}

fn member<'a>(members: &'a [Member], key: &str) -> Option<&'a Member> {
    members.iter().find(|m| m.key == key)
}

/// Remove the member at `k` from canonical `bytes` in place (no copy of the
/// document): what is left is the canonical form without it.
fn remove_member(bytes: &mut Vec<u8>, members: &[Member], k: usize) {
    let range = if k > 0 {
        members[k - 1].span.end..members[k].span.end
    } else if members.len() > 1 {
        members[0].span.start..members[1].span.start
    } else {
        // The only member: `{\n  M\n}\n` becomes `{}\n`.
        1..bytes.len() - 2
    };
    bytes.drain(range);
}

impl Job {
    /// Parse and verify a job from its bytes; `path` is used in messages
    /// only. With `trusted`, only a job signed by that key is accepted.
    pub fn from_bytes(
        mut bytes: Vec<u8>,
        path: &str,
        trusted: Option<&PublicKey>,
    ) -> Result<Job, JobError> {
        let p = || path.to_string();
        if bytes.iter().all(u8::is_ascii_whitespace) {
            return Err(JobError::Empty { path: p() });
        }
        if let Some(e) = basr_io::utf8_problem(&bytes, path) {
            return Err(JobError::NotUtf8(e));
        }
        let members = canonical::check(&bytes).map_err(|nc| explain(&bytes, nc, path))?;
        let head = Head {
            format: member_value(&bytes, &members, "format"),
            version: member_value(&bytes, &members, "version"),
        };
        check_head(head, path)?;
        let stated = member_value(&bytes, &members, "sha256")
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default();
        let actual = basr_io::sha256_hex_of(canonical::without(
            &bytes,
            &members,
            &["sha256", "signature"],
        ));
        if stated != actual {
            return Err(JobError::Hash {
                path: p(),
                stated: if stated.is_empty() {
                    "nothing".into()
                } else {
                    stated
                },
                actual,
            });
        }
        let signature: Option<Signature> = match member(&members, "signature") {
            None => None,
            Some(m) => Some(
                serde_json::from_slice(&bytes[m.value.clone()])
                    .map_err(|detail| JobError::Structure { path: p(), detail })?,
            ),
        };
        if let Some(key) = trusted {
            let Some(sig) = &signature else {
                return Err(JobError::Unsigned {
                    path: p(),
                    trusted: key.id(),
                });
            };
            if sig.key_id != key.id() {
                return Err(JobError::ForeignKey {
                    path: p(),
                    found: sig.key_id.clone(),
                    trusted: key.id(),
                });
            }
            let k = members.iter().position(|m| m.key == "signature");
            remove_member(&mut bytes, &members, k.expect("the signature is a member"));
            if !key.verifies(&bytes, sig) {
                return Err(JobError::BadSignature {
                    path: p(),
                    key_id: sig.key_id.clone(),
                });
            }
        }
        let mut job: Job = serde_json::from_slice(&bytes)
            .map_err(|detail| JobError::Structure { path: p(), detail })?;
        drop(bytes);
        job.signature = signature;
        let robot_actual = job.robot.sha256();
        if robot_actual != job.robot_sha256 {
            return Err(JobError::RobotHash {
                path: p(),
                stated: job.robot_sha256.clone(),
                actual: robot_actual,
            });
        }
        job.samples.check_lengths().map_err(|e| JobError::Invalid {
            path: p(),
            what: e.to_string(),
        })?;
        Ok(job)
    }
}

/// The bytes a job's signature signs: the file's bytes without its
/// `signature` member; `None` when the bytes are not a canonical job or
/// carry no signature.
pub fn signed_bytes(bytes: &[u8]) -> Option<Vec<u8>> {
    let members = canonical::check(bytes).ok()?;
    let k = members.iter().position(|m| m.key == "signature")?;
    let mut out = bytes.to_vec();
    remove_member(&mut out, &members, k);
    Some(out)
}

/// A small top-level member's value, parsed alone.
fn member_value(bytes: &[u8], members: &[Member], key: &str) -> Option<serde_json::Value> {
    member(members, key).and_then(|m| serde_json::from_slice(&bytes[m.value.clone()]).ok())
}
