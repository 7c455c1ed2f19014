use core::f64::consts::PI;

use dlw_geometry::Joint;

use super::stations::Stations;

/// A notch before wrapping: an axis-aligned rectangle in `(x, s)` with `s` unwrapped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NotchRect {
    /// The robot joint it belongs to ([`super::Notch::joint`]).
    pub joint: Option<usize>,
    /// Position along the tube, 0 at the distal end.
    pub level: usize,
    /// 0 for the notch centred at `s = π·r_o`, 1 for BSN's notch centred at `s = 0`.
    pub side: usize,
    /// Distal edge (mm).
    pub x0_mm: f64,
    /// Proximal edge (mm).
    pub x1_mm: f64,
    /// Lower edge in `s`, unwrapped (mm).
    pub s0_mm: f64,
    /// Upper edge in `s`, unwrapped (mm).
    pub s1_mm: f64,
}

/// Arc-length centre of a notch side: side 0 at `π·r_o`, side 1 (BSN only) at `0`.
pub(crate) fn notch_centre_s_mm(side: usize, outer_radius_mm: f64) -> f64 {
    if side == 0 {
        PI * outer_radius_mm
    } else {
        0.0
    }
}

/// Every notch of the joint: `N` levels with `x_k = d + k·(h + c)`, each `h` wide and `s_n`
/// long around the tube, one per level for UAN and a pair at the same `x` for BSN.
pub(crate) fn notch_rects(joint: &Joint, stations: &Stations) -> Vec<NotchRect> {
    let section = joint.section();
    let sides = joint.style().notches_per_level() as usize;
    let half_arc_mm = section.notch_arc_mm() / 2.0;
    let mut rects = Vec::with_capacity(joint.notch_count() as usize * sides);
    for level in 0..joint.notch_count() as usize {
        let x0_mm = stations.notch_x_mm(level);
        for side in 0..sides {
            let centre_mm = notch_centre_s_mm(side, section.outer_radius_mm());
            rects.push(NotchRect {
                joint: None,
                level,
                side,
                x0_mm,
                x1_mm: x0_mm + joint.notch_width_mm(),
                s0_mm: centre_mm - half_arc_mm,
                s1_mm: centre_mm + half_arc_mm,
            });
        }
    }
    rects
}
