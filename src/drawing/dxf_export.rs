//! Writing a layout as an AutoCAD DXF for designers.
//!
//! Frame: DXF `X = x` (along the tube from the distal end) and `Y = s` (arc length on the outer
//! surface, in the window `[seam, seam + 2π·r_o]`), both in mm, `$INSUNITS = 4`. Layers, colours
//! and the XDATA on every entity follow `dxf_convention`.
//!
//! Besides the features, the `TUBE` layer shows the tube itself: its outline, one circumference
//! unrolled from the distal end to the parting line, and the seam (both window edges are the
//! same line on the tube), labelled. When notches cross the seam, a note on `ANNOTATION` says
//! that the pieces along the two edges are one notch each, so a UAN joint split there does not
//! read as two rows of notches.

use dxf::entities::{Entity, EntityType, Line, LwPolyline, Text};
use dxf::enums::{AcadVersion, DrawingUnits, Units};
use dxf::tables::{AppId, Layer as DxfLayer};
use dxf::{Color, LwPolylineVertex, Point, XData, XDataItem};
use geo::Coord;

use crate::layout::Layout;

use super::dxf_convention::{
    Layer, APP_ID, TAG_LAYOUT, TAG_LEAD, TAG_NOTCH, TAG_PAD, TAG_PARTING, TAG_SENSOR, TUBE_ACI,
    TUBE_LAYER,
};

/// Why a DXF could not be written.
#[derive(Debug, thiserror::Error)]
pub enum DxfExportError {
    /// The `dxf` crate refused the drawing.
    #[error("cannot encode the DXF drawing: {0}")]
    Encode(String),
    /// `SOURCE_DATE_EPOCH` is set but is not a time the drawing can carry.
    #[error(
        "SOURCE_DATE_EPOCH = {value:?} is not whole seconds since 1970 from 0 to 253402300799 \
         (the drawing's dates come from it when it is set)"
    )]
    SourceDateEpoch {
        /// The variable's value.
        value: String,
    },
    /// A list is too long for DXF's 16-bit integers.
    #[error("{what} count {count} is more than a DXF drawing can number (limit 32767)")]
    TooMany {
        /// What was counted.
        what: &'static str,
        /// How many.
        count: usize,
    },
}

/// Text height of the annotation (mm).
const TEXT_MM: f64 = 0.25;

/// How far the seam lines run past both ends of the tube's outline (mm).
const SEAM_OVERRUN_MM: f64 = 4.0 * TEXT_MM;

/// What a drawing adds to its layout's features: the title's wording and labels above the tube
/// (a robot names its joints; `crate::robot`). The default is a joint's drawing.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DxfNotes {
    /// What the title calls the drawing after the name: `unrolled joint` when `None`.
    pub title: Option<String>,
    /// Texts on `ANNOTATION` above the tube's top edge, each at its `x` (mm).
    pub labels: Vec<(f64, String)>,
}

/// The layout as the bytes of an R2000 DXF, with `clearance_mm` recorded in the metadata so
/// that `dlw import-dxf` checks the same clearance.
///
/// # Errors
/// [`DxfExportError`] if the drawing cannot be encoded.
pub fn layout_to_dxf(layout: &Layout, clearance_mm: f64) -> Result<Vec<u8>, DxfExportError> {
    layout_to_dxf_with(layout, clearance_mm, &DxfNotes::default())
}

/// [`layout_to_dxf`] with a title and labels of its own.
///
/// # Errors
/// [`DxfExportError`] if the drawing cannot be encoded.
pub fn layout_to_dxf_with(
    layout: &Layout,
    clearance_mm: f64,
    notes: &DxfNotes,
) -> Result<Vec<u8>, DxfExportError> {
    let mut drawing = dxf::Drawing::new();
    drawing.header.version = AcadVersion::R2000;
    drawing.header.default_drawing_units = Units::Millimeters;
    drawing.header.drawing_units = DrawingUnits::Metric;
    let reproducible = source_date_epoch()?;
    if let Some(when) = reproducible {
        drawing.header.creation_date = when.into();
        drawing.header.creation_date_universal = when;
        drawing.header.update_date = when.into();
        drawing.header.update_date_universal = when;
        drawing.header.fingerprint_guid = uuid::Uuid::nil();
        drawing.header.version_guid = uuid::Uuid::nil();
    }
    drawing.add_app_id(AppId {
        name: APP_ID.to_string(),
        ..Default::default()
    });
    for layer in Layer::ALL {
        drawing.add_layer(DxfLayer {
            name: layer.name().to_string(),
            color: Color::from_index(layer.aci()),
            ..Default::default()
        });
    }
    drawing.add_layer(DxfLayer {
        name: TUBE_LAYER.to_string(),
        color: Color::from_index(TUBE_ACI),
        ..Default::default()
    });
    for entity in entities(layout, clearance_mm, notes)? {
        drawing.add_entity(entity);
    }
    if let Some(ext) = layout.extents() {
        // The seam lines overrun both ends; their labels run on beyond the far end (text
        // about 0.6 of its height per character).
        let overrun = SEAM_OVERRUN_MM;
        let label = TEXT_MM * (1.0 + 0.6 * 80.0);
        // The split note starts at x = 0 and may run past the seam labels.
        let note = split_note(layout).map_or(0.0, |n| TEXT_MM * 0.6 * n.chars().count() as f64);
        drawing.header.minimum_drawing_extents = Point::new(
            (0.0_f64.min(ext.min().x)) - overrun,
            scale_bar_s_mm(layout) - TEXT_MM,
            0.0,
        );
        let above = if notes.labels.is_empty() {
            0.0
        } else {
            2.0 * TEXT_MM
        };
        drawing.header.maximum_drawing_extents = Point::new(
            (ext.max().x.max(layout.length_mm) + overrun + label).max(note),
            ext.max().y.max(layout.seam_s_mm + layout.circumference_mm) + above,
            0.0,
        );
    }
    let mut text = save(&drawing)?;
    if reproducible.is_some() {
        // The GUIDs, random by default, become a digest of the drawing itself.
        let guid = content_guid(&text);
        drawing.header.fingerprint_guid = guid;
        drawing.header.version_guid = guid;
        text = save(&drawing)?;
    }
    Ok(add_table_handles(&text).into_bytes())
}

/// The drawing's DXF text as the `dxf` crate writes it.
fn save(drawing: &dxf::Drawing) -> Result<String, DxfExportError> {
    let mut bytes = Vec::new();
    drawing
        .save(&mut bytes)
        .map_err(|e| DxfExportError::Encode(e.to_string()))?;
    String::from_utf8(bytes).map_err(|e| DxfExportError::Encode(e.to_string()))
}

/// A version-4-shaped GUID made of the first 16 bytes of the text's SHA-256: the same drawing
/// gets the same GUID, another drawing almost surely another.
fn content_guid(text: &str) -> uuid::Uuid {
    use sha2::{Digest, Sha256};
    let digest = Sha256::digest(text.as_bytes());
    let mut bytes = [0u8; 16];
    bytes.copy_from_slice(&digest[..16]);
    uuid::Builder::from_random_bytes(bytes).into_uuid()
}

/// The instant `SOURCE_DATE_EPOCH` names, when it is set.
///
/// The drawing's creation and update dates (`$TDCREATE`, `$TDUPDATE` and their universal
/// twins) are the time it was written and its GUIDs (`$FINGERPRINTGUID`, `$VERSIONGUID`) are
/// random, unless `SOURCE_DATE_EPOCH` (the reproducible-builds convention) is set: then the
/// dates are that instant and the GUIDs a digest of the drawing, so that the same design gives
/// the same bytes. The local dates are that instant in the machine's time zone, as the `dxf`
/// crate writes them.
fn source_date_epoch() -> Result<Option<chrono::DateTime<chrono::Utc>>, DxfExportError> {
    let Some(raw) = std::env::var_os("SOURCE_DATE_EPOCH") else {
        return Ok(None);
    };
    let value = raw.to_string_lossy().into_owned();
    value
        .parse::<i64>()
        .ok()
        .filter(|s| (0..=253_402_300_799).contains(s))
        .and_then(|s| chrono::DateTime::from_timestamp(s, 0))
        .map(Some)
        .ok_or(DxfExportError::SourceDateEpoch { value })
}

/// Gives every `TABLE` head a handle (group code 5) and moves `$HANDSEED` past them.
///
/// The `dxf` crate (0.6) writes table heads without handles; AutoCAD's R2000 format has them,
/// and `ezdxf`'s audit "fixes" their absence. Handles are numbered from `$HANDSEED`, which is
/// above every handle the crate gave out.
fn add_table_handles(text: &str) -> String {
    let lines: Vec<&str> = text.split("\r\n").collect();
    let code = |i: usize| lines.get(i).map(|c| c.trim());
    let mut seed = None;
    let mut i = 0;
    while i + 3 < lines.len() {
        if code(i) == Some("9") && lines[i + 1] == "$HANDSEED" && code(i + 2) == Some("5") {
            seed = u64::from_str_radix(lines[i + 3].trim(), 16)
                .ok()
                .map(|s| (i + 3, s));
            break;
        }
        i += 2;
    }
    let Some((seed_line, mut next)) = seed else {
        return text.to_string();
    };
    let mut out: Vec<String> = Vec::with_capacity(lines.len() + 32);
    let mut i = 0;
    while i < lines.len() {
        out.push(lines[i].to_string());
        let is_table_head =
            i % 2 == 0 && code(i) == Some("0") && lines.get(i + 1) == Some(&"TABLE");
        if is_table_head && code(i + 2) == Some("2") {
            out.push(lines[i + 1].to_string());
            out.push(lines[i + 2].to_string());
            out.push(lines[i + 3].to_string());
            out.push("  5".to_string());
            out.push(format!("{next:X}"));
            next += 1;
            i += 4;
            continue;
        }
        i += 1;
    }
    // $HANDSEED comes before the tables, so its line number is unchanged.
    out[seed_line] = format!("{next:X}");
    out.join("\r\n")
}

/// Where the 1 mm scale bar sits (`s`, mm): under the lines of text below the window (three,
/// and the note on split notches when there is one).
fn scale_bar_s_mm(layout: &Layout) -> f64 {
    let lines = 3.0 + f64::from(u8::from(split_note(layout).is_some()));
    layout.seam_s_mm - 3.0 * TEXT_MM - lines * 1.6 * TEXT_MM - TEXT_MM
}

/// The note for notches the seam splits, naming them (1-based levels and sides, as people
/// count); `None` when the seam splits none.
pub(crate) fn split_note(layout: &Layout) -> Option<String> {
    let split: Vec<&crate::layout::Notch> = layout
        .notches
        .iter()
        .filter(|n| n.outline.len() > 1)
        .collect();
    if split.is_empty() {
        return None;
    }
    let two_sides = layout.notches.iter().any(|n| n.side == 1);
    let names: Vec<String> = split
        .iter()
        .map(|n| {
            let joint = n
                .joint
                .map_or_else(String::new, |j| format!(" of joint {}", j + 1));
            if two_sides {
                format!("{} (side {}{joint})", n.level + 1, n.side)
            } else if n.joint.is_some() {
                format!("{} ({})", n.level + 1, joint.trim_start())
            } else {
                (n.level + 1).to_string()
            }
        })
        .collect();
    let list = if names.len() == layout.notches.len() {
        format!("all {} notches", names.len())
    } else {
        format!(
            "notch{} {}",
            if names.len() == 1 { "" } else { "es" },
            names.join(", ")
        )
    };
    Some(format!(
        "NOTE: {list} cross the seam (s = {:.4} mm) and are drawn split in two: the piece at the bottom edge and the piece at the top edge of the same x are ONE notch on the tube (layer TUBE shows the seam).",
        layout.seam_s_mm
    ))
}

/// The `TUBE` layer: the outline of one circumference unrolled, from the distal end to the
/// parting line, and the seam at both edges of the window, each labelled.
fn tube(layout: &Layout) -> Vec<Entity> {
    let (s0, s1) = (layout.seam_s_mm, layout.seam_s_mm + layout.circumference_mm);
    let l = layout.length_mm;
    let on_tube = |mut e: Entity| {
        e.common.layer = TUBE_LAYER.to_string();
        e
    };
    let mut outline = LwPolyline::default();
    outline.set_is_closed(true);
    outline.vertices = [(0.0, s0), (l, s0), (l, s1), (0.0, s1)]
        .iter()
        .map(|&(x, y)| LwPolylineVertex {
            x,
            y,
            ..Default::default()
        })
        .collect();
    let mut out = vec![on_tube(Entity::new(EntityType::LwPolyline(outline)))];
    // The seam runs past both ends of the outline, so it reads as its own line.
    let overrun = SEAM_OVERRUN_MM;
    for (s, which) in [(s0, "bottom"), (s1, "top")] {
        out.push(on_tube(Entity::new(EntityType::Line(Line::new(
            Point::new(-overrun, s, 0.0),
            Point::new(l + overrun, s, 0.0),
        )))));
        let mut t = Text {
            location: Point::new(l + overrun + TEXT_MM, s - TEXT_MM / 2.0, 0.0),
            text_height: TEXT_MM,
            value: format!(
                "seam, s = {s:.4} mm ({which} edge; the tube is cut open here to unroll it)"
            ),
            ..Default::default()
        };
        t.second_alignment_point = t.location.clone();
        out.push(on_tube(Entity::new(EntityType::Text(t))));
    }
    out
}

/// Every entity of the drawing, features first, then annotation.
fn entities(
    layout: &Layout,
    clearance_mm: f64,
    notes: &DxfNotes,
) -> Result<Vec<Entity>, DxfExportError> {
    let mut out = Vec::new();
    for (index, notch) in layout.notches.iter().enumerate() {
        for (piece, outline) in notch.outline.iter().enumerate() {
            // A closed LWPOLYLINE lists each corner once; the ring repeats its first.
            let ring = &outline.exterior().0;
            let corners = &ring[..ring.len().saturating_sub(1)];
            let tag = vec![
                XDataItem::Str(TAG_NOTCH.into()),
                int(index, "notch")?,
                int(piece, "notch piece")?,
            ];
            out.push(polyline(Layer::Notches, corners, true, tag));
        }
    }
    for (tag, layer, traces) in [
        (TAG_SENSOR, Layer::Sensor, &layout.sensors),
        (TAG_LEAD, Layer::LeadsPads, &layout.leads),
        (TAG_PAD, Layer::LeadsPads, &layout.pads),
    ] {
        for (index, trace) in traces.iter().enumerate() {
            for (piece, line) in trace.pieces.iter().enumerate() {
                let items = vec![
                    XDataItem::Str(tag.into()),
                    int(index, tag)?,
                    int(trace.sensor, "sensor")?,
                    int(piece, "trace piece")?,
                ];
                out.push(polyline(layer, &line.0, false, items));
            }
        }
    }
    for (piece, line) in layout.parting.iter().enumerate() {
        let items = vec![
            XDataItem::Str(TAG_PARTING.into()),
            int(piece, "parting piece")?,
        ];
        out.push(polyline(Layer::Parting, &line.0, false, items));
    }
    out.extend(annotation(layout, clearance_mm, notes));
    out.extend(tube(layout));
    Ok(out)
}

fn int(value: usize, what: &'static str) -> Result<XDataItem, DxfExportError> {
    i16::try_from(value)
        .map(XDataItem::Integer)
        .map_err(|_| DxfExportError::TooMany { what, count: value })
}

/// An LWPOLYLINE on `layer` through `points`, tagged with `DLW` XDATA `items`.
fn polyline(layer: Layer, points: &[Coord], closed: bool, items: Vec<XDataItem>) -> Entity {
    let mut poly = LwPolyline::default();
    poly.set_is_closed(closed);
    poly.vertices = points
        .iter()
        .map(|c| LwPolylineVertex {
            x: c.x,
            y: c.y,
            ..Default::default()
        })
        .collect();
    let mut entity = Entity::new(EntityType::LwPolyline(poly));
    entity.common.layer = layer.name().to_string();
    entity.common.x_data.push(XData {
        application_name: APP_ID.to_string(),
        items,
    });
    entity
}

/// Title, frame note and scale note below the drawing, a 1 mm scale bar, and the layout's
/// numbers as XDATA on the title.
fn annotation(layout: &Layout, clearance_mm: f64, notes: &DxfNotes) -> Vec<Entity> {
    let base = layout.seam_s_mm - 3.0 * TEXT_MM;
    let text = |line: usize, value: String| {
        let mut t = Text {
            location: Point::new(0.0, base - line as f64 * 1.6 * TEXT_MM, 0.0),
            text_height: TEXT_MM,
            value,
            ..Default::default()
        };
        t.second_alignment_point = t.location.clone();
        let mut e = Entity::new(EntityType::Text(t));
        e.common.layer = Layer::Annotation.name().to_string();
        e
    };
    let what = notes.title.as_deref().unwrap_or("unrolled joint");
    let mut title = text(0, format!("{}: {what} (dlw)", layout.name));
    title.common.x_data.push(XData {
        application_name: APP_ID.to_string(),
        items: vec![
            XDataItem::Str(TAG_LAYOUT.into()),
            XDataItem::Str(layout.name.clone()),
            XDataItem::Real(layout.outer_radius_mm),
            XDataItem::Real(layout.circumference_mm),
            XDataItem::Real(layout.seam_s_mm),
            XDataItem::Real(layout.trace_width_mm),
            XDataItem::Real(layout.kerf_mm),
            XDataItem::Real(layout.length_mm),
            XDataItem::Real(clearance_mm),
        ],
    });
    let frame = text(
        1,
        format!(
            "X = x along the tube from the distal end; Y = s = r_o*phi, arc length on the outer surface, phi from +y; seam at s = {:.4} mm",
            layout.seam_s_mm
        ),
    );
    let scale = text(
        2,
        format!(
            "units mm ($INSUNITS = 4), scale 1:1; r_o = {} mm, circumference {:.4} mm, trace width {} mm, kerf {} mm",
            layout.outer_radius_mm, layout.circumference_mm, layout.trace_width_mm, layout.kerf_mm
        ),
    );
    // A 1 mm scale bar with end ticks, under the text.
    let y = scale_bar_s_mm(layout);
    let tick = TEXT_MM / 2.0;
    let bar_points = [
        Coord {
            x: 0.0,
            y: y + tick,
        },
        Coord { x: 0.0, y },
        Coord { x: 1.0, y },
        Coord {
            x: 1.0,
            y: y + tick,
        },
    ];
    let mut bar = polyline(Layer::Annotation, &bar_points, false, Vec::new());
    bar.common.x_data.clear();
    let mut label = text(0, "1 mm".into());
    if let EntityType::Text(t) = &mut label.specific {
        t.location = Point::new(1.2, y, 0.0);
        t.second_alignment_point = t.location.clone();
    }
    let mut out = vec![title, frame, scale, bar, label];
    if let Some(note) = split_note(layout) {
        out.push(text(3, note));
    }
    for (x, value) in &notes.labels {
        let mut label = text(0, value.clone());
        if let EntityType::Text(t) = &mut label.specific {
            t.location = Point::new(
                *x,
                layout.seam_s_mm + layout.circumference_mm + TEXT_MM,
                0.0,
            );
            t.second_alignment_point = t.location.clone();
        }
        out.push(label);
    }
    out
}
