//! Importing real bench files (issue 18): the NDI tracker log so far; the DAQ readers, the
//! bending angle, the clock alignment and `dlw import-recording` are still to come.

pub mod ndi;

pub use ndi::{NdiError, ToolFrame, TrackerLog};
