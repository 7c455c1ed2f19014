//! The largest connected component of a pin mask (imageproc's `connected_components`, 8-connected)
//! and its pixel moments.
//!
//! The largest component is the pin: thresholding also catches noise specks, other dense objects
//! (a smaller marker, a wire) and background patches, and the pin is taken to be the largest of
//! them inside the crop.
//!
//! The labelling runs on the bounding box of the mask's pixels only: imageproc allocates a
//! union-find forest and a label image per pixel of its input, about 25 bytes a pixel, and on a
//! 1024×1024 frame with a small pin that memory traffic, not the labelling, is the cost.

use image::{GrayImage, Luma};
use imageproc::region_labelling::{connected_components, Connectivity};

/// The moments of one component, in the mask's pixel coordinates (x right, y down, pixel
/// centres at integer coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Component {
    /// Pixels in the component.
    pub area_px: u64,
    /// Mean x (px).
    pub mean_x: f64,
    /// Mean y (px).
    pub mean_y: f64,
    /// Central second moments per pixel: `mean((x − x̄)²)`, `mean((x − x̄)(y − ȳ))`,
    /// `mean((y − ȳ)²)` (px²).
    pub mu20: f64,
    /// See `mu20`.
    pub mu11: f64,
    /// See `mu20`.
    pub mu02: f64,
    /// Whether the component touches the mask's border (the pin may be cut off by the crop).
    pub touches_border: bool,
}

/// The largest 8-connected component of `mask`'s 255 pixels, `None` when the mask is empty.
/// Ties go to the lower label (the one met first in row order).
pub fn largest_component(mask: &GrayImage) -> Option<Component> {
    let (w, h) = mask.dimensions();
    let (x0, y0, x1, y1) = bounding_box(mask)?;
    let boxed = image::imageops::crop_imm(mask, x0, y0, x1 - x0 + 1, y1 - y0 + 1).to_image();
    let labels = connected_components(&boxed, Connectivity::Eight, Luma([0u8]));
    let mut areas: Vec<u64> = Vec::new();
    for &l in labels.iter() {
        if l == 0 {
            continue;
        }
        let l = l as usize;
        if areas.len() <= l {
            areas.resize(l + 1, 0);
        }
        areas[l] += 1;
    }
    let (best, &area) = areas
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(&a.0)))?;
    if area == 0 {
        return None;
    }
    let best = best as u32;
    // Moments about a fixed origin near the middle keep the sums well conditioned.
    let (ox, oy) = (f64::from(w) / 2.0, f64::from(h) / 2.0);
    let (mut sx, mut sy, mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let mut touches_border = false;
    for (y, row) in labels.rows().enumerate() {
        for (x, p) in row.enumerate() {
            if p[0] != best {
                continue;
            }
            let (x, y) = (x as u32 + x0, y as u32 + y0);
            let (fx, fy) = (f64::from(x) - ox, f64::from(y) - oy);
            sx += fx;
            sy += fy;
            sxx += fx * fx;
            sxy += fx * fy;
            syy += fy * fy;
            touches_border |= x == 0 || y == 0 || x == w - 1 || y == h - 1;
        }
    }
    let n = area as f64;
    let (mx, my) = (sx / n, sy / n);
    Some(Component {
        area_px: area,
        mean_x: mx + ox,
        mean_y: my + oy,
        mu20: sxx / n - mx * mx,
        mu11: sxy / n - mx * my,
        mu02: syy / n - my * my,
        touches_border,
    })
}

/// The smallest box `(x0, y0, x1, y1)` (inclusive) holding every non-zero pixel, `None` for an
/// empty mask.
fn bounding_box(mask: &GrayImage) -> Option<(u32, u32, u32, u32)> {
    let mut b: Option<(u32, u32, u32, u32)> = None;
    let width = (mask.width() as usize).max(1);
    for (y, row) in mask.as_raw().chunks_exact(width).enumerate() {
        let (Some(first), Some(last)) = (
            row.iter().position(|&p| p != 0),
            row.iter().rposition(|&p| p != 0),
        ) else {
            continue;
        };
        let (y, first, last) = (y as u32, first as u32, last as u32);
        b = Some(match b {
            None => (first, y, last, y),
            Some((x0, y0, x1, _)) => (x0.min(first), y0, x1.max(last), y),
        });
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_the_largest_and_measures_it() {
        let mut mask = GrayImage::new(20, 10);
        // A 2×2 speck and a 6×3 bar from (10, 4).
        for (x, y) in [(1, 1), (2, 1), (1, 2), (2, 2)] {
            mask.put_pixel(x, y, Luma([255]));
        }
        for x in 10..16 {
            for y in 4..7 {
                mask.put_pixel(x, y, Luma([255]));
            }
        }
        let c = largest_component(&mask).unwrap();
        assert_eq!(c.area_px, 18);
        assert!((c.mean_x - 12.5).abs() < 1e-12 && (c.mean_y - 5.0).abs() < 1e-12);
        // Variance of 6 consecutive integers is 35/12, of 3 is 2/3.
        assert!((c.mu20 - 35.0 / 12.0).abs() < 1e-12, "{}", c.mu20);
        assert!((c.mu02 - 2.0 / 3.0).abs() < 1e-12 && c.mu11.abs() < 1e-12);
        assert!(!c.touches_border);
        assert!(largest_component(&GrayImage::new(5, 5)).is_none());
        // A component on the mask's last column touches the border, although the labelling
        // sees only the bounding box.
        for y in 0..10 {
            mask.put_pixel(19, y, Luma([255]));
        }
        let c = largest_component(&mask).unwrap();
        assert_eq!(c.area_px, 18, "the bar is still the largest");
        for y in 0..9 {
            mask.put_pixel(18, y, Luma([255]));
        }
        let c = largest_component(&mask).unwrap();
        assert_eq!(c.area_px, 19);
        assert!(c.touches_border);
        assert!(
            (c.mean_x - (19.0 * 10.0 + 18.0 * 9.0) / 19.0).abs() < 1e-12,
            "{c:?}"
        );
    }
}
