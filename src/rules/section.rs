//! Rules on the cross-section: radii, notch arc, BSN pair, sensor arc.

use core::f64::consts::PI;

use dlw_geometry::{CrossSection, Joint, Mechanics, NotchStyle};

use crate::design::DesignFile;

use super::Violation;

/// `r_i < r_o`; `s_n < 2π·r_o` (UAN) or `s_n < π·r_o` (BSN, the pair must not overlap); the
/// sensor's arms on the backbone. Values that are not positive are reported by the dimension
/// rules, so these only run on positive values.
pub(crate) fn check(file: &DesignFile, out: &mut Vec<Violation>) {
    let (ro, ri, sn, ss) = (
        file.outer_radius_mm,
        file.inner_radius_mm,
        file.notch_arc_mm,
        file.sensor_arc_mm,
    );
    let ok = |v: f64| v.is_finite() && v > 0.0;
    if ok(ro) && ok(ri) && ri >= ro {
        out.push(Violation::InnerRadius {
            inner_mm: ri,
            outer_mm: ro,
        });
    }
    if !(ok(ro) && ok(sn)) {
        return;
    }
    let circumference_mm = 2.0 * PI * ro;
    let notch_fits = match file.style {
        NotchStyle::Uan if sn >= circumference_mm => {
            out.push(Violation::NotchArc {
                notch_arc_mm: sn,
                circumference_mm,
            });
            false
        }
        NotchStyle::Bsn if 2.0 * sn >= circumference_mm => {
            out.push(Violation::PairOverlap {
                notch_arc_mm: sn,
                half_mm: PI * ro,
            });
            false
        }
        _ => true,
    };
    if notch_fits && ok(ss) {
        let (min_mm, max_mm) = match file.style {
            NotchStyle::Uan => (0.0, circumference_mm - sn),
            NotchStyle::Bsn => (sn, PI * ro),
        };
        if ss <= min_mm || ss >= max_mm {
            out.push(Violation::SensorArc {
                sensor_arc_mm: ss,
                min_mm,
                max_mm,
            });
        }
    }
}

/// Whatever else the geometry crate refuses (a sensor on the neutral plane, a tendon outside
/// the lumen), once the rules
/// above pass.
pub(crate) fn check_geometry(file: &DesignFile, out: &mut Vec<Violation>) {
    let built = CrossSection::new(
        file.style,
        file.outer_radius_mm,
        file.inner_radius_mm,
        file.notch_arc_mm,
        file.sensor_arc_mm,
    )
    .and_then(|s| {
        Joint::new(
            s,
            file.notch_width_mm,
            file.notch_spacing_mm,
            file.notch_count,
            file.joint_length_mm,
        )
    })
    .and_then(|j| Mechanics::new(j, file.tendon_offset_mm()));
    if let Err(e) = built {
        out.push(Violation::Geometry(e));
    }
}
