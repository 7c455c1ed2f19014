//! The drawing's length unit: `$INSUNITS` when the file has it, else what the user says.

use dxf::enums::Units;

use super::DxfImportError;

/// A length unit dlw reads drawings in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrawingUnits {
    /// Millimetres (`$INSUNITS = 4`), dlw's own.
    Mm,
    /// Micrometres (`$INSUNITS = 13`).
    Um,
    /// Inches (`$INSUNITS = 1`).
    In,
}

impl DrawingUnits {
    /// Millimetres per drawing unit.
    pub fn mm_per_unit(self) -> f64 {
        match self {
            DrawingUnits::Mm => 1.0,
            DrawingUnits::Um => 1e-3,
            DrawingUnits::In => 25.4,
        }
    }

    /// The name used on the command line: `mm`, `um`, `in`.
    pub fn name(self) -> &'static str {
        match self {
            DrawingUnits::Mm => "mm",
            DrawingUnits::Um => "um",
            DrawingUnits::In => "in",
        }
    }

    /// The unit called `name` (`mm`, `um` or `µm`, `in`).
    pub fn from_name(name: &str) -> Option<Self> {
        match name.trim().to_ascii_lowercase().as_str() {
            "mm" => Some(DrawingUnits::Mm),
            "um" | "µm" | "micron" | "microns" => Some(DrawingUnits::Um),
            "in" | "inch" | "inches" => Some(DrawingUnits::In),
            _ => None,
        }
    }

    fn from_insunits(u: Units) -> Option<Self> {
        match u {
            Units::Millimeters => Some(DrawingUnits::Mm),
            Units::Microns => Some(DrawingUnits::Um),
            Units::Inches => Some(DrawingUnits::In),
            _ => None,
        }
    }
}

/// Where the unit came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnitsSource {
    /// The file's `$INSUNITS`.
    Header,
    /// The user (`--units`), the file having none.
    Given,
}

/// The unit to read the drawing in: `$INSUNITS` if set (and `given` must agree), else `given`.
/// `has_insunits` says whether the header holds `$INSUNITS` at all (R12 cannot).
///
/// # Errors
/// [`DxfImportError::NoUnits`], [`DxfImportError::Units`] or [`DxfImportError::UnitsConflict`].
pub(super) fn resolve(
    insunits: Units,
    has_insunits: bool,
    given: Option<DrawingUnits>,
) -> Result<(DrawingUnits, UnitsSource), DxfImportError> {
    let name = format!("{insunits:?}").to_lowercase();
    if insunits == Units::Unitless {
        return given
            .map(|g| (g, UnitsSource::Given))
            .ok_or_else(|| DxfImportError::NoUnits {
                found: if has_insunits {
                    "0 (unitless)".into()
                } else {
                    "missing".into()
                },
            });
    }
    let Some(own) = DrawingUnits::from_insunits(insunits) else {
        return Err(DxfImportError::Units {
            insunits: insunits as i16,
            name,
        });
    };
    match given {
        Some(g) if g != own => Err(DxfImportError::UnitsConflict {
            given: g.name().into(),
            insunits: insunits as i16,
            name,
        }),
        _ => Ok((own, UnitsSource::Header)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_wins_given_fills_in_and_conflicts_are_refused() {
        let mm = Some(DrawingUnits::Mm);
        assert_eq!(
            resolve(Units::Millimeters, true, None).unwrap(),
            (DrawingUnits::Mm, UnitsSource::Header)
        );
        assert_eq!(
            resolve(Units::Unitless, false, Some(DrawingUnits::In)).unwrap(),
            (DrawingUnits::In, UnitsSource::Given)
        );
        let e = resolve(Units::Unitless, false, None).unwrap_err();
        assert!(e.to_string().contains("$INSUNITS is missing"), "{e}");
        assert!(e.to_string().contains("--units mm|um|in"), "{e}");
        let e = resolve(Units::Inches, true, mm).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("--units mm contradicts the drawing's $INSUNITS = 1 (inches)"),
            "{e}"
        );
        assert!(matches!(
            resolve(Units::Feet, true, None),
            Err(DxfImportError::Units { insunits: 2, .. })
        ));
        assert_eq!(DrawingUnits::from_name("µm"), Some(DrawingUnits::Um));
        assert_eq!(DrawingUnits::In.mm_per_unit(), 25.4);
    }
}
