//! Ordering the paths of one operation to keep rapid travel short: greedy nearest neighbour,
//! each path entered the way (direction, start corner) nearest to where the beam is.

use std::f64::consts::TAU;

use super::plan::{Path, Point};

/// Rapid distance over the surface from `from` to `to`, going the short way round.
pub fn rapid_distance_mm(from: Point, to: Point, outer_radius_mm: f64) -> f64 {
    let da = to.a_rad - from.a_rad;
    let da = da - TAU * (da / TAU).round();
    (to.x_mm - from.x_mm).hypot(outer_radius_mm * da)
}

/// `path` shifted by whole turns so that it starts within half a turn of `at`.
pub fn nearest_turn(path: &Path, at: Point) -> Path {
    let turns = ((at.a_rad - path.start().a_rad) / TAU).round();
    if turns == 0.0 {
        path.clone()
    } else {
        path.shifted(turns)
    }
}

/// The items in order, each as the chosen one of its ways in, plus where the beam ends and the
/// rapid travel. `items[i]` lists the ways to run item `i` (at least one).
pub fn nearest_neighbour(
    items: &[Vec<Path>],
    start: Point,
    passes: u32,
    outer_radius_mm: f64,
) -> (Vec<Path>, Point, f64) {
    let mut left: Vec<&Vec<Path>> = items.iter().filter(|w| !w.is_empty()).collect();
    let mut at = start;
    let mut travel = 0.0;
    let mut out = Vec::with_capacity(left.len());
    while !left.is_empty() {
        let mut best: Option<(usize, usize, f64)> = None;
        for (i, ways) in left.iter().enumerate() {
            for (j, way) in ways.iter().enumerate() {
                let d = rapid_distance_mm(at, way.start(), outer_radius_mm);
                if best.map_or(true, |(_, _, bd)| d < bd - 1e-12) {
                    best = Some((i, j, d));
                }
            }
        }
        let Some((i, j, d)) = best else { break };
        let chosen = nearest_turn(&left[i][j], at);
        travel += d;
        at = chosen.end_after(passes);
        out.push(chosen);
        left.remove(i);
    }
    (out, at, travel)
}

/// The same items in the given order, each entered its first way: the baseline the planner's
/// ordering is measured against.
pub fn given_order(
    items: &[Vec<Path>],
    start: Point,
    passes: u32,
    outer_radius_mm: f64,
) -> (Vec<Path>, Point, f64) {
    let mut at = start;
    let mut travel = 0.0;
    let mut out = Vec::with_capacity(items.len());
    for ways in items {
        let Some(first) = ways.first() else { continue };
        let chosen = nearest_turn(first, at);
        travel += rapid_distance_mm(at, chosen.start(), outer_radius_mm);
        at = chosen.end_after(passes);
        out.push(chosen);
    }
    (out, at, travel)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::toolpath::plan::Feature;
    use approx::assert_abs_diff_eq;

    fn line(x0: f64, x1: f64, a: f64) -> Vec<Path> {
        let p = |x| Point::new(x, a);
        let fwd = vec![p(x0), p(x1)];
        let rev: Vec<Point> = fwd.iter().rev().copied().collect();
        let way = |f: Vec<Point>, r: Vec<Point>| Path {
            feature: Feature::Parting,
            forward: f,
            reverse: Some(r),
            lead_in: false,
        };
        vec![way(fwd.clone(), rev.clone()), way(rev, fwd)]
    }

    #[test]
    fn nearest_neighbour_beats_layout_order_and_reverses_lines() {
        let items = vec![
            line(8.0, 9.0, 0.0),
            line(0.0, 1.0, 0.0),
            line(4.0, 5.0, 0.0),
        ];
        let (_, _, given) = given_order(&items, Point::new(0.0, 0.0), 1, 1.0);
        let (paths, end, planned) = nearest_neighbour(&items, Point::new(0.0, 0.0), 1, 1.0);
        assert_abs_diff_eq!(given, 8.0 + 9.0 + 3.0, epsilon = 1e-12);
        assert_abs_diff_eq!(planned, 0.0 + 3.0 + 3.0, epsilon = 1e-12);
        assert_eq!(end, Point::new(9.0, 0.0));
        assert_eq!(paths[1].start(), Point::new(4.0, 0.0));
    }

    #[test]
    fn rapids_take_the_short_way_round() {
        // A path drawn at a = 350° is entered at -10° from a = 0.
        let items = vec![line(0.0, 1.0, 350f64.to_radians())];
        let (paths, _, travel) = nearest_neighbour(&items, Point::new(0.0, 0.0), 1, 1.0);
        assert_abs_diff_eq!(paths[0].start().a_rad, -10f64.to_radians(), epsilon = 1e-12);
        assert_abs_diff_eq!(travel, 10f64.to_radians(), epsilon = 1e-12);
    }
}
