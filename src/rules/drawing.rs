//! A drawing checked against the design it is to be cut with, and the design's numbers taken
//! from what the drawing will cut.
//!
//! - The drawing must be of this design: the same name, outer radius, notch style (notches on
//!   one side, UAN, or on both, BSN) and sensor count. Otherwise the program would be labelled
//!   with one joint and cut another.
//! - Every layout rule ([`super::check_layout`]) runs on the drawn geometry.
//! - The derived numbers come from the drawing: the notch levels `N`, the mean notch width `h`,
//!   web `c` and arc `s_n` make the joint as drawn; its closing angle `θ_close = N·h/(ȳ + r_o)`
//!   (so `Σ h` over the levels) and the strain warnings are computed from it, not from the
//!   design's `notch_count`.

use geo::BoundingRect;

use crate::design::Design;
use crate::drawing::{ImportedDxf, Provenance};
use crate::layout::Layout;

use super::{check_layout, strain, Checked, RulesError, Violation, Warning};

/// Two lengths closer than this are the same (mm).
const SAME_MM: f64 = 1e-9;

/// What the drawing check found.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawingReport {
    /// Broken rules: nothing may be cut while there are any.
    pub errors: Vec<Violation>,
    /// Warnings for the joint as drawn.
    pub warnings: Vec<Warning>,
    /// The joint as drawn, when the drawing is of this design and has notches.
    pub derived: Option<Derived>,
}

/// The joint's numbers as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct Derived {
    /// Notch levels along the tube (the drawn `N`).
    pub levels: u32,
    /// Notches (pieces of one notch split at the seam count once).
    pub notches: usize,
    /// Mean notch width along `x` (mm).
    pub notch_width_mm: f64,
    /// Mean web between consecutive levels (mm); the design's when there is one level.
    pub notch_spacing_mm: f64,
    /// Mean notch arc along `s` (mm).
    pub notch_arc_mm: f64,
    /// The design with these numbers in place of its notch pattern.
    pub design: Design,
}

impl Derived {
    /// Notch-closing angle of the joint as drawn (°).
    pub fn closing_angle_deg(&self) -> f64 {
        self.design.joint.closing_angle_rad().to_degrees()
    }

    /// Two lines (ASCII, for program headers): the numbers as drawn, then the design's.
    pub fn summary(&self, design: &Design) -> [String; 2] {
        [
            format!(
                "as drawn: {} notch levels ({} notches), mean h = {:.4} mm, c = {:.4} mm, s_n = {:.4} mm, closing angle {:.1} deg",
                self.levels,
                self.notches,
                self.notch_width_mm,
                self.notch_spacing_mm,
                self.notch_arc_mm,
                self.closing_angle_deg()
            ),
            format!(
                "as designed: {} notch levels, h = {} mm, c = {} mm, s_n = {} mm, closing angle {:.1} deg",
                design.file.notch_count,
                design.file.notch_width_mm,
                design.file.notch_spacing_mm,
                design.file.notch_arc_mm,
                design.joint.closing_angle_rad().to_degrees()
            ),
        ]
    }
}

/// An imported drawing that passed every rule of the design it is to be cut with.
#[derive(Debug, Clone)]
pub struct CheckedDrawing {
    /// The drawn layout, with the design's kerf and trace width (a drawing carries neither).
    pub layout: Layout,
    /// Where the drawing came from, how it differs from the design's own layout, and the
    /// joint's numbers as drawn.
    pub provenance: Provenance,
    /// Warnings for the joint as drawn.
    pub warnings: Vec<Warning>,
}

/// Checks `imported`, read from `bytes` of the file `file_name`, against the design `checked`
/// ([`check_drawing`], with the design's clearance) and records its provenance.
///
/// # Errors
/// [`RulesError`] naming the design and listing every broken rule.
pub fn check_imported(
    checked: &Checked,
    imported: &ImportedDxf,
    file_name: &str,
    bytes: &[u8],
) -> Result<CheckedDrawing, RulesError> {
    let design = &checked.design;
    let clearance_mm = design.file.fabrication.clearance_mm();
    let provenance = Provenance::new(file_name, bytes, imported, &checked.layout);
    let mut layout = imported.layout.clone();
    layout.kerf_mm = checked.layout.kerf_mm;
    layout.trace_width_mm = checked.layout.trace_width_mm;
    let report = check_drawing(design, &layout, clearance_mm);
    if !report.errors.is_empty() {
        return Err(RulesError {
            name: design.file.name.clone(),
            violations: report.errors,
        });
    }
    let provenance = match &report.derived {
        Some(d) => provenance.with_derived(d.summary(design)),
        None => provenance,
    };
    Ok(CheckedDrawing {
        layout,
        provenance,
        warnings: report.warnings,
    })
}

/// Checks a drawn `layout` against `design`, with `clearance_mm` edge to edge.
pub fn check_drawing(design: &Design, layout: &Layout, clearance_mm: f64) -> DrawingReport {
    let mut errors = mismatches(design, layout);
    if !errors.is_empty() {
        return DrawingReport {
            errors,
            warnings: Vec::new(),
            derived: None,
        };
    }
    errors.extend(check_layout(layout, clearance_mm));
    let mut warnings = Vec::new();
    let derived = match derive(design, layout) {
        Ok(d) => {
            strain::check(&d.design, &mut warnings);
            Some(d)
        }
        Err(v) => {
            errors.push(v);
            None
        }
    };
    DrawingReport {
        errors,
        warnings,
        derived,
    }
}

fn mismatches(design: &Design, layout: &Layout) -> Vec<Violation> {
    let file = &design.file;
    let mut out = Vec::new();
    if layout.name != file.name {
        out.push(Violation::DrawingMismatch {
            quantity: "name",
            drawing: format!("{:?}", layout.name),
            design: format!("{:?}", file.name),
        });
    }
    if (layout.outer_radius_mm - file.outer_radius_mm).abs() > SAME_MM {
        out.push(Violation::DrawingMismatch {
            quantity: "outer radius r_o",
            drawing: format!("{} mm", layout.outer_radius_mm),
            design: format!("{} mm (outer_radius_mm)", file.outer_radius_mm),
        });
    }
    let style_name = |bsn: bool| {
        if bsn {
            "BSN (notches on both sides)"
        } else {
            "UAN (notches on one side)"
        }
    };
    let drawn_bsn = layout.notches.iter().any(|n| n.side == 1);
    let design_bsn = file.style.notches_per_level() == 2;
    if drawn_bsn != design_bsn {
        out.push(Violation::DrawingMismatch {
            quantity: "notch style",
            drawing: style_name(drawn_bsn).into(),
            design: style_name(design_bsn).into(),
        });
    }
    let drawn_sensors = layout.sensor_count();
    let design_sensors = file.style.sensor_count() as usize;
    if drawn_sensors != design_sensors {
        out.push(Violation::DrawingMismatch {
            quantity: "sensor count",
            drawing: drawn_sensors.to_string(),
            design: design_sensors.to_string(),
        });
    }
    out
}

/// `x` range and `s` extent of each notch, by level.
pub(crate) fn derive(design: &Design, layout: &Layout) -> Result<Derived, Violation> {
    let c_mm = layout.circumference_mm;
    let mut levels: Vec<(usize, f64, f64)> = Vec::new();
    let (mut widths, mut arcs) = (Vec::new(), Vec::new());
    for notch in &layout.notches {
        let boxes: Vec<_> = notch
            .outline
            .iter()
            .filter_map(|p| p.bounding_rect())
            .collect();
        let Some(first) = boxes.first() else {
            continue;
        };
        let x0 = boxes
            .iter()
            .map(|r| r.min().x)
            .fold(first.min().x, f64::min);
        let x1 = boxes
            .iter()
            .map(|r| r.max().x)
            .fold(first.max().x, f64::max);
        // Pieces split at the seam are disjoint in s: their extents add up.
        let arc: f64 = boxes.iter().map(|r| r.height()).sum::<f64>().min(c_mm);
        widths.push(x1 - x0);
        arcs.push(arc);
        match levels.iter_mut().find(|(l, _, _)| *l == notch.level) {
            Some((_, lo, hi)) => {
                *lo = lo.min(x0);
                *hi = hi.max(x1);
            }
            None => levels.push((notch.level, x0, x1)),
        }
    }
    if levels.is_empty() {
        return Err(Violation::Other(
            "the drawing has no notches on layer NOTCHES: the joint would not bend".into(),
        ));
    }
    levels.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let webs: Vec<f64> = levels.windows(2).map(|w| w[1].1 - w[0].2).collect();
    let n = levels.len();
    let h = mean(&widths);
    let c = if webs.is_empty() {
        design.file.notch_spacing_mm
    } else {
        mean(&webs)
    };
    let s_n = mean(&arcs);
    let mut file = design.file.clone();
    file.notch_count = u32::try_from(n).unwrap_or(u32::MAX);
    file.notch_width_mm = h;
    file.notch_spacing_mm = c;
    file.notch_arc_mm = s_n;
    file.joint_length_mm = n as f64 * h + (n as f64 - 1.0) * c;
    let drawn = Design::from_file(file).map_err(|e| match e {
        crate::design::DesignError::Geometry { reason, .. } => Violation::Geometry(reason),
        other => Violation::Other(other.to_string()),
    })?;
    Ok(Derived {
        levels: drawn.file.notch_count,
        notches: layout.notches.len(),
        notch_width_mm: h,
        notch_spacing_mm: c,
        notch_arc_mm: s_n,
        design: drawn,
    })
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    fn design(text: &str) -> Design {
        Design::from_toml(text).unwrap()
    }

    #[test]
    fn the_design_own_layout_derives_the_design_numbers() {
        for text in [
            include_str!("../../designs/joint-a.toml"),
            include_str!("../../designs/joint-c.toml"),
        ] {
            let d = design(text);
            let l = Layout::from_design(&d).unwrap();
            let r = check_drawing(&d, &l, d.file.fabrication.clearance_mm());
            assert!(r.errors.is_empty(), "{:?}", r.errors);
            let derived = r.derived.unwrap();
            assert_eq!(derived.levels, d.file.notch_count);
            assert_relative_eq!(
                derived.closing_angle_deg(),
                d.joint.closing_angle_rad().to_degrees(),
                max_relative = 1e-9
            );
            assert_relative_eq!(derived.notch_arc_mm, d.file.notch_arc_mm, epsilon = 1e-9);
            assert_eq!(r.warnings.len(), 2);
        }
    }

    #[test]
    fn joint_b_drawn_for_joint_c_is_refused_on_every_count() {
        let b = design(include_str!("../../designs/joint-b.toml"));
        let c = design(include_str!("../../designs/joint-c.toml"));
        let l = Layout::from_design(&b).unwrap();
        let r = check_drawing(&c, &l, 0.08);
        let m: Vec<String> = r.errors.iter().map(ToString::to_string).collect();
        assert!(
            m.iter().any(|m| m.starts_with(
                "the drawing's notch style is UAN (notches on one side) but the design's is BSN"
            )),
            "{m:?}"
        );
        assert!(
            m.iter()
                .any(|m| m.starts_with("the drawing's sensor count is 1 but the design's is 2")),
            "{m:?}"
        );
        assert!(r.derived.is_none());
    }

    #[test]
    fn fewer_notches_close_at_a_smaller_angle() {
        let d = design(include_str!("../../designs/joint-a.toml"));
        let mut l = Layout::from_design(&d).unwrap();
        l.notches.pop();
        let derived = check_drawing(&d, &l, 0.08).derived.unwrap();
        assert_eq!(derived.levels, 9);
        assert_relative_eq!(
            derived.closing_angle_deg(),
            0.9 * d.joint.closing_angle_rad().to_degrees(),
            max_relative = 1e-9
        );
    }
}
