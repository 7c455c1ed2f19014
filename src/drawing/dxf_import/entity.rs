//! Entity geometry in mm: the vertices of polylines and lines, arcs flattened; the names used
//! in messages.

use dxf::entities::{Entity, EntityType};
use geo::Coord;

use super::super::dxf_convention::Layer;
use super::{loops, DxfImportError};

pub(super) fn type_name(entity: &Entity) -> String {
    let debug = format!("{:?}", entity.specific);
    debug
        .split(['(', ' ', '{'])
        .next()
        .unwrap_or("entity")
        .to_uppercase()
}

pub(super) fn handle(entity: &Entity) -> String {
    format!("#{}", entity.common.handle.as_string())
}

pub(super) fn bad(entity: &Entity, layer: Layer, problem: String) -> DxfImportError {
    DxfImportError::BadPolyline {
        entity: type_name(entity),
        handle: handle(entity),
        layer: layer.name(),
        problem,
    }
}

/// Reads entity geometry in mm.
pub(super) struct Reader {
    /// mm per drawing unit.
    pub k: f64,
    /// Join tolerance and arc chord error (mm).
    pub tol: f64,
}

/// The largest coordinate magnitude a joint's drawing may hold (mm): a metre.
pub const MAX_ABS_COORD_MM: f64 = 1e3;

impl Reader {
    fn at(&self, x: f64, y: f64) -> Coord {
        Coord {
            x: x * self.k,
            y: y * self.k,
        }
    }

    /// [`Self::shape`], refusing coordinates that are not finite numbers.
    pub(super) fn points(
        &self,
        entity: &Entity,
        layer: Layer,
        expected: &'static str,
        arcs: bool,
    ) -> Result<(Vec<Coord>, bool), DxfImportError> {
        let (points, closed) = self.shape(entity, layer, expected, arcs)?;
        if let Some(p) = points
            .iter()
            .find(|p| !(p.x.is_finite() && p.y.is_finite()))
        {
            return Err(bad(
                entity,
                layer,
                format!("a vertex at ({}, {}) is not a finite number", p.x, p.y),
            ));
        }
        // A drawing of a joint spans millimetres; a vertex kilometres away only overflows the
        // areas and lengths computed from it (a vertex at 1e308 gave "notch area NaN mm²").
        if let Some(p) = points
            .iter()
            .find(|p| p.x.abs() > MAX_ABS_COORD_MM || p.y.abs() > MAX_ABS_COORD_MM)
        {
            return Err(bad(
                entity,
                layer,
                format!(
                    "a vertex at ({}, {}) mm lies beyond ±{MAX_ABS_COORD_MM} mm, the limit of a drawing of a joint",
                    crate::limits::short(p.x),
                    crate::limits::short(p.y)
                ),
            ));
        }
        Ok((points, closed))
    }

    /// The vertices (mm) of an LWPOLYLINE or POLYLINE (and whether it is closed), of a LINE, or
    /// of an ARC flattened (when `arcs`).
    fn shape(
        &self,
        entity: &Entity,
        layer: Layer,
        expected: &'static str,
        arcs: bool,
    ) -> Result<(Vec<Coord>, bool), DxfImportError> {
        let mirrored = || {
            bad(
                entity,
                layer,
                "mirrored (extrusion −Z); explode or mirror it back".into(),
            )
        };
        let bulge = |b: f64, x: f64, y: f64| {
            bad(
                entity,
                layer,
                format!("arc segment (bulge {b}) at x = {:.4} mm, s = {:.4} mm; dlw reads straight polyline segments only (draw arcs as ARC entities)", x * self.k, y * self.k),
            )
        };
        match &entity.specific {
            EntityType::LwPolyline(p) => {
                if p.extrusion_direction.z < 0.0 {
                    return Err(mirrored());
                }
                if let Some(v) = p.vertices.iter().find(|v| v.bulge != 0.0) {
                    return Err(bulge(v.bulge, v.x, v.y));
                }
                let points = p.vertices.iter().map(|v| self.at(v.x, v.y)).collect();
                Ok((points, p.is_closed()))
            }
            EntityType::Polyline(p) => {
                if p.normal.z < 0.0 {
                    return Err(mirrored());
                }
                if p.is_3d_polygon_mesh() || p.is_polyface_mesh() {
                    return Err(bad(
                        entity,
                        layer,
                        "a polygon mesh or polyface, not a 2D outline".into(),
                    ));
                }
                if let Some(v) = p.vertices().find(|v| v.bulge != 0.0) {
                    return Err(bulge(v.bulge, v.location.x, v.location.y));
                }
                let points = p
                    .vertices()
                    .map(|v| self.at(v.location.x, v.location.y))
                    .collect();
                Ok((points, p.is_closed()))
            }
            EntityType::Line(l) => Ok((
                vec![self.at(l.p1.x, l.p1.y), self.at(l.p2.x, l.p2.y)],
                false,
            )),
            EntityType::Arc(a) if arcs => {
                let r = a.radius * self.k;
                let c = self.at(a.center.x, a.center.y);
                // An arc seen from below (extrusion −Z) is the mirror image in x of its
                // object-coordinate form.
                let flat = if a.normal.z < 0.0 {
                    flatten_mirrored(c, r, a.start_angle, a.end_angle, self.tol)
                } else {
                    loops::flatten_arc(c, r, a.start_angle, a.end_angle, self.tol)
                };
                let Some(mut points) = flat else {
                    return Err(bad(
                        entity,
                        layer,
                        format!(
                            "an arc of radius {r} mm from {}° to {}° cannot be flattened within {} mm in at most {} chords",
                            a.start_angle,
                            a.end_angle,
                            self.tol,
                            loops::MAX_ARC_SEGMENTS
                        ),
                    ));
                };
                points.dedup();
                Ok((points, false))
            }
            _ => Err(DxfImportError::WrongEntity {
                entity: type_name(entity),
                handle: handle(entity),
                layer: layer.name(),
                expected,
            }),
        }
    }
}

/// An arc whose extrusion is −Z: flattened in its object frame (centre `(−cx, cy)`), then
/// mirrored in x into the drawing.
fn flatten_mirrored(
    c: Coord,
    r: f64,
    start_deg: f64,
    end_deg: f64,
    tol: f64,
) -> Option<Vec<Coord>> {
    let points = loops::flatten_arc(Coord { x: -c.x, y: c.y }, r, start_deg, end_deg, tol)?;
    Some(
        points
            .into_iter()
            .map(|p| Coord { x: -p.x, y: p.y })
            .collect(),
    )
}
