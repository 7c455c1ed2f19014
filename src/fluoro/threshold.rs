//! From grey levels to a binary pin mask: Otsu's level (imageproc's `otsu_level`) or a fixed
//! value.
//!
//! The pin is dark (it absorbs X-rays) on a brighter background unless `invert` is set.
//! imageproc's Otsu works on 8-bit images, so the cropped region is first stretched linearly
//! from its own darkest to its brightest pixel onto 0-255; for a 16-bit frame this keeps the
//! contrast that a plain `>> 8` would lose when the frame uses a narrow part of its range.
//! Pixels at or below the level are the pin (above it with `invert`). A fixed value is in the
//! frame's own units (0-255 or 0-65535) and compared with the unstretched pixels.

use std::str::FromStr;

use image::{GrayImage, Luma};

use super::frames::Grey16;
use super::Crop;

/// How the pin is told from the background.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Threshold {
    /// Otsu's level over the cropped region.
    Otsu,
    /// A fixed grey level in the frame's units.
    Value(u16),
}

impl FromStr for Threshold {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == "otsu" {
            return Ok(Self::Otsu);
        }
        s.parse::<u16>()
            .map(Self::Value)
            .map_err(|_| format!("threshold {s:?} is neither `otsu` nor a grey level 0..=65535"))
    }
}

/// The mask (255 = pin) of `crop` and the level used, in the frame's units.
///
/// The crop must lie inside the image (checked by the caller).
pub fn pin_mask(
    image: &Grey16,
    crop: Crop,
    threshold: Threshold,
    invert: bool,
) -> (GrayImage, f64) {
    let rows = crop.y as usize..(crop.y + crop.h) as usize;
    let cols = crop.x as usize..(crop.x + crop.w) as usize;
    let width = image.width() as usize;
    let raw = image.as_raw();
    let row = |r: usize| &raw[r * width + cols.start..r * width + cols.end];
    let mut mask = GrayImage::new(crop.w, crop.h);
    let cw = crop.w as usize;
    match threshold {
        Threshold::Value(level) => {
            let out: &mut [u8] = &mut mask;
            for (i, r) in rows.enumerate() {
                for (o, &v) in out[i * cw..(i + 1) * cw].iter_mut().zip(row(r)) {
                    *o = if (v <= level) != invert { 255 } else { 0 };
                }
            }
            (mask, f64::from(level))
        }
        Threshold::Otsu => {
            let (mut lo, mut hi) = (u16::MAX, 0u16);
            for r in rows.clone() {
                for &v in row(r) {
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
            if lo == hi {
                // A flat region has no pin to separate; an empty mask says so.
                return (mask, f64::from(lo));
            }
            let span = u32::from(hi - lo);
            // `(v − lo)·255/span` rounded, with the division done once: a 32.32 fixed-point
            // factor (a division per pixel costs more than the rest of the stretch).
            let factor = (255u64 << 32) / u64::from(span);
            let out: &mut [u8] = &mut mask;
            for (i, r) in rows.enumerate() {
                for (o, &v) in out[i * cw..(i + 1) * cw].iter_mut().zip(row(r)) {
                    let x = (u64::from(v - lo) * factor + (1 << 31)) >> 32;
                    *o = x.min(255) as u8;
                }
            }
            let level = imageproc::contrast::otsu_level(&mask);
            for p in mask.iter_mut() {
                *p = if (*p <= level) != invert { 255 } else { 0 };
            }
            // The native level whose stretched value rounds to `level` at its top.
            let native = f64::from(lo) + (f64::from(level) + 0.5) * f64::from(span) / 255.0;
            (mask, native)
        }
    }
}

/// A mask pixel that belongs to the pin.
pub const PIN: Luma<u8> = Luma([255]);

#[cfg(test)]
mod tests {
    use super::*;

    fn two_level(dark: u16, bright: u16) -> Grey16 {
        // Left third dark, the rest bright.
        Grey16::from_fn(9, 4, |x, _| Luma([if x < 3 { dark } else { bright }]))
    }

    #[test]
    fn otsu_separates_two_levels_in_16_bit() {
        let img = two_level(30_000, 30_400);
        let (mask, level) = pin_mask(&img, Crop::whole(9, 4), Threshold::Otsu, false);
        assert!((30_000.0..30_400.0).contains(&level), "{level}");
        let pins: Vec<u32> = (0..9).filter(|&x| mask.get_pixel(x, 0)[0] == 255).collect();
        assert_eq!(pins, [0, 1, 2]);
        let (inv, _) = pin_mask(&img, Crop::whole(9, 4), Threshold::Otsu, true);
        assert_eq!(inv.get_pixel(0, 0)[0], 0);
        assert_eq!(inv.get_pixel(8, 3)[0], 255);
    }

    #[test]
    fn fixed_level_and_crop() {
        let img = two_level(10, 200);
        let crop = Crop {
            x: 2,
            y: 1,
            w: 4,
            h: 2,
        };
        let (mask, level) = pin_mask(&img, crop, Threshold::Value(10), false);
        assert_eq!(level, 10.0);
        assert_eq!(mask.dimensions(), (4, 2));
        assert_eq!(mask.get_pixel(0, 0)[0], 255);
        assert_eq!(mask.get_pixel(1, 1)[0], 0);
        let (flat, _) = pin_mask(&two_level(7, 7), Crop::whole(9, 4), Threshold::Otsu, false);
        assert!(flat.iter().all(|&p| p == 0));
        assert_eq!("otsu".parse(), Ok(Threshold::Otsu));
        assert_eq!("1200".parse(), Ok(Threshold::Value(1200)));
        assert!("70000".parse::<Threshold>().is_err());
    }
}
