//! Reading a DXF in `dlw`'s convention (see `dxf_convention`) back into a [`Layout`], for
//! example after a designer moved a notch in AutoCAD.
//!
//! How each entity is read:
//! - `NOTCHES`: closed LWPOLYLINEs (the closed flag, or a last vertex on the first), straight
//!   segments only. Pieces with the same `DLW` notch index form one notch; an untagged polyline
//!   is a notch of its own, except that two untagged pieces with the same `x` range, one ending
//!   on the window's top edge and one starting on the seam, are the halves of one split notch. Level and side always come from the geometry, so an edited drawing
//!   describes itself: levels rank the notches' distal edges `x` (edges within 1 µm share a
//!   level), and the side is the notch centre nearer `s = π·r_o` (side 0) or `s = 0` (side 1).
//! - `SENSOR`: open LWPOLYLINEs or LINEs, U-trace pieces.
//! - `LEADS_PADS`: tagged entities say whether they are a lead or a pad. An untagged one is a
//!   pad if it turns through at least a full turn (a spiral), else a lead.
//! - Which sensor a trace belongs to: its tag; untagged, sensor 1 (index 1) if the drawing has
//!   BSN notch pairs and the trace's mean `s` is nearer `π·r_o` than `0`, else sensor 0.
//! - `PARTING`: LWPOLYLINEs or LINEs; the joint length is the parting cut's largest `x`.
//! - `ANNOTATION`: anything; the title's XDATA gives the layout's numbers.
//!
//! Tagged traces keep their list order and piece order; untagged ones follow in file order.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use dxf::entities::{Entity, EntityType};
use dxf::{XData, XDataItem};
use geo::{Area, BoundingRect, Coord, LineString, Polygon};

use crate::layout::{Layout, Notch, Trace};

use super::dxf_convention::{
    Layer, APP_ID, TAG_LAYOUT, TAG_LEAD, TAG_NOTCH, TAG_PAD, TAG_PARTING, TAG_SENSOR,
};

/// Why a DXF could not be read as a layout.
#[derive(Debug, thiserror::Error)]
pub enum DxfImportError {
    /// The bytes are not a DXF the reader understands.
    #[error("not a readable DXF: {0}")]
    Parse(String),
    /// The drawing is not in millimetres.
    #[error("drawing units are $INSUNITS = {insunits} ({name}); dlw drawings are in millimetres ($INSUNITS = 4)")]
    Units {
        /// `$INSUNITS` as found.
        insunits: i16,
        /// Its meaning.
        name: String,
    },
    /// An entity sits on a layer the convention does not have.
    #[error("{entity} {handle} is on layer {layer:?}, which is not a dlw layer (expected NOTCHES, SENSOR, LEADS_PADS, PARTING or ANNOTATION)")]
    UnknownLayer {
        /// Entity type.
        entity: String,
        /// Entity handle.
        handle: String,
        /// The layer.
        layer: String,
    },
    /// A notch contour is not closed.
    #[error("notch contour {handle} from x = {x_mm:.4} mm, s = {s_mm:.4} mm is open: notches must be closed LWPOLYLINEs")]
    OpenNotch {
        /// Entity handle.
        handle: String,
        /// First vertex, x (mm).
        x_mm: f64,
        /// First vertex, s (mm).
        s_mm: f64,
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
    #[error("LWPOLYLINE {handle} on layer {layer}: {problem}")]
    BadPolyline {
        /// Entity handle.
        handle: String,
        /// The layer.
        layer: &'static str,
        /// What is wrong, with the value.
        problem: String,
    },
    /// The title's numbers are missing or unreadable.
    #[error("no dlw layout numbers: {0} (the title TEXT on layer ANNOTATION carries them as DLW XDATA; the outer radius, seam and trace width cannot be read from the geometry)")]
    Metadata(String),
}

/// What a DXF held.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportedDxf {
    /// The layout read.
    pub layout: Layout,
    /// The clearance recorded by the writer (mm).
    pub clearance_mm: f64,
    /// Entities per layer, as named in the file.
    pub layer_counts: BTreeMap<String, usize>,
    /// Feature entities without `DLW` XDATA, read from their geometry alone.
    pub untagged: usize,
}

/// A notch polygon as read, with its tag (notch index, piece) if it had one.
type NotchPiece = (Option<(i16, i16)>, Polygon<f64>);
/// The pieces of one notch (numbered), under its tag's notch index if it had one.
type NotchGroup = (Option<i16>, Vec<(i16, Polygon<f64>)>);
/// A tagged trace: its sensor and its numbered pieces.
type TaggedTrace = (usize, Vec<(i16, LineString<f64>)>);

/// Layout numbers from the title's XDATA.
struct Numbers {
    name: String,
    outer_radius_mm: f64,
    circumference_mm: f64,
    seam_s_mm: f64,
    trace_width_mm: f64,
    kerf_mm: f64,
    length_mm: f64,
    clearance_mm: f64,
}

/// A trace entity as read: its tag (kind, list index, sensor, piece) if it had one.
struct TracePiece {
    kind: &'static str,
    tag: Option<(i16, i16, i16)>,
    line: LineString<f64>,
}

/// Reads a DXF's bytes as a layout.
///
/// # Errors
/// [`DxfImportError`] for unreadable files, units other than mm, unknown layers, open notch
/// contours, entity types the convention does not use, or missing layout numbers.
pub fn layout_from_dxf(bytes: &[u8]) -> Result<ImportedDxf, DxfImportError> {
    let drawing = dxf::Drawing::load(&mut std::io::Cursor::new(bytes))
        .map_err(|e| DxfImportError::Parse(e.to_string()))?;
    let insunits = drawing.header.default_drawing_units as i16;
    if insunits != 4 {
        return Err(DxfImportError::Units {
            insunits,
            name: format!("{:?}", drawing.header.default_drawing_units).to_lowercase(),
        });
    }
    let mut layer_counts = BTreeMap::new();
    let mut numbers = None;
    let mut notch_pieces: Vec<NotchPiece> = Vec::new();
    let mut traces: Vec<TracePiece> = Vec::new();
    let mut parting: Vec<(Option<i16>, LineString<f64>)> = Vec::new();
    for entity in drawing.entities() {
        let layer_name = entity.common.layer.clone();
        *layer_counts.entry(layer_name.clone()).or_insert(0) += 1;
        let layer = Layer::from_name(&layer_name).ok_or_else(|| DxfImportError::UnknownLayer {
            entity: type_name(entity),
            handle: handle(entity),
            layer: layer_name.clone(),
        })?;
        let tag = dlw_xdata(entity);
        match layer {
            Layer::Annotation => {
                if let Some(items) = tag.filter(|i| is_tag(i, TAG_LAYOUT)) {
                    numbers = Some(read_numbers(items)?);
                }
            }
            Layer::Notches => {
                let (points, closed) = polyline_points(entity, layer, "a closed LWPOLYLINE")?;
                let mut points = points;
                let closed = closed || (points.len() > 3 && points.first() == points.last());
                if !closed {
                    let first = points.first().copied().unwrap_or(Coord { x: 0.0, y: 0.0 });
                    return Err(DxfImportError::OpenNotch {
                        handle: handle(entity),
                        x_mm: first.x,
                        s_mm: first.y,
                    });
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
                notch_pieces.push((id, Polygon::new(LineString::new(points), vec![])));
            }
            Layer::Sensor | Layer::LeadsPads => {
                let expected = "an open LWPOLYLINE or a LINE";
                let (points, closed) = polyline_points(entity, layer, expected)?;
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
                let line = LineString::new(points);
                traces.push(match tagged {
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
            }
            Layer::Parting => {
                let (points, _) = polyline_points(entity, layer, "an LWPOLYLINE or a LINE")?;
                let piece = tag
                    .filter(|i| is_tag(i, TAG_PARTING))
                    .and_then(|i| int_at(i, 1));
                parting.push((piece, LineString::new(points)));
            }
        }
    }
    let numbers = numbers.ok_or_else(|| DxfImportError::Metadata("none found".into()))?;
    let untagged = notch_pieces.iter().filter(|(t, _)| t.is_none()).count()
        + traces.iter().filter(|t| t.tag.is_none()).count()
        + parting.iter().filter(|(t, _)| t.is_none()).count();
    let notches = notches(notch_pieces, &numbers);
    let bsn = notches.iter().any(|n| n.side == 1);
    parting.sort_by_key(|(piece, _)| piece.unwrap_or(i16::MAX));
    let parting: Vec<LineString<f64>> = parting.into_iter().map(|(_, l)| l).collect();
    let length_mm = parting
        .iter()
        .flat_map(|l| l.0.iter().map(|c| c.x))
        .reduce(f64::max)
        .unwrap_or(numbers.length_mm);
    let group = |kind: &str| group_traces(&traces, kind, bsn, numbers.outer_radius_mm);
    let layout = Layout {
        name: numbers.name,
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
    Ok(ImportedDxf {
        layout,
        clearance_mm: numbers.clearance_mm,
        layer_counts,
        untagged,
    })
}

fn type_name(entity: &Entity) -> String {
    let debug = format!("{:?}", entity.specific);
    debug
        .split(['(', ' ', '{'])
        .next()
        .unwrap_or("entity")
        .to_uppercase()
}

fn handle(entity: &Entity) -> String {
    format!("#{}", entity.common.handle.as_string())
}

fn bad(entity: &Entity, layer: Layer, problem: String) -> DxfImportError {
    DxfImportError::BadPolyline {
        handle: handle(entity),
        layer: layer.name(),
        problem,
    }
}

/// The `DLW` XDATA items of an entity, if any.
fn dlw_xdata(entity: &Entity) -> Option<&[XDataItem]> {
    entity
        .common
        .x_data
        .iter()
        .find(|x: &&XData| x.application_name.eq_ignore_ascii_case(APP_ID))
        .map(|x| x.items.as_slice())
}

fn is_tag(items: &[XDataItem], tag: &str) -> bool {
    matches!(items.first(), Some(XDataItem::Str(s)) if s == tag)
}

fn int_at(items: &[XDataItem], at: usize) -> Option<i16> {
    match items.get(at) {
        Some(XDataItem::Integer(i)) => Some(*i),
        _ => None,
    }
}

fn read_numbers(items: &[XDataItem]) -> Result<Numbers, DxfImportError> {
    let name = match items.get(1) {
        Some(XDataItem::Str(s)) => s.clone(),
        _ => {
            return Err(DxfImportError::Metadata(
                "the title's XDATA has no name".into(),
            ))
        }
    };
    let reals: Vec<f64> = items[2..]
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
    Ok(Numbers {
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

/// The vertices of an LWPOLYLINE (and whether it is closed) or of a LINE.
fn polyline_points(
    entity: &Entity,
    layer: Layer,
    expected: &'static str,
) -> Result<(Vec<Coord>, bool), DxfImportError> {
    match &entity.specific {
        EntityType::LwPolyline(p) => {
            if p.extrusion_direction.z < 0.0 {
                return Err(bad(
                    entity,
                    layer,
                    "mirrored (extrusion −Z); explode or mirror it back".into(),
                ));
            }
            if let Some(v) = p.vertices.iter().find(|v| v.bulge != 0.0) {
                return Err(bad(
                    entity,
                    layer,
                    format!("arc segment (bulge {}) at x = {:.4} mm, s = {:.4} mm; dlw reads straight segments only", v.bulge, v.x, v.y),
                ));
            }
            let points = p
                .vertices
                .iter()
                .map(|v| Coord { x: v.x, y: v.y })
                .collect();
            Ok((points, p.is_closed()))
        }
        EntityType::Line(l) if layer != Layer::Notches => Ok((
            vec![
                Coord {
                    x: l.p1.x,
                    y: l.p1.y,
                },
                Coord {
                    x: l.p2.x,
                    y: l.p2.y,
                },
            ],
            false,
        )),
        _ => Err(DxfImportError::WrongEntity {
            entity: type_name(entity),
            handle: handle(entity),
            layer: layer.name(),
            expected,
        }),
    }
}

/// A polyline that turns through at least a full turn is a spiral.
fn is_spiral(points: &[Coord]) -> bool {
    let mut turning = 0.0;
    for w in points.windows(3) {
        let (a, b) = (w[1] - w[0], w[2] - w[1]);
        turning += (a.x * b.y - a.y * b.x).atan2(a.x * b.x + a.y * b.y);
    }
    turning.abs() >= 2.0 * PI - 1e-6
}

/// Notch pieces grouped into notches, with level and side from their geometry.
fn notches(pieces: Vec<NotchPiece>, numbers: &Numbers) -> Vec<Notch> {
    let outer_radius_mm = numbers.outer_radius_mm;
    // Group tagged pieces by notch index (pieces in tag order); untagged pieces stand alone.
    let mut groups: Vec<NotchGroup> = Vec::new();
    for (tag, poly) in pieces {
        match tag {
            Some((index, piece)) => match groups.iter_mut().find(|(i, _)| *i == Some(index)) {
                Some((_, list)) => list.push((piece, poly)),
                None => groups.push((Some(index), vec![(piece, poly)])),
            },
            None => groups.push((None, vec![(0, poly)])),
        }
    }
    groups.sort_by_key(|(i, _)| i.unwrap_or(i16::MAX));
    merge_seam_halves(&mut groups, numbers.seam_s_mm, numbers.circumference_mm);
    let mut notches: Vec<(f64, Notch)> = groups
        .into_iter()
        .map(|(_, mut list)| {
            list.sort_by_key(|(piece, _)| *piece);
            let outline: Vec<Polygon<f64>> = list.into_iter().map(|(_, p)| p).collect();
            let x0 = outline
                .iter()
                .filter_map(|p| p.bounding_rect())
                .map(|r| r.min().x)
                .fold(f64::INFINITY, f64::min);
            // Which of s = 0 and s = π·r_o the pieces' centres lie nearer, weighted by area
            // (a notch split at the seam has pieces at both window edges).
            let mut cos = 0.0;
            for p in &outline {
                if let Some(r) = p.bounding_rect() {
                    let phi = r.center().y / outer_radius_mm;
                    let a = p.unsigned_area();
                    cos += a * phi.cos();
                }
            }
            let side = usize::from(cos > 0.0);
            (
                x0,
                Notch {
                    level: 0,
                    side,
                    outline,
                },
            )
        })
        .collect();
    // Levels rank the distal edges; edges within 1 µm share a level.
    let mut edges: Vec<f64> = notches.iter().map(|(x, _)| *x).collect();
    edges.sort_by(f64::total_cmp);
    edges.dedup_by(|a, b| (*a - *b).abs() <= 1e-3);
    for (x0, notch) in &mut notches {
        notch.level = edges
            .iter()
            .position(|e| (*e - *x0).abs() <= 1e-3)
            .unwrap_or(0);
    }
    let mut notches: Vec<Notch> = notches.into_iter().map(|(_, n)| n).collect();
    notches.sort_by_key(|n| (n.level, n.side));
    notches
}

/// Joins untagged notch pieces that are the two halves of one notch split at the seam: the
/// same `x` range, one ending on the window's top edge and one starting on the seam. The top
/// piece comes first, as the layout writes them.
fn merge_seam_halves(groups: &mut Vec<NotchGroup>, seam_mm: f64, c_mm: f64) {
    const TOL_MM: f64 = 1e-6;
    let bounds = |p: &Polygon<f64>| p.bounding_rect();
    let mut i = 0;
    while i < groups.len() {
        let top = match &groups[i] {
            (None, list) if list.len() == 1 => bounds(&list[0].1),
            _ => None,
        };
        let partner = top
            .filter(|t| (t.max().y - (seam_mm + c_mm)).abs() <= TOL_MM)
            .and_then(|t| {
                groups.iter().position(|(tag, list)| {
                    tag.is_none()
                        && list.len() == 1
                        && bounds(&list[0].1).is_some_and(|b| {
                            (b.min().y - seam_mm).abs() <= TOL_MM
                                && (b.min().x - t.min().x).abs() <= TOL_MM
                                && (b.max().x - t.max().x).abs() <= TOL_MM
                        })
                })
            });
        if let Some(j) = partner.filter(|&j| j != i) {
            let (_, mut bottom) = groups.remove(j);
            let at = if j < i { i - 1 } else { i };
            if let Some((_, piece)) = bottom.pop() {
                groups[at].1.push((1, piece));
            }
            i = at + 1;
        } else {
            i += 1;
        }
    }
}

/// The traces of one kind: tagged ones by list index (pieces by piece number), then untagged
/// ones, each its own trace.
fn group_traces(pieces: &[TracePiece], kind: &str, bsn: bool, outer_radius_mm: f64) -> Vec<Trace> {
    let mut tagged: BTreeMap<i16, TaggedTrace> = BTreeMap::new();
    let mut untagged = Vec::new();
    for p in pieces.iter().filter(|p| p.kind == kind) {
        match p.tag {
            Some((index, sensor, piece)) => tagged
                .entry(index)
                .or_insert_with(|| (sensor.max(0) as usize, Vec::new()))
                .1
                .push((piece, p.line.clone())),
            None => {
                let mean_s = p.line.0.iter().map(|c| c.y).sum::<f64>() / p.line.0.len() as f64;
                let phi = mean_s / outer_radius_mm;
                let sensor = usize::from(bsn && phi.cos() < 0.0);
                untagged.push(Trace {
                    sensor,
                    pieces: vec![p.line.clone()],
                });
            }
        }
    }
    tagged
        .into_values()
        .map(|(sensor, mut list)| {
            list.sort_by_key(|(piece, _)| *piece);
            Trace {
                sensor,
                pieces: list.into_iter().map(|(_, l)| l).collect(),
            }
        })
        .chain(untagged)
        .collect()
}
