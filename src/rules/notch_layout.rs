//! Rules on the notches as laid out or drawn: they lie inside the joint, do not overlap, and
//! leave a web between them wider than the kerf.
//!
//! A generated layout keeps these by construction (`notch_spacing_mm` > kerf, the distal and
//! proximal margins); a drawing a designer edited need not, so they run on every layout.
//!
//! - Inside the joint: every notch outline lies strictly between the free end `x = 0` and the
//!   parting line `x = length_mm` (the cutting beam then stays in the notch's own scrap).
//! - Overlap: two notch outlines that touch or overlap, round the cylinder, would cut one hole.
//! - Web: the least distance between two notch outlines, round the cylinder, must be larger than
//!   the kerf, the same limit the design rule puts on `notch_spacing_mm`.

use geo::BoundingRect;

use crate::layout::Layout;

use super::parts::{closest_on_cylinder, Part};
use super::Violation;

/// Checks the notches of `layout`.
pub(crate) fn check(layout: &Layout, out: &mut Vec<Violation>) {
    let bsn = layout.notches.iter().any(|n| n.side == 1);
    let kerf_mm = layout.kerf_mm;
    let mut boxes: Vec<(f64, f64, String, Part)> = Vec::new();
    for notch in &layout.notches {
        let label = notch.label(bsn);
        let (lo, hi) = notch
            .outline
            .iter()
            .filter_map(|p| p.bounding_rect())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
                (lo.min(r.min().x), hi.max(r.max().x))
            });
        if !(lo.is_finite() && hi.is_finite()) {
            continue;
        }
        if lo <= 0.0 {
            out.push(Violation::OutsideJoint {
                what: label.clone(),
                x_mm: lo,
                beyond: "the free end x = 0".into(),
                past_mm: -lo,
                length_mm: layout.length_mm,
            });
        }
        if hi >= layout.length_mm {
            out.push(Violation::OutsideJoint {
                what: label.clone(),
                x_mm: hi,
                beyond: format!("the parting line x = {:.4} mm", layout.length_mm),
                past_mm: hi - layout.length_mm,
                length_mm: layout.length_mm,
            });
        }
        let part = Part::from_polygons(&notch.outline, &label);
        boxes.push((lo, hi, label, part));
    }
    // Sweep along x: only notches whose x ranges come within the kerf can be too close.
    boxes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let c_mm = layout.circumference_mm;
    for (i, (_, hi, label, part)) in boxes.iter().enumerate() {
        for (lo_j, _, label_j, part_j) in &boxes[i + 1..] {
            if *lo_j > hi + kerf_mm {
                break;
            }
            let Some(hit) = closest_on_cylinder(part, part_j, c_mm, kerf_mm) else {
                continue;
            };
            let s_mm = layout.seam_s_mm + (hit.at.y - layout.seam_s_mm).rem_euclid(c_mm);
            if hit.distance_mm <= 0.0 {
                out.push(Violation::NotchOverlap {
                    what: label.clone(),
                    other: label_j.clone(),
                    x_mm: hit.at.x,
                    s_mm,
                });
            } else if hit.distance_mm <= kerf_mm {
                out.push(Violation::NotchWeb {
                    what: label.clone(),
                    other: label_j.clone(),
                    x_mm: hit.at.x,
                    s_mm,
                    web_mm: hit.distance_mm,
                    kerf_mm,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use geo::{Coord, LineString, MapCoordsInPlace, Polygon};

    use super::*;
    use crate::design::Design;
    use crate::layout::Notch;

    fn joint_a() -> Layout {
        let d = Design::from_toml(include_str!("../../designs/joint-a.toml")).unwrap();
        Layout::from_design(&d).unwrap()
    }

    fn shift(notch: &mut Notch, dx: f64) {
        for p in &mut notch.outline {
            p.map_coords_in_place(|c| Coord {
                x: c.x + dx,
                y: c.y,
            });
        }
    }

    fn messages(layout: &Layout) -> Vec<String> {
        let mut out = Vec::new();
        check(layout, &mut out);
        out.iter().map(ToString::to_string).collect()
    }

    #[test]
    fn the_generated_layout_passes() {
        assert!(messages(&joint_a()).is_empty());
    }

    #[test]
    fn a_notch_past_the_free_end_is_named_with_the_distance() {
        let mut l = joint_a();
        // Joint A's first notch starts at x = 1.0: move it 1.185 mm towards the free end.
        shift(&mut l.notches[0], -1.185);
        let m = messages(&l);
        assert_eq!(m.len(), 1, "{m:?}");
        assert!(
            m[0].starts_with("notch 1 reaches x = -0.1850 mm, 0.1850 mm past the free end x = 0"),
            "{m:?}"
        );
    }

    #[test]
    fn overlap_and_a_thin_web_are_named() {
        let mut l = joint_a();
        // Notch 2 starts 0.5 mm after notch 1 ends; move it 0.48 mm back: a 0.02 mm web.
        shift(&mut l.notches[1], -0.48);
        let m = messages(&l);
        assert_eq!(m.len(), 1, "{m:?}");
        assert!(
            m[0].contains("web between notch 1 and notch 2")
                && m[0].contains("is 0.0200 mm wide")
                && m[0].ends_with("kerf kerf_mm = 0.03"),
            "{m:?}"
        );
        shift(&mut l.notches[1], -0.1);
        let m = messages(&l);
        assert!(
            m[0].starts_with("notch 1 overlaps notch 2 at x = "),
            "{m:?}"
        );
    }

    #[test]
    fn a_notch_past_the_parting_line_is_refused() {
        let mut l = joint_a();
        l.notches.push(Notch {
            joint: None,
            level: 10,
            side: 0,
            outline: vec![Polygon::new(
                LineString::from(vec![(13.0, 3.0), (13.5, 3.0), (13.5, 4.0), (13.0, 4.0)]),
                vec![],
            )],
        });
        let m = messages(&l);
        assert!(
            m.iter()
                .any(|m| m.starts_with("notch 11 reaches x = 13.5000 mm")
                    && m.contains("past the parting line x = 13.3000 mm")),
            "{m:?}"
        );
    }
}
