//! Drawings of a joint: DXF for designers (written and read back) and SVG for people.
//!
//! Every drawing of the layout uses its frame (`docs/frames.md`): `x` along the tube from the
//! distal end, `s` arc length on the outer surface, both in mm. In a DXF, `X = x` and `Y = s`.

mod dxf_convention;
mod dxf_export;
mod dxf_import;
mod provenance;

/// SVG drawings for people: the unrolled layout and the cross-section through a notch.
pub mod svg;

/// Layer names, colours and the XDATA that tags each entity (the DXF convention).
pub use dxf_convention::{Layer, APP_ID};
/// Writing a layout as an AutoCAD DXF.
pub use dxf_export::{layout_to_dxf, layout_to_dxf_with, DxfExportError, DxfNotes};
/// Reading a DXF in that convention back into a layout.
pub use dxf_import::{
    layout_from_dxf, read_dxf, DrawingUnits, DxfImportError, ImportOptions, ImportedDxf,
    LayoutNumbers, UnitsSource, DEFAULT_JOIN_TOLERANCE_MM, DLW_LAYERS_NOT_READ,
};
/// Where a program's layout came from when it was read from a drawing.
pub use provenance::{sha256_hex, Provenance};
