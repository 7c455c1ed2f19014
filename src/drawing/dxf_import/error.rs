/// Why a DXF could not be read as a layout.
#[derive(Debug, thiserror::Error)]
pub enum DxfImportError {
    /// The file has no bytes at all.
    #[error("the file is empty (0 bytes): expected a DXF drawing")]
    Empty,
    /// The bytes do not start like a DXF (group code 0, then SECTION).
    #[error("not a DXF file: a DXF starts with the group code 0 and SECTION, this file starts with {start:?}")]
    NotDxf {
        /// The first characters, as text.
        start: String,
    },
    /// The file stops before the `0 EOF` that ends every DXF.
    #[error("the DXF is truncated: it ends after {bytes} bytes (line {line}, in {section}) without the closing 0/EOF; save or copy the file again")]
    Truncated {
        /// File size.
        bytes: usize,
        /// Number of the last line.
        line: usize,
        /// The section the file stops in (e.g. `the ENTITIES section`).
        section: String,
    },
    /// The bytes look like a DXF but the reader failed on them.
    #[error("not a readable DXF: {0}")]
    Parse(String),
    /// The drawing is not in a unit dlw reads.
    #[error("drawing units are $INSUNITS = {insunits} ({name}); dlw reads drawings in mm ($INSUNITS = 4), µm (13) or inches (1)")]
    Units {
        /// `$INSUNITS` as found.
        insunits: i16,
        /// Its meaning.
        name: String,
    },
    /// The drawing does not say its units and none were given.
    #[error("the drawing does not say its units ($INSUNITS is {found}; R12 files cannot store it): give them with --units mm|um|in")]
    NoUnits {
        /// What was found: `missing` or `0 (unitless)`.
        found: String,
    },
    /// The units given disagree with the drawing's own.
    #[error("--units {given} contradicts the drawing's $INSUNITS = {insunits} ({name}); leave --units out or correct the drawing")]
    UnitsConflict {
        /// The units given.
        given: String,
        /// `$INSUNITS` as found.
        insunits: i16,
        /// Its meaning.
        name: String,
    },
    /// Lines and arcs on a feature layer do not join into closed loops.
    #[error("{layer} outline does not close: its end at x = {x_mm:.4} mm, s = {s_mm:.4} mm {gap} (ends within {tolerance_mm} mm are joined)")]
    OpenLoop {
        /// The layer.
        layer: &'static str,
        /// The loose end, x (mm).
        x_mm: f64,
        /// The loose end, s (mm).
        s_mm: f64,
        /// How far the nearest other end is, as words.
        gap: String,
        /// The join tolerance (mm).
        tolerance_mm: f64,
    },
    /// A feature layer holds an entity type the convention does not use there.
    #[error("{entity} {handle} on layer {layer}: expected {expected}")]
    WrongEntity {
        /// Entity type.
        entity: String,
        /// Entity handle.
        handle: String,
        /// The layer.
        layer: &'static str,
        /// What the layer holds.
        expected: &'static str,
    },
    /// A polyline has arc segments, or is mirrored, or has too few vertices.
    #[error("{entity} {handle} on layer {layer}: {problem}")]
    BadPolyline {
        /// Entity type.
        entity: String,
        /// Entity handle.
        handle: String,
        /// The layer.
        layer: &'static str,
        /// What is wrong, with the value.
        problem: String,
    },
    /// The title's numbers are missing or unreadable, and no design gives them.
    #[error("no dlw layout numbers: {0} (the title TEXT on layer ANNOTATION carries them as DLW XDATA; a drawing that lost them, e.g. rebuilt by ezdxf's Importer, can be read with --design DESIGN, which gives the outer radius, seam and trace width)")]
    Metadata(String),
}
