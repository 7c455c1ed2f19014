//! Writing output files so that a failed command leaves no partial file behind.
//!
//! Every file `dlw` writes goes through [`write_atomic`]: the bytes land in a temporary file in
//! the destination's folder, which is renamed over the destination only once complete.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Why an output file could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
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

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename.
///
/// # Errors
/// [`OutputError::Io`] naming the path; the destination is then untouched.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    persist(path, stage(path, bytes)?)
}

/// Writes several files so that either all of them appear or (up to a failing rename at the very
/// end) none: every temporary file is written completely first, then all are renamed.
///
/// # Errors
/// [`OutputError::Io`] naming the first path that could not be written; no destination has been
/// touched when a temporary file cannot be created or written.
pub fn write_all_atomic(files: &[(PathBuf, Vec<u8>)]) -> Result<(), OutputError> {
    let staged = files
        .iter()
        .map(|(path, bytes)| Ok((path, stage(path, bytes)?)))
        .collect::<Result<Vec<_>, OutputError>>()?;
    for (path, tmp) in staged {
        persist(path, tmp)?;
    }
    Ok(())
}

/// Writes `files` (names relative to `dir`) as the folder `dir`, so that either the whole new
/// folder appears or nothing changes: the files are written into a temporary folder beside
/// `dir`, which then takes `dir`'s place. An existing `dir` is replaced; whether it may be is
/// the caller's decision, made before calling.
///
/// # Errors
/// [`OutputError::Staging`] naming the parent folder and why the temporary folder could not be
/// made in it (it does not exist, is not a folder, cannot be written); [`OutputError::Io`]
/// naming the path for anything else. `dir` is then as it was.
pub fn write_folder_atomic(dir: &Path, files: &[(String, Vec<u8>)]) -> Result<(), OutputError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| OutputError::Io { path, source }
    };
    let parent = folder_of(dir);
    let staging_err = |what: &'static str| {
        move |reason| OutputError::Staging {
            what,
            parent: parent.to_path_buf(),
            dir: dir.to_path_buf(),
            reason,
        }
    };
    let staging = tempfile::Builder::new()
        .prefix(".dlw-staging-")
        .tempdir_in(parent)
        .map_err(staging_err("staging"))?;
    for (name, bytes) in files {
        write_atomic(&staging.path().join(name), bytes)?;
    }
    // Temporary folders are created private (0700); an output folder is an ordinary one.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(staging.path(), std::fs::Permissions::from_mode(0o755))
            .map_err(io(dir))?;
    }
    if std::fs::symlink_metadata(dir).is_err() {
        std::fs::rename(staging.path(), dir).map_err(io(dir))?;
        let _ = staging.keep();
        return Ok(());
    }
    // rename cannot replace a non-empty folder: move the old one aside first, and back if the
    // new one cannot take its place.
    let old = tempfile::Builder::new()
        .prefix(".dlw-replaced-")
        .tempdir_in(parent)
        .map_err(staging_err("set-aside"))?;
    let aside = old.path().join("old");
    std::fs::rename(dir, &aside).map_err(io(dir))?;
    if let Err(source) = std::fs::rename(staging.path(), dir) {
        let _ = std::fs::rename(&aside, dir);
        return Err(io(dir)(source));
    }
    let _ = staging.keep();
    Ok(())
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
    let mut tmp = tempfile::NamedTempFile::new_in(folder_of(path)).map_err(io)?;
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

fn persist(path: &Path, tmp: tempfile::NamedTempFile) -> Result<(), OutputError> {
    tmp.persist(path).map(drop).map_err(|e| OutputError::Io {
        path: path.to_path_buf(),
        source: e.error,
    })
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
