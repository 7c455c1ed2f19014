//! Outlines drawn as separate LINEs, ARCs and open polylines, joined end to end into closed
//! loops, the way a CAD tool's "join" does: two ends meet when they are within a stated
//! tolerance.

use std::collections::HashMap;
use std::f64::consts::TAU;

use geo::Coord;

use super::DxfImportError;

/// Most chords one arc is flattened into: enough for a 50 mm radius at 1 µm (a joint's whole
/// circumference is a few mm), and a bound on what one ARC entity can allocate.
pub(super) const MAX_ARC_SEGMENTS: usize = 1024;

/// The points of an arc from `start_deg` counter-clockwise to `end_deg`, flattened so that no
/// chord strays more than `tolerance_mm` from the arc; ends exact. `None` when that takes more
/// than [`MAX_ARC_SEGMENTS`] chords, or the numbers are not finite.
pub(super) fn flatten_arc(
    center: Coord,
    radius_mm: f64,
    start_deg: f64,
    end_deg: f64,
    tolerance_mm: f64,
) -> Option<Vec<Coord>> {
    let finite = [
        center.x,
        center.y,
        radius_mm,
        start_deg,
        end_deg,
        tolerance_mm,
    ];
    if !finite.iter().all(|v| v.is_finite()) || radius_mm <= 0.0 || tolerance_mm <= 0.0 {
        return None;
    }
    let a0 = start_deg.to_radians();
    let mut sweep = (end_deg.to_radians() - a0).rem_euclid(TAU);
    if sweep == 0.0 {
        sweep = TAU;
    }
    let step = if tolerance_mm < radius_mm {
        2.0 * (1.0 - tolerance_mm / radius_mm).acos()
    } else {
        sweep
    };
    let n = (sweep / step).ceil().max(1.0);
    if n > MAX_ARC_SEGMENTS as f64 {
        return None;
    }
    let n = n as usize;
    Some(
        (0..=n)
            .map(|i| {
                let a = a0 + sweep * i as f64 / n as f64;
                Coord {
                    x: center.x + radius_mm * a.cos(),
                    y: center.y + radius_mm * a.sin(),
                }
            })
            .collect(),
    )
}

fn dist(a: Coord, b: Coord) -> f64 {
    (a.x - b.x).hypot(a.y - b.y)
}

/// Chain ends in a grid of cells one tolerance wide, so that the ends near a point are found
/// without looking at every chain (a drawing may hold many thousands of LINEs).
struct Ends {
    cell_mm: f64,
    cells: HashMap<(i64, i64), Vec<(usize, bool)>>,
}

impl Ends {
    fn new(chains: &[Vec<Coord>], tolerance_mm: f64) -> Self {
        let mut ends = Self {
            cell_mm: tolerance_mm,
            cells: HashMap::new(),
        };
        for (i, c) in chains.iter().enumerate() {
            for (reversed, p) in [(false, c[0]), (true, c[c.len() - 1])] {
                ends.cells
                    .entry(ends.key(p))
                    .or_default()
                    .push((i, reversed));
            }
        }
        ends
    }

    fn key(&self, p: Coord) -> (i64, i64) {
        // `as` saturates, so huge coordinates share the last cell rather than wrap.
        (
            (p.x / self.cell_mm).floor() as i64,
            (p.y / self.cell_mm).floor() as i64,
        )
    }

    /// Every unused chain end within `tolerance_mm` of `p`, with whether the chain must be
    /// reversed to continue from `p`.
    fn within(
        &self,
        p: Coord,
        chains: &[Vec<Coord>],
        used: &[bool],
        tolerance_mm: f64,
    ) -> Vec<(usize, bool)> {
        let (kx, ky) = self.key(p);
        let mut out = Vec::new();
        for dx in -1..=1 {
            for dy in -1..=1 {
                let cell = (kx.saturating_add(dx), ky.saturating_add(dy));
                for &(i, reversed) in self.cells.get(&cell).into_iter().flatten() {
                    let c = &chains[i];
                    let end = if reversed { c[c.len() - 1] } else { c[0] };
                    if !used[i] && dist(p, end) <= tolerance_mm {
                        out.push((i, reversed));
                    }
                }
            }
        }
        out
    }

    /// The unused chain end nearest `p` within one cell, and whether the chain must be reversed
    /// to continue from `p`.
    fn nearest(
        &self,
        p: Coord,
        chains: &[Vec<Coord>],
        used: &[bool],
    ) -> Option<(usize, bool, f64)> {
        let (kx, ky) = self.key(p);
        let mut best: Option<(usize, bool, f64)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                let cell = (kx.saturating_add(dx), ky.saturating_add(dy));
                for &(i, reversed) in self.cells.get(&cell).into_iter().flatten() {
                    if used[i] {
                        continue;
                    }
                    let c = &chains[i];
                    let end = if reversed { c[c.len() - 1] } else { c[0] };
                    let d = dist(p, end);
                    if best.map_or(true, |b| d < b.2) {
                        best = Some((i, reversed, d));
                    }
                }
            }
        }
        best
    }
}

/// Joins open chains into closed loops (each without its closing point repeated). Ends within
/// `tolerance_mm` meet; a closed loop needs at least 3 corners.
///
/// # Errors
/// [`DxfImportError::OpenLoop`] naming the first loose end and how far the nearest other end is.
pub(super) fn join_loops(
    chains: Vec<Vec<Coord>>,
    layer: &'static str,
    tolerance_mm: f64,
) -> Result<Vec<Vec<Coord>>, DxfImportError> {
    let chains: Vec<Vec<Coord>> = chains
        .into_iter()
        .filter(|c| c.len() >= 2 && c.windows(2).any(|w| dist(w[0], w[1]) > tolerance_mm))
        .collect();
    let ends = Ends::new(&chains, tolerance_mm);
    let mut used = vec![false; chains.len()];
    let mut loops = Vec::new();
    for start in 0..chains.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut current = chains[start].clone();
        loop {
            let (first, last) = (current[0], current[current.len() - 1]);
            if current.len() >= 4 && dist(first, last) <= tolerance_mm {
                current.pop();
                loops.push(current);
                break;
            }
            match ends.nearest(last, &chains, &used) {
                Some((i, reversed, d)) if d <= tolerance_mm => {
                    used[i] = true;
                    let more = &chains[i];
                    if reversed {
                        current.extend(more.iter().rev().skip(1));
                    } else {
                        current.extend(more.iter().skip(1));
                    }
                }
                _ => {
                    // Only now look everywhere: how far is the nearest other end?
                    let others = chains
                        .iter()
                        .zip(&used)
                        .filter(|(_, u)| !**u)
                        .flat_map(|(c, _)| [c[0], c[c.len() - 1]]);
                    let own = (current.len() >= 3).then_some(first);
                    let nearest = others
                        .chain(own)
                        .map(|p| (dist(last, p), p))
                        .min_by(|a, b| a.0.total_cmp(&b.0));
                    let gap = match nearest {
                        Some((d, p)) => format!(
                            "is {d:.4} mm from the nearest other end, at x = {:.4} mm, s = {:.4} mm",
                            p.x, p.y
                        ),
                        None => "meets no other line".into(),
                    };
                    return Err(DxfImportError::OpenLoop {
                        layer,
                        x_mm: last.x,
                        s_mm: last.y,
                        gap,
                        tolerance_mm,
                    });
                }
            }
        }
    }
    Ok(loops)
}

/// Open lines chained end to end where exactly two ends meet (a node where three or more meet
/// is a junction and ends the chains there). Chains come in the order of their first line.
pub(super) fn chain_open(lines: Vec<Vec<Coord>>, tolerance_mm: f64) -> Vec<Vec<Coord>> {
    let lines: Vec<Vec<Coord>> = lines.into_iter().filter(|l| l.len() >= 2).collect();
    let ends = Ends::new(&lines, tolerance_mm);
    let mut used = vec![false; lines.len()];
    let none_used = vec![false; lines.len()];
    let mut out = Vec::new();
    for start in 0..lines.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut chain = lines[start].clone();
        for _ in 0..2 {
            loop {
                let last = chain[chain.len() - 1];
                // Every line end at this node, the chain's own included: two make a joint,
                // three or more a junction.
                let here = ends.within(last, &lines, &none_used, tolerance_mm);
                let next: Vec<_> = here.iter().filter(|(i, _)| !used[*i]).collect();
                let (2, [&(i, reversed)]) = (here.len(), &next[..]) else {
                    break;
                };
                used[i] = true;
                if reversed {
                    chain.extend(lines[i].iter().rev().skip(1));
                } else {
                    chain.extend(lines[i].iter().skip(1));
                }
                if dist(chain[0], chain[chain.len() - 1]) <= tolerance_mm {
                    break;
                }
            }
            chain.reverse();
        }
        out.push(chain);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn c(x: f64, y: f64) -> Coord {
        Coord { x, y }
    }

    #[test]
    fn lines_in_any_order_and_direction_join_into_a_rectangle() {
        let lines = vec![
            vec![c(1.0, 0.0), c(1.0, 2.0)],
            vec![c(0.0, 0.0), c(1.0, 0.0)],
            vec![c(0.0, 2.0), c(0.0, 0.0)],
            vec![c(0.0, 2.0), c(1.0, 2.0 + 5e-4)],
        ];
        let loops = join_loops(lines, "NOTCHES", 1e-3).unwrap();
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].len(), 4);
    }

    #[test]
    fn open_lines_chain_through_two_way_nodes_and_stop_at_junctions() {
        let lines = vec![
            vec![c(1.0, 0.0), c(2.0, 0.0)],
            vec![c(0.0, 0.0), c(1.0, 0.0)],
            vec![c(2.0, 1.0), c(2.0, 0.0)],
            // A junction at (5, 0): three lines meet.
            vec![c(5.0, 0.0), c(6.0, 0.0)],
            vec![c(5.0, 0.0), c(5.0, 1.0)],
            vec![c(4.0, 0.0), c(5.0, 0.0)],
        ];
        let chains = chain_open(lines, 1e-3);
        assert_eq!(
            chains[0],
            vec![c(0.0, 0.0), c(1.0, 0.0), c(2.0, 0.0), c(2.0, 1.0)]
        );
        assert_eq!(chains.len(), 4, "{chains:?}");
    }

    #[test]
    fn a_gap_wider_than_the_tolerance_is_named() {
        let lines = vec![
            vec![c(0.0, 0.0), c(1.0, 0.0)],
            vec![c(1.0, 0.0), c(1.0, 2.0)],
            vec![c(1.0, 2.0), c(0.0, 2.0)],
            vec![c(0.0, 2.0), c(0.0, 0.02)],
        ];
        let e = join_loops(lines, "NOTCHES", 1e-3).unwrap_err().to_string();
        assert!(
            e.contains("end at x = 0.0000 mm, s = 0.0200 mm is 0.0200 mm from the nearest other end, at x = 0.0000 mm, s = 0.0000 mm"),
            "{e}"
        );
    }

    #[test]
    fn many_lines_join_quickly() {
        // 20000 unit squares drawn as 80000 LINEs, shuffled by a fixed stride.
        let mut lines = Vec::new();
        for k in 0..20_000 {
            let x = 2.0 * k as f64;
            let p = [c(x, 0.0), c(x + 1.0, 0.0), c(x + 1.0, 1.0), c(x, 1.0)];
            for i in 0..4 {
                lines.push(vec![p[i], p[(i + 1) % 4]]);
            }
        }
        let n = lines.len();
        let shuffled: Vec<_> = (0..n).map(|i| lines[(i * 7919) % n].clone()).collect();
        let loops = join_loops(shuffled, "NOTCHES", 1e-3).unwrap();
        assert_eq!(loops.len(), 20_000);
        assert!(loops.iter().all(|l| l.len() == 4));
    }

    #[test]
    fn arcs_flatten_within_the_tolerance() {
        let pts = flatten_arc(c(0.0, 0.0), 1.0, 0.0, 90.0, 1e-4).unwrap();
        assert_relative_eq!(pts[0].x, 1.0);
        assert_relative_eq!(pts.last().unwrap().y, 1.0);
        for w in pts.windows(2) {
            let mid = c((w[0].x + w[1].x) / 2.0, (w[0].y + w[1].y) / 2.0);
            assert!(1.0 - mid.x.hypot(mid.y) <= 1e-4 + 1e-12);
        }
        // 350° → 10° goes the short way through 0°.
        let pts = flatten_arc(c(0.0, 0.0), 1.0, 350.0, 10.0, 1e-3).unwrap();
        assert!(pts.iter().all(|p| p.x > 0.98));
        // A 1 m arc at 1 µm needs too many chords; NaN is no arc.
        assert!(flatten_arc(c(0.0, 0.0), 1000.0, 0.0, 360.0, 1e-3).is_none());
        assert!(flatten_arc(c(0.0, f64::NAN), 1.0, 0.0, 90.0, 1e-3).is_none());
    }
}
