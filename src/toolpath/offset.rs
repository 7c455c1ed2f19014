//! Offsetting a closed outline inward, so a beam following the result cuts the outline's size.
//!
//! The eroded outline of a polygon by a distance `d`: at a convex corner the two shifted edges
//! meet at their miter point; at a reflex corner the boundary is a circular arc of radius `d`
//! around the corner, flattened to chords whose sagitta is at most `arc_tolerance_mm`.

use geo::Coord;

/// Why an outline could not be offset.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OffsetError {
    /// Fewer than three distinct corners, or no area.
    #[error("outline has no area ({corners} distinct corners)")]
    Degenerate {
        /// Distinct, non-collinear corners found.
        corners: usize,
    },
    /// The offset outline crosses itself or leaves the original: the outline is narrower than
    /// twice the offset somewhere.
    #[error(
        "outline is narrower than 2 × {offset_mm} mm somewhere, so its inward offset collapses"
    )]
    TooNarrow {
        /// The offset asked for (mm).
        offset_mm: f64,
    },
}

/// Offsets the closed ring `ring` (first point not repeated at the end, either orientation)
/// inward by `offset_mm`; returns a counter-clockwise ring, first point not repeated.
///
/// # Errors
/// [`OffsetError`] when the ring is degenerate or too narrow for the offset.
pub fn offset_inward(
    ring: &[Coord<f64>],
    offset_mm: f64,
    arc_tolerance_mm: f64,
) -> Result<Vec<Coord<f64>>, OffsetError> {
    let pts = clean_ring(ring);
    if pts.len() < 3 {
        return Err(OffsetError::Degenerate { corners: pts.len() });
    }
    let n = pts.len();
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let prev = pts[(i + n - 1) % n];
        let p = pts[i];
        let next = pts[(i + 1) % n];
        let n1 = left_normal(prev, p);
        let n2 = left_normal(p, next);
        let turn = cross(sub(p, prev), sub(next, p));
        if turn > 0.0 {
            // Convex: the shifted edges meet at the miter point.
            let k = offset_mm / (1.0 + dot(n1, n2));
            out.push(add(p, scale(add(n1, n2), k)));
        } else {
            // Reflex: an arc of radius `offset_mm` round the corner, clockwise from n1 to n2.
            let a1 = n1.y.atan2(n1.x);
            let mut a2 = n2.y.atan2(n2.x);
            while a2 > a1 {
                a2 -= std::f64::consts::TAU;
            }
            let sweep = a1 - a2;
            let ratio = (1.0 - arc_tolerance_mm / offset_mm).clamp(-1.0, 1.0);
            let step = (2.0 * ratio.acos()).max(1e-3);
            let segments = (sweep / step).ceil().max(1.0) as usize;
            for j in 0..=segments {
                let a = a1 - sweep * j as f64 / segments as f64;
                out.push(add(
                    p,
                    scale(
                        Coord {
                            x: a.cos(),
                            y: a.sin(),
                        },
                        offset_mm,
                    ),
                ));
            }
        }
    }
    check(&pts, &out, offset_mm)?;
    Ok(out)
}

/// Drops repeated and collinear corners and orients the ring counter-clockwise.
fn clean_ring(ring: &[Coord<f64>]) -> Vec<Coord<f64>> {
    let scale_mm = ring
        .iter()
        .fold(0.0f64, |m, c| m.max(c.x.abs()).max(c.y.abs()))
        .max(1.0);
    let eps = 1e-12 * scale_mm;
    let mut pts: Vec<Coord<f64>> = Vec::with_capacity(ring.len());
    for &c in ring {
        if pts.last().map_or(true, |&l| dist(l, c) > eps) {
            pts.push(c);
        }
    }
    while pts.len() > 1 && dist(pts[0], pts[pts.len() - 1]) <= eps {
        pts.pop();
    }
    loop {
        let n = pts.len();
        if n < 3 {
            return pts;
        }
        // A corner whose edges turn by less than ~1e-10 rad (or fold back on themselves) is
        // not a corner.
        let collinear = (0..n).find(|&i| {
            let (a, b, c) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
            cross(sub(b, a), sub(c, b)).abs() <= 1e-10 * dist(a, b) * dist(b, c)
        });
        match collinear {
            Some(i) => {
                pts.remove(i);
            }
            None => break,
        }
    }
    if signed_area(&pts) < 0.0 {
        pts.reverse();
    }
    pts
}

/// The offset ring must be simple, counter-clockwise, and every corner inside the original
/// at least `offset_mm` from its boundary.
fn check(orig: &[Coord<f64>], out: &[Coord<f64>], offset_mm: f64) -> Result<(), OffsetError> {
    let too_narrow = OffsetError::TooNarrow { offset_mm };
    if out.len() < 3 || signed_area(out) <= 0.0 {
        return Err(too_narrow);
    }
    let tol = 1e-9 * offset_mm.max(1e-3);
    for &p in out {
        if !inside(orig, p) || ring_distance(orig, p) < offset_mm - tol {
            return Err(too_narrow);
        }
    }
    let n = out.len();
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if !adjacent && segments_cross(out[i], out[(i + 1) % n], out[j], out[(j + 1) % n]) {
                return Err(too_narrow);
            }
        }
    }
    Ok(())
}

/// Twice-signed area / 2 (shoelace): positive for counter-clockwise rings.
pub(crate) fn signed_area(ring: &[Coord<f64>]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| cross(ring[i], ring[(i + 1) % n]))
        .sum::<f64>()
        / 2.0
}

/// Even-odd point-in-ring test.
pub(crate) fn inside(ring: &[Coord<f64>], p: Coord<f64>) -> bool {
    let n = ring.len();
    let mut c = false;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) {
            c = !c;
        }
    }
    c
}

/// Distance from `p` to the closed ring's edges.
pub(crate) fn ring_distance(ring: &[Coord<f64>], p: Coord<f64>) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| segment_distance(ring[i], ring[(i + 1) % n], p))
        .fold(f64::INFINITY, f64::min)
}

/// Distance from `p` to the segment `a`–`b`.
pub(crate) fn segment_distance(a: Coord<f64>, b: Coord<f64>, p: Coord<f64>) -> f64 {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 > 0.0 {
        (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    dist(add(a, scale(ab, t)), p)
}

/// True when the open segments `a`–`b` and `c`–`d` cross or touch.
fn segments_cross(a: Coord<f64>, b: Coord<f64>, c: Coord<f64>, d: Coord<f64>) -> bool {
    let d1 = cross(sub(b, a), sub(c, a));
    let d2 = cross(sub(b, a), sub(d, a));
    let d3 = cross(sub(d, c), sub(a, c));
    let d4 = cross(sub(d, c), sub(b, c));
    (d1 > 0.0) != (d2 > 0.0) && (d3 > 0.0) != (d4 > 0.0) && d1 != 0.0 && d2 != 0.0
}

fn left_normal(a: Coord<f64>, b: Coord<f64>) -> Coord<f64> {
    let d = sub(b, a);
    let len = d.x.hypot(d.y);
    Coord {
        x: -d.y / len,
        y: d.x / len,
    }
}

fn add(a: Coord<f64>, b: Coord<f64>) -> Coord<f64> {
    Coord {
        x: a.x + b.x,
        y: a.y + b.y,
    }
}
fn sub(a: Coord<f64>, b: Coord<f64>) -> Coord<f64> {
    Coord {
        x: a.x - b.x,
        y: a.y - b.y,
    }
}
fn scale(a: Coord<f64>, k: f64) -> Coord<f64> {
    Coord {
        x: a.x * k,
        y: a.y * k,
    }
}
fn dot(a: Coord<f64>, b: Coord<f64>) -> f64 {
    a.x * b.x + a.y * b.y
}
fn cross(a: Coord<f64>, b: Coord<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}
fn dist(a: Coord<f64>, b: Coord<f64>) -> f64 {
    (a.x - b.x).hypot(a.y - b.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    fn c(x: f64, y: f64) -> Coord<f64> {
        Coord { x, y }
    }

    fn bbox(r: &[Coord<f64>]) -> (f64, f64, f64, f64) {
        r.iter().fold(
            (
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ),
            |(a, b, cc, d), p| (a.min(p.x), b.min(p.y), cc.max(p.x), d.max(p.y)),
        )
    }

    #[test]
    fn rectangle_shrinks_by_the_offset_on_every_side() {
        // A clockwise rectangle with a repeated closing point and a collinear midpoint.
        let ring = [
            c(1.0, 0.0),
            c(1.0, 5.61),
            c(1.5, 5.61),
            c(1.5, 2.0),
            c(1.5, 0.0),
            c(1.0, 0.0),
        ];
        let out = offset_inward(&ring, 0.015, 1e-4).unwrap();
        assert_eq!(out.len(), 4);
        let (x0, y0, x1, y1) = bbox(&out);
        for (got, want) in [(x0, 1.015), (y0, 0.015), (x1, 1.485), (y1, 5.595)] {
            assert_abs_diff_eq!(got, want, epsilon = 1e-12);
        }
        assert!(signed_area(&out) > 0.0);
    }

    #[test]
    fn reflex_corner_gets_an_arc_at_the_offset() {
        // An L shape: the corner at (1, 1) is reflex.
        let ring = [
            c(0.0, 0.0),
            c(2.0, 0.0),
            c(2.0, 1.0),
            c(1.0, 1.0),
            c(1.0, 2.0),
            c(0.0, 2.0),
        ];
        let d = 0.1;
        let out = offset_inward(&ring, d, 1e-5).unwrap();
        assert!(out.len() > 6);
        let near: Vec<_> = out
            .iter()
            .filter(|p| dist(**p, c(1.0, 1.0)) < 0.2)
            .collect();
        assert!(near.len() > 3);
        for p in near {
            assert_abs_diff_eq!(dist(*p, c(1.0, 1.0)), d, epsilon = 1e-12);
        }
    }

    #[test]
    fn refuses_outlines_narrower_than_the_kerf() {
        let ring = [c(0.0, 0.0), c(0.02, 0.0), c(0.02, 1.0), c(0.0, 1.0)];
        assert_eq!(
            offset_inward(&ring, 0.015, 1e-4),
            Err(OffsetError::TooNarrow { offset_mm: 0.015 })
        );
        assert!(matches!(
            offset_inward(&[c(0.0, 0.0), c(1.0, 0.0), c(2.0, 0.0)], 0.01, 1e-4),
            Err(OffsetError::Degenerate { .. })
        ));
    }
}
