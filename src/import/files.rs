//! An import's input files, read through the one bounded reader: the DAQ file, the tracker log
//! and the optional tracker map.

use std::path::Path;

use crate::limits::{MAX_RECORDING_BYTES, MAX_TEXT_INPUT_BYTES};

use super::map::MapError;
use super::TrackerMap;

/// Why an import's files could not be read.
#[derive(Debug, thiserror::Error)]
pub enum ImportFilesError {
    /// A file could not be read, or is over its size limit.
    #[error("reading {path}")]
    Read {
        /// The file.
        path: String,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// The tracker map is not one.
    #[error("{path}")]
    Map {
        /// The map file.
        path: String,
        /// What is wrong in it.
        #[source]
        source: MapError,
    },
}

/// Reads the tracker map at `path`.
///
/// # Errors
/// [`ImportFilesError`] naming the file.
pub fn read_map(path: &Path) -> Result<TrackerMap, ImportFilesError> {
    let text = crate::output::read_limited(path, MAX_TEXT_INPUT_BYTES).map_err(|source| {
        ImportFilesError::Read {
            path: path.display().to_string(),
            source,
        }
    })?;
    TrackerMap::from_toml(&text).map_err(|source| ImportFilesError::Map {
        path: path.display().to_string(),
        source,
    })
}

/// The files an import reads, read.
#[derive(Debug)]
pub struct ImportFiles {
    /// The tracker map, when the log is not in NDI's layout.
    pub map: Option<TrackerMap>,
    /// The DAQ file's bytes.
    pub daq_bytes: Vec<u8>,
    /// The tracker log's text.
    pub tracker_text: String,
    /// The DAQ file's path, as messages and the provenance name it.
    pub daq_name: String,
    /// The tracker log's path, as messages and the provenance name it.
    pub tracker_name: String,
}

impl ImportFiles {
    /// Reads the tracker map, the DAQ file and the tracker log, in that order.
    ///
    /// # Errors
    /// [`ImportFilesError`] naming the file.
    pub fn read(daq: &Path, tracker: &Path, map: Option<&Path>) -> Result<Self, ImportFilesError> {
        let read_error = |path: &Path| {
            let path = path.display().to_string();
            move |source| ImportFilesError::Read { path, source }
        };
        let map = map.map(read_map).transpose()?;
        let daq_bytes =
            crate::output::read_limited_bytes(daq, MAX_RECORDING_BYTES).map_err(read_error(daq))?;
        let tracker_text = crate::output::read_limited(tracker, MAX_RECORDING_BYTES)
            .map_err(read_error(tracker))?;
        Ok(Self {
            map,
            daq_bytes,
            tracker_text,
            daq_name: daq.display().to_string(),
            tracker_name: tracker.display().to_string(),
        })
    }
}
