//! Notch pieces grouped into notches; level and side from the geometry.

use geo::{Area, BoundingRect, Polygon};

use super::xdata::LayoutNumbers;
use crate::layout::Notch;

/// A notch polygon as read, with its tag (notch index, piece) if it had one.
pub(super) type NotchPiece = (Option<(i16, i16)>, Polygon<f64>);
/// The pieces of one notch (numbered), under its tag's notch index if it had one.
type NotchGroup = (Option<i16>, Vec<(i16, Polygon<f64>)>);

/// Notch pieces grouped into notches, with level and side from their geometry.
pub(super) fn notches(pieces: Vec<NotchPiece>, numbers: &LayoutNumbers) -> Vec<Notch> {
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
                    joint: None,
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
        // The first edge within 1 µm (the edges are sorted).
        let at = edges.partition_point(|e| *e < *x0 - 1e-3);
        notch.level = if edges.get(at).is_some_and(|e| (*e - *x0).abs() <= 1e-3) {
            at
        } else {
            0
        };
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
    let single = |g: &NotchGroup| match g {
        (None, list) if list.len() == 1 => list[0].1.bounding_rect(),
        _ => None,
    };
    let boxes: Vec<_> = groups.iter().map(single).collect();
    // Pieces starting on the seam, by their distal edge, for a binary search (a drawing may
    // hold thousands of hand-drawn notches).
    let mut bottoms: Vec<(f64, usize)> = boxes
        .iter()
        .enumerate()
        .filter_map(|(j, b)| {
            b.filter(|b| (b.min().y - seam_mm).abs() <= TOL_MM)
                .map(|b| (b.min().x, j))
        })
        .collect();
    bottoms.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut partner: Vec<Option<usize>> = vec![None; groups.len()];
    let mut taken = vec![false; groups.len()];
    for (i, top) in boxes.iter().enumerate() {
        let Some(t) = top.filter(|t| (t.max().y - (seam_mm + c_mm)).abs() <= TOL_MM) else {
            continue;
        };
        if taken[i] {
            continue;
        }
        let from = bottoms.partition_point(|(x, _)| *x < t.min().x - TOL_MM);
        let found = bottoms[from..]
            .iter()
            .take_while(|(x, _)| *x <= t.min().x + TOL_MM)
            .map(|(_, j)| *j)
            .filter(|&j| {
                j != i
                    && !taken[j]
                    && partner[j].is_none()
                    && boxes[j].is_some_and(|b| (b.max().x - t.max().x).abs() <= TOL_MM)
            })
            .min();
        if let Some(j) = found {
            partner[i] = Some(j);
            taken[j] = true;
        }
    }
    let mut bottom_pieces: Vec<Option<Polygon<f64>>> = groups
        .iter_mut()
        .enumerate()
        .map(|(j, g)| {
            if taken[j] {
                g.1.pop().map(|(_, p)| p)
            } else {
                None
            }
        })
        .collect();
    let old = std::mem::take(groups);
    for (i, mut group) in old.into_iter().enumerate() {
        if taken[i] {
            continue;
        }
        if let Some(piece) = partner[i].and_then(|j| bottom_pieces[j].take()) {
            group.1.push((1, piece));
        }
        groups.push(group);
    }
}

#[cfg(test)]
mod tests {
    use geo::LineString;

    use super::*;

    fn rect(x0: f64, x1: f64, s0: f64, s1: f64) -> Polygon<f64> {
        Polygon::new(
            LineString::from(vec![(x0, s0), (x1, s0), (x1, s1), (x0, s1)]),
            vec![],
        )
    }

    #[test]
    fn thousands_of_seam_halves_pair_up_in_order() {
        // Window [0, 10): each notch's top half ends at s = 10, its bottom half starts at 0.
        let mut groups: Vec<NotchGroup> = Vec::new();
        let n = 10_000;
        for k in (0..n).rev() {
            let x = k as f64;
            groups.push((None, vec![(0, rect(x, x + 0.5, 0.0, 1.0))]));
        }
        for k in 0..n {
            let x = k as f64;
            groups.push((None, vec![(0, rect(x, x + 0.5, 9.0, 10.0))]));
        }
        groups.push((None, vec![(0, rect(0.2, 0.3, 4.0, 5.0))]));
        merge_seam_halves(&mut groups, 0.0, 10.0);
        assert_eq!(groups.len(), n + 1);
        // The lone notch stays; every top half now holds its bottom half as piece 1.
        assert_eq!(groups[n].1.len(), 1);
        for (k, (_, list)) in groups[..n].iter().enumerate() {
            assert_eq!(list.len(), 2);
            let top = list[0].1.bounding_rect().unwrap();
            let bottom = list[1].1.bounding_rect().unwrap();
            assert_eq!((top.min().x, top.max().y), (k as f64, 10.0));
            assert_eq!((bottom.min().x, bottom.min().y), (k as f64, 0.0));
        }
    }
}
