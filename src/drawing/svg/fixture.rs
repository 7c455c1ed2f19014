//! Hand-built layouts for the SVG tests, made directly from the frame described in
//! [`crate::layout`]: notches centred at `s = π·r_o` (and `s = 0` for BSN), the sensor U-traces
//! centred at `s = 0` (and `π·r_o`), leads to square-spiral pads, the parting cut at the end.
//! Unlike `Layout::from_design`, they take the seam as an argument, so the tests can force
//! features to be split at the seam.

use std::f64::consts::PI;

use dlw_geometry::NotchStyle;
use geo::{Coord, LineString, Polygon};

use crate::design::Design;
use crate::layout::{Layout, Notch, Trace};

/// A layout for `design` whose drawing window starts at `seam_s_mm`.
pub(crate) fn layout_for(design: &Design, seam_s_mm: f64) -> Layout {
    let d = &design.file;
    let fab = &d.fabrication;
    let ro = d.outer_radius_mm;
    let circ = 2.0 * PI * ro;
    let window = Window {
        seam: seam_s_mm,
        circ,
    };
    let (h, c, n) = (d.notch_width_mm, d.notch_spacing_mm, d.notch_count);
    let x_first = fab.distal_margin_mm;
    let notched = f64::from(n) * h + f64::from(n - 1) * c;
    let x_end = x_first + notched;
    let sides: &[usize] = match d.style {
        NotchStyle::Uan => &[0],
        NotchStyle::Bsn => &[0, 1],
    };
    let mut notches = Vec::new();
    for level in 0..n as usize {
        let x0 = x_first + level as f64 * (h + c);
        for &side in sides {
            let centre = if side == 0 { PI * ro } else { 0.0 };
            let outline = window
                .split_band(centre - d.notch_arc_mm / 2.0, d.notch_arc_mm)
                .into_iter()
                .map(|(s0, s1)| rect(x0, x0 + h, s0, s1))
                .collect();
            notches.push(Notch {
                joint: None,
                level,
                side,
                outline,
            });
        }
    }
    let pad_size = 2.0 * f64::from(fab.pad_turns) * fab.pad_pitch_mm;
    let x_pad = x_end + fab.lead_length_mm + pad_size / 2.0;
    let (mut sensors, mut leads, mut pads) = (Vec::new(), Vec::new(), Vec::new());
    for sensor in 0..d.style.sensor_count() as usize {
        let centre = if sensor == 0 { 0.0 } else { PI * ro };
        let (lo, hi) = (
            centre - d.sensor_arc_mm / 2.0,
            centre + d.sensor_arc_mm / 2.0,
        );
        let xb = x_first / 2.0;
        sensors.push(Trace {
            sensor,
            pieces: window.split_line(&[(x_end, lo), (xb, lo), (xb, hi), (x_end, hi)]),
        });
        for (arm, sign) in [(lo, -1.0), (hi, 1.0)] {
            let pad_centre = centre + sign * (pad_size + fab.pad_gap_mm) / 2.0;
            let spiral = spiral(x_pad, pad_centre, fab.pad_pitch_mm, fab.pad_turns);
            let start = spiral[0];
            let xm = x_end + fab.lead_length_mm / 2.0;
            leads.push(Trace {
                sensor,
                pieces: window.split_line(&[(x_end, arm), (xm, arm), (xm, start.1), start]),
            });
            pads.push(Trace {
                sensor,
                pieces: window.split_line(&spiral),
            });
        }
    }
    let length = x_pad + pad_size / 2.0 + fab.proximal_margin_mm;
    Layout {
        name: d.name.clone(),
        outer_radius_mm: ro,
        circumference_mm: circ,
        seam_s_mm,
        trace_width_mm: fab.trace_width_mm,
        kerf_mm: fab.kerf_mm,
        length_mm: length,
        notches,
        sensors,
        leads,
        pads,
        parting: vec![LineString::from(vec![
            (length, seam_s_mm),
            (length, seam_s_mm + circ),
        ])],
    }
}

/// A square spiral centred at `(x, s)`, from its outer end inward.
fn spiral(x: f64, s: f64, pitch: f64, turns: u32) -> Vec<(f64, f64)> {
    let mut pts = vec![(x, s)];
    let (mut px, mut ps) = (x, s);
    let dirs = [(0.0, 1.0), (-1.0, 0.0), (0.0, -1.0), (1.0, 0.0)];
    for leg in 0..(4 * turns) as usize {
        let len = pitch * ((leg / 2) + 1) as f64;
        let (dx, ds) = dirs[leg % 4];
        px += dx * len;
        ps += ds * len;
        pts.push((px, ps));
    }
    pts.reverse();
    pts
}

fn rect(x0: f64, x1: f64, s0: f64, s1: f64) -> Polygon<f64> {
    Polygon::new(
        LineString::from(vec![(x0, s0), (x1, s0), (x1, s1), (x0, s1), (x0, s0)]),
        vec![],
    )
}

struct Window {
    seam: f64,
    circ: f64,
}

impl Window {
    fn wrap(&self, s: f64) -> f64 {
        self.seam + (s - self.seam).rem_euclid(self.circ)
    }

    /// The band `[start, start + len]` on the circle, as one or two intervals in the window.
    fn split_band(&self, start: f64, len: f64) -> Vec<(f64, f64)> {
        let lo = self.wrap(start);
        let top = self.seam + self.circ;
        if lo + len <= top {
            vec![(lo, lo + len)]
        } else {
            vec![(lo, top), (self.seam, self.seam + (lo + len - top))]
        }
    }

    /// A polyline on the circle, cut where it crosses the seam, each piece in the window.
    fn split_line(&self, pts: &[(f64, f64)]) -> Vec<LineString<f64>> {
        let mut pieces = Vec::new();
        let Some(&(x0, s0)) = pts.first() else {
            return pieces;
        };
        // Turns above the window of the current point.
        let turn = |s: f64| ((s - self.seam) / self.circ).floor();
        let mut k = turn(s0);
        let mut cur = vec![Coord {
            x: x0,
            y: s0 - k * self.circ,
        }];
        for w in pts.windows(2) {
            let ((xa, sa), (xb, sb)) = (w[0], w[1]);
            let kb = turn(sb);
            while k != kb {
                let up = kb > k;
                let edge = self.seam
                    + if up {
                        (k + 1.0) * self.circ
                    } else {
                        k * self.circ
                    };
                let t = (edge - sa) / (sb - sa);
                let xe = xa + t * (xb - xa);
                cur.push(Coord {
                    x: xe,
                    y: edge - k * self.circ,
                });
                pieces.push(LineString::new(std::mem::take(&mut cur)));
                k += if up { 1.0 } else { -1.0 };
                cur.push(Coord {
                    x: xe,
                    y: edge - k * self.circ,
                });
            }
            cur.push(Coord {
                x: xb,
                y: sb - k * self.circ,
            });
        }
        pieces.push(LineString::new(cur));
        pieces
    }
}

/// The shipped design `designs/<stem>.toml`.
pub(crate) fn design(stem: &str) -> Design {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("designs")
        .join(format!("{stem}.toml"));
    Design::load(&path).unwrap()
}

/// A design outside the paper: a thin 3 mm UAN tube, 14 notches of unequal width and spacing,
/// a joint length longer than the notched length and a wider trace.
pub(crate) fn outside_design() -> Design {
    Design::from_toml(
        r#"
name = "Thin 3 mm UAN, 14 notches"
style = "uan"
outer_radius_mm = 1.5
inner_radius_mm = 1.35
notch_arc_mm = 6.0
notch_width_mm = 0.3
notch_spacing_mm = 0.7
notch_count = 14
joint_length_mm = 14.0
sensor_arc_mm = 1.2

[fabrication]
trace_width_mm = 0.08
distal_margin_mm = 1.5
lead_length_mm = 1.5
pad_pitch_mm = 0.15
pad_turns = 3
"#,
    )
    .unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_line_cuts_at_the_seam() {
        let w = Window {
            seam: 0.0,
            circ: 10.0,
        };
        let pieces = w.split_line(&[(0.0, 8.0), (4.0, 12.0)]);
        assert_eq!(pieces.len(), 2);
        let a: Vec<_> = pieces[0].coords().map(|c| (c.x, c.y)).collect();
        let b: Vec<_> = pieces[1].coords().map(|c| (c.x, c.y)).collect();
        assert_eq!(a, vec![(0.0, 8.0), (2.0, 10.0)]);
        assert_eq!(b, vec![(2.0, 0.0), (4.0, 2.0)]);
        assert_eq!(w.split_band(8.0, 4.0), vec![(8.0, 10.0), (0.0, 2.0)]);
        assert_eq!(w.split_band(-3.0, 2.0), vec![(7.0, 9.0)]);
    }
}
