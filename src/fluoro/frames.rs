//! Frames on disk: a folder's PNG and TIFF files in name order, decoded with `image`.
//!
//! Every regular file in the folder must be a frame (`.png`, `.tif`, `.tiff`, any case); hidden
//! files (names starting with `.`) and sub-folders are ignored. Frames are sorted by file name
//! as bytes, so number them with leading zeros (`frame_0001.png`). 8- and 16-bit greyscale are
//! read as they are; RGB frames (a screen capture) are converted to grey by `image`'s luma.

use std::path::{Path, PathBuf};

use image::{DynamicImage, ImageBuffer, Luma};

use super::FluoroError;

/// A greyscale frame held as 16-bit samples whatever its depth.
pub type Grey16 = ImageBuffer<Luma<u16>, Vec<u16>>;

/// A decoded frame.
#[derive(Debug, Clone)]
pub struct Frame {
    /// The pixels; an 8-bit frame keeps its values 0-255.
    pub image: Grey16,
    /// Bits per sample in the file: 8 or 16.
    pub bits: u32,
}

impl Frame {
    /// The largest value a pixel of this depth can take.
    pub fn max_value(&self) -> u16 {
        if self.bits == 8 {
            u8::MAX as u16
        } else {
            u16::MAX
        }
    }

    /// Width and height (px).
    pub fn dimensions(&self) -> (u32, u32) {
        self.image.dimensions()
    }
}

/// Whether a file name has a frame's extension.
pub fn is_frame_name(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| matches!(e.to_ascii_lowercase().as_str(), "png" | "tif" | "tiff"))
}

/// The frames in `dir`, in name order.
///
/// # Errors
/// [`FluoroError::ListDir`], [`FluoroError::NotAFrame`] for a file that is not a PNG or TIFF by
/// its name, [`FluoroError::NoFrames`] for a folder without frames.
pub fn list_frames(dir: &Path) -> Result<Vec<PathBuf>, FluoroError> {
    let list = |source| FluoroError::ListDir {
        path: dir.to_path_buf(),
        source,
    };
    let mut frames = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(list)? {
        let entry = entry.map_err(list)?;
        let name = entry.file_name();
        if name.to_string_lossy().starts_with('.') {
            continue;
        }
        let path = entry.path();
        if path.is_dir() {
            continue;
        }
        if !is_frame_name(&path) {
            return Err(FluoroError::NotAFrame { path });
        }
        frames.push(path);
    }
    if frames.is_empty() {
        return Err(FluoroError::NoFrames {
            path: dir.to_path_buf(),
        });
    }
    frames.sort_by(|a, b| a.file_name().cmp(&b.file_name()));
    Ok(frames)
}

/// Decodes one frame.
///
/// # Errors
/// [`FluoroError::Decode`] for a file `image` cannot decode, [`FluoroError::PixelType`] for
/// float or other pixel types.
pub fn read_frame(path: &Path) -> Result<Frame, FluoroError> {
    let bytes =
        crate::output::read_limited_bytes(path, crate::limits::MAX_FRAME_BYTES).map_err(|e| {
            FluoroError::Decode {
                path: path.to_path_buf(),
                message: e.to_string(),
            }
        })?;
    let img = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| FluoroError::Decode {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?
        .decode()
        .map_err(|e| FluoroError::Decode {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    from_dynamic(img).ok_or_else(|| FluoroError::PixelType {
        path: path.to_path_buf(),
        found: "a float or unknown format".to_string(),
    })
}

/// A decoded image as a frame, `None` for float pixels.
pub fn from_dynamic(img: DynamicImage) -> Option<Frame> {
    let widen = |g: image::GrayImage| -> Grey16 {
        let (w, h) = g.dimensions();
        ImageBuffer::from_raw(w, h, g.into_raw().into_iter().map(u16::from).collect())
            .expect("same dimensions")
    };
    Some(match img {
        DynamicImage::ImageLuma8(g) => Frame {
            image: widen(g),
            bits: 8,
        },
        DynamicImage::ImageLuma16(g) => Frame { image: g, bits: 16 },
        DynamicImage::ImageLumaA8(_) | DynamicImage::ImageRgb8(_) | DynamicImage::ImageRgba8(_) => {
            Frame {
                image: widen(img.to_luma8()),
                bits: 8,
            }
        }
        DynamicImage::ImageLumaA16(_)
        | DynamicImage::ImageRgb16(_)
        | DynamicImage::ImageRgba16(_) => Frame {
            image: img.to_luma16(),
            bits: 16,
        },
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_in_name_order_and_refuses_strangers() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["f_10.png", "f_02.TIF", "f_01.tiff", ".DS_Store"] {
            std::fs::write(dir.path().join(name), b"x").unwrap();
        }
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        let names: Vec<String> = list_frames(dir.path())
            .unwrap()
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, ["f_01.tiff", "f_02.TIF", "f_10.png"]);
        std::fs::write(dir.path().join("notes.txt"), b"x").unwrap();
        let err = list_frames(dir.path()).unwrap_err().to_string();
        assert!(
            err.contains("notes.txt") && err.contains("not a frame"),
            "{err}"
        );
        let empty = tempfile::tempdir().unwrap();
        let err = list_frames(empty.path()).unwrap_err().to_string();
        assert!(err.contains("no PNG or TIFF frames"), "{err}");
    }

    #[test]
    fn decodes_8_and_16_bit_and_names_bad_files() {
        let dir = tempfile::tempdir().unwrap();
        let p8 = dir.path().join("a.png");
        image::GrayImage::from_pixel(3, 2, Luma([200]))
            .save(&p8)
            .unwrap();
        let f = read_frame(&p8).unwrap();
        assert_eq!((f.bits, f.max_value(), f.dimensions()), (8, 255, (3, 2)));
        assert_eq!(f.image.get_pixel(2, 1)[0], 200);
        let p16 = dir.path().join("b.tif");
        Grey16::from_pixel(4, 4, Luma([40_000])).save(&p16).unwrap();
        let f = read_frame(&p16).unwrap();
        assert_eq!((f.bits, f.image.get_pixel(0, 0)[0]), (16, 40_000));
        let bad = dir.path().join("c.png");
        std::fs::write(&bad, b"not a png").unwrap();
        let err = read_frame(&bad).unwrap_err().to_string();
        assert!(err.contains("c.png"), "{err}");
    }
}
