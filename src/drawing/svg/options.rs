use super::error::SvgError;

/// Smallest print scale accepted (1:100).
pub const MIN_SCALE: f64 = 0.01;
/// Largest print scale accepted (1000:1).
pub const MAX_SCALE: f64 = 1000.0;

/// The standard scales a sheet picks from, largest first.
const STANDARD_SCALES: [f64; 12] = [
    100.0, 50.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.05, 0.02,
];

/// The printable area of A4 landscape inside 5 mm borders (paper mm): what the automatic
/// scale fits a sheet into.
pub const PAGE_MM: (f64, f64) = (287.0, 200.0);

/// Options shared by the SVG drawings.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SvgOptions {
    /// Print scale in paper mm per part mm (`10.0` is 10:1). `None` picks the largest standard
    /// scale (100:1, 50:1, 20:1, 10:1, 5:1, 2:1, 1:1, 1:2, …) at which the whole sheet fits
    /// [`PAGE_MM`], A4 landscape inside 5 mm borders.
    pub print_scale: Option<f64>,
}

/// A drawn sheet: the SVG text and its printed size (mm).
pub(crate) struct Drawn {
    /// The document.
    pub svg: String,
    /// Printed width and height (paper mm).
    pub size_mm: (f64, f64),
}

impl SvgOptions {
    /// [`Self::draw`], skipping the standard scales above `largest` (a scale at which the sheet
    /// cannot fit the page, known beforehand: the result is the same, with fewer drawings).
    pub(crate) fn draw_at_most(
        &self,
        largest: f64,
        draw: impl Fn(f64) -> Drawn,
    ) -> Result<String, SvgError> {
        if self.print_scale.is_some() {
            return self.draw(draw);
        }
        let mut last = None;
        for scale in STANDARD_SCALES.into_iter().filter(|s| *s <= largest) {
            let drawn = draw(scale);
            if drawn.size_mm.0 <= PAGE_MM.0 && drawn.size_mm.1 <= PAGE_MM.1 {
                return Ok(drawn.svg);
            }
            last = Some(drawn.svg);
        }
        match last {
            Some(svg) => Ok(svg),
            None => self.draw(draw),
        }
    }

    /// Draws at the scale asked for, or at each standard scale from the largest down until
    /// the sheet fits the page (the smallest standard scale if none does).
    pub(crate) fn draw(&self, draw: impl Fn(f64) -> Drawn) -> Result<String, SvgError> {
        match self.print_scale {
            Some(value) if value.is_finite() && (MIN_SCALE..=MAX_SCALE).contains(&value) => {
                Ok(draw(value).svg)
            }
            Some(value) => Err(SvgError::BadScale {
                value,
                min: MIN_SCALE,
                max: MAX_SCALE,
            }),
            None => {
                let mut last = String::new();
                for scale in STANDARD_SCALES {
                    let drawn = draw(scale);
                    if drawn.size_mm.0 <= PAGE_MM.0 && drawn.size_mm.1 <= PAGE_MM.1 {
                        return Ok(drawn.svg);
                    }
                    last = drawn.svg;
                }
                Ok(last)
            }
        }
    }
}
