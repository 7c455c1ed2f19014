//! The layout seen as parts on the cylinder, and the distance between two parts.
//!
//! A part is a set of labelled centre-line segments plus, for cuts and pads, filled areas.
//! Distances are Euclidean in the unrolled `(x, s)` plane, computed with `geo`, taken over every
//! copy of one part shifted by whole turns `k·C` in `s`, so a seam between two features never
//! hides how close they are.

use geo::{Contains, Coord, Distance, Euclidean, Line, LineIntersection, LineString, Polygon};

/// A labelled segment of a part.
#[derive(Debug, Clone)]
pub(crate) struct Segment {
    pub line: Line<f64>,
    pub label: String,
}

/// A feature the clearance rule measures.
#[derive(Debug, Clone, Default)]
pub(crate) struct Part {
    pub segments: Vec<Segment>,
    /// Filled areas (notch outlines, pad squares), with their labels.
    pub fills: Vec<(Polygon<f64>, String)>,
}

/// Where two parts come closest.
#[derive(Debug, Clone)]
pub(crate) struct Closest {
    /// Centre-line (or outline) distance (mm); 0 when they touch or one is inside the other.
    pub distance_mm: f64,
    /// The point of the first part that is closest, unshifted.
    pub at: Coord,
    /// Label of the first part's closest segment.
    pub label: String,
    /// Label of the second part's closest segment or area.
    pub other: String,
}

impl Part {
    /// Segments of polylines, each segment labelled by `label(segment)`.
    pub fn from_lines<'a>(
        lines: impl IntoIterator<Item = &'a LineString<f64>>,
        label: impl Fn(&Line<f64>) -> String,
    ) -> Self {
        let segments = lines
            .into_iter()
            .flat_map(|l| l.lines())
            .filter(|l| l.start != l.end)
            .map(|line| Segment {
                label: label(&line),
                line,
            })
            .collect();
        Self {
            segments,
            fills: Vec::new(),
        }
    }

    /// Outlines of closed polygons, filled.
    pub fn from_polygons<'a>(
        polygons: impl IntoIterator<Item = &'a Polygon<f64>>,
        label: &str,
    ) -> Self {
        let mut part = Self::default();
        for p in polygons {
            part.segments
                .extend(p.exterior().lines().map(|line| Segment {
                    line,
                    label: label.to_string(),
                }));
            part.fills.push((p.clone(), label.to_string()));
        }
        part
    }

    /// Range of `x` the part covers (mm).
    fn x_range(&self) -> Option<(f64, f64)> {
        self.segments
            .iter()
            .flat_map(|seg| [seg.line.start.x, seg.line.end.x])
            .fold(None, |acc, x| match acc {
                None => Some((x, x)),
                Some((lo, hi)) => Some((lo.min(x), hi.max(x))),
            })
    }

    /// Range of `s` the part covers (mm).
    fn s_range(&self) -> Option<(f64, f64)> {
        self.segments
            .iter()
            .flat_map(|seg| [seg.line.start.y, seg.line.end.y])
            .fold(None, |acc, s| match acc {
                None => Some((s, s)),
                Some((lo, hi)) => Some((lo.min(s), hi.max(s))),
            })
    }

    fn shifted(&self, ds: f64) -> Self {
        let shift = |c: Coord| Coord {
            x: c.x,
            y: c.y + ds,
        };
        Self {
            segments: self
                .segments
                .iter()
                .map(|seg| Segment {
                    line: Line::new(shift(seg.line.start), shift(seg.line.end)),
                    label: seg.label.clone(),
                })
                .collect(),
            fills: self
                .fills
                .iter()
                .map(|(p, l)| {
                    let ring = LineString::new(p.exterior().coords().map(|&c| shift(c)).collect());
                    (Polygon::new(ring, vec![]), l.clone())
                })
                .collect(),
        }
    }
}

/// The closest approach of `a` to `b` on a cylinder of circumference `c_mm`, looking only at
/// copies of `b` that could come within `reach_mm` of `a`.
pub(crate) fn closest_on_cylinder(a: &Part, b: &Part, c_mm: f64, reach_mm: f64) -> Option<Closest> {
    // Parts further apart along the tube than the reach have no copy within it (the fills lie
    // inside their outlines, which are segments too).
    let ((axlo, axhi), (bxlo, bxhi)) = (a.x_range()?, b.x_range()?);
    if bxlo > axhi + reach_mm || axlo > bxhi + reach_mm {
        return None;
    }
    let ((alo, ahi), (blo, bhi)) = (a.s_range()?, b.s_range()?);
    let k_min = ((alo - bhi - reach_mm) / c_mm).floor() as i64;
    let k_max = ((ahi - blo + reach_mm) / c_mm).ceil() as i64;
    (k_min..=k_max)
        .filter_map(|k| closest(a, &b.shifted(k as f64 * c_mm)))
        .min_by(|p, q| p.distance_mm.total_cmp(&q.distance_mm))
}

/// The closest approach of two parts in the plane.
fn closest(a: &Part, b: &Part) -> Option<Closest> {
    fn offer(best: &mut Option<Closest>, c: Closest) {
        if best
            .as_ref()
            .map_or(true, |b| c.distance_mm < b.distance_mm)
        {
            *best = Some(c);
        }
    }
    let mut best: Option<Closest> = None;
    for sa in &a.segments {
        for sb in &b.segments {
            let distance_mm = Euclidean::distance(&sa.line, &sb.line);
            // Where, and the labels, only for a pair nearer than the best so far.
            if best.as_ref().is_some_and(|b| distance_mm >= b.distance_mm) {
                continue;
            }
            offer(
                &mut best,
                Closest {
                    distance_mm,
                    at: point_nearest(&sa.line, &sb.line),
                    label: sa.label.clone(),
                    other: sb.label.clone(),
                },
            );
        }
        // A trace inside a filled area touches it everywhere.
        for (poly, label) in &b.fills {
            if poly.contains(&sa.line.start) {
                offer(
                    &mut best,
                    Closest {
                        distance_mm: 0.0,
                        at: sa.line.start,
                        label: sa.label.clone(),
                        other: label.clone(),
                    },
                );
            }
        }
    }
    for sb in &b.segments {
        for (poly, label) in &a.fills {
            if poly.contains(&sb.line.start) {
                offer(
                    &mut best,
                    Closest {
                        distance_mm: 0.0,
                        at: sb.line.start,
                        label: label.clone(),
                        other: sb.label.clone(),
                    },
                );
            }
        }
    }
    best
}

/// The point of segment `a` nearest to segment `b`: their crossing if they cross, else the
/// nearer of the endpoint-to-segment projections (the distance between two segments that do not
/// cross is always reached at an endpoint of one of them).
fn point_nearest(a: &Line<f64>, b: &Line<f64>) -> Coord {
    if let Some(hit) = geo::line_intersection::line_intersection(*a, *b) {
        return match hit {
            LineIntersection::SinglePoint { intersection, .. } => intersection,
            LineIntersection::Collinear { intersection } => intersection.start,
        };
    }
    let candidates = [
        (a.start, Euclidean::distance(&geo::Point(a.start), b)),
        (a.end, Euclidean::distance(&geo::Point(a.end), b)),
        (
            project(b.start, a),
            Euclidean::distance(&geo::Point(b.start), a),
        ),
        (
            project(b.end, a),
            Euclidean::distance(&geo::Point(b.end), a),
        ),
    ];
    candidates
        .into_iter()
        .min_by(|p, q| p.1.total_cmp(&q.1))
        .map_or(a.start, |(c, _)| c)
}

/// Orthogonal projection of `p` onto segment `l`, clamped to it.
fn project(p: Coord, l: &Line<f64>) -> Coord {
    let d = l.end - l.start;
    let len2 = d.x * d.x + d.y * d.y;
    if len2 == 0.0 {
        return l.start;
    }
    let t = (((p.x - l.start.x) * d.x + (p.y - l.start.y) * d.y) / len2).clamp(0.0, 1.0);
    l.start + d * t
}

/// Joins the pieces of a trace that the seam split (a piece that starts where the previous one
/// ended, one turn `c_mm` away) back into continuous polylines in unwrapped `s`.
pub(crate) fn join_pieces(pieces: &[LineString<f64>], c_mm: f64, tol_mm: f64) -> Vec<Vec<Coord>> {
    let mut joined: Vec<Vec<Coord>> = Vec::new();
    for piece in pieces {
        let (Some(first), Some(last)) = (piece.0.first(), joined.last().and_then(|j| j.last()))
        else {
            joined.push(piece.0.clone());
            continue;
        };
        let turns = ((last.y - first.y) / c_mm).round();
        let shifted_y = first.y + turns * c_mm;
        if (first.x - last.x).abs() <= tol_mm && (shifted_y - last.y).abs() <= tol_mm {
            let ds = turns * c_mm;
            if let Some(j) = joined.last_mut() {
                j.extend(piece.0.iter().skip(1).map(|c| Coord {
                    x: c.x,
                    y: c.y + ds,
                }));
            }
        } else {
            joined.push(piece.0.clone());
        }
    }
    joined
}

/// The part of a polyline between arc lengths `from` and `to` along it (mm).
pub(crate) fn sub_polyline(points: &[Coord], from_mm: f64, to_mm: f64) -> Vec<Coord> {
    let mut out = Vec::new();
    let mut walked = 0.0;
    for w in points.windows(2) {
        let (p, q) = (w[0], w[1]);
        let len = ((q.x - p.x).powi(2) + (q.y - p.y).powi(2)).sqrt();
        let (t0, t1) = (walked, walked + len);
        walked = t1;
        if len == 0.0 || t1 < from_mm || t0 > to_mm {
            continue;
        }
        let at = |t: f64| p + (q - p) * ((t - t0) / len).clamp(0.0, 1.0);
        if out.is_empty() {
            out.push(at(from_mm.max(t0)));
        }
        out.push(at(to_mm.min(t1)));
    }
    out
}

/// Length of a polyline (mm).
pub(crate) fn polyline_length(points: &[Coord]) -> f64 {
    points
        .windows(2)
        .map(|w| ((w[1].x - w[0].x).powi(2) + (w[1].y - w[0].y).powi(2)).sqrt())
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn seg(points: &[(f64, f64)], label: &str) -> Part {
        let l = LineString::from(points.to_vec());
        Part::from_lines([&l], |_| label.to_string())
    }

    #[test]
    fn distance_and_place_between_parallel_lines() {
        let a = seg(&[(0.0, 0.0), (5.0, 0.0)], "a");
        let b = seg(&[(2.0, 0.3), (3.0, 0.3)], "b");
        let c = closest_on_cylinder(&a, &b, 100.0, 1.0).unwrap();
        assert_relative_eq!(c.distance_mm, 0.3, epsilon = 1e-12);
        assert!(c.at.x >= 2.0 && c.at.x <= 3.0 && c.at.y == 0.0);
    }

    #[test]
    fn seam_does_not_hide_closeness() {
        // On a 10 mm circumference, s = 9.9 and s = 0.1 are 0.2 mm apart.
        let a = seg(&[(0.0, 9.9), (5.0, 9.9)], "a");
        let b = seg(&[(0.0, 0.1), (5.0, 0.1)], "b");
        let c = closest_on_cylinder(&a, &b, 10.0, 1.0).unwrap();
        assert_relative_eq!(c.distance_mm, 0.2, epsilon = 1e-12);
    }

    #[test]
    fn inside_a_fill_is_distance_zero() {
        let sq = Polygon::new(
            LineString::from(vec![
                (0.0, 0.0),
                (1.0, 0.0),
                (1.0, 1.0),
                (0.0, 1.0),
                (0.0, 0.0),
            ]),
            vec![],
        );
        let notch = Part::from_polygons([&sq], "notch");
        let a = seg(&[(0.4, 0.4), (0.6, 0.6)], "a");
        let c = closest_on_cylinder(&a, &notch, 100.0, 1.0).unwrap();
        assert_eq!(c.distance_mm, 0.0);
        assert_eq!(c.other, "notch");
    }

    #[test]
    fn joins_seam_pieces_and_cuts_sub_polylines() {
        let pieces = [
            LineString::from(vec![(0.0, 8.0), (1.0, 10.0)]),
            LineString::from(vec![(1.0, 0.0), (2.0, 1.0)]),
        ];
        let j = join_pieces(&pieces, 10.0, 1e-9);
        assert_eq!(j.len(), 1);
        assert_eq!(j[0][2], Coord { x: 2.0, y: 11.0 });
        let pts = [
            Coord { x: 0.0, y: 0.0 },
            Coord { x: 2.0, y: 0.0 },
            Coord { x: 2.0, y: 2.0 },
        ];
        assert_relative_eq!(polyline_length(&pts), 4.0);
        let sub = sub_polyline(&pts, 1.0, 3.0);
        assert_eq!(
            sub,
            vec![
                Coord { x: 1.0, y: 0.0 },
                Coord { x: 2.0, y: 0.0 },
                Coord { x: 2.0, y: 1.0 }
            ]
        );
    }
}
