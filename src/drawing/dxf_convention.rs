//! The DXF convention `dlw` writes and reads.
//!
//! | layer | ACI colour | holds |
//! |---|---|---|
//! | `NOTCHES` | 30 (orange) | one closed LWPOLYLINE per notch piece |
//! | `SENSOR` | 5 (blue) | one open LWPOLYLINE per U-trace piece (arms and bridge) |
//! | `LEADS_PADS` | 3 (green) | one open LWPOLYLINE per lead piece and per square-spiral pad piece |
//! | `PARTING` | 1 (red) | the parting cut |
//! | `ANNOTATION` | 7 (white/black) | title, frame note, scale note, the note on notches split at the seam; the layout's numbers |
//! | `TUBE` | 8 (grey) | reference only, never cut: the tube's outline (one circumference, unrolled, from the distal end to the parting line), the seam at both window edges and its labels |
//!
//! Units are millimetres (`$INSUNITS = 4`), `X = x` and `Y = s`; the file is AutoCAD R2000
//! (`AC1015`), the oldest version with LWPOLYLINE and layer colours, read by every current tool.
//!
//! Each feature entity carries XDATA of the registered application [`APP_ID`], so that a file a
//! designer edited still says what each polyline is:
//!
//! - notch: `1000 "notch"`, `1070` index in the layout's notch list, `1070` piece;
//! - sensor, lead, pad: `1000 "sensor" | "lead" | "pad"`, `1070` index in its list,
//!   `1070` sensor (0 or 1), `1070` piece;
//! - parting: `1000 "parting"`, `1070` piece.
//!
//! The title TEXT on `ANNOTATION` carries the layout's numbers: `1000 "layout"`, `1000` name,
//! then `1040` reals in this order: outer radius, circumference, seam, trace width, kerf,
//! length, clearance (mm). A drawing without them cannot be read back (the radius and trace
//! width are not in the geometry).
//!
//! An entity without `DLW` XDATA (drawn by hand) is read by its geometry: see
//! `dxf_import`.

/// Registered application name of `dlw`'s XDATA.
pub const APP_ID: &str = "DLW";

/// The reference layer: the tube's outline and the seam. Not a [`Layer`] of features: nothing
/// on it is cut, and a reader of `dlw` drawings ignores it ([`Layer::from_name`] reads it as
/// [`Layer::Annotation`]).
pub const TUBE_LAYER: &str = "TUBE";

/// ACI colour of [`TUBE_LAYER`]: 8, dark grey, behind the features.
pub const TUBE_ACI: u8 = 8;

/// A layer of the convention.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layer {
    /// Notch outlines.
    Notches,
    /// Sensor U-traces.
    Sensor,
    /// Leads and pads.
    LeadsPads,
    /// The parting cut.
    Parting,
    /// Text and metadata.
    Annotation,
}

impl Layer {
    /// Every layer, in drawing order.
    pub const ALL: [Layer; 5] = [
        Layer::Notches,
        Layer::Sensor,
        Layer::LeadsPads,
        Layer::Parting,
        Layer::Annotation,
    ];

    /// The layer's name in the DXF.
    pub fn name(self) -> &'static str {
        match self {
            Layer::Notches => "NOTCHES",
            Layer::Sensor => "SENSOR",
            Layer::LeadsPads => "LEADS_PADS",
            Layer::Parting => "PARTING",
            Layer::Annotation => "ANNOTATION",
        }
    }

    /// AutoCAD Color Index: the paper's Fig. 1 colours for notches (orange), sensor (blue) and
    /// leads and pads (green).
    pub fn aci(self) -> u8 {
        match self {
            Layer::Notches => 30,
            Layer::Sensor => 5,
            Layer::LeadsPads => 3,
            Layer::Parting => 1,
            Layer::Annotation => 7,
        }
    }

    /// The layer called `name`, if it is one of the convention's (case-insensitive, as in
    /// AutoCAD). The reference layer [`TUBE_LAYER`] reads as [`Layer::Annotation`]: its
    /// entities are drawn for people and never describe a feature.
    pub fn from_name(name: &str) -> Option<Layer> {
        if name.eq_ignore_ascii_case(TUBE_LAYER) {
            return Some(Layer::Annotation);
        }
        Layer::ALL
            .into_iter()
            .find(|l| l.name().eq_ignore_ascii_case(name))
    }
}

/// XDATA tag of a notch.
pub(crate) const TAG_NOTCH: &str = "notch";
/// XDATA tag of a sensor U-trace.
pub(crate) const TAG_SENSOR: &str = "sensor";
/// XDATA tag of a lead.
pub(crate) const TAG_LEAD: &str = "lead";
/// XDATA tag of a pad.
pub(crate) const TAG_PAD: &str = "pad";
/// XDATA tag of the parting line.
pub(crate) const TAG_PARTING: &str = "parting";
/// XDATA tag of the layout's numbers.
pub(crate) const TAG_LAYOUT: &str = "layout";
