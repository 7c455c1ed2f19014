//! Reading a DXF in `dlw`'s convention (see `dxf_convention`) back into a [`Layout`], as CAD
//! tools write it: a drawing `dlw` wrote, re-saved by AutoCAD, LibreCAD or ezdxf (R12 to
//! R2018), possibly without dlw's XDATA, with outlines redrawn as lines and arcs, and with a
//! title block or other content on layers of its own.
//!
//! Before reading: an empty file, a file that is not DXF and a truncated one each get their own
//! error (`sniff`). Units: `$INSUNITS` mm, µm or inches; a drawing without it (every R12 file)
//! needs [`ImportOptions::units`]. Everything is converted to mm.
//!
//! How each entity is read:
//! - `NOTCHES`: closed LWPOLYLINEs or POLYLINEs (the closed flag, or a last vertex on the
//!   first), straight segments only; LINEs, ARCs and open polylines are joined end to end into
//!   closed outlines, ends meeting within [`ImportOptions::join_tolerance_mm`] (`loops`). Pieces
//!   with the same `DLW` notch index form one notch; an untagged outline is a notch of its own,
//!   except that two untagged pieces with the same `x` range, one ending on the window's top
//!   edge and one starting on the seam, are the halves of one split notch. Level and side
//!   always come from the geometry, so an edited drawing describes itself: levels rank the
//!   notches' distal edges `x` (edges within 1 µm share a level), and the side is the notch
//!   centre nearer `s = π·r_o` (side 0) or `s = 0` (side 1).
//! - `SENSOR`: open LWPOLYLINEs, POLYLINEs or LINEs, U-trace pieces. Untagged LINEs here and
//!   on `LEADS_PADS` (an exploded polyline) are chained end to end first (`loops::chain_open`);
//!   a `LEADS_PADS` chain from a sensor end into a spiral is split into its lead and its pad.
//! - `LEADS_PADS`: tagged entities say whether they are a lead or a pad. An untagged one is a
//!   pad if it turns through at least a full turn (a spiral), else a lead.
//! - Which sensor a trace belongs to: its tag; untagged, sensor 1 (index 1) if the drawing has
//!   BSN notch pairs and the trace's mean `s` is nearer `π·r_o` than `0`, else sensor 0.
//! - `PARTING`: LWPOLYLINEs, POLYLINEs or LINEs; the joint length is the parting cut's largest
//!   `x`.
//! - `ANNOTATION`: anything; the title's XDATA gives the layout's numbers. Without it they come
//!   from [`ImportOptions::numbers`] (the design's own layout).
//! - `TUBE` (dlw's tube outline and seam, for people): skipped. Any other layer: skipped and
//!   counted ([`ImportedDxf::ignored`]).
//!
//! Tagged traces keep their list order and piece order; untagged ones follow in file order.

mod entity;
mod error;
mod loops;
mod notches;
mod sniff;
mod traces;
mod units;
mod xdata;

use std::collections::BTreeMap;

use dxf::entities::{Entity, EntityType};
use dxf::XDataItem;
use geo::{Coord, LineString, Polygon};

use crate::layout::Layout;

use super::dxf_convention::{
    Layer, TAG_LAYOUT, TAG_LEAD, TAG_NOTCH, TAG_PAD, TAG_PARTING, TAG_SENSOR,
};
use entity::{bad, Reader};
pub use error::DxfImportError;
use notches::{notches, NotchPiece};
use traces::{chain_trace_lines, group_traces, is_spiral, TracePiece};
pub use units::{DrawingUnits, UnitsSource};
pub use xdata::LayoutNumbers;
use xdata::{dlw_xdata, int_at, is_tag, read_numbers};

/// Ends of LINEs and ARCs closer than this join into one outline, unless told otherwise (mm):
/// 1 µm, a tenth of the finest trace width dlw writes, far above a CAD tool's rounding.
pub const DEFAULT_JOIN_TOLERANCE_MM: f64 = 1e-3;

/// Layers dlw writes for people that hold nothing to cut or write (the unrolled tube outline and
/// the seam): skipped without a warning.
pub const DLW_LAYERS_NOT_READ: [&str; 1] = ["TUBE"];

/// How to read a drawing that does not say everything itself.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportOptions {
    /// The drawing's unit when it has no `$INSUNITS` (R12); must agree with it when it has.
    pub units: Option<DrawingUnits>,
    /// The layout's numbers when the title's XDATA is gone (from the design).
    pub numbers: Option<LayoutNumbers>,
    /// Ends of lines and arcs within this join (mm); also the chord error of flattened arcs.
    pub join_tolerance_mm: f64,
}

impl Default for ImportOptions {
    fn default() -> Self {
        Self {
            units: None,
            numbers: None,
            join_tolerance_mm: DEFAULT_JOIN_TOLERANCE_MM,
        }
    }
}

/// What a DXF held.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportedDxf {
    /// The layout read (mm).
    pub layout: Layout,
    /// The clearance recorded by the writer, or the design's (mm).
    pub clearance_mm: f64,
    /// Entities per layer, as named in the file.
    pub layer_counts: BTreeMap<String, usize>,
    /// Feature entities without `DLW` XDATA, read from their geometry alone.
    pub untagged: usize,
    /// Entities on layers that are not dlw's, which were not read, per layer.
    pub ignored: BTreeMap<String, usize>,
    /// The unit the drawing was read in, and where it came from.
    pub units: (DrawingUnits, UnitsSource),
    /// The layout's numbers came from the title's XDATA (else from [`ImportOptions::numbers`]).
    pub numbers_from_xdata: bool,
    /// The file's AutoCAD version, e.g. `R12`.
    pub version: String,
    /// Notch outlines joined from separate LINEs, ARCs or open polylines.
    pub joined_outlines: usize,
}

impl ImportedDxf {
    /// One warning per layer whose entities were ignored, with their count.
    pub fn ignored_warnings(&self) -> Vec<String> {
        self.ignored
            .iter()
            .map(|(layer, n)| {
                format!(
                    "ignored {n} entit{} on layer {layer:?}, which is not a dlw layer (dlw reads NOTCHES, SENSOR, LEADS_PADS, PARTING and ANNOTATION)",
                    if *n == 1 { "y" } else { "ies" }
                )
            })
            .collect()
    }
}

/// Reads a DXF's bytes as a layout, with the default [`ImportOptions`] (the drawing must give
/// its units and carry dlw's layout numbers).
///
/// # Errors
/// See [`read_dxf`].
pub fn layout_from_dxf(bytes: &[u8]) -> Result<ImportedDxf, DxfImportError> {
    read_dxf(bytes, &ImportOptions::default())
}

/// Reads a DXF's bytes as a layout.
///
/// # Errors
/// [`DxfImportError`] for empty, foreign, truncated or unreadable files, missing or unknown
/// units, outlines that do not close, entity types the convention does not use on a feature
/// layer, or missing layout numbers.
pub fn read_dxf(bytes: &[u8], options: &ImportOptions) -> Result<ImportedDxf, DxfImportError> {
    let drawing = load(bytes)?;
    let has_insunits = sniff::has_header_variable(bytes, "$INSUNITS");
    let units = units::resolve(
        drawing.header.default_drawing_units,
        has_insunits,
        options.units,
    )?;
    let reader = Reader {
        k: units.0.mm_per_unit(),
        tol: options.join_tolerance_mm,
    };
    let mut found = Classified::default();
    for entity in drawing.entities() {
        found.classify(entity, &reader)?;
    }
    let numbers_from_xdata = found.numbers.is_some();
    let numbers = found
        .numbers
        .take()
        .or_else(|| options.numbers.clone())
        .ok_or_else(|| DxfImportError::Metadata("none found".into()))?;
    let layer_counts = std::mem::take(&mut found.layer_counts);
    let ignored = std::mem::take(&mut found.ignored);
    let assembled = found.assemble(&numbers, reader.tol)?;
    Ok(ImportedDxf {
        layout: assembled.layout,
        clearance_mm: numbers.clearance_mm,
        layer_counts,
        untagged: assembled.untagged,
        ignored,
        units,
        numbers_from_xdata,
        version: format!("{:?}", drawing.header.version),
        joined_outlines: assembled.joined_outlines,
    })
}

/// The drawing in `bytes`, after [`sniff::sniff`] has told an empty, foreign or truncated file
/// apart from a DXF.
fn load(bytes: &[u8]) -> Result<dxf::Drawing, DxfImportError> {
    sniff::sniff(bytes)?;
    // The `dxf` crate (0.6) panics on some malformed values (a header date out of range, found
    // by fuzzing): a panic there is a file it cannot read, not a crash of `dlw`.
    let loaded = std::panic::catch_unwind(|| dxf::Drawing::load(&mut std::io::Cursor::new(bytes)))
        .map_err(|_| {
            DxfImportError::Parse(
                "the DXF reader gave up on a malformed value (for example a header date out of range)"
                    .to_owned(),
            )
        })?;
    loaded.map_err(|e| DxfImportError::Parse(e.to_string()))
}

/// The entities of a drawing sorted by what they are, in file order, before anything is joined.
#[derive(Default)]
struct Classified {
    /// Entities per layer, as named in the file.
    layer_counts: BTreeMap<String, usize>,
    /// Entities on layers that are not dlw's, per layer.
    ignored: BTreeMap<String, usize>,
    /// The layout's numbers from the title's XDATA.
    numbers: Option<LayoutNumbers>,
    /// Closed notch outlines, with their tag's (notch, piece) if they had one.
    notch_pieces: Vec<NotchPiece>,
    /// Open pieces on `NOTCHES` (LINEs, ARCs, open polylines), to be joined into outlines.
    loose: Vec<Vec<Coord>>,
    /// Trace pieces read whole (tagged, or polylines).
    traces: Vec<TracePiece>,
    /// Parting-cut pieces, with their tag's piece index if they had one.
    parting: Vec<(Option<i16>, LineString<f64>)>,
    /// Untagged LINEs on `SENSOR`, to be chained.
    sensor_lines: Vec<Vec<Coord>>,
    /// Untagged LINEs on `LEADS_PADS`, to be chained.
    lead_pad_lines: Vec<Vec<Coord>>,
}

/// The layout assembled from a drawing's entities, and what the report counts.
struct Assembled {
    layout: Layout,
    /// Feature entities without `DLW` XDATA.
    untagged: usize,
    /// Notch outlines joined from separate pieces.
    joined_outlines: usize,
}

impl Classified {
    /// Counts `entity` on its layer and files it by what that layer holds.
    fn classify(&mut self, entity: &Entity, reader: &Reader) -> Result<(), DxfImportError> {
        let layer_name = entity.common.layer.clone();
        *self.layer_counts.entry(layer_name.clone()).or_insert(0) += 1;
        if DLW_LAYERS_NOT_READ
            .iter()
            .any(|l| l.eq_ignore_ascii_case(&layer_name))
        {
            return Ok(());
        }
        let Some(layer) = Layer::from_name(&layer_name) else {
            *self.ignored.entry(layer_name).or_insert(0) += 1;
            return Ok(());
        };
        let tag = dlw_xdata(entity);
        match layer {
            Layer::Annotation => {
                if let Some(items) = tag.filter(|i| is_tag(i, TAG_LAYOUT)) {
                    self.numbers = Some(read_numbers(items)?);
                }
                Ok(())
            }
            Layer::Notches => self.notch(entity, tag, reader),
            Layer::Sensor | Layer::LeadsPads => self.trace(entity, layer, tag, reader),
            Layer::Parting => self.parting(entity, tag, reader),
        }
    }

    /// A `NOTCHES` entity: a closed outline, or a loose piece of one.
    fn notch(
        &mut self,
        entity: &Entity,
        tag: Option<&[XDataItem]>,
        reader: &Reader,
    ) -> Result<(), DxfImportError> {
        let layer = Layer::Notches;
        let expected = "a closed LWPOLYLINE or POLYLINE, or LINEs and ARCs that close";
        let (mut points, closed) = reader.points(entity, layer, expected, true)?;
        let closed = closed || (points.len() > 3 && points.first() == points.last());
        if !closed {
            self.loose.push(points);
            return Ok(());
        }
        if points.len() > 1 && points.first() == points.last() {
            points.pop();
        }
        if points.len() < 3 {
            return Err(bad(
                entity,
                layer,
                format!("a notch needs at least 3 corners, found {}", points.len()),
            ));
        }
        let id = tag
            .filter(|i| is_tag(i, TAG_NOTCH))
            .and_then(|i| Some((int_at(i, 1)?, int_at(i, 2)?)));
        self.notch_pieces
            .push((id, Polygon::new(LineString::new(points), vec![])));
        Ok(())
    }

    /// A `SENSOR` or `LEADS_PADS` entity: a trace piece, or an untagged LINE to be chained.
    fn trace(
        &mut self,
        entity: &Entity,
        layer: Layer,
        tag: Option<&[XDataItem]>,
        reader: &Reader,
    ) -> Result<(), DxfImportError> {
        let expected = "an open LWPOLYLINE or POLYLINE, or a LINE";
        let (points, closed) = reader.points(entity, layer, expected, false)?;
        if closed {
            return Err(bad(
                entity,
                layer,
                "a trace must be open (the closed flag is set)".into(),
            ));
        }
        if points.len() < 2 {
            return Err(bad(
                entity,
                layer,
                format!("a trace needs at least 2 vertices, found {}", points.len()),
            ));
        }
        let tagged = tag.and_then(|i| {
            let kind = match (layer, i.first()) {
                (Layer::Sensor, Some(XDataItem::Str(s))) if s == TAG_SENSOR => TAG_SENSOR,
                (Layer::LeadsPads, Some(XDataItem::Str(s))) if s == TAG_LEAD => TAG_LEAD,
                (Layer::LeadsPads, Some(XDataItem::Str(s))) if s == TAG_PAD => TAG_PAD,
                _ => return None,
            };
            Some((kind, (int_at(i, 1)?, int_at(i, 2)?, int_at(i, 3)?)))
        });
        // Untagged LINEs (a polyline exploded in CAD) are chained before they are
        // classified: one LINE of a spiral is no spiral.
        if tagged.is_none() && matches!(entity.specific, EntityType::Line(_)) {
            let list = if layer == Layer::Sensor {
                &mut self.sensor_lines
            } else {
                &mut self.lead_pad_lines
            };
            list.push(points);
            return Ok(());
        }
        let line = LineString::new(points);
        self.traces.push(match tagged {
            Some((kind, ids)) => TracePiece {
                kind,
                tag: Some(ids),
                line,
            },
            None => TracePiece {
                kind: match layer {
                    Layer::Sensor => TAG_SENSOR,
                    _ if is_spiral(&line.0) => TAG_PAD,
                    _ => TAG_LEAD,
                },
                tag: None,
                line,
            },
        });
        Ok(())
    }

    /// A `PARTING` entity: a piece of the parting cut.
    fn parting(
        &mut self,
        entity: &Entity,
        tag: Option<&[XDataItem]>,
        reader: &Reader,
    ) -> Result<(), DxfImportError> {
        let expected = "an LWPOLYLINE, a POLYLINE or a LINE";
        let (points, _) = reader.points(entity, Layer::Parting, expected, false)?;
        let piece = tag
            .filter(|i| is_tag(i, TAG_PARTING))
            .and_then(|i| int_at(i, 1));
        self.parting.push((piece, LineString::new(points)));
        Ok(())
    }

    /// Joins the loose notch pieces and the untagged trace LINEs, then builds the layout:
    /// notches ranked from their geometry, traces grouped per sensor, the parting cut in piece
    /// order giving the joint's length.
    fn assemble(mut self, numbers: &LayoutNumbers, tol: f64) -> Result<Assembled, DxfImportError> {
        let joined = loops::join_loops(self.loose, Layer::Notches.name(), tol)?;
        let joined_outlines = joined.len();
        self.notch_pieces.extend(
            joined
                .into_iter()
                .map(|ring| (None, Polygon::new(LineString::new(ring), vec![]))),
        );
        chain_trace_lines(
            &mut self.traces,
            self.sensor_lines,
            self.lead_pad_lines,
            numbers,
            tol,
        );
        let untagged = self
            .notch_pieces
            .iter()
            .filter(|(t, _)| t.is_none())
            .count()
            + self.traces.iter().filter(|t| t.tag.is_none()).count()
            + self.parting.iter().filter(|(t, _)| t.is_none()).count();
        let notches = notches(self.notch_pieces, numbers);
        let bsn = notches.iter().any(|n| n.side == 1);
        let parting = in_piece_order(self.parting);
        let length_mm = parting
            .iter()
            .flat_map(|l| l.0.iter().map(|c| c.x))
            .reduce(f64::max)
            .unwrap_or(numbers.length_mm);
        let group = |kind: &str| group_traces(&self.traces, kind, bsn, numbers.outer_radius_mm);
        let layout = Layout {
            name: numbers.name.clone(),
            outer_radius_mm: numbers.outer_radius_mm,
            circumference_mm: numbers.circumference_mm,
            seam_s_mm: numbers.seam_s_mm,
            trace_width_mm: numbers.trace_width_mm,
            kerf_mm: numbers.kerf_mm,
            length_mm,
            notches,
            sensors: group(TAG_SENSOR),
            leads: group(TAG_LEAD),
            pads: group(TAG_PAD),
            parting,
        };
        Ok(Assembled {
            layout,
            untagged,
            joined_outlines,
        })
    }
}

/// The parting cut's pieces in their tags' order, untagged ones after in file order.
fn in_piece_order(mut parting: Vec<(Option<i16>, LineString<f64>)>) -> Vec<LineString<f64>> {
    parting.sort_by_key(|(piece, _)| piece.unwrap_or(i16::MAX));
    parting.into_iter().map(|(_, l)| l).collect()
}
