//! # basr-io
//!
//! Files basr reads and writes: atomic, staged outputs; bounded inputs; SHA-256; canonical JSON bytes (`canon`); numbers as messages print them. Imports no other basr crate: every other crate may use it. The workspace's crates are the pipeline (docs/architecture.md).
//!
//! Output files written atomically: a temporary file in the target's folder,
//! renamed over the target only when complete. An interrupted or failed run
//! leaves no partial file (SPEC §1).
//!
//! The binary stages its outputs ([`stage_outputs`]): every file of a run is
//! written to its temporary and all are renamed together at the end
//! ([`commit_outputs`]) or all dropped ([`discard_outputs`]). A run that fails
//! or is interrupted after writing its CSV but before its job leaves neither,
//! and the files an earlier run left under those names are untouched.

pub mod canon;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The temporary files of this run and, when staging, the finished ones
/// waiting for [`commit_outputs`]. One lock for all: the interrupt handler
/// holds it while it removes files and exits, and a writer holds it while it
/// creates or renames, so no file slips between the two.
struct Outputs {
    /// Temporary files on disk (being written, or staged).
    in_flight: Vec<PathBuf>,
    /// Complete temporaries and their targets, renamed by `commit_outputs`.
    staged: Vec<(tempfile::NamedTempFile, PathBuf)>,
    staging: bool,
    /// The run's outputs are in place: an interrupt now changes nothing.
    committed: bool,
}

static OUTPUTS: Mutex<Outputs> = Mutex::new(Outputs {
    in_flight: Vec::new(),
    staged: Vec::new(),
    staging: false,
    committed: false,
});

fn outputs() -> std::sync::MutexGuard<'static, Outputs> {
    // A panic while the lock was held leaves the lists intact: keep going.
    OUTPUTS.lock().unwrap_or_else(|e| e.into_inner())
}

/// From now on, [`write_atomic`] keeps each finished file as a temporary
/// until [`commit_outputs`]. The binary calls it once at start-up; library
/// callers (tests, benches) that do not, get the file in place at once.
pub fn stage_outputs() {
    outputs().staging = true;
}

/// Rename every staged output over its target, in the order written
/// (commands write their job last, so a job never stands beside a CSV
/// older or newer than itself). All or none: when a rename fails, the
/// targets already replaced get their earlier contents back and the rest
/// are not touched. Call once, when the run has succeeded (or reached its
/// verdict). The lock is held throughout, so a signal waits for the end.
pub fn commit_outputs() -> Result<(), WriteError> {
    let mut out = outputs();
    let staged = std::mem::take(&mut out.staged);
    let result = commit_all(staged);
    out.committed = result.is_ok();
    out.in_flight.clear();
    result
}

/// A target replaced during a commit, and the earlier file under it.
struct Replaced {
    target: PathBuf,
    /// A hard link (or copy) of the earlier file, `None` when there was none.
    backup: Option<PathBuf>,
}

/// Keep the earlier file at `target` under a new name beside it (a hard
/// link: nothing is copied), so a failed commit can put it back.
fn keep_earlier(target: &Path, n: usize) -> std::io::Result<Option<PathBuf>> {
    match std::fs::symlink_metadata(target) {
        Ok(m) if m.is_file() => {}
        _ => return Ok(None),
    }
    let backup = folder_of(target).join(format!(".basr-{}-{n}.old", std::process::id()));
    let _ = std::fs::remove_file(&backup);
    if std::fs::hard_link(target, &backup).is_err() {
        std::fs::copy(target, &backup)?;
    }
    Ok(Some(backup))
}

/// Rename each staged temporary over its target; on the first failure put
/// back what was replaced (see [`commit_outputs`]).
fn commit_all(staged: Vec<(tempfile::NamedTempFile, PathBuf)>) -> Result<(), WriteError> {
    let mut done: Vec<Replaced> = Vec::new();
    let mut failure = None;
    for (n, (tmp, target)) in staged.into_iter().enumerate() {
        let step = keep_earlier(&target, n).and_then(|backup| match tmp.persist(&target) {
            Ok(_) => Ok(backup),
            Err(e) => {
                if let Some(b) = &backup {
                    let _ = std::fs::remove_file(b);
                }
                Err(e.error)
            }
        });
        match step {
            Ok(backup) => done.push(Replaced { target, backup }),
            Err(source) => {
                failure = Some(WriteError::Io {
                    path: target,
                    source: without_temp_name(source),
                });
                break;
            }
        }
        // The temporaries not reached are deleted when the loop's
        // remaining items drop.
    }
    if let Some(e) = failure {
        for r in done.iter().rev() {
            let _ = match &r.backup {
                Some(b) => std::fs::rename(b, &r.target),
                None => std::fs::remove_file(&r.target),
            };
        }
        return Err(e);
    }
    for r in &done {
        if let Some(b) = &r.backup {
            let _ = std::fs::remove_file(b);
        }
    }
    Ok(())
}

/// Drop every staged output (their temporaries are deleted); the targets
/// keep whatever they held before the run.
pub fn discard_outputs() {
    let mut out = outputs();
    out.staged.clear();
    out.in_flight.clear();
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
    #[error("cannot write {path}: {why}")]
    Unwritable { path: PathBuf, why: String },
}

/// Why `folder` (which does not exist) cannot take an output, in words: a
/// file where one of its folders should be (`-o notes.txt/x.csv`) is named
/// as such, since "does not exist" would send the user to make a folder
/// that cannot be made there.
pub fn no_folder(folder: &Path) -> String {
    let file = folder
        .ancestors()
        .find(|a| !a.as_os_str().is_empty() && a.exists())
        .filter(|a| !a.is_dir());
    match file {
        Some(f) if f == folder => format!(
            "{} is a file, not a folder; give a path in an existing folder",
            f.display()
        ),
        Some(f) => format!(
            "{} is a file, not a folder, so the folder {} cannot be made; give a path in an \
             existing folder",
            f.display(),
            folder.display()
        ),
        None => format!(
            "the folder {} does not exist; create it first or give another path",
            folder.display()
        ),
    }
}

/// Check before the work starts that `path` can be written as an output:
/// not a folder, in a folder that exists and takes new files (tried with a
/// temporary that is removed at once). A device or FIFO is written in place
/// and passes. Commands call it for every output path before computing.
pub fn check_writable(path: &Path) -> Result<(), WriteError> {
    let bad = |why: String| WriteError::Unwritable {
        path: path.to_path_buf(),
        why,
    };
    if path == Path::new("-") {
        return Ok(());
    }
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => {
            return Err(bad(
                "it is a folder; give a file name inside it (e.g. FOLDER/NAME)".to_string(),
            ))
        }
        Ok(m) if !m.is_file() => return Ok(()),
        _ => {}
    }
    let folder = folder_of(path);
    match std::fs::metadata(folder) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => {
            return Err(bad(format!(
                "{} is not a folder; give a path in an existing folder",
                folder.display()
            )))
        }
        Err(_) => return Err(bad(no_folder(folder))),
    }
    // Held while the probe exists: an interrupt waits until it is gone.
    let _out = outputs();
    tempfile::Builder::new()
        .prefix(".basr-")
        .suffix(".part")
        .tempfile_in(folder)
        .map(drop)
        .map_err(|e| {
            bad(format!(
                "the folder {} does not take new files ({}); give a writable folder",
                folder.display(),
                without_temp_name(e)
            ))
        })
}

/// The signals that end a run like Ctrl-C: interrupt, terminate (`kill`, a
/// CI timeout), hang-up (a closed terminal) and quit.
pub const INTERRUPTS: [i32; 4] = [
    signal_hook::consts::SIGINT,
    signal_hook::consts::SIGTERM,
    signal_hook::consts::SIGHUP,
    signal_hook::consts::SIGQUIT,
];

fn signal_name(sig: i32) -> &'static str {
    match sig {
        signal_hook::consts::SIGINT => "SIGINT",
        signal_hook::consts::SIGTERM => "SIGTERM",
        signal_hook::consts::SIGHUP => "SIGHUP",
        _ => "SIGQUIT",
    }
}

/// Install a handler for [`INTERRUPTS`] that deletes this run's temporary
/// files (being written or staged), then exits with 128 + the signal
/// (130 for Ctrl-C, 143 for SIGTERM, 129 for SIGHUP, 131 for SIGQUIT).
/// After [`commit_outputs`] a signal is ignored: the outputs are complete
/// and the run is ending. Call once at start-up.
pub fn install_interrupt_cleanup() {
    let Ok(mut signals) = signal_hook::iterator::Signals::new(INTERRUPTS) else {
        return;
    };
    std::thread::spawn(move || {
        for sig in signals.forever() {
            // Held until exit: no writer creates or renames a file after this.
            let out = outputs();
            if out.committed {
                continue;
            }
            for p in &out.in_flight {
                let _ = std::fs::remove_file(p);
            }
            // Not eprintln!: with stderr closed it would panic in the
            // handler's thread and the process would carry on.
            let _ = writeln!(
                std::io::stderr(),
                "interrupted ({}): no output file was written",
                signal_name(sig)
            );
            std::process::exit(128 + sig);
        }
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
    write_output(path, None, fill).map(drop)
}

/// Permissions of a Unix mode (ignored elsewhere).
fn mode_perms(mode: u32) -> std::fs::Permissions {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::Permissions::from_mode(mode)
    }
    #[cfg(not(unix))]
    {
        let _ = mode;
        std::fs::metadata(".")
            .map(|m| m.permissions())
            .expect("cwd")
    }
}

/// A writer that hashes what passes through it.
struct Hashing<'a> {
    inner: &'a mut dyn Write,
    hash: sha2::Sha256,
}

impl Write for Hashing<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        use sha2::Digest;
        let n = self.inner.write(buf)?;
        self.hash.update(&buf[..n]);
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// Write to `path` atomically through `fill` and return the SHA-256 (hex)
/// of the bytes written, for a job to record (SPEC §7 `outputs`). `mode`
/// sets the file's Unix mode (a secret key's 0600); without it a replaced
/// file keeps its mode and a new one is 0644.
pub fn write_output(
    path: &Path,
    mode: Option<u32>,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<String, WriteError> {
    let hash = std::cell::RefCell::new(None);
    let hashing = |w: &mut dyn Write| {
        use sha2::Digest;
        let mut h = Hashing {
            inner: w,
            hash: sha2::Sha256::new(),
        };
        fill(&mut h)?;
        *hash.borrow_mut() = Some(hex(&h.hash.finalize()));
        Ok(())
    };
    write_atomic_inner(path, mode, hashing)?;
    Ok(hash.into_inner().unwrap_or_default())
}

fn write_atomic_inner(
    path: &Path,
    mode: Option<u32>,
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
    // the crew shares, so give it the usual rw-r--r--, or the mode of the
    // file it replaces (a 0600 job stays 0600), or the one asked for.
    let perms = match (mode, std::fs::metadata(path)) {
        (Some(m), _) => mode_perms(m),
        (None, Ok(meta)) if meta.is_file() => meta.permissions(),
        _ => mode_perms(0o644),
    };
    let (tmp, tmp_path) = {
        let mut out = outputs();
        let tmp = builder
            .permissions(perms.clone())
            .tempfile_in(folder_of(path))
            .map_err(|e| err(without_temp_name(e)))?;
        // The creation mode passed through the umask; give the exact one.
        tmp.as_file()
            .set_permissions(perms)
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
        if out.staging {
            // Stays in `in_flight` (its temporary is on disk) until commit.
            out.staged.push((tmp, path.to_path_buf()));
            return Ok(true);
        }
        tmp.persist(path).map_err(|e| e.error)?;
        Ok(false)
    })();
    if !matches!(result, Ok(true)) {
        outputs().in_flight.retain(|p| p != &tmp_path);
    }
    result.map(|_| ()).map_err(err)
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
        // Say where the write went: "No space left on device" alone named
        // no file (issue 31, D15).
        Err(e) => Err(std::io::Error::new(
            e.kind(),
            format!(
                "cannot write to standard output ({e}): free space where it is sent, or send it \
                 elsewhere"
            ),
        )),
        Ok(()) => Ok(()),
    }
}

/// Lower-case hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    sha256_hex_of([bytes])
}

/// A writer that only hashes what passes through it (SHA-256): a
/// document's hash taken as it is printed, never held whole.
#[derive(Default)]
pub struct Sha256Writer(sha2::Sha256);

impl Sha256Writer {
    /// Lower-case hex of the SHA-256 of everything written.
    pub fn hex(self) -> String {
        use sha2::Digest;
        hex(&self.0.finalize())
    }
}

impl Write for Sha256Writer {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        use sha2::Digest;
        self.0.update(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Lower-case hex SHA-256 of `pieces` one after the other (no copy).
pub fn sha256_hex_of<'a>(pieces: impl IntoIterator<Item = &'a [u8]>) -> String {
    use sha2::{Digest, Sha256};
    let mut h = Sha256::new();
    for piece in pieces {
        h.update(piece);
    }
    hex(&h.finalize())
}

fn hex(digest: &[u8]) -> String {
    let mut s = String::with_capacity(2 * digest.len());
    for b in digest {
        s.push_str(&format!("{b:02x}"));
    }
    s
}

/// The file a path names, for telling whether two paths are one file: the
/// canonical path when the file exists, else the canonical folder joined
/// with the name (a file about to be written), else the path as given.
fn file_identity(p: &Path) -> std::path::PathBuf {
    if let Ok(c) = p.canonicalize() {
        return c;
    }
    let parent = match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    match (parent.canonicalize(), p.file_name()) {
        (Ok(d), Some(name)) => d.join(name),
        _ => p.to_path_buf(),
    }
}

/// A path with what it is for (`"--csv"`), for messages.
pub type NamedPath<'a> = (&'a str, &'a Path);

/// The first pair of `(what, path)` entries that name the same file, so a
/// command can refuse to write one output over another or over its input
/// (`compile -o STOP.csv --csv STOP.csv` wrote the job over the CSV).
/// `-` (standard input or output) is never a file and never clashes.
pub fn same_file_pair<'a>(paths: &[NamedPath<'a>]) -> Option<(NamedPath<'a>, NamedPath<'a>)> {
    let ids: Vec<_> = paths
        .iter()
        .map(|(_, p)| (*p != Path::new("-")).then(|| file_identity(p)))
        .collect();
    for i in 0..paths.len() {
        for j in i + 1..paths.len() {
            if ids[i].is_some() && ids[i] == ids[j] {
                return Some((paths[i], paths[j]));
            }
        }
    }
    None
}

/// `v` rounded to the `decimals` a message prints it with, and 0 where
/// that is zero, so that `{:.3}` or `{:+.1}` of it never reads "-0.000".
pub fn shown_as(v: f64, decimals: i32) -> f64 {
    let k = 10f64.powi(decimals);
    (v * k).round() / k + 0.0
}

/// `v` with `decimals` decimals, trailing zeros (and a bare point)
/// dropped, and no negative zero: `fixed(2.50, 3)` is `2.5`, `fixed(-0.0001,
/// 2)` is `0`.
pub fn fixed(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// A number for a message, at most six significant digits (issue 31: a
/// message printed 300 digits of 1e300): as written for everyday
/// magnitudes (`-2`, `2.44`, `9.76` for 9.7600000001), in scientific
/// notation when plain digits would run long (`1e300`, `1e-12`).
pub fn show_num(v: f64) -> String {
    // Six digits tell every bound of a range table from its neighbours and
    // a measured value from its limit within a micrometre per metre.
    show_digits(v, 6)
}

/// Two numbers a message sets against each other (a value and the limit it
/// misses), each with [`show_num`]'s six significant digits, or more
/// where six would print them the same ("9.760 m but must be at least
/// 9.760 m"); at most 17, which tell any two f64 apart.
pub fn show_apart(a: f64, b: f64) -> (String, String) {
    let mut pair = (show_num(a), show_num(b));
    for digits in 7..=17 {
        if pair.0 != pair.1 || a == b {
            break;
        }
        pair = (show_digits(a, digits), show_digits(b, digits));
    }
    pair
}

/// `v` with at most `digits` significant digits (see [`show_num`]).
fn show_digits(v: f64, digits: i32) -> String {
    let sig = digits.max(1);
    let a = v.abs();
    if !v.is_finite() {
        return format!("{v}");
    }
    if a == 0.0 {
        return "0".into();
    }
    if (1e-4..1e6).contains(&a) {
        let decimals = (sig - 1 - a.log10().floor() as i32).max(0) as usize;
        fixed(v, decimals)
    } else {
        let s = format!("{v:.prec$e}", prec = (sig - 1) as usize);
        match s.split_once('e') {
            Some((m, e)) if m.contains('.') => {
                format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => s,
        }
    }
}

/// Largest input file basr reads, bytes. The largest file basr itself writes
/// is a job at the compiler's limits (200 letters, 5 ms setpoints, 1 mm
/// rungs): about 0.9 GB; fonts, robots and markings are kilobytes. Past 2 GiB
/// the input is not a basr file (`basr check /dev/zero` read until the
/// machine ran out of memory).
pub const MAX_INPUT_BYTES: u64 = 2 << 30;

/// Read a whole input file, or `-` for standard input, with an error that
/// names the file and says what to do. A file over [`MAX_INPUT_BYTES`] is
/// refused from its size before anything is read; standard input is read
/// to at most one byte past the limit. A file's buffer is allocated once, at
/// its size (no growth by doubling: a job's bytes are the largest thing its
/// readers hold).
pub fn read_bytes(path: &Path) -> anyhow::Result<Vec<u8>> {
    use anyhow::Context;
    use std::io::Read;
    let too_big = |name: &str| {
        anyhow::anyhow!(
            "{name} is larger than {} GiB, more than any file basr reads (the largest job \
             basr writes is about 0.9 GB): give a font, robot, marking or job file",
            MAX_INPUT_BYTES >> 30
        )
    };
    if path == Path::new("-") {
        let mut bytes = Vec::new();
        std::io::stdin()
            .take(MAX_INPUT_BYTES + 1)
            .read_to_end(&mut bytes)
            .context("cannot read standard input")?;
        if bytes.len() as u64 > MAX_INPUT_BYTES {
            return Err(too_big("standard input"));
        }
        return Ok(bytes);
    }
    let why = || {
        format!(
            "cannot read {}: check the path and that the file is readable",
            path.display()
        )
    };
    let file = std::fs::File::open(path).with_context(why)?;
    let meta = file.metadata().ok();
    // A device never ends or is no file at all: `basr check /dev/zero` read
    // 2 GB before it refused (issue 31, D15). Pipes (and `-`) stay bounded
    // by the limit below.
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if let Some(t) = meta.as_ref().map(std::fs::Metadata::file_type) {
            if t.is_char_device() || t.is_block_device() {
                anyhow::bail!(
                    "{} is a device, not a file: give a font, robot, marking or job file (or `-` \
                     to read standard input)",
                    path.display()
                );
            }
        }
    }
    let size = meta.map(|m| m.len()).unwrap_or(0);
    if size > MAX_INPUT_BYTES {
        return Err(too_big(&path.display().to_string()));
    }
    // A device or pipe says 0 and may never end: the limit still holds.
    let mut bytes = Vec::with_capacity(size as usize + 1);
    file.take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut bytes)
        .with_context(why)?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(too_big(&path.display().to_string()));
    }
    Ok(bytes)
}

/// Read a whole input file as UTF-8 text ([`read_bytes`]); text that is
/// not UTF-8 is refused at `file:line:col` of its first invalid byte.
pub fn read_text(path: &Path) -> anyhow::Result<String> {
    let bytes = read_bytes(path)?;
    utf8_text(bytes, &shown_name(path))
}

/// How messages name an input: its path, or `standard input` for `-`.
pub fn shown_name(path: &Path) -> String {
    if path == Path::new("-") {
        "standard input".to_string()
    } else {
        path.display().to_string()
    }
}

/// `bytes` as UTF-8 text, or an error at `name:line:col` of the first
/// invalid byte.
pub fn utf8_text(bytes: Vec<u8>, name: &str) -> anyhow::Result<String> {
    String::from_utf8(bytes)
        .map_err(|e| anyhow::anyhow!(utf8_problem(e.as_bytes(), name).unwrap_or_default()))
}

/// Where `bytes` stop being UTF-8, as `name:line:col: not UTF-8 text …`,
/// or `None` when they are UTF-8 throughout.
pub fn utf8_problem(bytes: &[u8], name: &str) -> Option<String> {
    let e = std::str::from_utf8(bytes).err()?;
    let at = e.valid_up_to();
    // Everything before `at` is valid UTF-8 by definition.
    let before = std::str::from_utf8(&bytes[..at]).unwrap_or_default();
    let (line, col) = line_col(before, at);
    Some(format!(
        "{name}:{line}:{col}: not UTF-8 text (invalid byte 0x{:02x}); save the file as UTF-8",
        bytes[at]
    ))
}

/// A parser's message on one line: toml spreads some over several
/// ("invalid array\nexpected `]`"); their lines are joined with "; ".
/// Shared by every reader of TOML (fonts, robots, markings).
pub fn one_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
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
    fn show_num_keeps_messages_short() {
        assert_eq!(show_num(-2.0), "-2");
        assert_eq!(show_num(2.44), "2.44");
        assert_eq!(show_num(1e300), "1e300");
        assert_eq!(show_num(1e-12), "1e-12");
        assert_eq!(show_num(f64::NAN), "NaN");
        assert_eq!(show_num(f64::NEG_INFINITY), "-inf");
        assert_eq!(show_num(9.7600000001), "9.76");
        assert_eq!(show_num(1.0 / 3.0), "0.333333");
        assert_eq!(show_num(123456.789), "123457");
        assert_eq!(show_num(-1.23456789e300), "-1.23457e300");
        assert_eq!(show_num(0.000123456789), "0.000123457");
        assert_eq!(show_num(-0.0), "0");
        // Told apart where six digits would print them the same.
        assert_eq!(
            show_apart(9.7600000001, 9.76),
            ("9.7600000001".to_string(), "9.76".to_string())
        );
        assert_eq!(show_apart(2.5, 3.0), ("2.5".to_string(), "3".to_string()));
    }

    #[test]
    fn same_file_pair_sees_one_file_under_two_spellings() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.csv");
        let a2 = dir.path().join(".").join("a.csv");
        let b = dir.path().join("b.json");
        let clash = same_file_pair(&[("-o", &b), ("--csv", &a), ("--adept", &a2)]);
        assert_eq!(
            clash,
            Some((("--csv", a.as_path()), ("--adept", a2.as_path())))
        );
        assert_eq!(same_file_pair(&[("-o", &b), ("--csv", &a)]), None);
        let dash = Path::new("-");
        assert_eq!(same_file_pair(&[("--robot", dash), ("--font", dash)]), None);
        // An existing file reached through a symlink is the same file.
        std::fs::write(&a, "x").unwrap();
        let link = dir.path().join("link.csv");
        std::os::unix::fs::symlink(&a, &link).unwrap();
        assert!(same_file_pair(&[("--csv", &a), ("-o", &link)]).is_some());
    }

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

    /// A staged temporary holding `text`, in `dir`.
    fn staged(dir: &Path, text: &str) -> tempfile::NamedTempFile {
        let mut t = tempfile::Builder::new()
            .prefix(".basr-")
            .suffix(".part")
            .tempfile_in(dir)
            .unwrap();
        t.write_all(text.as_bytes()).unwrap();
        t
    }

    #[test]
    fn a_rename_failing_part_way_puts_back_what_was_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::write(d.join("a.csv"), "EARLIER a").unwrap();
        std::fs::create_dir(d.join("folder")).unwrap();
        std::fs::create_dir(d.join("folder").join("x")).unwrap();
        let run = vec![
            (staged(d, "new a"), d.join("a.csv")),
            (staged(d, "new b"), d.join("b.v2")),
            // Renaming a file over a non-empty folder fails.
            (staged(d, "new job"), d.join("folder")),
            (staged(d, "never"), d.join("c.json")),
        ];
        let e = commit_all(run).unwrap_err();
        assert!(e.to_string().contains("folder"), "{e}");
        assert_eq!(
            std::fs::read_to_string(d.join("a.csv")).unwrap(),
            "EARLIER a"
        );
        let mut left: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(
            left,
            ["a.csv", "folder"],
            "no new file, no temporary, no backup"
        );
        // And when every rename succeeds: all new, no backup left.
        let run = vec![
            (staged(d, "new a"), d.join("a.csv")),
            (staged(d, "new c"), d.join("c.json")),
        ];
        commit_all(run).unwrap();
        assert_eq!(std::fs::read_to_string(d.join("a.csv")).unwrap(), "new a");
        assert_eq!(std::fs::read_dir(d).unwrap().count(), 3);
    }

    #[cfg(unix)]
    #[test]
    fn a_replaced_file_keeps_its_mode_and_a_key_gets_its_own() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("job.json");
        std::fs::write(&p, "old").unwrap();
        std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o600)).unwrap();
        let sha = write_output(&p, None, |w| w.write_all(b"new")).unwrap();
        assert_eq!(sha, sha256_hex(b"new"));
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&p), 0o600);
        let k = dir.path().join("key");
        write_output(&k, Some(0o600), |w| w.write_all(b"secret")).unwrap();
        assert_eq!(mode(&k), 0o600);
    }

    #[test]
    fn unwritable_outputs_are_found_before_the_work() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        assert!(check_writable(&d.join("new.json")).is_ok());
        let e = check_writable(d).unwrap_err().to_string();
        assert!(e.contains("is a folder"), "{e}");
        let e = check_writable(&d.join("no").join("x.csv"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("does not exist"), "{e}");
        // A file where a folder should be is named as a file.
        std::fs::write(d.join("notes.txt"), "x").unwrap();
        let e = check_writable(&d.join("notes.txt").join("x.csv"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("is not a folder"), "{e}");
        let e = check_writable(&d.join("notes.txt").join("sub").join("x.csv"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("notes.txt is a file, not a folder"), "{e}");
        std::fs::remove_file(d.join("notes.txt")).unwrap();
        assert_eq!(
            std::fs::read_dir(d).unwrap().count(),
            0,
            "the probe is gone"
        );
    }

    #[test]
    fn failed_fill_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.txt");
        let r = write_atomic_with(&p, |_| Err(std::io::Error::other("boom")));
        assert!(r.is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
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
    fn shown_as_never_prints_a_negative_zero() {
        assert_eq!(format!("{:.3}", shown_as(-0.0004, 3)), "0.000");
        assert_eq!(format!("{:+.1}", shown_as(-0.04, 1)), "+0.0");
        assert_eq!(format!("{:.3}", shown_as(-0.0006, 3)), "-0.001");
        assert_eq!(shown_as(1.23456, 2), 1.23);
        // what it replaces: the plain format of a tiny negative number
        assert_eq!(format!("{:.3}", -0.0004), "-0.000");
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
    fn non_utf8_is_refused_at_line_and_column() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("latin1.toml");
        std::fs::write(&p, b"[a]\nname = \"\xc3\xa7a\xdfe\"\n").unwrap();
        let e = format!("{:#}", read_text(&p).unwrap_err());
        // Line 2, column 11: after `name = "ça` (10 characters).
        assert!(e.contains("latin1.toml:2:11: not UTF-8"), "{e}");
        assert!(e.contains("0xdf") && !e.contains("offset"), "{e}");
    }

    #[test]
    fn sha256_of_empty_is_known() {
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
    }
}
