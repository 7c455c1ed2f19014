//! A folder written whole or not at all: the overlay folder of `dlw fluoro` and the frames of
//! `dlw fluoro-render`, too many and too large to hold in memory for
//! `dlw::output::write_folder_atomic`.
//!
//! Files are written one by one into a staging folder beside the destination; [`finish`]
//! renames it into place (moving an old folder aside first, and back if the rename fails).
//!
//! [`finish`]: StagedFolder::finish

use std::path::{Path, PathBuf};

use image::RgbImage;

use super::FluoroError;

/// A folder being written: files go into a staging folder beside the destination, which takes
/// the destination's place in [`finish`](Self::finish). Dropped unfinished, the staging folder
/// is removed.
#[derive(Debug)]
pub struct StagedFolder {
    dest: PathBuf,
    staging: tempfile::TempDir,
}

fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

impl StagedFolder {
    /// Starts a folder at `dest`; an existing non-empty `dest` is replaced only with
    /// `replace`.
    ///
    /// # Errors
    /// [`FluoroError::FolderExists`], or [`FluoroError::Write`] when the staging folder cannot
    /// be created.
    pub fn create(dest: &Path, replace: bool) -> Result<Self, FluoroError> {
        let occupied = match std::fs::read_dir(dest) {
            Ok(mut entries) => entries.next().is_some(),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => false,
            Err(_) => true,
        };
        if occupied && !replace {
            return Err(FluoroError::FolderExists {
                path: dest.to_path_buf(),
            });
        }
        let staging = tempfile::Builder::new()
            .prefix(".dlw-staging-")
            .tempdir_in(parent_of(dest))
            .map_err(|source| FluoroError::Write {
                path: dest.to_path_buf(),
                source,
            })?;
        Ok(Self {
            dest: dest.to_path_buf(),
            staging,
        })
    }

    /// Writes `image` as the PNG file `name` into the staging folder.
    ///
    /// # Errors
    /// [`FluoroError::Encode`] naming the file.
    pub fn add_png(&self, name: &str, image: &RgbImage) -> Result<(), FluoroError> {
        let path = self.staging.path().join(name);
        image
            .save_with_format(&path, image::ImageFormat::Png)
            .map_err(|e| FluoroError::Encode {
                name: name.to_string(),
                message: e.to_string(),
            })
    }

    /// Writes `bytes` as the file `name` into the staging folder.
    ///
    /// # Errors
    /// [`FluoroError::Write`] naming the file.
    pub fn add_bytes(&self, name: &str, bytes: &[u8]) -> Result<(), FluoroError> {
        let path = self.staging.path().join(name);
        std::fs::write(&path, bytes).map_err(|source| FluoroError::Write { path, source })
    }

    /// Moves the finished folder into place, replacing an old one.
    ///
    /// # Errors
    /// [`FluoroError::Write`]; the old folder is then as it was.
    pub fn finish(self) -> Result<(), FluoroError> {
        let io = |source| FluoroError::Write {
            path: self.dest.clone(),
            source,
        };
        // Temporary folders are created private (0700); an output folder is an ordinary one.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(self.staging.path(), std::fs::Permissions::from_mode(0o755))
                .map_err(io)?;
        }
        if std::fs::symlink_metadata(&self.dest).is_err() {
            std::fs::rename(self.staging.path(), &self.dest).map_err(io)?;
            let _ = self.staging.keep();
            return Ok(());
        }
        let old = tempfile::Builder::new()
            .prefix(".dlw-replaced-")
            .tempdir_in(parent_of(&self.dest))
            .map_err(io)?;
        let aside = old.path().join("old");
        std::fs::rename(&self.dest, &aside).map_err(io)?;
        if let Err(source) = std::fs::rename(self.staging.path(), &self.dest) {
            let _ = std::fs::rename(&aside, &self.dest);
            return Err(io(source));
        }
        let _ = self.staging.keep();
        Ok(())
    }
}
