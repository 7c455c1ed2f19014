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
