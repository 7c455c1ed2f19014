//! Choosing the seam and wrapping unwrapped features into the drawing's `s` window.

use geo::{Coord, LineString, Polygon};

/// An arc `[start, end]` of the circumference a feature occupies (mm, unwrapped, `end ≥ start`).
pub(crate) type Arc = (f64, f64);

/// Features that need not be split are preferred in order: the seam first avoids everything;
/// failing that it may cut notches (which split into two clean rectangles); failing that it
/// only avoids notches. Each tier is a list of occupied arcs; the first tier with a free gap
/// wins.
///
/// Within a tier the seam is the middle of the widest free gap; ties (within `tie_mm`) go to
/// the seam with the smallest value in `[−C/2, C/2)`. The result lies in `[−C/2, C/2)`.
pub(crate) fn choose_seam_mm(tiers: &[Vec<Arc>], circumference_mm: f64, tie_mm: f64) -> f64 {
    for arcs in tiers {
        if let Some(seam) = widest_gap_middle(arcs, circumference_mm, tie_mm) {
            return seam;
        }
    }
    -circumference_mm / 2.0
}

/// The middle of the widest gap between `arcs` on a circle of `circumference_mm`, or `None` if
/// they cover it all.
fn widest_gap_middle(arcs: &[Arc], circumference_mm: f64, tie_mm: f64) -> Option<f64> {
    let c = circumference_mm;
    if arcs.is_empty() {
        return Some(-c / 2.0);
    }
    if arcs.iter().any(|(a, b)| b - a >= c) {
        return None;
    }
    let mut normal: Vec<Arc> = arcs
        .iter()
        .map(|&(a, b)| {
            let start = a.rem_euclid(c);
            (start, start + (b - a))
        })
        .collect();
    normal.sort_by(|p, q| p.0.total_cmp(&q.0));
    // Sweep once round, then measure the gap from the last end back to the first start.
    let first_start = normal[0].0;
    let mut end = normal[0].1;
    let mut gaps: Vec<(f64, f64)> = Vec::new();
    for &(a, b) in &normal[1..] {
        if a > end {
            gaps.push((end, a));
        }
        end = end.max(b);
    }
    if first_start + c > end {
        gaps.push((end, first_start + c));
    }
    let mut best: Option<(f64, f64)> = None; // (width, seam)
    for (a, b) in gaps {
        let width = b - a;
        if width <= tie_mm {
            continue;
        }
        let seam = normalise((a + b) / 2.0, c);
        best = match best {
            Some((w, s)) if w > width + tie_mm || (w >= width - tie_mm && s <= seam) => {
                Some((w, s))
            }
            _ => Some((width, seam)),
        };
    }
    best.map(|(_, seam)| seam)
}

/// `s` moved by whole turns into `[−C/2, C/2)`.
fn normalise(s: f64, c: f64) -> f64 {
    let v = (s + c / 2.0).rem_euclid(c) - c / 2.0;
    if v >= c / 2.0 {
        v - c
    } else {
        v
    }
}

/// Splits an unwrapped polyline where it crosses the window's edges `seam + k·C` and moves each
/// piece into the window `[seam, seam + C]`. Pieces keep the polyline's order and direction.
pub(crate) fn wrap_polyline(
    points: &[Coord],
    seam_mm: f64,
    circumference_mm: f64,
) -> Vec<LineString<f64>> {
    let c = circumference_mm;
    let turn = |s: f64| ((s - seam_mm) / c).floor();
    let mut pieces: Vec<(f64, Vec<Coord>)> = Vec::new();
    for pair in points.windows(2) {
        let (p, q) = (pair[0], pair[1]);
        // Parameters where the segment crosses an edge strictly inside it.
        let mut cuts = vec![0.0];
        if p.y != q.y {
            let (lo, hi) = (p.y.min(q.y), p.y.max(q.y));
            let mut k = turn(lo) + 1.0;
            while seam_mm + k * c < hi {
                let edge = seam_mm + k * c;
                cuts.push((edge - p.y) / (q.y - p.y));
                k += 1.0;
            }
        }
        cuts.push(1.0);
        cuts.sort_by(f64::total_cmp);
        for w in cuts.windows(2) {
            let at = |t: f64| Coord {
                x: p.x + t * (q.x - p.x),
                y: p.y + t * (q.y - p.y),
            };
            let (a, b) = (at(w[0]), at(w[1]));
            let k = turn((a.y + b.y) / 2.0);
            let shift = |c0: Coord| Coord {
                x: c0.x,
                y: c0.y - k * c,
            };
            match pieces.last_mut() {
                Some((last_k, pts)) if *last_k == k => pts.push(shift(b)),
                _ => pieces.push((k, vec![shift(a), shift(b)])),
            }
        }
    }
    if points.len() == 1 {
        let k = turn(points[0].y);
        pieces.push((
            k,
            vec![Coord {
                x: points[0].x,
                y: points[0].y - k * c,
            }],
        ));
    }
    let all: Vec<LineString<f64>> = pieces
        .into_iter()
        .map(|(_, pts)| LineString::new(pts))
        .collect();
    // A polyline that ends on an edge to within rounding leaves a piece of no length on the
    // far side (a point written twice, a laser-on move to where it is): drop it, the pieces
    // still join across the seam.
    let long: Vec<LineString<f64>> = all
        .iter()
        .filter(|l| {
            l.0.len() < 2 || l.lines().map(|e| e.dx().hypot(e.dy())).sum::<f64>() > DEGENERATE_MM
        })
        .cloned()
        .collect();
    if long.is_empty() {
        all
    } else {
        long
    }
}

/// A piece of a wrapped polyline shorter than this is rounding, not a line (mm).
const DEGENERATE_MM: f64 = 1e-9;

/// Moves an axis-aligned rectangle `[x0, x1] × [s0, s1]` (unwrapped, `s1 − s0 < C`) into the
/// window, split into two closed rectangles if it crosses the seam. Overhangs below `tol_mm`
/// are not split off, so a rectangle that ends on the seam gives no sliver.
pub(crate) fn wrap_rectangle(
    (x0, x1): (f64, f64),
    (s0, s1): (f64, f64),
    seam_mm: f64,
    circumference_mm: f64,
    tol_mm: f64,
) -> Vec<Polygon<f64>> {
    let c = circumference_mm;
    let mut a = seam_mm + (s0 - seam_mm).rem_euclid(c);
    if a > seam_mm + c - tol_mm {
        a -= c;
    }
    let b = a + (s1 - s0);
    let top = seam_mm + c;
    if b <= top + tol_mm {
        vec![rectangle(x0, x1, a, b)]
    } else {
        vec![rectangle(x0, x1, a, top), rectangle(x0, x1, seam_mm, b - c)]
    }
}

/// A closed, counter-clockwise rectangle in `(x, s)`.
pub(crate) fn rectangle(x0: f64, x1: f64, s0: f64, s1: f64) -> Polygon<f64> {
    Polygon::new(
        LineString::new(vec![
            Coord { x: x0, y: s0 },
            Coord { x: x1, y: s0 },
            Coord { x: x1, y: s1 },
            Coord { x: x0, y: s1 },
            Coord { x: x0, y: s0 },
        ]),
        vec![],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const C: f64 = 10.0;

    #[test]
    fn seam_goes_mid_widest_gap_with_stable_ties() {
        assert_relative_eq!(
            choose_seam_mm(&[vec![(-1.0, 1.0), (4.0, 6.0)]], C, 1e-9),
            -2.5
        );
        assert_relative_eq!(
            choose_seam_mm(&[vec![(-1.0, 1.0), (3.0, 4.0)]], C, 1e-9),
            -3.5
        );
        // First tier covers everything: fall back to the second.
        let tiers = [vec![(0.0, 10.0)], vec![(-1.0, 1.0)]];
        assert_relative_eq!(choose_seam_mm(&tiers, C, 1e-9), -5.0);
        // Arcs given past a full turn still count where they are.
        assert_relative_eq!(
            choose_seam_mm(&[vec![(9.0, 11.0), (14.0, 16.0)]], C, 1e-9),
            -2.5
        );
    }

    #[test]
    fn polyline_splits_at_every_edge() {
        let pts = [
            Coord { x: 0.0, y: -1.0 },
            Coord { x: 1.0, y: 1.0 },
            Coord { x: 2.0, y: 1.0 },
        ];
        let pieces = wrap_polyline(&pts, 0.0, C);
        assert_eq!(pieces.len(), 2);
        assert_eq!(
            pieces[0].0,
            vec![Coord { x: 0.0, y: 9.0 }, Coord { x: 0.5, y: 10.0 }]
        );
        assert_eq!(
            pieces[1].0,
            vec![
                Coord { x: 0.5, y: 0.0 },
                Coord { x: 1.0, y: 1.0 },
                Coord { x: 2.0, y: 1.0 }
            ]
        );
        // A polyline inside the window is untouched.
        let inside = [Coord { x: 0.0, y: 2.0 }, Coord { x: 1.0, y: 3.0 }];
        assert_eq!(wrap_polyline(&inside, 0.0, C)[0].0, inside.to_vec());
        // One spanning more than a turn splits twice.
        let long = [Coord { x: 0.0, y: -1.0 }, Coord { x: 0.0, y: 12.0 }];
        assert_eq!(wrap_polyline(&long, 0.0, C).len(), 3);
    }

    /// A polyline that starts on the window's edge to within rounding (a robot's pad spiral
    /// at the seam, found by tests/robot_router.rs) gives no piece of no length on the far
    /// side: every piece written is a line.
    #[test]
    fn a_polyline_on_the_edge_leaves_no_empty_piece() {
        let edge = C * (1.0 - f64::EPSILON);
        let pts = [
            Coord { x: 0.0, y: edge },
            Coord {
                x: 0.0,
                y: C + 1e-15,
            },
            Coord { x: 0.5, y: C + 1.0 },
        ];
        let pieces = wrap_polyline(&pts, 0.0, C);
        assert_eq!(pieces.len(), 1, "{pieces:?}");
        assert!(pieces[0].0.len() >= 2);
    }

    #[test]
    fn rectangle_split_keeps_area() {
        use geo::Area;
        let pieces = wrap_rectangle((0.0, 1.0), (8.0, 13.0), 0.0, C, 1e-12);
        assert_eq!(pieces.len(), 2);
        let area: f64 = pieces.iter().map(|p| p.unsigned_area()).sum();
        assert_relative_eq!(area, 5.0, epsilon = 1e-12);
        let whole = wrap_rectangle((0.0, 1.0), (8.0, 13.0), -5.0, C, 1e-12);
        assert_eq!(whole.len(), 1);
        assert_relative_eq!(whole[0].unsigned_area(), 5.0);
        assert!(whole[0].signed_area() > 0.0);
    }
}
