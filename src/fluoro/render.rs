//! Synthetic frames: a pin at a known angle on a fluoroscopy-like background, for tests,
//! benchmarks and `dlw fluoro-render`.
//!
//! The scene is an X-ray transmission image: a bright background (`background` of full scale)
//! with a linear brightness gradient across the frame (`gradient`, the fraction it changes from
//! left to right), the pin absorbing `contrast` of it, optionally a smaller round dense blob to
//! distract the component selection. The pin is a filled rectangle (or ellipse) rotated to the
//! given angle, counter-clockwise positive as displayed, with anti-aliased edges; then a Gaussian
//! blur (`blur_px`, imageproc) and Poisson-like noise (`photons` counts at full scale: a value
//! `I` becomes `I + √I·n`, `n` standard normal from a seeded stream).

use image::{ImageBuffer, Luma};

use super::frames::{Frame, Grey16};
use crate::sim::Stream;

/// The pin's outline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PinShape {
    /// A rectangle `length_px` × `width_px`.
    Rectangle,
    /// An ellipse of axes `length_px` and `width_px`.
    Ellipse,
}

/// What a synthetic frame shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinScene {
    /// Frame width (px).
    pub width: u32,
    /// Frame height (px).
    pub height: u32,
    /// 8 or 16 bits per pixel.
    pub bits: u32,
    /// Pin centre x (px).
    pub center_x: f64,
    /// Pin centre y (px, downward).
    pub center_y: f64,
    /// Pin length along its axis (px).
    pub length_px: f64,
    /// Pin width across its axis (px).
    pub width_px: f64,
    /// Rectangle or ellipse.
    pub shape: PinShape,
    /// Background brightness at the frame's left edge, as a fraction of full scale.
    pub background: f64,
    /// Fraction by which the background brightens from the left edge to the right edge.
    pub gradient: f64,
    /// Fraction of the background the pin absorbs.
    pub contrast: f64,
    /// Gaussian blur σ (px); 0 for none.
    pub blur_px: f64,
    /// Photon counts at full scale for the noise; 0 for a noise-free frame.
    pub photons: f64,
    /// A dense round blob: centre x, centre y, radius (px).
    pub distractor: Option<(f64, f64, f64)>,
    /// Width of a dark band along the left edge (px), as a collimator leaf leaves; 0 for none.
    pub collimator_px: f64,
}

impl PinScene {
    /// A `size`×`size` 16-bit scene with the pin in the middle, a third of the frame long and a
    /// twelfth wide, a 20 % gradient, blur, noise and a distracting blob.
    pub fn standard(size: u32) -> Self {
        let s = f64::from(size);
        Self {
            width: size,
            height: size,
            bits: 16,
            center_x: s / 2.0,
            center_y: s / 2.0,
            length_px: s / 3.0,
            width_px: s / 12.0,
            shape: PinShape::Rectangle,
            background: 0.6,
            gradient: 0.2,
            contrast: 0.5,
            blur_px: s / 400.0 + 0.5,
            photons: 20_000.0,
            distractor: Some((0.82 * s, 0.18 * s, s / 30.0)),
            collimator_px: 0.0,
        }
    }
}

/// A recorded angle filmed at `fps` from the recording's first sample (`dlw fluoro-render`):
/// frame `k`, at `t0 + k/fps`, shows the pin at the recorded angle there (linear between
/// samples, the last one after the end) plus `offset_deg`, with the noise of seed `seed + k`.
#[derive(Debug, Clone, Copy)]
pub struct RecordedAngle<'a> {
    /// Sample times (s), increasing, at least one.
    pub time_s: &'a [f64],
    /// The angle at each (°).
    pub angle_deg: &'a [f64],
    /// Frames per second.
    pub fps: f64,
    /// Added to every angle (°).
    pub offset_deg: f64,
    /// The first frame's noise seed.
    pub seed: u64,
}

impl RecordedAngle<'_> {
    /// The first and last sample times (s).
    pub fn span_s(&self) -> (f64, f64) {
        (self.time_s[0], self.time_s[self.time_s.len() - 1])
    }

    /// Frames from the first sample to the last, both included where they fall on a frame.
    pub fn frames(&self) -> usize {
        let (t0, t1) = self.span_s();
        ((t1 - t0) * self.fps).floor() as usize + 1
    }

    /// Frame `k`'s file name, `frame_00012.png`.
    pub fn name(k: usize) -> String {
        format!("frame_{k:05}.png")
    }

    /// Frame `k` of `scene`.
    pub fn render(&self, scene: &PinScene, k: usize) -> Frame {
        let (t0, t1) = self.span_s();
        let t = t0 + k as f64 / self.fps;
        let angle = crate::stats::interpolate(self.time_s, self.angle_deg, t.min(t1))
            .unwrap_or(self.angle_deg[0]);
        render_frame(
            scene,
            self.offset_deg + angle,
            self.seed.wrapping_add(k as u64),
        )
    }
}

/// Renders `scene` with the pin at `angle_deg`; `seed` picks the noise.
pub fn render_frame(scene: &PinScene, angle_deg: f64, seed: u64) -> Frame {
    let (w, h) = (scene.width, scene.height);
    let (s, c) = angle_deg.to_radians().sin_cos();
    let (half_l, half_w) = (scene.length_px / 2.0, scene.width_px / 2.0);
    let coverage = |x: f64, y: f64| -> f64 {
        let (dx, dy) = (x - scene.center_x, y - scene.center_y);
        // Displayed CCW angle: the axis direction in image coordinates is (cos, −sin).
        let u = dx * c - dy * s;
        let v = dx * s + dy * c;
        let d = match scene.shape {
            PinShape::Rectangle => (u.abs() - half_l).max(v.abs() - half_w),
            PinShape::Ellipse => {
                let r = ((u / half_l).powi(2) + (v / half_w).powi(2)).sqrt();
                (r - 1.0) * half_w
            }
        };
        (0.5 - d).clamp(0.0, 1.0)
    };
    let blob = |x: f64, y: f64| -> f64 {
        scene.distractor.map_or(0.0, |(bx, by, r)| {
            (0.5 - ((x - bx).hypot(y - by) - r)).clamp(0.0, 1.0)
        })
    };
    let mut img: ImageBuffer<Luma<f32>, Vec<f32>> = ImageBuffer::from_fn(w, h, |x, y| {
        let (fx, fy) = (f64::from(x), f64::from(y));
        let mut bg = scene.background * (1.0 + scene.gradient * fx / f64::from(w.max(1)));
        if fx < scene.collimator_px {
            // The collimator passes a tenth of the beam.
            bg *= 0.1;
        }
        let absorbed = coverage(fx, fy).max(blob(fx, fy));
        Luma([(bg * (1.0 - scene.contrast * absorbed)) as f32])
    });
    if scene.blur_px > 0.0 {
        img = imageproc::filter::gaussian_blur_f32(&img, scene.blur_px as f32);
    }
    let max = if scene.bits == 8 { 255.0 } else { 65_535.0 };
    let mut noise = Stream::new(seed, 0);
    let pixels = img
        .into_raw()
        .into_iter()
        .map(|v| {
            let mut v = f64::from(v);
            if scene.photons > 0.0 {
                let counts = (v * scene.photons).max(0.0);
                v = (counts + counts.sqrt() * noise.normal()) / scene.photons;
            }
            (v * max).round().clamp(0.0, max) as u16
        })
        .collect();
    Frame {
        image: Grey16::from_raw(w, h, pixels).expect("one value per pixel"),
        bits: if scene.bits == 8 { 8 } else { 16 },
    }
}

/// The frame as PNG bytes, at its own bit depth.
///
/// # Errors
/// The encoder's message.
pub fn png_bytes(frame: &Frame) -> Result<Vec<u8>, String> {
    let mut out = std::io::Cursor::new(Vec::new());
    let res = if frame.bits == 8 {
        let (w, h) = frame.dimensions();
        let g: image::GrayImage = ImageBuffer::from_raw(
            w,
            h,
            frame
                .image
                .as_raw()
                .iter()
                .map(|&v| v.min(255) as u8)
                .collect(),
        )
        .expect("one value per pixel");
        g.write_to(&mut out, image::ImageFormat::Png)
    } else {
        frame.image.write_to(&mut out, image::ImageFormat::Png)
    };
    res.map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frame `k` shows the angle interpolated at `t0 + k/fps` plus the offset, with seed
    /// `seed + k`; the last frame stays within the recording.
    #[test]
    fn recorded_angle_frames_follow_the_recording() {
        let film = RecordedAngle {
            time_s: &[1.0, 2.0, 3.0],
            angle_deg: &[0.0, 10.0, 30.0],
            fps: 2.0,
            offset_deg: 5.0,
            seed: 7,
        };
        assert_eq!(film.frames(), 5);
        assert_eq!(RecordedAngle::name(12), "frame_00012.png");
        let scene = PinScene::standard(64);
        for (k, angle) in [(0, 5.0), (1, 10.0), (3, 25.0), (4, 35.0)] {
            let (got, want) = (
                film.render(&scene, k),
                render_frame(&scene, angle, 7 + k as u64),
            );
            assert!(got.image.as_raw() == want.image.as_raw(), "frame {k}");
        }
    }

    #[test]
    fn the_pin_is_dark_and_where_the_angle_puts_it() {
        let mut scene = PinScene::standard(200);
        scene.photons = 0.0;
        scene.distractor = None;
        let f = render_frame(&scene, 30.0, 1);
        let at = |x: f64, y: f64| f.image.get_pixel(x as u32, y as u32)[0];
        // 25 px along the axis at 30° CCW as displayed: right and up.
        let (s, c) = 30f64.to_radians().sin_cos();
        let on = at(100.0 + 25.0 * c, 100.0 - 25.0 * s);
        let mirrored = at(100.0 + 25.0 * c, 100.0 + 25.0 * s);
        assert!(f64::from(on) < 0.5 * f64::from(mirrored), "{on} {mirrored}");
        let noisy = render_frame(&PinScene::standard(200), 30.0, 1);
        assert_eq!(noisy.bits, 16);
        assert_ne!(noisy.image, f.image);
        assert_eq!(
            render_frame(&PinScene::standard(200), 30.0, 1).image,
            noisy.image
        );
    }
}
