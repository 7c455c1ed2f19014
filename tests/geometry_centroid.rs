//! Eq. 2 checked against the centroid of the remaining annular section computed numerically
//! from `geo` polygons, to 1e-9 relative.
//!
//! The section left at a notch level is the annulus `r_i ≤ r ≤ r_o` minus the notch sector(s)
//! of angle `φ_n = s_n/r_o`. It is drawn as a polygon with `n` straight edges along each arc and
//! its centroid taken with `geo::Centroid`. An inscribed polygon's area and first moment differ
//! from the true section's by a series in even powers of the angular step, so Richardson
//! extrapolation of the centroid at `n` and `2n` edges, `(4·ȳ(2n) − ȳ(n))/3`, removes the `1/n²`
//! term and leaves `O(1/n⁴)`, far below 1e-9 at `n = 4096`.

use std::f64::consts::PI;

use dlw_geometry::{CrossSection, NotchStyle};
use geo::{Centroid, Coord, LineString, MultiPolygon, Polygon};

/// An annular sector centred on `centre_rad` (measured from +y), half-angle `half_rad`, with
/// `n` edges along each arc.
fn annular_sector(ro: f64, ri: f64, centre_rad: f64, half_rad: f64, n: usize) -> Polygon<f64> {
    let at = |r: f64, phi: f64| Coord {
        x: r * phi.sin(),
        y: r * phi.cos(),
    };
    let step = 2.0 * half_rad / n as f64;
    let mut ring: Vec<Coord> = (0..=n)
        .map(|k| at(ro, centre_rad - half_rad + k as f64 * step))
        .collect();
    ring.extend(
        (0..=n)
            .rev()
            .map(|k| at(ri, centre_rad - half_rad + k as f64 * step)),
    );
    Polygon::new(LineString::new(ring), vec![])
}

/// The section left at a notch level, as polygons.
fn remaining(style: NotchStyle, ro: f64, ri: f64, sn: f64, n: usize) -> MultiPolygon<f64> {
    let phi_n = sn / ro;
    match style {
        // Notch centred at φ = π: what is left is centred at φ = 0 with half-angle π − φ_n/2.
        NotchStyle::Uan => {
            MultiPolygon::new(vec![annular_sector(ro, ri, 0.0, PI - phi_n / 2.0, n)])
        }
        // Notches at φ = 0 and φ = π: two backbones centred at ±π/2, half-angle (π − φ_n)/2.
        NotchStyle::Bsn => MultiPolygon::new(vec![
            annular_sector(ro, ri, PI / 2.0, (PI - phi_n) / 2.0, n),
            annular_sector(ro, ri, -PI / 2.0, (PI - phi_n) / 2.0, n),
        ]),
    }
}

fn numeric_centroid_y(style: NotchStyle, ro: f64, ri: f64, sn: f64, n: usize) -> f64 {
    let y = |n| remaining(style, ro, ri, sn, n).centroid().unwrap().y();
    (4.0 * y(2 * n) - y(n)) / 3.0
}

/// (style, r_o, r_i, s_n, s_s): Table I's joints and sections well outside it.
const SECTIONS: &[(NotchStyle, f64, f64, f64, f64)] = &[
    (NotchStyle::Uan, 1.24, 0.875, 5.61, 0.4), // Joint A
    (NotchStyle::Uan, 0.8, 0.61, 3.52, 0.4),   // Joints B and D
    (NotchStyle::Uan, 0.6, 0.45, 2.4, 0.3),
    (NotchStyle::Uan, 2.0, 1.9, 1.0, 0.5), // thin wall, small notch
    (NotchStyle::Uan, 1.0, 0.2, 6.0, 0.1), // thick wall, notch nearly all round
    (NotchStyle::Uan, 1.0, 0.5, PI, 0.4),  // half the tube cut
];

#[test]
fn eq2_matches_the_numeric_centroid() {
    for &(style, ro, ri, sn, ss) in SECTIONS {
        let exact = CrossSection::new(style, ro, ri, sn, ss)
            .unwrap()
            .neutral_axis_mm();
        let numeric = numeric_centroid_y(style, ro, ri, sn, 4096);
        let relative = ((numeric - exact) / exact).abs();
        eprintln!(
            "r_o {ro}, r_i {ri}, s_n {sn}: ȳ = {exact:.12} mm, relative error {relative:.1e}"
        );
        assert!(
            relative < 1e-9,
            "r_o {ro}, r_i {ri}, s_n {sn}: Eq. 2 gives {exact}, polygons {numeric} (relative {relative:e})"
        );
    }
}

#[test]
fn the_extrapolation_is_what_reaches_1e_9() {
    // Without it, 4096 edges are not enough: the comparison above can fail.
    let (ro, ri, sn) = (1.24, 0.875, 5.61);
    let exact = CrossSection::new(NotchStyle::Uan, ro, ri, sn, 0.4)
        .unwrap()
        .neutral_axis_mm();
    let raw = remaining(NotchStyle::Uan, ro, ri, sn, 4096)
        .centroid()
        .unwrap()
        .y();
    assert!(
        ((raw - exact) / exact).abs() > 1e-8,
        "raw polygon already within 1e-8"
    );
    // A wrong half-angle (the notch's instead of the backbone's) is far off.
    let wrong = 2.0 * (sn / (2.0 * ro)).sin() * (ro.powi(3) - ri.powi(3))
        / (3.0 * (sn / (2.0 * ro)) * (ro * ro - ri * ri));
    let numeric = numeric_centroid_y(NotchStyle::Uan, ro, ri, sn, 4096);
    assert!(((numeric - wrong) / wrong).abs() > 1e-3);
}

#[test]
fn bsn_centroid_is_on_the_axis() {
    for (ro, ri, sn, ss) in [(0.8, 0.61, 1.65, 2.13), (1.0, 0.8, 1.5, 2.4)] {
        let exact = CrossSection::new(NotchStyle::Bsn, ro, ri, sn, ss)
            .unwrap()
            .neutral_axis_mm();
        assert_eq!(exact, 0.0);
        let numeric = numeric_centroid_y(NotchStyle::Bsn, ro, ri, sn, 4096);
        assert!(numeric.abs() < 1e-12 * ro, "BSN centroid y = {numeric}");
    }
}
