//! Signed jobs (SPEC §7, docs/job-signing.md): Ed25519 keys written by
//! `basr keygen`, the `signature` member a job carries, and `--trust`, the
//! option (or `BASR_TRUST`) under which a reader accepts only jobs signed by
//! one key.
//!
//! Key files are one line of text: `basr-ed25519-secret <base64 seed>` (the
//! 32-byte RFC 8032 secret, file mode 0600) and `basr-ed25519-public <base64
//! key>`. A key's id is the first 16 hex digits of the SHA-256 of its 32
//! public-key bytes; a signature names the id of the key that made it.

use std::path::{Path, PathBuf};

use base64::Engine as _;
use ed25519_dalek::{Signer as _, SigningKey, VerifyingKey};
use serde::{Deserialize, Serialize};

use super::Job;

const SECRET_TAG: &str = "basr-ed25519-secret";
const PUBLIC_TAG: &str = "basr-ed25519-public";
/// Environment variable read when `--trust` is not given.
pub const TRUST_ENV: &str = "BASR_TRUST";

/// The `signature` member of a job: the Ed25519 signature (RFC 8032, base64)
/// of the job's canonical bytes without this member, and the id of the key.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Signature {
    pub key_id: String,
    pub ed25519: String,
}

fn b64() -> base64::engine::GeneralPurpose {
    base64::engine::general_purpose::STANDARD
}

/// Id of a public key (see the module docs).
fn key_id(key: &VerifyingKey) -> String {
    basr_io::sha256_hex(key.as_bytes())[..16].to_string()
}

/// The 32 bytes after `tag` on the key file's one line.
fn parse_key_text(text: &str, tag: &str, origin: &str) -> anyhow::Result<[u8; 32]> {
    let what = if tag == SECRET_TAG {
        "secret"
    } else {
        "public"
    };
    let line = text.trim();
    let body = line
        .strip_prefix(tag)
        .map(str::trim)
        .filter(|b| !b.contains(char::is_whitespace));
    let bytes = body.and_then(|b| b64().decode(b).ok());
    match bytes.and_then(|b| <[u8; 32]>::try_from(b).ok()) {
        Some(k) => Ok(k),
        None => {
            let other = if tag == SECRET_TAG {
                PUBLIC_TAG
            } else {
                SECRET_TAG
            };
            let hint = if line.starts_with(other) {
                format!(
                    " (it is a {} key: give the {what} one)",
                    if what == "secret" { "public" } else { "secret" }
                )
            } else {
                String::new()
            };
            anyhow::bail!(
                "{origin}: not a basr {what} key{hint}: expected one line `{tag} <base64 of 32 \
                 bytes>` as written by `basr keygen -o NAME`"
            )
        }
    }
}

/// A secret (signing) key.
pub struct SecretKey {
    key: SigningKey,
}

impl SecretKey {
    /// A new key from the operating system's random source.
    pub fn generate() -> anyhow::Result<SecretKey> {
        let mut seed = [0u8; 32];
        getrandom::fill(&mut seed)
            .map_err(|e| anyhow::anyhow!("the system's random source failed: {e}"))?;
        Ok(SecretKey {
            key: SigningKey::from_bytes(&seed),
        })
    }

    /// A key from its 32-byte seed (tests, fuzzing: a fixed key).
    pub fn from_seed(seed: [u8; 32]) -> SecretKey {
        SecretKey {
            key: SigningKey::from_bytes(&seed),
        }
    }

    pub fn from_text(text: &str, origin: &str) -> anyhow::Result<SecretKey> {
        Ok(SecretKey::from_seed(parse_key_text(
            text, SECRET_TAG, origin,
        )?))
    }

    /// Read a secret key file; one that others may read is refused (its
    /// signatures would prove nothing).
    pub fn load(path: &Path) -> anyhow::Result<SecretKey> {
        let text = basr_io::read_text(path)?;
        // A public key is no secret: say so before its mode (it was told to
        // `chmod 600` a .pub file, issue 31 R10).
        if text.trim_start().starts_with(PUBLIC_TAG) {
            anyhow::bail!(
                "{}: this is a public key; give the secret key (the file `basr keygen -o NAME` \
                 wrote as NAME, without .pub)",
                path.display()
            );
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            if let Ok(meta) = std::fs::metadata(path) {
                let mode = meta.permissions().mode() & 0o777;
                anyhow::ensure!(
                    mode & 0o077 == 0,
                    "{}: the secret key is readable by others (mode {mode:o}): anyone who \
                     read it can sign jobs; make a new key with `basr keygen`, or if it never \
                     left your hands, `chmod 600 {}`",
                    path.display(),
                    path.display()
                );
            }
        }
        SecretKey::from_text(&text, &path.display().to_string())
    }

    /// The key file's text.
    pub fn to_text(&self) -> String {
        format!("{SECRET_TAG} {}\n", b64().encode(self.key.to_bytes()))
    }

    pub fn public(&self) -> PublicKey {
        PublicKey {
            key: self.key.verifying_key(),
        }
    }

    /// Sign `message`.
    pub fn sign(&self, message: &[u8]) -> Signature {
        Signature {
            key_id: key_id(&self.key.verifying_key()),
            ed25519: b64().encode(self.key.sign(message).to_bytes()),
        }
    }
}

/// A public (verifying) key.
#[derive(Clone, Debug, PartialEq)]
pub struct PublicKey {
    key: VerifyingKey,
}

impl PublicKey {
    pub fn from_text(text: &str, origin: &str) -> anyhow::Result<PublicKey> {
        let bytes = parse_key_text(text, PUBLIC_TAG, origin)?;
        let key = VerifyingKey::from_bytes(&bytes).map_err(|_| {
            anyhow::anyhow!("{origin}: the public key is not a point of Ed25519's curve")
        })?;
        Ok(PublicKey { key })
    }

    pub fn load(path: &Path) -> anyhow::Result<PublicKey> {
        let text = basr_io::read_text(path)?;
        PublicKey::from_text(&text, &path.display().to_string())
    }

    pub fn to_text(&self) -> String {
        format!("{PUBLIC_TAG} {}\n", b64().encode(self.key.as_bytes()))
    }

    /// The key's id (see the module docs).
    pub fn id(&self) -> String {
        key_id(&self.key)
    }

    /// Whether `sig` is this key's signature of `message` (RFC 8032, with
    /// the strict checks that refuse malleable signatures). The base64 is
    /// decoded strictly (padding and trailing bits), so a signature that
    /// verifies has one spelling: under `--trust` no byte of the file is
    /// free to change.
    pub fn verifies(&self, message: &[u8], sig: &Signature) -> bool {
        let Ok(bytes) = b64().decode(&sig.ed25519) else {
            return false;
        };
        let Ok(sig) = ed25519_dalek::Signature::from_slice(&bytes) else {
            return false;
        };
        self.key.verify_strict(message, &sig).is_ok()
    }
}

/// `--trust KEY.pub`, for every command that reads a job (check, preview,
/// simulate, report): flatten it into the command's clap arguments.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct TrustOptions {
    /// Accept only jobs signed by this public key (NAME.pub from `basr
    /// keygen`); unsigned jobs and jobs signed by another key are refused.
    /// Set BASR_TRUST once on a truck's controller instead of passing it.
    #[arg(long, value_name = "KEY.pub", env = TRUST_ENV)]
    pub trust: Option<PathBuf>,
}

impl TrustOptions {
    /// The trusted key, when one is given (an empty BASR_TRUST is none).
    pub fn key(&self) -> anyhow::Result<Option<PublicKey>> {
        match &self.trust {
            Some(p) if !p.as_os_str().is_empty() => PublicKey::load(p).map(Some),
            _ => Ok(None),
        }
    }

    /// Read and verify a job, under the trusted key when one is given.
    pub fn read_job(&self, path: &Path) -> anyhow::Result<Job> {
        let key = self.key()?;
        Job::read_trusted(path, key.as_ref())
    }
}

/// Environment variable naming the folder of public keys `check` and
/// `report` verify a signature with when no `--trust` is given.
pub const KEYS_ENV: &str = "BASR_KEYS";

/// The folder of known public keys: `BASR_KEYS` when set (and not empty),
/// else `$XDG_CONFIG_HOME/basr/keys`, else `$HOME/.config/basr/keys`.
pub fn key_folder() -> Option<PathBuf> {
    let var = |k: &str| {
        std::env::var_os(k)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    var(KEYS_ENV)
        .or_else(|| var("XDG_CONFIG_HOME").map(|c| c.join("basr").join("keys")))
        .or_else(|| var("HOME").map(|h| h.join(".config").join("basr").join("keys")))
}

/// The public key with id `key_id` among the `*.pub` files of `folder`;
/// files that are not basr public keys are passed over (the folder may
/// hold anything).
pub fn find_key(folder: &Path, key_id: &str) -> Option<(PathBuf, PublicKey)> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(folder)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "pub") && p.is_file())
        .collect();
    // The same key found first whatever order the folder lists.
    paths.sort();
    paths
        .into_iter()
        .filter_map(|p| PublicKey::load(&p).ok().map(|k| (p, k)))
        .find(|(_, k)| k.id() == key_id)
}

/// What a reader can say of a job's signature.
#[derive(Clone, Debug, PartialEq)]
pub enum Seal {
    Unsigned,
    /// Verified with this key file (a `--trust` key or one of [`key_folder`]).
    Verified {
        key_id: String,
        key: PathBuf,
    },
    /// Well formed, but no key with its id was at hand: anyone could have
    /// written it (a copied or forged signature looks the same).
    Unverified {
        key_id: String,
    },
}

impl Seal {
    /// For messages and the job sheet; never "signed by" unverified.
    pub fn describe(&self) -> String {
        match self {
            Seal::Unsigned => "not signed".into(),
            Seal::Verified { key_id, key } => {
                format!("signed by key {key_id}, verified with {}", key.display())
            }
            Seal::Unverified { key_id } => format!(
                "signed, not verified (give --trust KEY.pub); the signature names key {key_id}"
            ),
        }
    }
}

/// Why a signature cannot be anyone's, read without a key: its key id is not
/// 16 lowercase hex digits, or its `ed25519` is not the strict base64 of 64
/// bytes (an empty or garbage signature).
pub fn malformed(sig: &Signature) -> Option<String> {
    let hex = |c: char| c.is_ascii_digit() || ('a'..='f').contains(&c);
    if sig.key_id.len() != 16 || !sig.key_id.chars().all(hex) {
        return Some(format!(
            "its key_id {:?} is not a key id (16 lowercase hex digits)",
            basr_io::one_line(&sig.key_id.chars().take(40).collect::<String>())
        ));
    }
    match b64().decode(&sig.ed25519) {
        Ok(b) if b.len() == 64 => None,
        Ok(b) => Some(format!(
            "its ed25519 holds {} bytes, not the 64 of an Ed25519 signature",
            b.len()
        )),
        Err(_) => Some("its ed25519 is not base64".into()),
    }
}

/// Why a job's signature is no signature of it.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SealError {
    /// Not a signature at all (what is wrong with it).
    #[error(
        "the signature is malformed ({0}): it is no one's signature; compile the job again \
         with --sign"
    )]
    Malformed(String),
    /// A signature, but the key with its id at hand refuses it.
    #[error(
        "integrity check failed: the signature does not verify with key {key_id} ({}): the job \
         was edited after it was signed or the signature was copied from another job; compile \
         it again",
        .key.display()
    )]
    DoesNotVerify { key_id: String, key: PathBuf },
}

/// The seal of a job read without `--trust`: `signature` as read from the
/// job, `signed` the bytes it signs ([`super::signed_bytes`]), checked
/// against the key with its id in [`key_folder`]. Err says why it is no
/// signature of this job: malformed, or the key at hand refuses it.
pub fn examine(
    signature: Option<&Signature>,
    signed: Option<&[u8]>,
    folder: Option<&Path>,
) -> Result<Seal, SealError> {
    let Some(sig) = signature else {
        return Ok(Seal::Unsigned);
    };
    if let Some(why) = malformed(sig) {
        return Err(SealError::Malformed(why));
    }
    let found = folder.and_then(|f| find_key(f, &sig.key_id));
    match (found, signed) {
        (Some((path, key)), Some(bytes)) => {
            if key.verifies(bytes, sig) {
                Ok(Seal::Verified {
                    key_id: sig.key_id.clone(),
                    key: path,
                })
            } else {
                Err(SealError::DoesNotVerify {
                    key_id: sig.key_id.clone(),
                    key: path,
                })
            }
        }
        _ => Ok(Seal::Unverified {
            key_id: sig.key_id.clone(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_round_trip_and_sign() {
        let k = SecretKey::from_seed([7; 32]);
        let back = SecretKey::from_text(&k.to_text(), "k").unwrap();
        assert_eq!(back.to_text(), k.to_text());
        let p = PublicKey::from_text(&k.public().to_text(), "k.pub").unwrap();
        assert_eq!(p, k.public());
        assert_eq!(p.id().len(), 16);
        let sig = k.sign(b"job bytes");
        assert_eq!(sig.key_id, p.id());
        assert!(p.verifies(b"job bytes", &sig));
        assert!(!p.verifies(b"job bytez", &sig));
        let other = SecretKey::from_seed([8; 32]).public();
        assert_ne!(other.id(), p.id());
        assert!(!other.verifies(b"job bytes", &sig));
        let e = PublicKey::from_text(&k.to_text(), "k")
            .unwrap_err()
            .to_string();
        assert!(e.contains("it is a secret key"), "{e}");
        assert!(SecretKey::from_text("basr-ed25519-secret AAAA\n", "k").is_err());
    }
}
