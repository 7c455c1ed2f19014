//! The region of a frame the pin is searched in: `--crop x,y,w,h` in pixels, `x` from the left
//! column, `y` from the top row, as an image viewer shows them.
//!
//! Cropping matters beyond speed: Otsu's method splits a histogram into two classes, and over a
//! whole frame the two largest classes are usually parts of the background (collimator edges,
//! the phantom's border, a brightness gradient), not the small pin against its surroundings.
//! A crop around the pin's sweep makes the pin one of the two classes.

use std::str::FromStr;

use super::FluoroError;

/// The smallest crop width and height (px): smaller leaves no room for a pin with an axis.
pub const MIN_CROP_PX: u32 = 4;

/// A rectangle of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Crop {
    /// Left column (px).
    pub x: u32,
    /// Top row (px).
    pub y: u32,
    /// Width (px).
    pub w: u32,
    /// Height (px).
    pub h: u32,
}

impl Crop {
    /// The whole of a `width`×`height` frame.
    pub fn whole(width: u32, height: u32) -> Self {
        Self {
            x: 0,
            y: 0,
            w: width,
            h: height,
        }
    }

    /// Checks that the crop lies inside a `width`×`height` frame.
    ///
    /// # Errors
    /// [`FluoroError::CropOutside`] naming the crop and the frame.
    pub fn check_inside(&self, width: u32, height: u32) -> Result<(), FluoroError> {
        let fits = |o: u32, l: u32, size: u32| o.checked_add(l).is_some_and(|end| end <= size);
        if fits(self.x, self.w, width) && fits(self.y, self.h, height) {
            Ok(())
        } else {
            Err(FluoroError::CropOutside {
                x: self.x,
                y: self.y,
                w: self.w,
                h: self.h,
                width,
                height,
            })
        }
    }
}

impl FromStr for Crop {
    type Err = FluoroError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || FluoroError::CropSyntax {
            text: s.to_string(),
            min: MIN_CROP_PX,
        };
        let v: Vec<u32> = s
            .split(',')
            .map(|p| p.trim().parse::<u32>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad())?;
        match v[..] {
            [x, y, w, h] if w >= MIN_CROP_PX && h >= MIN_CROP_PX => Ok(Self { x, y, w, h }),
            _ => Err(bad()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_checks_bounds() {
        let c: Crop = "10, 20,100,50".parse().unwrap();
        assert_eq!(
            c,
            Crop {
                x: 10,
                y: 20,
                w: 100,
                h: 50
            }
        );
        assert!(c.check_inside(110, 70).is_ok());
        let err = c.check_inside(109, 70).unwrap_err().to_string();
        assert!(err.contains("x + w ≤ 109"), "{err}");
        assert!(c.check_inside(110, 69).is_err());
        for bad in ["1,2,3", "1,2,3,4,5", "-1,0,10,10", "0,0,2,10", "a,b,c,d"] {
            assert!(bad.parse::<Crop>().is_err(), "{bad}");
        }
        let huge = Crop {
            x: u32::MAX,
            y: 0,
            w: 10,
            h: 10,
        };
        assert!(huge.check_inside(100, 100).is_err());
    }
}
