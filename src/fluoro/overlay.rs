//! Overlays: each frame with the fitted ellipse and its major axis drawn on it (imageproc's
//! drawing functions), so that a person can check the fit.
//!
//! The frame is shown in grey, stretched from its darkest to its brightest pixel. Drawn on it:
//! the crop (blue), the second-moment ellipse (green when the pin counts, red when the frame was
//! skipped, e.g. too round) and its major axis across the full ellipse (yellow). No text is
//! drawn (imageproc's text needs a font file); the numbers are in `angles.csv`.
//!
//! The overlay folder is written through a [`StagedFolder`](super::StagedFolder), so a failed
//! run leaves no partial folder.

use image::{Rgb, RgbImage};
use imageproc::drawing::{draw_hollow_polygon_mut, draw_hollow_rect_mut, draw_line_segment_mut};
use imageproc::point::Point;
use imageproc::rect::Rect;

use super::analyze::FrameFit;
use super::frames::Frame;
use super::Crop;

const BLUE: Rgb<u8> = Rgb([60, 120, 255]);
const GREEN: Rgb<u8> = Rgb([40, 220, 40]);
const RED: Rgb<u8> = Rgb([255, 40, 40]);
const YELLOW: Rgb<u8> = Rgb([255, 220, 0]);

/// The frame in grey with the fit drawn on it.
pub fn draw_overlay(frame: &Frame, fit: &FrameFit, crop: Crop) -> RgbImage {
    let (w, h) = frame.dimensions();
    let raw = frame.image.as_raw();
    let lo = raw.iter().copied().min().unwrap_or(0);
    let hi = raw.iter().copied().max().unwrap_or(0).max(lo + 1);
    let span = u32::from(hi - lo);
    let mut img = RgbImage::from_fn(w, h, |x, y| {
        let v = frame.image.get_pixel(x, y)[0];
        let g = (u32::from(v - lo) * 255 / span) as u8;
        Rgb([g, g, g])
    });
    // Lines a few pixels wide on large frames, drawn as parallel one-pixel lines.
    let thick = (w.max(h) / 400).max(1) as i32;
    if crop != Crop::whole(w, h) {
        for t in 0..thick {
            let (cw, ch) = (crop.w as i32 - 2 * t, crop.h as i32 - 2 * t);
            if cw > 0 && ch > 0 {
                let r =
                    Rect::at(crop.x as i32 + t, crop.y as i32 + t).of_size(cw as u32, ch as u32);
                draw_hollow_rect_mut(&mut img, r, BLUE);
            }
        }
    }
    if let Some(e) = fit.ellipse {
        let colour = if fit.skip.is_none() { GREEN } else { RED };
        // Displayed CCW angle: the axis direction in image coordinates is (cos, −sin).
        let (s, c) = e.angle_deg.to_radians().sin_cos();
        let (a, b) = (e.semi_major_px, e.semi_minor_px.max(0.5));
        let at = |u: f64, v: f64, off: f64| {
            let (u, v) = (u * (1.0 + off / a), v * (1.0 + off / b));
            (
                (e.center_x + u * c + v * s) as f32,
                (e.center_y - u * s + v * c) as f32,
            )
        };
        for t in 0..thick {
            let off = f64::from(t);
            let poly: Vec<Point<f32>> = (0..96)
                .map(|k| {
                    let q = f64::from(k) * std::f64::consts::TAU / 96.0;
                    let (x, y) = at(a * q.cos(), b * q.sin(), off);
                    Point::new(x, y)
                })
                .collect();
            draw_hollow_polygon_mut(&mut img, &poly, colour);
            let (nx, ny) = (f64::from(t) * s, f64::from(t) * c);
            let (x0, y0) = at(-a, 0.0, 0.0);
            let (x1, y1) = at(a, 0.0, 0.0);
            draw_line_segment_mut(
                &mut img,
                (x0 + nx as f32, y0 + ny as f32),
                (x1 + nx as f32, y1 + ny as f32),
                YELLOW,
            );
        }
    }
    img
}
