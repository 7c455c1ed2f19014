//! Handling the drawing's seam: pieces the layout split at the seam are joined again, with `s`
//! continuous across it, so the beam never stops at the seam or unwinds the tube the long way.

use geo::{BooleanOps, Coord, LineString, MultiPolygon, Polygon};

/// Why pieces could not be joined.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SeamError {
    /// The pieces of one outline do not form a single outline once shifted across the seam.
    #[error("its {pieces} pieces do not join into one outline across the seam (got {outlines} outlines, {holes} holes)")]
    Disjoint {
        /// Pieces in the layout.
        pieces: usize,
        /// Outlines after joining.
        outlines: usize,
        /// Holes after joining.
        holes: usize,
    },
    /// An outline without points.
    #[error("it has no outline")]
    Empty,
}

/// Joins the pieces of one closed outline, given in `(x, s)`, into one ring (first point not
/// repeated): each piece after the first is shifted by a whole circumference, if that brings it
/// next to the others, and the pieces are united.
///
/// # Errors
/// [`SeamError`] when there are no pieces or they do not form one outline without holes.
pub fn join_outline(
    pieces: &[Polygon<f64>],
    circumference_mm: f64,
) -> Result<Vec<Coord<f64>>, SeamError> {
    let first = pieces.first().ok_or(SeamError::Empty)?;
    if pieces.len() == 1 {
        return Ok(open_ring(first.exterior()));
    }
    let mut joined = MultiPolygon::new(vec![first.clone()]);
    let mut corners: Vec<Coord<f64>> = first.exterior().coords().copied().collect();
    for piece in &pieces[1..] {
        let (lo, hi) = s_range(&joined);
        let (plo, phi) = s_range(&MultiPolygon::new(vec![piece.clone()]));
        // The shift that leaves the smallest gap in s between the piece and the rest.
        let shift = [-circumference_mm, 0.0, circumference_mm]
            .into_iter()
            .min_by(|a, b| {
                let gap = |k: f64| (plo + k - hi).max(lo - (phi + k)).max(0.0);
                gap(*a).total_cmp(&gap(*b))
            })
            .unwrap_or(0.0);
        let moved = Polygon::new(
            LineString::from(
                piece
                    .exterior()
                    .coords()
                    .map(|c| Coord {
                        x: c.x,
                        y: c.y + shift,
                    })
                    .collect::<Vec<_>>(),
            ),
            vec![],
        );
        corners.extend(moved.exterior().coords().copied());
        joined = joined.union(&MultiPolygon::new(vec![moved]));
    }
    let holes: usize = joined.0.iter().map(|p| p.interiors().len()).sum();
    match joined.0.as_slice() {
        // The union works in fixed point; put its corners back on the pieces' own corners.
        [one] if holes == 0 => Ok(open_ring(one.exterior())
            .into_iter()
            .map(|p| snap(p, &corners, 1e-6 * circumference_mm.max(1.0)))
            .collect()),
        _ => Err(SeamError::Disjoint {
            pieces: pieces.len(),
            outlines: joined.0.len(),
            holes,
        }),
    }
}

/// Joins open polylines in `(x, s)` whose ends meet, allowing for the seam: two ends meet when
/// they are within `tolerance_mm` after shifting one by a whole number of circumferences.
/// Each input carries a tag; each output chain lists the tags of its pieces in order.
pub fn chain_lines<T: Clone>(
    lines: Vec<(T, Vec<Coord<f64>>)>,
    circumference_mm: f64,
    tolerance_mm: f64,
) -> Vec<(Vec<T>, Vec<Coord<f64>>)> {
    let mut pool: Vec<(T, Vec<Coord<f64>>)> =
        lines.into_iter().filter(|(_, l)| !l.is_empty()).collect();
    let mut chains = Vec::new();
    while !pool.is_empty() {
        let (tag, mut line) = pool.remove(0);
        let mut tags = vec![tag];
        loop {
            let mut grew = false;
            // Extend at the end.
            if let Some(&end) = line.last() {
                if let Some((i, reversed, shift)) =
                    find_match(&pool, end, circumference_mm, tolerance_mm)
                {
                    let (t, mut piece) = pool.remove(i);
                    if reversed {
                        piece.reverse();
                    }
                    line.extend(piece.iter().skip(1).map(|c| Coord {
                        x: c.x,
                        y: c.y + shift,
                    }));
                    tags.push(t);
                    grew = true;
                }
            }
            // Extend at the start.
            if let Some(&start) = line.first() {
                if let Some((i, reversed, shift)) =
                    find_match(&pool, start, circumference_mm, tolerance_mm)
                {
                    let (t, mut piece) = pool.remove(i);
                    if !reversed {
                        piece.reverse();
                    }
                    let mut front: Vec<Coord<f64>> = piece
                        .iter()
                        .map(|c| Coord {
                            x: c.x,
                            y: c.y + shift,
                        })
                        .collect();
                    front.pop();
                    front.extend(line);
                    line = front;
                    tags.insert(0, t);
                    grew = true;
                }
            }
            if !grew {
                break;
            }
        }
        chains.push((tags, line));
    }
    chains
}

/// A pool line with an end at `at` (modulo the circumference): its index, whether the match is
/// its last point (so it must be reversed to continue from `at`), and the shift in `s`.
fn find_match<T>(
    pool: &[(T, Vec<Coord<f64>>)],
    at: Coord<f64>,
    circumference_mm: f64,
    tolerance_mm: f64,
) -> Option<(usize, bool, f64)> {
    pool.iter().enumerate().find_map(|(i, (_, l))| {
        let ends = [(l.first()?, false), (l.last()?, true)];
        ends.into_iter().find_map(|(p, reversed)| {
            let ds = at.y - p.y;
            let k = (ds / circumference_mm).round();
            let residual = ds - k * circumference_mm;
            ((at.x - p.x).hypot(residual) <= tolerance_mm).then_some((
                i,
                reversed,
                k * circumference_mm,
            ))
        })
    })
}

/// Wraps `delta_s` into `[-C/2, C/2)`: the short way round.
pub fn short_way_mm(delta_s_mm: f64, circumference_mm: f64) -> f64 {
    delta_s_mm - circumference_mm * (delta_s_mm / circumference_mm).round()
}

/// `p` moved onto the nearest of `corners` when one is within `tolerance_mm`.
fn snap(p: Coord<f64>, corners: &[Coord<f64>], tolerance_mm: f64) -> Coord<f64> {
    corners
        .iter()
        .map(|c| (*c, (c.x - p.x).hypot(c.y - p.y)))
        .filter(|(_, d)| *d <= tolerance_mm)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(p, |(c, _)| c)
}

fn open_ring(ring: &LineString<f64>) -> Vec<Coord<f64>> {
    let mut pts: Vec<Coord<f64>> = ring.coords().copied().collect();
    if pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    pts
}

fn s_range(mp: &MultiPolygon<f64>) -> (f64, f64) {
    mp.0.iter()
        .flat_map(|p| p.exterior().coords())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c.y), hi.max(c.y))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;
    use geo::polygon;

    #[test]
    fn notch_split_at_the_seam_joins_into_one_rectangle() {
        // A BSN notch centred at s = 0, drawn in the window [0, C): one piece at the bottom,
        // one at the top.
        let c = 5.0265;
        let bottom =
            polygon![(x: 1.0, y: 0.0), (x: 1.5, y: 0.0), (x: 1.5, y: 0.825), (x: 1.0, y: 0.825)];
        let top = polygon![(x: 1.0, y: c - 0.825), (x: 1.5, y: c - 0.825), (x: 1.5, y: c), (x: 1.0, y: c)];
        let ring = join_outline(&[bottom, top], c).unwrap();
        let (lo, hi) = ring
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.y), hi.max(p.y))
            });
        assert_abs_diff_eq!(hi - lo, 1.65, epsilon = 1e-12);
        assert!(
            (lo + 0.825).abs() < 1e-12 || (hi - c - 0.825).abs() < 1e-12,
            "{lo} {hi}"
        );
    }

    #[test]
    fn separate_outlines_are_refused() {
        let a = polygon![(x: 0.0, y: 0.0), (x: 1.0, y: 0.0), (x: 1.0, y: 1.0), (x: 0.0, y: 1.0)];
        let b = polygon![(x: 3.0, y: 0.0), (x: 4.0, y: 0.0), (x: 4.0, y: 1.0), (x: 3.0, y: 1.0)];
        assert!(matches!(
            join_outline(&[a, b], 10.0),
            Err(SeamError::Disjoint { outlines: 2, .. })
        ));
    }

    #[test]
    fn lines_chain_across_the_seam_and_in_either_direction() {
        let c = 10.0;
        let xy = |v: &[(f64, f64)]| v.iter().map(|&(x, y)| Coord { x, y }).collect::<Vec<_>>();
        let lines = vec![
            ("arm", xy(&[(0.0, 9.0), (0.0, 10.0)])),
            ("lead", xy(&[(5.0, 1.0), (0.0, 1.0)])), // runs towards the arm's continuation
            ("arm2", xy(&[(0.0, 0.0), (0.0, 1.0)])),
            ("other", xy(&[(7.0, 7.0), (8.0, 7.0)])),
        ];
        let chains = chain_lines(lines, c, 1e-9);
        assert_eq!(chains.len(), 2);
        let (tags, line) = &chains[0];
        assert_eq!(tags, &vec!["arm", "arm2", "lead"]);
        assert_eq!(line.len(), 4);
        assert_abs_diff_eq!(line[2].y, 11.0, epsilon = 1e-12);
        assert_abs_diff_eq!(line[3].x, 5.0, epsilon = 1e-12);
        assert_abs_diff_eq!(short_way_mm(9.0, c), -1.0, epsilon = 1e-12);
        assert_abs_diff_eq!(short_way_mm(-6.0, c), 4.0, epsilon = 1e-12);
    }
}
