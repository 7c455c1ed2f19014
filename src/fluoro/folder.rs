//! A folder of frames, analyzed in name order: every frame is read, checked against the first
//! (same size, same bit depth), analyzed and, when asked, drawn into an overlay folder.
//!
//! The settings are checked against the first frame before anything is analyzed, and nothing is
//! written to the destination until every frame has been read: the overlays go into a
//! [`StagedFolder`] the caller finishes once the whole output is ready.

use std::path::Path;

use super::analyze::{analyze_frame, FrameFit, Settings};
use super::{draw_overlay, list_frames, read_frame, Crop, FluoroError, StagedFolder};

/// The frames' fits, in name order.
#[derive(Debug, Clone)]
pub struct FolderFits {
    /// Each frame's file name.
    pub names: Vec<String>,
    /// Each frame's fit.
    pub fits: Vec<FrameFit>,
    /// Frame width and height (px).
    pub dimensions: (u32, u32),
    /// Bits per pixel.
    pub bits: u32,
}

/// Analyzes every frame in `dir`; with `overlay`, writes `NAME.png` (the frame's stem) into it.
///
/// # Errors
/// [`FluoroError`]: no frames, a file that is not a frame or cannot be decoded, a frame whose
/// size or depth differs from the first, settings that do not fit the frames.
pub fn analyze_folder(
    dir: &Path,
    settings: &Settings,
    overlay: Option<&StagedFolder>,
) -> Result<FolderFits, FluoroError> {
    let paths = list_frames(dir)?;
    let mut out = FolderFits {
        names: Vec::with_capacity(paths.len()),
        fits: Vec::with_capacity(paths.len()),
        dimensions: (0, 0),
        bits: 0,
    };
    for (k, path) in paths.iter().enumerate() {
        let frame = read_frame(path)?;
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        let (w, h) = frame.dimensions();
        if k == 0 {
            settings.check(w, h, frame.bits)?;
            out.dimensions = (w, h);
            out.bits = frame.bits;
        } else if (w, h) != out.dimensions {
            return Err(FluoroError::MixedSizes {
                path: path.clone(),
                width: w,
                height: h,
                first: out.names[0].clone(),
                first_width: out.dimensions.0,
                first_height: out.dimensions.1,
            });
        } else if frame.bits != out.bits {
            return Err(FluoroError::MixedDepths {
                path: path.clone(),
                bits: frame.bits,
                first: out.names[0].clone(),
                first_bits: out.bits,
            });
        }
        let fit = analyze_frame(&frame, settings);
        if let Some(folder) = overlay {
            let crop = settings.crop.unwrap_or(Crop::whole(w, h));
            let stem = path.file_stem().map_or_else(
                || format!("frame_{k:05}"),
                |s| s.to_string_lossy().into_owned(),
            );
            folder.add_png(&format!("{stem}.png"), &draw_overlay(&frame, &fit, crop))?;
        }
        out.names.push(name);
        out.fits.push(fit);
    }
    Ok(out)
}
