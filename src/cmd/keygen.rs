//! `basr keygen -o NAME`: a new Ed25519 key pair for signing jobs (docs/signed-jobs.md).

use std::path::{Path, PathBuf};

use basr::job::trust::SecretKey;

use super::{Global, Outcome};

/// Make a key pair for signing jobs: NAME (secret, mode 0600) and NAME.pub.
///
/// `basr compile --sign NAME` signs a job with the secret; readers given
/// `--trust NAME.pub` (or BASR_TRUST=NAME.pub) accept only jobs it signed.
/// Keep NAME where the jobs are compiled and copy only NAME.pub to the
/// truck. Existing files are never replaced.
#[derive(clap::Args)]
#[command(after_help = "\
Examples:
  basr keygen -o crew.key                  # writes crew.key and crew.key.pub
  basr compile STOP --sign crew.key
  basr simulate STOP.job.json --trust crew.key.pub
  export BASR_TRUST=$PWD/crew.key.pub      # on the truck's controller, once

The key id printed (16 hex digits) is the one a signed job names.")]
pub struct Args {
    /// Secret key file to write; the public key goes to NAME.pub.
    #[arg(short, long, value_name = "NAME")]
    pub output: PathBuf,
}

fn public_path(secret: &Path) -> PathBuf {
    let mut name = secret.as_os_str().to_owned();
    name.push(".pub");
    PathBuf::from(name)
}

pub fn run(args: Args, global: &Global) -> anyhow::Result<Outcome> {
    let secret_path = &args.output;
    let public_path = public_path(secret_path);
    for p in [secret_path, &public_path] {
        anyhow::ensure!(
            std::fs::symlink_metadata(p).is_err(),
            "{} exists: basr keygen never replaces a key (jobs signed with it could no longer \
             be trusted); remove it first or give another name",
            p.display()
        );
        basr::io::check_writable(p)?;
    }
    let key = SecretKey::generate()?;
    let public = key.public();
    basr::io::write_output(secret_path, Some(0o600), |w| {
        w.write_all(key.to_text().as_bytes())
    })?;
    basr::io::write_output(&public_path, Some(0o644), |w| {
        w.write_all(public.to_text().as_bytes())
    })?;
    if !global.quiet {
        note!(
            "{}: secret key (mode 600; keep it private); {}: public key; key id {}",
            secret_path.display(),
            public_path.display(),
            public.id()
        );
    }
    Ok(Outcome::Success)
}
