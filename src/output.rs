//! The one output policy every command follows (documented for users in `docs/outputs.md`).
//!
//! - A command first [`claim`]s each output, naming its inputs and whether `--force` was given:
//!   an existing output (a file, or a non-empty folder) is refused without `--force`, and an
//!   output that is one of the inputs, or a folder holding one, is refused even with it.
//! - Files are written through [`write_atomic`]: `-` means standard output; a FIFO or character
//!   device is written to directly; a symlink is followed and its target replaced; anything else
//!   gets a temporary file beside it that takes its place only once complete, with a no-replace
//!   rename unless the output was claimed with `--force`, so a file that appeared meanwhile is
//!   never lost.
//! - Folders are written through [`write_folder_atomic`] into a `.dlw-staging-<pid>-*` folder
//!   beside the destination. Staging folders are removed on SIGINT and SIGTERM, and a stale one
//!   whose process is gone is removed by the next run in that folder, which says so.

use std::collections::HashSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The output name that means standard output.
pub const STDOUT: &str = "-";

/// Outputs claimed with `--force` in this process: only these may be replaced. A registry rather
/// than a token passed along, so that library writers (`Page::write`, `Recording::write`) stay
/// safe by default without changing their signatures.
static REPLACEABLE: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);

/// Staging folders and files being written by this process, removed if a signal ends it.
static STAGING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Folders this process stages in, noted before anything is made there: a signal may come
/// between a staging folder's creation and its entry in [`STAGING`], and the handler then finds
/// it by this process's prefix ([`staging_prefix`]).
static STAGING_FOLDERS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Notes `folder` in [`STAGING_FOLDERS`].
fn note_staging_folder(folder: &Path) {
    let mut folders = lock(&STAGING_FOLDERS);
    if !folders.iter().any(|f| f == folder) {
        folders.push(folder.to_path_buf());
    }
}

/// Why an output file could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The output exists and `--force` was not given.
    #[error("output {path} already exists{what} (pass --force to replace it)")]
    Exists {
        /// The output.
        path: PathBuf,
        /// ` and is not empty` for a folder.
        what: &'static str,
    },
    /// The output is one of the command's inputs, or a folder holding one.
    #[error("output {output} {relation} input {input}; refused even with --force, since writing it would destroy the input")]
    IsInput {
        /// The output.
        output: PathBuf,
        /// The input.
        input: PathBuf,
        /// `is the`, `holds the` or `is part of the`.
        relation: &'static str,
    },
    /// Two outputs of one command are the same file.
    #[error("outputs {first} and {second} are the same file; give different paths")]
    SameOutput {
        /// The first output.
        first: PathBuf,
        /// The second output.
        second: PathBuf,
    },
    /// A folder was to be written to `-`.
    #[error("output {path} means standard output, which cannot hold a folder; give a folder's path (./- for a folder named -)")]
    FolderToStdout {
        /// The output as given.
        path: PathBuf,
    },
    /// Something appeared at the output while the command ran.
    #[error("output {path} appeared while this run was writing it (another run?); nothing was replaced, run again or pass --force")]
    Appeared {
        /// The output.
        path: PathBuf,
    },
    /// The destination's folder does not exist or cannot be written.
    #[error("cannot write {path}")]
    Io {
        /// The destination.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The temporary folder a whole output folder is written in could not be made beside it.
    #[error(
        "cannot make a temporary {what} folder in {parent} (the folder that holds {dir}): {reason}"
    )]
    Staging {
        /// `staging` (the new folder being written) or `set-aside` (where the old one goes).
        what: &'static str,
        /// The folder it was to be made in.
        parent: PathBuf,
        /// The output folder.
        dir: PathBuf,
        /// What the operating system said: why. Part of the message, not a `source`, so an
        /// error chain does not print it twice.
        reason: std::io::Error,
    },
}

/// Checks that `output` may be written by a command reading `inputs`, and records a `force`
/// permission to replace it. Call once per output, before the work starts.
///
/// # Errors
/// [`OutputError::IsInput`] when `output` is an input or a folder holding one (even with
/// `force`); [`OutputError::Exists`] when it is an existing file or non-empty folder and `force`
/// is false. `-`, FIFOs and character devices are always accepted.
pub fn claim<P: AsRef<Path>>(
    output: &Path,
    inputs: impl IntoIterator<Item = P>,
    force: bool,
) -> Result<(), OutputError> {
    install_signal_cleanup();
    if is_stdout(output) || is_stream(output) {
        return Ok(());
    }
    let out = resolved(output);
    for input in inputs {
        let input = input.as_ref();
        if is_stdout(input) {
            continue;
        }
        let inp = resolved(input);
        let relation = if inp == out {
            "is the"
        } else if inp.starts_with(&out) {
            "holds the"
        } else if out.starts_with(&inp) && std::fs::symlink_metadata(&out).is_ok() {
            // An existing file inside an input folder is part of that input.
            "is part of the"
        } else {
            continue;
        };
        return Err(OutputError::IsInput {
            output: output.to_path_buf(),
            input: input.to_path_buf(),
            relation,
        });
    }
    let what = match std::fs::metadata(&out) {
        Err(_) => return Ok(()),
        Ok(m) if m.is_dir() => match std::fs::read_dir(&out).map(|mut e| e.next().is_none()) {
            Ok(true) => return Ok(()),
            _ => " and is not empty",
        },
        Ok(_) => "",
    };
    if !force {
        return Err(OutputError::Exists {
            path: output.to_path_buf(),
            what,
        });
    }
    lock(&REPLACEABLE)
        .get_or_insert_with(HashSet::new)
        .insert(out);
    Ok(())
}

/// [`claim`] for an output **folder**: `-` (standard output, which cannot hold a folder) is
/// refused with [`OutputError::FolderToStdout`] instead of making a folder named `-`.
///
/// # Errors
/// As [`claim`], and [`OutputError::FolderToStdout`].
pub fn claim_folder<P: AsRef<Path>>(
    output: &Path,
    inputs: impl IntoIterator<Item = P>,
    force: bool,
) -> Result<(), OutputError> {
    if is_stdout(output) {
        return Err(OutputError::FolderToStdout {
            path: output.to_path_buf(),
        });
    }
    claim(output, inputs, force)
}

/// Lets this process replace `path` (a library caller's explicit `replace`, the same as a
/// [`claim`] with `--force` and no inputs).
pub fn allow_replace(path: &Path) {
    lock(&REPLACEABLE)
        .get_or_insert_with(HashSet::new)
        .insert(resolved(path));
}

/// [`claim`] for several outputs of one command, which must also differ from each other.
///
/// # Errors
/// As [`claim`], and [`OutputError::SameOutput`] when two outputs are the same file.
pub fn claim_all<P: AsRef<Path>>(
    outputs: &[&Path],
    inputs: impl IntoIterator<Item = P>,
    force: bool,
) -> Result<(), OutputError> {
    let inputs: Vec<PathBuf> = inputs
        .into_iter()
        .map(|p| p.as_ref().to_path_buf())
        .collect();
    for (i, first) in outputs.iter().enumerate() {
        for second in &outputs[i + 1..] {
            if !is_stdout(first) && resolved(first) == resolved(second) {
                return Err(OutputError::SameOutput {
                    first: first.to_path_buf(),
                    second: second.to_path_buf(),
                });
            }
        }
        claim(first, &inputs, force)?;
    }
    Ok(())
}

/// Whether `path` is `-`, standard output.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == STDOUT
}

/// Whether `path` is a FIFO or character device: written to directly, never replaced.
fn is_stream(path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if let Ok(m) = std::fs::metadata(path) {
            let t = m.file_type();
            return t.is_fifo() || t.is_char_device();
        }
    }
    false
}

/// The absolute path `path` stands for, symlinks followed; for a path that does not exist yet,
/// its resolved folder joined with its name.
fn resolved(path: &Path) -> PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    let parent = folder_of(path);
    match (std::fs::canonicalize(parent), path.file_name()) {
        (Ok(p), Some(name)) => p.join(name),
        _ => std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf()),
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn may_replace(path: &Path) -> bool {
    lock(&REPLACEABLE)
        .as_ref()
        .is_some_and(|set| set.contains(&resolved(path)))
}

/// Writes `bytes` to `path`: `-` is standard output, a FIFO or character device is written to
/// directly, and anything else through a temporary file beside the (symlink-followed) target
/// and a rename that replaces an existing file only if it was [`claim`]ed with `--force`.
///
/// # Errors
/// [`OutputError::Io`] naming the path, [`OutputError::Exists`] for an unclaimed existing file,
/// [`OutputError::Appeared`] when the file appeared after the claim; the destination is then
/// untouched.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let io = |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    };
    if is_stdout(path) {
        let mut out = std::io::stdout().lock();
        return out.write_all(bytes).and_then(|()| out.flush()).map_err(io);
    }
    if is_stream(path) {
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(io)?;
        return f.write_all(bytes).and_then(|()| f.flush()).map_err(io);
    }
    let target = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    persist(path, &target, stage(&target, bytes)?)
}

/// Writes several files so that either all of them appear or (up to a failing rename at the very
/// end) none: every temporary file is written completely first, then all are renamed.
///
/// # Errors
/// [`OutputError::SameOutput`] when two paths are the same file; [`OutputError::Io`] naming
/// the first path that could not be written; no destination has been touched when a temporary
/// file cannot be created or written.
pub fn write_all_atomic(files: &[(PathBuf, Vec<u8>)]) -> Result<(), OutputError> {
    for (i, (first, _)) in files.iter().enumerate() {
        for (second, _) in &files[i + 1..] {
            if !is_stdout(first) && resolved(first) == resolved(second) {
                return Err(OutputError::SameOutput {
                    first: first.clone(),
                    second: second.clone(),
                });
            }
        }
    }
    let mut direct = Vec::new();
    let mut staged = Vec::new();
    for (path, bytes) in files {
        if is_stdout(path) || is_stream(path) {
            direct.push((path, bytes));
        } else {
            let target = std::fs::canonicalize(path).unwrap_or_else(|_| path.clone());
            let tmp = stage(&target, bytes)?;
            staged.push((path, target, tmp));
        }
    }
    for (path, target, tmp) in staged {
        persist(path, &target, tmp)?;
    }
    for (path, bytes) in direct {
        write_atomic(path, bytes)?;
    }
    Ok(())
}

/// Writes `files` (names relative to `dir`) as the folder `dir`, so that either the whole new
/// folder appears or nothing changes: the files are written into a staging folder beside
/// `dir`, which then takes `dir`'s place. A missing or empty `dir` is taken with a rename that
/// fails if anything appeared in it meanwhile; a non-empty one is replaced only if it was
/// [`claim`]ed with `--force`.
///
/// # Errors
/// [`OutputError::Staging`] naming the parent folder and why the staging folder could not be
/// made in it; [`OutputError::Exists`] or [`OutputError::Appeared`] for an occupied `dir`;
/// [`OutputError::Io`] naming the path for anything else. `dir` is then as it was.
pub fn write_folder_atomic(dir: &Path, files: &[(String, Vec<u8>)]) -> Result<(), OutputError> {
    stage_folder(dir, files)?.commit()
}

/// A whole output folder written into its staging folder beside the destination, not yet in
/// place: [`StagedFolder::commit`] puts it there, dropping it removes it. A command with
/// several outputs stages them all before committing any, so that a failure to write one
/// leaves none (`import-recording`'s recording and `--report`).
#[derive(Debug)]
pub struct StagedFolder {
    staging: Staged,
    /// The destination, a symlink followed.
    dir: PathBuf,
    /// The destination as the user gave it.
    shown: PathBuf,
}

/// Writes `files` (names relative to `dir`) into a staging folder beside `dir`, to be put in
/// its place by [`StagedFolder::commit`].
///
/// # Errors
/// [`OutputError::FolderToStdout`] for `-`; [`OutputError::Staging`] naming the parent folder
/// and why the staging folder could not be made in it; [`OutputError::Io`] naming the path.
pub fn stage_folder(dir: &Path, files: &[(String, Vec<u8>)]) -> Result<StagedFolder, OutputError> {
    install_signal_cleanup();
    if is_stdout(dir) {
        return Err(OutputError::FolderToStdout {
            path: dir.to_path_buf(),
        });
    }
    let dir_target = match std::fs::read_link(dir) {
        Ok(_) => std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf()),
        Err(_) => dir.to_path_buf(),
    };
    let parent = folder_of(&dir_target);
    sweep_stale(parent);
    note_staging_folder(parent);
    let staging = Staged::new(
        tempfile::Builder::new()
            .prefix(&staging_prefix())
            .tempdir_in(parent)
            .map_err(|reason| OutputError::Staging {
                what: "staging",
                parent: parent.to_path_buf(),
                dir: dir.to_path_buf(),
                reason,
            })?,
    );
    for (name, bytes) in files {
        write_atomic(&staging.path().join(name), bytes)?;
    }
    // Temporary folders are created private (0700); an output folder is an ordinary one.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(staging.path(), std::fs::Permissions::from_mode(0o755)).map_err(
            |source| OutputError::Io {
                path: dir.to_path_buf(),
                source,
            },
        )?;
    }
    Ok(StagedFolder {
        staging,
        dir: dir_target,
        shown: dir.to_path_buf(),
    })
}

impl StagedFolder {
    /// The staging folder, holding the files as they will be (to read them back before
    /// committing).
    pub fn path(&self) -> &Path {
        self.staging.path()
    }

    /// Puts the staged folder in the destination's place. A missing or empty destination is
    /// taken with a rename that fails if anything appeared in it meanwhile; a non-empty one is
    /// replaced only if it was [`claim`]ed with `--force`.
    ///
    /// # Errors
    /// [`OutputError::Exists`] or [`OutputError::Appeared`] for an occupied destination;
    /// [`OutputError::Staging`] or [`OutputError::Io`] otherwise. The destination is then as
    /// it was.
    pub fn commit(self) -> Result<(), OutputError> {
        let StagedFolder {
            staging,
            dir,
            shown,
        } = self;
        let dir = dir.as_path();
        let io = |source| OutputError::Io {
            path: shown.clone(),
            source,
        };
        let occupied = match std::fs::read_dir(dir) {
            Ok(mut entries) => entries.next().is_some(),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => false,
            Err(_) => true,
        };
        if !occupied || !may_replace(dir) {
            if occupied {
                return Err(OutputError::Exists {
                    path: shown.clone(),
                    what: " and is not empty",
                });
            }
            // rename(2) replaces only an empty folder: anything that appeared meanwhile makes
            // it fail instead of being lost.
            return match std::fs::rename(staging.path(), dir) {
                Ok(()) => {
                    staging.keep();
                    Ok(())
                }
                Err(e)
                    if matches!(
                        e.raw_os_error(),
                        Some(libc::ENOTEMPTY | libc::EEXIST | libc::ENOTDIR | libc::EISDIR)
                    ) =>
                {
                    Err(OutputError::Appeared {
                        path: shown.clone(),
                    })
                }
                Err(e) => Err(io(e)),
            };
        }
        // rename cannot replace a non-empty folder: move the old one aside first, and back if
        // the new one cannot take its place.
        let parent = folder_of(dir);
        note_staging_folder(parent);
        let old = Staged::new(
            tempfile::Builder::new()
                .prefix(&staging_prefix())
                .tempdir_in(parent)
                .map_err(|reason| OutputError::Staging {
                    what: "set-aside",
                    parent: parent.to_path_buf(),
                    dir: shown.clone(),
                    reason,
                })?,
        );
        let aside = old.path().join("old");
        std::fs::rename(dir, &aside).map_err(io)?;
        if let Err(source) = std::fs::rename(staging.path(), dir) {
            let _ = std::fs::rename(&aside, dir);
            old.keep_if_restore_failed(&aside);
            return Err(io(source));
        }
        staging.keep();
        Ok(())
    }
}

/// A staging folder registered for removal on a signal, removed when dropped unless kept.
#[derive(Debug)]
struct Staged {
    dir: Option<tempfile::TempDir>,
    path: PathBuf,
}

impl Staged {
    fn new(dir: tempfile::TempDir) -> Self {
        let path = dir.path().to_path_buf();
        lock(&STAGING).push(path.clone());
        Self {
            dir: Some(dir),
            path,
        }
    }

    fn path(&self) -> &Path {
        &self.path
    }

    /// The folder has been renamed into place: nothing to remove.
    fn keep(mut self) {
        if let Some(dir) = self.dir.take() {
            let _ = dir.keep();
        }
    }

    /// The old folder could not be moved back: keep it rather than delete the user's data.
    fn keep_if_restore_failed(self, aside: &Path) {
        if aside.exists() {
            self.keep();
        }
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        lock(&STAGING).retain(|p| p != &self.path);
    }
}

/// `.dlw-staging-<pid>-`: the pid lets a later run tell a dead run's leftovers from a live one's.
fn staging_prefix() -> String {
    format!(".dlw-staging-{}-", std::process::id())
}

/// Removes `.dlw-staging-<pid>-*` entries in `folder` whose process is gone, saying so.
fn sweep_stale(folder: &Path) {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(rest) = name.to_str().and_then(|n| n.strip_prefix(".dlw-staging-")) else {
            continue;
        };
        let Some(pid) = rest.split('-').next().and_then(|p| p.parse::<i32>().ok()) else {
            continue;
        };
        if pid <= 0 || process_alive(pid) {
            continue;
        }
        let path = entry.path();
        let removed = if path.is_dir() {
            std::fs::remove_dir_all(&path)
        } else {
            std::fs::remove_file(&path)
        };
        if removed.is_ok() {
            eprintln!(
                "removed {}, left by an interrupted dlw run (process {pid}, no longer running)",
                path.display()
            );
        }
    }
}

fn process_alive(pid: i32) -> bool {
    // kill(pid, 0) sends nothing; ESRCH means no such process. EPERM: alive, someone else's.
    // SAFETY: signal 0 performs only the existence and permission check.
    let r = unsafe { libc::kill(pid, 0) };
    r == 0 || std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
}

/// How many times the signal handler tries to remove a staging path that is still there.
const STAGING_REMOVAL_TRIES: usize = 50;

/// Installs (once) a SIGINT/SIGTERM handler that removes this process's staging folders and
/// files, then exits with 128 + the signal's number as a shell would report.
fn install_signal_cleanup() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let _ = ctrlc::set_handler(|| {
            // A staging folder was left behind once under load (the suite's
            // `sigterm_during_simulate_leaves_no_staging_folder`): one made before its entry in
            // `STAGING`, or a file made in it
            // between `remove_dir_all`'s listing and its last `rmdir` by a thread still writing.
            // So the handler also looks for this process's prefix in every folder it stages
            // in, and tries a removal again until the path is gone.
            let mut paths: Vec<PathBuf> = lock(&STAGING).clone();
            let prefix = staging_prefix();
            for folder in lock(&STAGING_FOLDERS).iter() {
                let Ok(entries) = std::fs::read_dir(folder) else {
                    continue;
                };
                paths.extend(
                    entries
                        .flatten()
                        .filter(|e| e.file_name().to_string_lossy().starts_with(&prefix))
                        .map(|e| e.path()),
                );
            }
            for path in &paths {
                for _ in 0..STAGING_REMOVAL_TRIES {
                    let _ = if path.is_dir() {
                        std::fs::remove_dir_all(path)
                    } else {
                        std::fs::remove_file(path)
                    };
                    if std::fs::symlink_metadata(path).is_err() {
                        break;
                    }
                    std::thread::sleep(std::time::Duration::from_millis(2));
                }
            }
            eprintln!("interrupted; removed the partial output");
            std::process::exit(130);
        });
    });
}

/// The folder a path lives in (`.` for a bare file name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Writes `bytes` completely to a temporary file beside `path`.
fn stage(path: &Path, bytes: &[u8]) -> Result<tempfile::NamedTempFile, OutputError> {
    let io = |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    };
    note_staging_folder(folder_of(path));
    let mut tmp = tempfile::Builder::new()
        .prefix(&staging_prefix())
        .tempfile_in(folder_of(path))
        .map_err(io)?;
    lock(&STAGING).push(tmp.path().to_path_buf());
    tmp.write_all(bytes).map_err(io)?;
    tmp.flush().map_err(io)?;
    // Temporary files are created private (0600); an output file is an ordinary document.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))
            .map_err(io)?;
    }
    Ok(tmp)
}

/// Renames the staged file onto `target` (`shown` is the path the user gave): replacing only
/// a file claimed with `--force`, otherwise with a no-replace rename.
fn persist(shown: &Path, target: &Path, tmp: tempfile::NamedTempFile) -> Result<(), OutputError> {
    let tmp_path = tmp.path().to_path_buf();
    let result = if may_replace(target) {
        tmp.persist(target).map(drop)
    } else {
        tmp.persist_noclobber(target).map(drop)
    };
    lock(&STAGING).retain(|p| p != &tmp_path);
    result.map_err(|e| {
        if e.error.kind() == std::io::ErrorKind::AlreadyExists {
            OutputError::Exists {
                path: shown.to_path_buf(),
                what: "",
            }
        } else {
            OutputError::Io {
                path: shown.to_path_buf(),
                source: e.error,
            }
        }
    })
}

/// Reads a text input of at most `limit` bytes, through [`read_limited_bytes`] (a regular file,
/// or a pipe with data within [`crate::limits::PIPE_WAIT_MS`]); a UTF-8 byte-order mark before
/// the text is dropped.
///
/// # Errors
/// As [`read_limited_bytes`], or the file is not UTF-8.
pub fn read_limited(path: &Path, limit: u64) -> std::io::Result<String> {
    let bytes = read_limited_bytes(path, limit)?;
    let mut text = String::from_utf8(bytes).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("{} is not UTF-8 text ({e})", path.display()),
        )
    })?;
    if text.starts_with(UTF8_BOM) {
        text.drain(..UTF8_BOM.len());
    }
    Ok(text)
}

/// The byte-order mark some Windows programs write before UTF-8 text.
pub const UTF8_BOM: &str = "\u{feff}";

/// The one bounded reader every input of `dlw` goes through. It reads a **regular file** of at
/// most `limit` bytes (one past it is refused with the limit named, after reading `limit + 1`
/// bytes), or a **pipe** (a FIFO, a shell's `<(...)`) that has data within
/// [`crate::limits::PIPE_WAIT_MS`]; anything else (a device such as `/dev/zero`, a folder, a
/// socket) is refused naming what it is, and a pipe with no data (a FIFO no program writes) is
/// refused after the wait instead of blocking forever. The limits are in [`crate::limits`].
///
/// # Errors
/// The file cannot be opened or read, is not a regular file or a pipe with data, or is past
/// the limit.
pub fn read_limited_bytes(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let refuse = |what: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, what);
    let file = open_for_reading(path)?;
    let kind = file.metadata()?.file_type();
    if !kind.is_file() {
        match file_kind(&kind) {
            Some("a pipe") => wait_for_data(&file, path)?,
            Some(what) => {
                return Err(refuse(format!(
                    "{} is {what}, not a regular file: dlw reads files (or a pipe with data)",
                    path.display()
                )))
            }
            None => {
                return Err(refuse(format!(
                    "{} is not a regular file: dlw reads files (or a pipe with data)",
                    path.display()
                )))
            }
        }
    }
    let mut bytes = Vec::new();
    (&file).take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "{} is larger than the {} limit for this input",
                path.display(),
                byte_size(limit)
            ),
        ));
    }
    Ok(bytes)
}

/// Opens `path` for reading without blocking on a FIFO that has no writer (`open(2)` would wait
/// for one), then makes reads blocking again.
fn open_for_reading(path: &Path) -> std::io::Result<std::fs::File> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        use std::os::unix::io::AsRawFd;
        let file = std::fs::OpenOptions::new()
            .read(true)
            .custom_flags(libc::O_NONBLOCK)
            .open(path)?;
        // SAFETY: F_GETFL/F_SETFL on a descriptor this function owns.
        unsafe {
            let fd = file.as_raw_fd();
            let flags = libc::fcntl(fd, libc::F_GETFL);
            if flags >= 0 {
                libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK);
            }
        }
        Ok(file)
    }
    #[cfg(not(unix))]
    {
        std::fs::File::open(path)
    }
}

/// What a file that is not a regular file is, in words.
fn file_kind(kind: &std::fs::FileType) -> Option<&'static str> {
    if kind.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return Some("a pipe");
        }
        if kind.is_char_device() {
            return Some("a character device");
        }
        if kind.is_block_device() {
            return Some("a block device");
        }
        if kind.is_socket() {
            return Some("a socket");
        }
    }
    None
}

/// Waits up to [`crate::limits::PIPE_WAIT_MS`] for a pipe to have data (or to be closed by its
/// writer, which reads as an empty file).
fn wait_for_data(file: &std::fs::File, path: &Path) -> std::io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::io::AsRawFd;
        let mut poll = libc::pollfd {
            fd: file.as_raw_fd(),
            events: libc::POLLIN,
            revents: 0,
        };
        let wait_ms = i32::try_from(crate::limits::PIPE_WAIT_MS).unwrap_or(i32::MAX);
        // SAFETY: one pollfd, owned here, for the duration of the call.
        let ready = unsafe { libc::poll(&mut poll, 1, wait_ms) };
        if ready < 0 {
            return Err(std::io::Error::last_os_error());
        }
        if ready == 0 {
            return Err(std::io::Error::new(
                std::io::ErrorKind::TimedOut,
                format!(
                    "{} is a pipe with no data within {} ms (does a program write to it?); dlw \
                     reads files, or a pipe that has data",
                    path.display(),
                    crate::limits::PIPE_WAIT_MS
                ),
            ));
        }
    }
    #[cfg(not(unix))]
    let _ = (file, path);
    Ok(())
}

/// A byte count as a person reads it: `64 MiB`, `4 GiB`, `1000 bytes`.
fn byte_size(bytes: u64) -> String {
    const UNITS: [(u64, &str); 3] = [(1 << 30, "GiB"), (1 << 20, "MiB"), (1 << 10, "KiB")];
    UNITS
        .iter()
        .find(|(size, _)| bytes >= *size && bytes % size == 0)
        .map_or_else(
            || format!("{bytes}-byte"),
            |(size, unit)| format!("{} {unit}", bytes / size),
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_whole_file_and_refuses_missing_folder() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        write_atomic(&path, b"hello").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"hello");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&path).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o644, "{mode:o}");
        }
        let missing = dir.path().join("no/such/folder/b.txt");
        let err = write_atomic(&missing, b"x").unwrap_err();
        assert!(format!("{err:#}").contains("b.txt"), "{err}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn inputs_are_refused_even_with_force_and_files_are_not_replaced_unclaimed() {
        let root = tempfile::tempdir().unwrap();
        let rec = root.path().join("rec");
        std::fs::create_dir(&rec).unwrap();
        let data = rec.join("data.csv");
        std::fs::write(&data, b"x").unwrap();
        for (out, relation) in [
            (&rec, "is the"),
            (&data, "is part of the"),
            (&root.path().to_path_buf(), "holds the"),
        ] {
            let err = claim(out, [&rec], true).unwrap_err();
            let text = err.to_string();
            assert!(
                text.contains(relation) && text.contains(&rec.display().to_string()),
                "{text}"
            );
        }
        let err = claim(&data, [&data], true).unwrap_err().to_string();
        assert!(err.contains("refused even with --force"), "{err}");
        // An existing file is kept without a claim, replaced with one.
        let other = root.path().join("other.csv");
        std::fs::write(&other, b"old").unwrap();
        assert!(matches!(
            write_atomic(&other, b"new"),
            Err(OutputError::Exists { .. })
        ));
        assert_eq!(std::fs::read(&other).unwrap(), b"old");
        claim(&other, [&rec], true).unwrap();
        write_atomic(&other, b"new").unwrap();
        assert_eq!(std::fs::read(&other).unwrap(), b"new");
        // Two outputs that are the same file.
        let err = write_all_atomic(&[
            (other.clone(), b"1".to_vec()),
            (other.clone(), b"2".to_vec()),
        ]);
        assert!(matches!(err, Err(OutputError::SameOutput { .. })));
    }

    #[cfg(unix)]
    #[test]
    fn symlinks_are_followed_and_stale_staging_is_swept() {
        let root = tempfile::tempdir().unwrap();
        let target = root.path().join("target.csv");
        std::fs::write(&target, b"old").unwrap();
        let link = root.path().join("link.csv");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        claim(&link, [&link; 0], true).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        // A staging folder of a process that is gone (pid beyond pid_max) is removed.
        let stale = root.path().join(".dlw-staging-2147483646-abc");
        std::fs::create_dir(&stale).unwrap();
        let live = root
            .path()
            .join(format!(".dlw-staging-{}-abc", std::process::id()));
        std::fs::create_dir(&live).unwrap();
        write_folder_atomic(&root.path().join("out"), &[("a".into(), b"x".to_vec())]).unwrap();
        assert!(!stale.exists());
        assert!(live.exists());
    }

    #[test]
    fn writes_all_or_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a"), dir.path().join("b"));
        write_all_atomic(&[(a.clone(), b"1".to_vec()), (b.clone(), b"2".to_vec())]).unwrap();
        assert_eq!(std::fs::read(&b).unwrap(), b"2");
        let c = dir.path().join("c");
        let missing = dir.path().join("no/such/d");
        let err = write_all_atomic(&[(c.clone(), b"3".to_vec()), (missing, b"4".to_vec())]);
        assert!(format!("{:#}", err.unwrap_err()).contains("no/such/d"));
        assert!(!c.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
    }

    #[test]
    fn folders_appear_whole_and_replace_the_old_one() {
        let root = tempfile::tempdir().unwrap();
        let dir = root.path().join("job");
        let files = |text: &str| vec![("a.txt".to_string(), text.as_bytes().to_vec())];
        write_folder_atomic(&dir, &files("one")).unwrap();
        std::fs::write(dir.join("stale.txt"), b"x").unwrap();
        // Not claimed with --force: the folder is kept.
        let err = write_folder_atomic(&dir, &files("two")).unwrap_err();
        assert!(matches!(err, OutputError::Exists { .. }), "{err:?}");
        assert!(dir.join("stale.txt").exists());
        assert!(matches!(
            claim(&dir, [&dir; 0], false),
            Err(OutputError::Exists { .. })
        ));
        claim(&dir, [&dir; 0], true).unwrap();
        write_folder_atomic(&dir, &files("two")).unwrap();
        assert_eq!(std::fs::read(dir.join("a.txt")).unwrap(), b"two");
        assert!(!dir.join("stale.txt").exists());
        // A file that cannot be written leaves the old folder as it was, and no staging behind.
        let bad = vec![("no/such/sub/b.txt".to_string(), b"x".to_vec())];
        assert!(write_folder_atomic(&dir, &bad).is_err());
        assert_eq!(std::fs::read(dir.join("a.txt")).unwrap(), b"two");
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 1);
    }

    #[test]
    fn staging_errors_name_the_parent_and_why() {
        let root = tempfile::tempdir().unwrap();
        let files = vec![("a.txt".to_string(), b"x".to_vec())];
        // The parent is a file: no folder can be made in it.
        let file = root.path().join("plain");
        std::fs::write(&file, b"x").unwrap();
        let err = write_folder_atomic(&file.join("job"), &files).unwrap_err();
        let text = err.to_string();
        assert!(matches!(err, OutputError::Staging { .. }), "{err:?}");
        assert!(
            text.contains(&format!("in {} ", file.display())) && text.contains("Not a directory"),
            "{text}"
        );
        // The parent does not exist.
        let missing = root.path().join("no/such");
        let text = write_folder_atomic(&missing.join("job"), &files)
            .unwrap_err()
            .to_string();
        assert!(
            text.contains(&format!("in {} ", missing.display()))
                && text.contains("No such file or directory"),
            "{text}"
        );
    }
}
