//! Output files written atomically: a temporary file in the target's folder,
//! renamed over the target only when complete. An interrupted or failed run
//! leaves no partial file (SPEC §1).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// What an interrupt must remove: temporary files being written, and the
/// outputs this run already finished (an interrupted run leaves no output
/// file, not even the CSV written before its job). One lock for both: the
/// handler holds it while it removes files and exits, and a writer holds it
/// while it creates or renames, so no file slips between the two lists.
struct Outputs {
    in_flight: Vec<PathBuf>,
    finished: Vec<PathBuf>,
}

static OUTPUTS: Mutex<Outputs> = Mutex::new(Outputs {
    in_flight: Vec::new(),
    finished: Vec::new(),
});

fn outputs() -> std::sync::MutexGuard<'static, Outputs> {
    // A panic while the lock was held leaves the lists intact: keep going.
    OUTPUTS.lock().unwrap_or_else(|e| e.into_inner())
}

/// Errors from writing an output file.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    // The OS reason is the source, printed after this by `{:#}` (main's
    // error line), so it is not repeated here.
    #[error("cannot write {path} (check that the folder exists and is writable)")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

/// Install a Ctrl-C handler that deletes the temporary files in flight and
/// the outputs this run has finished, then exits with 130. Call once at
/// start-up; later calls are ignored.
pub fn install_interrupt_cleanup() {
    let _ = ctrlc::set_handler(|| {
        // Held until exit: no writer creates or renames a file after this.
        let out = outputs();
        for p in out.in_flight.iter().chain(&out.finished) {
            let _ = std::fs::remove_file(p);
        }
        // Not eprintln!: with stderr closed it would panic in the handler's
        // thread and the process would carry on instead of exiting.
        let _ = writeln!(std::io::stderr(), "interrupted: no output file was written");
        std::process::exit(130);
    });
}

fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// tempfile's error names the random temporary (`at path …/.basr-x1Y2.part`),
/// a file the user never asked for; keep only the OS reason.
fn without_temp_name(e: std::io::Error) -> std::io::Error {
    let text = e.to_string();
    match text.split_once(" at path ") {
        Some((reason, _)) => std::io::Error::new(e.kind(), reason.to_string()),
        None => e,
    }
}

/// Write `bytes` to `path` atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Write to `path` atomically through `fill`, which receives a buffered writer.
pub fn write_atomic_with(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), WriteError> {
    let err = |source| WriteError::Io {
        path: path.to_path_buf(),
        source,
    };
    // A device or a FIFO (`-o /dev/null`, `--csv /dev/stdout`, a named pipe)
    // is written in place: renaming a temporary file over it would replace
    // the device with a regular file, which for /dev/null breaks every
    // program on the machine. Nothing partial can be left in such a target.
    if let Ok(meta) = std::fs::metadata(path) {
        if !meta.is_file() && !meta.is_dir() {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(err)?;
            let mut w = std::io::BufWriter::new(file);
            return fill(&mut w).and_then(|()| w.flush()).map_err(err);
        }
    }
    // A symbolic link keeps pointing where it did: the new contents replace
    // the file it names, not the link itself.
    let resolved;
    let path = match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => match std::fs::canonicalize(path) {
            Ok(p) => {
                resolved = p;
                resolved.as_path()
            }
            Err(_) => path,
        },
        _ => path,
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".basr-").suffix(".part");
    // tempfile creates 0600 files; an output file is an ordinary document
    // the crew shares, so give it the usual rw-r--r--.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let (tmp, tmp_path) = {
        let mut out = outputs();
        let tmp = builder
            .tempfile_in(folder_of(path))
            .map_err(|e| err(without_temp_name(e)))?;
        let tmp_path = tmp.path().to_path_buf();
        out.in_flight.push(tmp_path.clone());
        (tmp, tmp_path)
    };
    let result = (|| {
        let mut w = std::io::BufWriter::new(tmp.as_file());
        fill(&mut w)?;
        w.flush()?;
        drop(w);
        tmp.as_file().sync_all()?;
        let mut out = outputs();
        tmp.persist(path).map_err(|e| e.error)?;
        out.finished.push(path.to_path_buf());
        Ok(())
    })();
    outputs().in_flight.retain(|p| p != &tmp_path);
    result.map_err(err)
}

/// Run `write`, which writes a set of outputs through [`write_atomic`] or
/// [`write_atomic_with`]; if it fails, remove the outputs it had finished,
/// so a failed run leaves none of its set behind (SPEC §1: a failed command
/// leaves no output file). The files come from the list the Ctrl-C handler
/// removes, so a command need not keep its own.
pub fn all_or_none<T, E>(write: impl FnOnce() -> Result<T, E>) -> Result<T, E> {
    let before = outputs().finished.len();
    let result = write();
    if result.is_err() {
        let mut out = outputs();
        let from = before.min(out.finished.len());
        for p in out.finished.drain(from..) {
            let _ = std::fs::remove_file(p);
        }
    }
    result
}

/// Write machine output (`--json`, `robot --toml`, completions) to standard
/// output. A reader that stops early (`basr glyphs --json | head`) closes the
/// pipe; that is not an error: the rest of the output is dropped and the
/// command ends with its own exit code. Other write errors (a full disk
/// behind `> file`) are returned.
pub fn print_stdout(text: &str) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        r => r,
    }
}

/// Lower-case hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    let digest = Sha256::digest(bytes);
    let mut s = String::with_capacity(64);
    for b in digest {
        s.push_str(&format!("{b:02x}"));
    }
    s
}

/// Read a whole input file as UTF-8 text, or `-` for standard input, with an
/// error that names the file and says what to do.
pub fn read_text(path: &Path) -> anyhow::Result<String> {
    use anyhow::Context;
    if path == Path::new("-") {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut s)
            .context("cannot read standard input as UTF-8 text")?;
        return Ok(s);
    }
    let bytes = std::fs::read(path).with_context(|| {
        format!(
            "cannot read {}: check the path and that the file is readable",
            path.display()
        )
    })?;
    String::from_utf8(bytes).map_err(|e| {
        anyhow::anyhow!(
            "{} is not UTF-8 text (invalid byte at offset {}): save it as UTF-8",
            path.display(),
            e.utf8_error().valid_up_to()
        )
    })
}

/// 1-based (line, column) of byte offset `offset` in `text`, columns counted
/// in characters; offsets past the end or inside a character never panic.
/// Shared by every reader that turns a parser's byte span into `file:line:col`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_whole_file_and_leaves_no_temp() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.txt");
        write_atomic(&p, b"first").unwrap();
        write_atomic(&p, b"second").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"second");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&p).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o644, "outputs are world-readable documents");
        }
    }

    #[test]
    fn a_missing_folder_is_reported_without_the_temporary_name() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("no-such-folder").join("out.txt");
        let e = anyhow::Error::from(write_atomic(&p, b"x").unwrap_err());
        let text = format!("{e:#}");
        assert!(
            text.contains("out.txt") && text.contains("folder exists"),
            "{text}"
        );
        assert!(!text.contains(".basr-"), "{text}");
        assert_eq!(text.matches("os error").count(), 1, "{text}");
    }

    #[test]
    fn failed_fill_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.txt");
        let r = write_atomic_with(&p, |_| Err(std::io::Error::other("boom")));
        assert!(r.is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn all_or_none_removes_the_outputs_of_a_failed_set_only() {
        let dir = tempfile::tempdir().unwrap();
        let kept = dir.path().join("kept.txt");
        write_atomic(&kept, b"before").unwrap();
        let (a, b) = (
            dir.path().join("a.txt"),
            dir.path().join("no-dir").join("b.txt"),
        );
        let r = all_or_none(|| {
            write_atomic(&a, b"first")?;
            write_atomic(&b, b"second")
        });
        assert!(r.is_err());
        assert!(!a.exists(), "the finished part of the set is removed");
        assert!(kept.exists(), "outputs of earlier, successful sets stay");
        let ok: Result<(), WriteError> = all_or_none(|| write_atomic(&a, b"again"));
        assert!(ok.is_ok() && a.exists());
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_target_is_written_in_place_not_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&p).status();
        if !made.map(|s| s.success()).unwrap_or(false) {
            return; // no mkfifo on this system: nothing to check
        }
        let reader = {
            let p = p.clone();
            std::thread::spawn(move || std::fs::read(p).unwrap())
        };
        write_atomic(&p, b"through the pipe").unwrap();
        // Checked before joining: had the FIFO been replaced, the reader
        // would wait on it forever.
        let kind = std::fs::symlink_metadata(&p).unwrap().file_type();
        assert!(kind.is_fifo(), "the FIFO must survive the write");
        assert_eq!(reader.join().unwrap(), b"through the pipe");
    }

    #[cfg(unix)]
    #[test]
    fn a_symlink_target_keeps_its_link() {
        let dir = tempfile::tempdir().unwrap();
        let real = dir.path().join("real.txt");
        let link = dir.path().join("link.txt");
        std::fs::write(&real, b"old").unwrap();
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
    }

    #[test]
    fn line_col_counts_lines_and_characters() {
        let t = "ab\nçd\nx";
        assert_eq!(line_col(t, 0), (1, 1));
        assert_eq!(line_col(t, 3), (2, 1));
        assert_eq!(line_col(t, 6), (2, 3));
        assert_eq!(line_col(t, 4), (2, 1), "inside a character: no panic");
        assert_eq!(line_col(t, 99), (3, 2));
    }

    #[test]
    fn sha256_of_empty_is_known() {
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
    }
}
