//! Fluoroscopy ground truth: the joint angle from X-ray frames (the paper's Section IV-D).
//!
//! In the hydrogel phantom the EM tracker cannot be used, so the paper took the angle from
//! fluoroscopy frames at 2 Hz: each frame cropped, thresholded to find the gold-plated pin in the
//! tip, an ellipse fitted to the pin, the angle of its major axis to the horizontal taken as the
//! joint angle, then an 8-sample moving average and the mean before bending subtracted.
//!
//! The pieces, one per file, in the order a frame goes through them:
//! - [`frames`]: listing a folder's PNG and TIFF frames in name order and decoding them
//!   (8- and 16-bit greyscale, with `image`);
//! - [`crop`]: the `x,y,w,h` region the pin is searched in;
//! - [`threshold`]: Otsu's level (imageproc) or a fixed value, to a binary pin mask;
//! - [`component`]: the largest connected component of the mask (imageproc) and its moments;
//! - [`ellipse`]: the second-moment ellipse of that component and its major axis's angle;
//! - [`analyze`]: one frame from pixels to a fitted pin, or the reason it has none;
//! - [`folder`]: every frame of a folder, checked against the first and analyzed;
//! - [`unwrap`], [`smooth`], [`baseline`]: the series across frames;
//! - [`series`]: all of it over a sequence of frames;
//! - [`csv`]: `angles.csv`, written and read back (by `dlw estimate --truth`);
//! - [`summary`]: the series in numbers, as `dlw fluoro` prints them;
//! - [`overlay`]: frames with the fitted ellipse and axis drawn on them, for a person to check;
//! - [`staged`]: output folders written whole or not at all;
//! - [`render`]: synthetic frames of a pin at known angles (tests, benchmarks, `dlw
//!   fluoro-render`).
//!
//! Conventions (`docs/fluoro.md`): angles are counter-clockwise positive as the frame is
//! displayed, 0 along +x (image rows run downward, so the image's y is flipped), in degrees at
//! the edges.

pub mod analyze;
pub mod baseline;
pub mod component;
pub mod crop;
pub mod csv;
pub mod ellipse;
pub mod folder;
pub mod frames;
pub mod overlay;
mod pipeline;
pub mod render;
pub mod series;
pub mod smooth;
pub mod staged;
pub mod summary;
pub mod threshold;
pub mod unwrap;

use std::path::PathBuf;

/// One frame's analysis and the settings it runs with.
pub use analyze::{analyze_frame, FrameFit, Settings, Skip};
/// The mean before motion, subtracted from every angle.
pub use baseline::{baseline, Baseline, BaselineRule};
/// The largest connected component of a mask and its moments.
pub use component::{largest_component, Component};
/// The region of a frame the pin is searched in.
pub use crop::Crop;
/// `angles.csv`, written and read.
pub use csv::{angles_csv_bytes, ANGLES_HEADER};
/// The second-moment ellipse.
pub use ellipse::Ellipse;
/// A folder of frames analyzed in name order.
pub use folder::{analyze_folder, FolderFits};
/// Frames on disk.
pub use frames::{list_frames, read_frame, Frame};
/// Drawing the fit on a frame, and the overlay folder.
pub use overlay::draw_overlay;
/// `dlw fluoro` as one call.
pub use pipeline::{fluoro, Fluoro, FluoroRequest};
/// Synthetic frames.
pub use render::{render_frame, PinScene};
/// A sequence of frames to a series of angles.
pub use series::{AngleSeries, Row, SeriesSettings};
/// The centred moving average.
pub use smooth::moving_average;
/// A folder written whole or not at all.
pub use staged::StagedFolder;
/// The series in numbers: frames fitted and skipped, baseline, angle range.
pub use summary::{FluoroSummary, Skipped};
/// Otsu or a fixed threshold.
pub use threshold::{pin_mask, Threshold};
/// Unwrapping axis angles across frames.
pub use unwrap::unwrap_axis_deg;

/// Why frames could not be read, analyzed or written.
#[derive(Debug, thiserror::Error)]
pub enum FluoroError {
    /// The frames folder could not be listed.
    #[error("cannot list frames folder {path}")]
    ListDir {
        /// The folder.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The frames folder holds no frames.
    #[error("frames folder {path} has no PNG or TIFF frames")]
    NoFrames {
        /// The folder.
        path: PathBuf,
    },
    /// A file in the frames folder is not a PNG or TIFF by its name.
    #[error("{path} is not a frame: expected a .png, .tif or .tiff file (move other files out of the frames folder)")]
    NotAFrame {
        /// The file.
        path: PathBuf,
    },
    /// A frame could not be decoded.
    #[error("cannot decode frame {path}: {message}")]
    Decode {
        /// The frame.
        path: PathBuf,
        /// The decoder's message.
        message: String,
    },
    /// A frame's pixel type is not one `dlw fluoro` reads.
    #[error("frame {path} has pixel type {found}; expected 8- or 16-bit greyscale (or RGB, converted to grey)")]
    PixelType {
        /// The frame.
        path: PathBuf,
        /// The pixel type found.
        found: String,
    },
    /// A frame's size differs from the first frame's.
    #[error("frame {path} is {width}×{height} px but the first frame {first} is {first_width}×{first_height} px (every frame must have the same size)")]
    MixedSizes {
        /// The frame.
        path: PathBuf,
        /// Its width (px).
        width: u32,
        /// Its height (px).
        height: u32,
        /// The first frame's file name.
        first: String,
        /// The first frame's width (px).
        first_width: u32,
        /// The first frame's height (px).
        first_height: u32,
    },
    /// A frame's bit depth differs from the first frame's.
    #[error("frame {path} is {bits}-bit but the first frame {first} is {first_bits}-bit (every frame must have the same bit depth)")]
    MixedDepths {
        /// The frame.
        path: PathBuf,
        /// Its bit depth.
        bits: u32,
        /// The first frame's file name.
        first: String,
        /// The first frame's bit depth.
        first_bits: u32,
    },
    /// `--crop` is not four non-negative integers.
    #[error("crop {text:?} is not x,y,w,h (four non-negative integers, w and h at least {min})")]
    CropSyntax {
        /// The text given.
        text: String,
        /// The smallest width and height.
        min: u32,
    },
    /// `--crop` reaches outside the frame.
    #[error("crop x={x}, y={y}, w={w}, h={h} reaches outside the {width}×{height} px frame (needs x + w ≤ {width} and y + h ≤ {height})")]
    CropOutside {
        /// Left column.
        x: u32,
        /// Top row.
        y: u32,
        /// Width.
        w: u32,
        /// Height.
        h: u32,
        /// The frame's width.
        width: u32,
        /// The frame's height.
        height: u32,
    },
    /// A fixed threshold beyond the frames' bit depth.
    #[error("threshold {value} is beyond the {bits}-bit frames' range 0..={max}")]
    ThresholdRange {
        /// The threshold given.
        value: u32,
        /// The frames' bit depth.
        bits: u32,
        /// The largest pixel value.
        max: u32,
    },
    /// A setting is out of range.
    #[error("{name} = {value} is out of range ({limit})")]
    Setting {
        /// The setting's name as on the command line.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        limit: &'static str,
    },
    /// No frame had a plausible pin.
    #[error("no frame of {frames} has a plausible pin (largest component ≥ {min_area_px} px with axis ratio ≥ {min_axis_ratio}); check --crop, --threshold and --invert")]
    NoPin {
        /// Frames read.
        frames: usize,
        /// The smallest pin area (px).
        min_area_px: u32,
        /// The smallest axis ratio.
        min_axis_ratio: f64,
    },
    /// The baseline window holds no fitted frame.
    #[error("the baseline window (the first {baseline_s} s) has no frame with a fitted pin")]
    EmptyBaseline {
        /// The window (s).
        baseline_s: f64,
    },
    /// An output folder exists and is not empty.
    #[error("output folder {path} already exists and is not empty (pass --force to replace it)")]
    FolderExists {
        /// The folder.
        path: PathBuf,
    },
    /// An image could not be encoded.
    #[error("cannot encode {name}: {message}")]
    Encode {
        /// The overlay's file name.
        name: String,
        /// The encoder's message.
        message: String,
    },
    /// A file or folder could not be written.
    #[error("cannot write {path}")]
    Write {
        /// The path.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// An output file could not be written.
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// A command-line option out of its range.
    #[error("{flag} {value} is out of range ({limit})")]
    Option {
        /// The option.
        flag: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        limit: &'static str,
    },
    /// A setting beyond the limits of `crate::limits` (the message names value and limit).
    #[error("{message}")]
    Limit {
        /// The limit's message.
        message: String,
    },
    /// The folder `angles.csv` goes in does not exist.
    #[error("cannot write {}: folder {} does not exist", output.display(), folder.display())]
    NoOutputFolder {
        /// `angles.csv`.
        output: PathBuf,
        /// Its folder.
        folder: PathBuf,
    },
    /// A failure while analyzing a folder of frames.
    #[error("analyzing frames in {}", frames.display())]
    Analyzing {
        /// The frames folder.
        frames: PathBuf,
        /// Why.
        source: Box<FluoroError>,
    },
}
