//! Output paths checked before any work: a folder, a missing folder or a
//! name whose extension says another format is refused with what to give
//! instead, so a long run never ends in "Is a directory". Success lines
//! ("wrote STOP.svg") wait in [`after_commit`] until `main` has renamed
//! every output into place.

use std::path::Path;
use std::sync::Mutex;

/// Refuse `path` as the output `what` (`-o`, `--svg`) unless it can be
/// created as a file whose extension is one of `exts` (lower case, no dot;
/// empty: any). `-` (stdout) is always fine.
pub fn check(what: &str, path: &Path, exts: &[&str]) -> anyhow::Result<()> {
    if path.as_os_str() == "-" {
        return Ok(());
    }
    let shown = path.display();
    let example = exts
        .first()
        .map_or("out".to_string(), |e| format!("out.{e}"));
    let ends_in_slash = path.to_string_lossy().ends_with(['/', '\\']);
    if path.is_dir() || ends_in_slash {
        anyhow::bail!(
            "{what} {shown} is a folder; give a file name, e.g. {}",
            path.join(&example).display()
        );
    }
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
    if let Some(dir) = parent {
        if !dir.is_dir() {
            anyhow::bail!("{what} {shown}: {}", basr::io::no_folder(dir));
        }
    }
    if exts.is_empty() {
        return Ok(());
    }
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some(e) if exts.contains(&e) => Ok(()),
        Some("png") if exts.contains(&"svg") => anyhow::bail!(
            "{what} {shown}: basr draws SVG; give a .svg name and convert it if you need \
             PNG (`rsvg-convert -o {} {}`)",
            shown,
            path.with_extension("svg").display()
        ),
        got => anyhow::bail!(
            "{what} {shown}: this output is {}; give a name ending in .{}{}",
            describe(exts[0]),
            exts.join(" or ."),
            got.map_or(String::new(), |g| format!(" (not .{g})"))
        ),
    }
}

fn describe(ext: &str) -> &'static str {
    match ext {
        "svg" => "an SVG picture",
        "json" => "a JSON job",
        "csv" => "a CSV table",
        "html" | "htm" => "an HTML page",
        "toml" => "a TOML file",
        "yaml" | "yml" => "a YAML document",
        "mcap" => "an MCAP recording",
        "script" | "urscript" => "a URScript program",
        _ => "a file of another kind",
    }
}

static AFTER_COMMIT: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Human text to print once every output is in place (on success only).
pub fn after_commit(text: String) {
    if let Ok(mut v) = AFTER_COMMIT.lock() {
        v.push(text);
    }
}

/// The texts held by [`after_commit`], emptied.
pub fn take_after_commit() -> Vec<String> {
    AFTER_COMMIT
        .lock()
        .map(|mut v| std::mem::take(&mut *v))
        .unwrap_or_default()
}

/// Write `job` to `out` with the files that go with it: the setpoint CSV
/// and the Adept program where asked, written first and bound into the job
/// (resealed, so it records their hashes), then the signature with `key`,
/// then the job itself, last. `main` renames them all into place together
/// when the run succeeds.
pub fn write_job(
    job: &mut basr::job::Job,
    out: &Path,
    csv: Option<&Path>,
    adept: Option<&Path>,
    key: Option<&basr::job::trust::SecretKey>,
) -> anyhow::Result<()> {
    if let Some(csv) = csv {
        let sha256 = basr::job::csv::write(&job.samples, csv)?;
        job.bind_output("csv", csv, sha256);
    }
    if let Some(adept) = adept {
        let sha256 =
            basr::job::adept::write(&job.message, &job.samples, &job.stations, &job.road, adept)?;
        job.bind_output("adept", adept, sha256);
    }
    if !job.outputs.is_empty() {
        job.seal();
    }
    if let Some(key) = key {
        job.sign(key);
    }
    // WriteError names the path and the OS reason.
    job.write(out)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folders_missing_folders_and_wrong_extensions_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let err = check("-o", dir.path(), &["svg"]).unwrap_err().to_string();
        assert!(
            err.contains("is a folder") && err.contains("out.svg"),
            "{err}"
        );
        let err = check("-o", &dir.path().join("no/x.svg"), &["svg"])
            .unwrap_err()
            .to_string();
        assert!(err.contains("does not exist"), "{err}");
        let err = check("-o", &dir.path().join("x.png"), &["svg"])
            .unwrap_err()
            .to_string();
        assert!(err.contains("rsvg-convert"), "{err}");
        let err = check("-o", &dir.path().join("x.txt"), &["html", "htm"])
            .unwrap_err()
            .to_string();
        assert!(err.contains(".html or .htm (not .txt)"), "{err}");
        assert!(check("-o", &dir.path().join("x.SVG"), &["svg"]).is_ok());
        assert!(check("-o", Path::new("x.svg"), &["svg"]).is_ok());
        assert!(check("-o", Path::new("-"), &["svg"]).is_ok());
        assert!(check("--adept", Path::new("a.v2"), &[]).is_ok());
    }
}
