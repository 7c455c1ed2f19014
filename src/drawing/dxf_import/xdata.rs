//! dlw's XDATA: the tags on feature entities and the layout's numbers on the title.

use dxf::entities::Entity;
use dxf::{XData, XDataItem};

use super::super::dxf_convention::APP_ID;
use super::DxfImportError;
use crate::layout::Layout;

/// The numbers of a layout that its geometry does not carry: the title's XDATA, or, for a
/// drawing that lost it, the design's own layout.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutNumbers {
    /// The design's name.
    pub name: String,
    /// Outer radius `r_o` (mm).
    pub outer_radius_mm: f64,
    /// Circumference `2π·r_o` (mm).
    pub circumference_mm: f64,
    /// Lower edge of the drawing's `s` window (mm).
    pub seam_s_mm: f64,
    /// Width of a written line (mm).
    pub trace_width_mm: f64,
    /// Kerf (mm).
    pub kerf_mm: f64,
    /// Joint length (mm), used when the drawing has no parting cut.
    pub length_mm: f64,
    /// Clearance the layout keeps (mm).
    pub clearance_mm: f64,
}

impl LayoutNumbers {
    /// The numbers of `layout`, checked with `clearance_mm`.
    pub fn of(layout: &Layout, clearance_mm: f64) -> Self {
        Self {
            name: layout.name.clone(),
            outer_radius_mm: layout.outer_radius_mm,
            circumference_mm: layout.circumference_mm,
            seam_s_mm: layout.seam_s_mm,
            trace_width_mm: layout.trace_width_mm,
            kerf_mm: layout.kerf_mm,
            length_mm: layout.length_mm,
            clearance_mm,
        }
    }
}

/// The `DLW` XDATA items of an entity, if any.
pub(super) fn dlw_xdata(entity: &Entity) -> Option<&[XDataItem]> {
    entity
        .common
        .x_data
        .iter()
        .find(|x: &&XData| x.application_name.eq_ignore_ascii_case(APP_ID))
        .map(|x| x.items.as_slice())
}

pub(super) fn is_tag(items: &[XDataItem], tag: &str) -> bool {
    matches!(items.first(), Some(XDataItem::Str(s)) if s == tag)
}

pub(super) fn int_at(items: &[XDataItem], at: usize) -> Option<i16> {
    match items.get(at) {
        Some(XDataItem::Integer(i)) => Some(*i),
        _ => None,
    }
}

/// The title's numbers (always mm: dlw writes them, whatever the drawing's unit).
pub(super) fn read_numbers(items: &[XDataItem]) -> Result<LayoutNumbers, DxfImportError> {
    let name = match items.get(1) {
        Some(XDataItem::Str(s)) => s.clone(),
        _ => {
            return Err(DxfImportError::Metadata(
                "the title's XDATA has no name".into(),
            ))
        }
    };
    let reals: Vec<f64> = items
        .get(2..)
        .unwrap_or_default()
        .iter()
        .filter_map(|i| match i {
            XDataItem::Real(r) | XDataItem::Distance(r) => Some(*r),
            _ => None,
        })
        .collect();
    let [ro, c, seam, w, kerf, length, clearance] = reals[..] else {
        return Err(DxfImportError::Metadata(format!(
            "the title's XDATA has {} numbers, expected 7",
            reals.len()
        )));
    };
    for (what, v) in [
        ("outer radius", ro),
        ("circumference", c),
        ("trace width", w),
        ("kerf", kerf),
        ("clearance", clearance),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(DxfImportError::Metadata(format!(
                "{what} = {v} must be greater than 0"
            )));
        }
    }
    for (what, v) in [("seam", seam), ("length", length)] {
        if !v.is_finite() {
            return Err(DxfImportError::Metadata(format!(
                "{what} = {v} must be a finite number"
            )));
        }
    }
    Ok(LayoutNumbers {
        name,
        outer_radius_mm: ro,
        circumference_mm: c,
        seam_s_mm: seam,
        trace_width_mm: w,
        kerf_mm: kerf,
        length_mm: length,
        clearance_mm: clearance,
    })
}
