//! Outlines drawn as separate LINEs, ARCs and open polylines, joined end to end into closed
//! loops, the way a CAD tool's "join" does: two ends meet when they are within a stated
//! tolerance.

use std::f64::consts::TAU;

use geo::Coord;

use super::DxfImportError;

/// Most segments one arc is flattened into.
const MAX_ARC_SEGMENTS: usize = 4096;

/// The points of an arc from `start_deg` counter-clockwise to `end_deg`, flattened so that no
/// chord strays more than `tolerance_mm` from the arc; ends exact.
pub(super) fn flatten_arc(
    center: Coord,
    radius_mm: f64,
    start_deg: f64,
    end_deg: f64,
    tolerance_mm: f64,
) -> Vec<Coord> {
    let a0 = start_deg.to_radians();
    let mut sweep = (end_deg.to_radians() - a0).rem_euclid(TAU);
    if sweep == 0.0 {
        sweep = TAU;
    }
    let step = if tolerance_mm > 0.0 && tolerance_mm < radius_mm {
        2.0 * (1.0 - tolerance_mm / radius_mm).acos()
    } else {
        sweep
    };
    let n = ((sweep / step).ceil() as usize).clamp(1, MAX_ARC_SEGMENTS);
    (0..=n)
        .map(|i| {
            let a = a0 + sweep * i as f64 / n as f64;
            Coord {
                x: center.x + radius_mm * a.cos(),
                y: center.y + radius_mm * a.sin(),
            }
        })
        .collect()
}

fn dist(a: Coord, b: Coord) -> f64 {
    (a.x - b.x).hypot(a.y - b.y)
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
    let mut pool: Vec<Vec<Coord>> = chains
        .into_iter()
        .filter(|c| c.len() >= 2 && c.windows(2).any(|w| dist(w[0], w[1]) > tolerance_mm))
        .collect();
    let mut loops = Vec::new();
    while !pool.is_empty() {
        let mut current = pool.swap_remove(0);
        loop {
            let (first, last) = (current[0], current[current.len() - 1]);
            if current.len() >= 4 && dist(first, last) <= tolerance_mm {
                current.pop();
                loops.push(current);
                break;
            }
            // The chain whose end is nearest the loose end.
            let next = pool
                .iter()
                .enumerate()
                .flat_map(|(i, c)| {
                    [
                        (i, false, dist(last, c[0])),
                        (i, true, dist(last, c[c.len() - 1])),
                    ]
                })
                .min_by(|a, b| a.2.total_cmp(&b.2));
            match next {
                Some((i, reversed, d)) if d <= tolerance_mm => {
                    let mut more = pool.swap_remove(i);
                    if reversed {
                        more.reverse();
                    }
                    current.extend(more.into_iter().skip(1));
                }
                _ => {
                    let own = (current.len() >= 3).then(|| dist(last, first));
                    let nearest = next
                        .map(|(i, reversed, d)| {
                            let c = &pool[i];
                            (d, if reversed { c[c.len() - 1] } else { c[0] })
                        })
                        .into_iter()
                        .chain(own.map(|d| (d, first)))
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
    fn arcs_flatten_within_the_tolerance() {
        let pts = flatten_arc(c(0.0, 0.0), 1.0, 0.0, 90.0, 1e-4);
        assert_relative_eq!(pts[0].x, 1.0);
        assert_relative_eq!(pts.last().unwrap().y, 1.0);
        for w in pts.windows(2) {
            let mid = c((w[0].x + w[1].x) / 2.0, (w[0].y + w[1].y) / 2.0);
            assert!(1.0 - mid.x.hypot(mid.y) <= 1e-4 + 1e-12);
        }
        // 350° → 10° goes the short way through 0°.
        let pts = flatten_arc(c(0.0, 0.0), 1.0, 350.0, 10.0, 1e-3);
        assert!(pts.iter().all(|p| p.x > 0.98));
    }
}
