//! Every difference between the design's own layout and a drawing's: notches added, removed,
//! moved, resized or reshaped; sensor traces, leads and pads changed; the parting line moved;
//! numbers (kerf, trace width) that differ.
//!
//! Notches are matched by their centres, round the cylinder: pairs are taken nearest first, and
//! a pair further apart than half the least distance between two of the design's notch centres
//! is not a match (the drawn notch is "added", the design's "removed").

use geo::{Area, BoundingRect, LineString};

use crate::layout::{Layout, Notch, Trace};

/// Lines are ASCII: the program header carries them as G-code comments.
///
/// Changes smaller than this are not differences (mm, mm²).
const SAME: f64 = 1e-6;

/// A notch's box: `x` range, `s` range unwrapped across the seam, area.
struct NotchBox {
    label: String,
    x: [f64; 2],
    s: [f64; 2],
    area_mm2: f64,
}

impl NotchBox {
    fn of(notch: &Notch, bsn: bool, c_mm: f64) -> Option<Self> {
        let mut x = [f64::INFINITY, f64::NEG_INFINITY];
        let mut s: Option<[f64; 2]> = None;
        for piece in &notch.outline {
            let r = piece.bounding_rect()?;
            x = [x[0].min(r.min().x), x[1].max(r.max().x)];
            let (lo, hi) = (r.min().y, r.max().y);
            s = Some(match s {
                None => [lo, hi],
                Some([a, b]) => {
                    // The piece shifted by whole turns to sit next to what we have.
                    let gap = |k: f64| (lo + k * c_mm - b).max(a - (hi + k * c_mm)).max(0.0);
                    let k = [-1.0, 0.0, 1.0]
                        .into_iter()
                        .min_by(|p, q| gap(*p).total_cmp(&gap(*q)))
                        .unwrap_or(0.0);
                    [a.min(lo + k * c_mm), b.max(hi + k * c_mm)]
                }
            });
        }
        Some(Self {
            label: notch.label(bsn),
            x,
            s: s?,
            area_mm2: notch.outline.iter().map(|p| p.unsigned_area()).sum(),
        })
    }

    fn centre(&self) -> (f64, f64) {
        ((self.x[0] + self.x[1]) / 2.0, (self.s[0] + self.s[1]) / 2.0)
    }

    fn describe(&self) -> String {
        format!(
            "x {:.4}..{:.4} mm, s {:.4}..{:.4} mm",
            self.x[0], self.x[1], self.s[0], self.s[1]
        )
    }
}

/// `(Δx, Δs)` from `a` to `b`, with `Δs` the short way round.
fn delta(a: (f64, f64), b: (f64, f64), c_mm: f64) -> (f64, f64) {
    let ds = (b.1 - a.1 + c_mm / 2.0).rem_euclid(c_mm) - c_mm / 2.0;
    (b.0 - a.0, ds)
}

/// `v` with its sign to 4 decimals, never `-0.0000`.
fn signed(v: f64) -> String {
    if v.abs() < 5e-5 {
        "+0.0000".into()
    } else {
        format!("{v:+.4}")
    }
}

/// Every difference, one line each; empty when the drawing is the design's own layout.
pub(super) fn differences(design: &Layout, drawing: &Layout) -> Vec<String> {
    let mut out = Vec::new();
    let c_mm = design.circumference_mm;
    for (what, a, b) in [
        ("kerf", design.kerf_mm, drawing.kerf_mm),
        ("trace width", design.trace_width_mm, drawing.trace_width_mm),
    ] {
        if (a - b).abs() > SAME {
            out.push(format!(
                "{what}: the drawing was made for {b} mm, the design says {a} mm (the design's is used)"
            ));
        }
    }
    notch_differences(design, drawing, c_mm, &mut out);
    for (what, a, b) in [
        ("U-trace", &design.sensors, &drawing.sensors),
        ("lead", &design.leads, &drawing.leads),
        ("pad", &design.pads, &drawing.pads),
    ] {
        trace_differences(what, a, b, &mut out);
    }
    if (design.length_mm - drawing.length_mm).abs() > SAME {
        out.push(format!(
            "parting line moved from x = {:.4} mm to x = {:.4} mm",
            design.length_mm, drawing.length_mm
        ));
    }
    out
}

fn notch_differences(design: &Layout, drawing: &Layout, c_mm: f64, out: &mut Vec<String>) {
    let bsn_a = design.notches.iter().any(|n| n.side == 1);
    let bsn_b = drawing.notches.iter().any(|n| n.side == 1);
    let a: Vec<NotchBox> = design
        .notches
        .iter()
        .filter_map(|n| NotchBox::of(n, bsn_a, c_mm))
        .collect();
    let b: Vec<NotchBox> = drawing
        .notches
        .iter()
        .filter_map(|n| NotchBox::of(n, bsn_b, c_mm))
        .collect();
    let dist = |p: &NotchBox, q: &NotchBox| {
        let (dx, ds) = delta(p.centre(), q.centre(), c_mm);
        dx.hypot(ds)
    };
    // Both lists by centre x, so that only notches near in x are compared (a design may have
    // thousands).
    let by_x = |boxes: &[NotchBox]| {
        let mut order: Vec<usize> = (0..boxes.len()).collect();
        order.sort_by(|&i, &j| boxes[i].centre().0.total_cmp(&boxes[j].centre().0));
        order
    };
    let (order_a, order_b) = (by_x(&a), by_x(&b));
    let mut reach = f64::INFINITY;
    for (k, &i) in order_a.iter().enumerate() {
        for &j in &order_a[k + 1..] {
            if a[j].centre().0 - a[i].centre().0 >= 2.0 * reach {
                break;
            }
            reach = reach.min(dist(&a[i], &a[j]) / 2.0);
        }
    }
    let xs_b: Vec<f64> = order_b.iter().map(|&j| b[j].centre().0).collect();
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, p) in a.iter().enumerate() {
        let x = p.centre().0;
        let from = xs_b.partition_point(|v| *v <= x - reach);
        for &j in &order_b[from..] {
            if b[j].centre().0 >= x + reach {
                break;
            }
            let d = dist(p, &b[j]);
            if d < reach {
                pairs.push((d, i, j));
            }
        }
    }
    pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
    let (mut used_a, mut used_b) = (vec![false; a.len()], vec![false; b.len()]);
    let mut matched = Vec::new();
    for (_, i, j) in pairs {
        if !used_a[i] && !used_b[j] {
            used_a[i] = true;
            used_b[j] = true;
            matched.push((i, j));
        }
    }
    matched.sort_unstable();
    for (i, j) in matched {
        let (p, q) = (&a[i], &b[j]);
        let mut changes = Vec::new();
        let (dx, ds) = delta(p.centre(), q.centre(), c_mm);
        if dx.abs() > SAME || ds.abs() > SAME {
            changes.push(format!(
                "moved by dx = {} mm, ds = {} mm",
                signed(dx),
                signed(ds)
            ));
        }
        let (w0, h0) = (p.x[1] - p.x[0], p.s[1] - p.s[0]);
        let (w1, h1) = (q.x[1] - q.x[0], q.s[1] - q.s[0]);
        if (w0 - w1).abs() > SAME || (h0 - h1).abs() > SAME {
            changes.push(format!(
                "resized from {w0:.4} x {h0:.4} mm to {w1:.4} x {h1:.4} mm (along x by s)"
            ));
        } else if (p.area_mm2 - q.area_mm2).abs() > SAME {
            changes.push(format!(
                "reshaped: area {:.6} mm^2 instead of {:.6} mm^2",
                q.area_mm2, p.area_mm2
            ));
        }
        if !changes.is_empty() {
            let label = if p.label == q.label {
                p.label.clone()
            } else {
                format!("{} (drawn as {})", p.label, q.label)
            };
            out.push(format!("{label} {}", changes.join(", ")));
        }
    }
    for (p, _) in a.iter().zip(&used_a).filter(|(_, u)| !**u) {
        out.push(format!("{} removed (was at {})", p.label, p.describe()));
    }
    for (q, _) in b.iter().zip(&used_b).filter(|(_, u)| !**u) {
        out.push(format!(
            "notch added at {} (drawn as {})",
            q.describe(),
            q.label
        ));
    }
}

/// Per sensor: the traces of one kind, as count, total length and extents.
fn trace_summary(traces: &[Trace], sensor: usize) -> Option<(usize, f64, [f64; 4])> {
    let lines: Vec<&LineString<f64>> = traces
        .iter()
        .filter(|t| t.sensor == sensor)
        .flat_map(|t| &t.pieces)
        .collect();
    if lines.is_empty() {
        return None;
    }
    let count = traces.iter().filter(|t| t.sensor == sensor).count();
    let mut length = 0.0;
    let mut ext = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for l in lines {
        for w in l.0.windows(2) {
            length += (w[1].x - w[0].x).hypot(w[1].y - w[0].y);
        }
        for c in &l.0 {
            ext = [
                ext[0].min(c.x),
                ext[1].max(c.x),
                ext[2].min(c.y),
                ext[3].max(c.y),
            ];
        }
    }
    Some((count, length, ext))
}

fn trace_differences(what: &str, design: &[Trace], drawing: &[Trace], out: &mut Vec<String>) {
    let sensors = design
        .iter()
        .chain(drawing)
        .map(|t| t.sensor + 1)
        .max()
        .unwrap_or(0);
    for sensor in 0..sensors {
        let name = format!("sensor {} {what}", sensor + 1);
        match (
            trace_summary(design, sensor),
            trace_summary(drawing, sensor),
        ) {
            (Some(_), None) => out.push(format!("{name}s removed")),
            (None, Some(_)) => out.push(format!("{name}s added")),
            (Some((n0, l0, e0)), Some((n1, l1, e1))) => {
                let mut changes = Vec::new();
                if n0 != n1 {
                    changes.push(format!("{n1} instead of {n0}"));
                }
                if (l0 - l1).abs() > SAME {
                    changes.push(format!("length {l1:.4} mm instead of {l0:.4} mm"));
                }
                if e0.iter().zip(&e1).any(|(a, b)| (a - b).abs() > SAME) {
                    changes.push(format!(
                        "extents x {:.4}..{:.4}, s {:.4}..{:.4} mm instead of x {:.4}..{:.4}, s {:.4}..{:.4} mm",
                        e1[0], e1[1], e1[2], e1[3], e0[0], e0[1], e0[2], e0[3]
                    ));
                }
                if !changes.is_empty() {
                    out.push(format!("{name}s changed: {}", changes.join(", ")));
                }
            }
            (None, None) => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use geo::{Coord, MapCoordsInPlace};

    use super::*;
    use crate::design::Design;

    fn layout(text: &str) -> Layout {
        Layout::from_design(&Design::from_toml(text).unwrap()).unwrap()
    }

    #[test]
    fn the_same_layout_has_no_differences() {
        for text in [
            include_str!("../../../designs/joint-b.toml"),
            include_str!("../../../designs/joint-c.toml"),
        ] {
            let l = layout(text);
            assert!(differences(&l, &l).is_empty());
        }
    }

    #[test]
    fn moved_removed_added_resized_and_trace_changes_are_listed() {
        let design = layout(include_str!("../../../designs/joint-a.toml"));
        let mut drawn = design.clone();
        for p in &mut drawn.notches[3].outline {
            p.map_coords_in_place(|c| Coord {
                x: c.x,
                y: c.y + 0.05,
            });
        }
        for p in &mut drawn.notches[5].outline {
            p.map_coords_in_place(|c| Coord {
                x: if c.x > 6.0 { c.x + 0.1 } else { c.x },
                y: c.y,
            });
        }
        let last = drawn.notches.pop().unwrap();
        let mut far = last.clone();
        for p in &mut far.outline {
            p.map_coords_in_place(|c| Coord {
                x: c.x,
                y: c.y - 3.0,
            });
        }
        drawn.notches.push(far);
        drawn.pads[0].pieces[0].0.pop();
        let d = differences(&design, &drawn);
        assert_eq!(d.len(), 5, "{d:#?}");
        assert!(
            d[0].starts_with("notch 4 moved by dx = +0.0000 mm, ds = +0.0500 mm"),
            "{d:#?}"
        );
        assert!(
            d[1].starts_with("notch 6 moved by dx = +0.0500 mm"),
            "{d:#?}"
        );
        assert!(d[1].contains("resized from 0.5000 x "), "{d:#?}");
        assert!(
            d[2].starts_with("notch 10 removed (was at x 10.0000..10.5000 mm"),
            "{d:#?}"
        );
        assert!(
            d[3].starts_with("notch added at x 10.0000..10.5000 mm"),
            "{d:#?}"
        );
        assert!(d[4].starts_with("sensor 1 pads changed: length"), "{d:#?}");
    }
}
