//! The mechanics (`dlw_geometry::Mechanics`, `docs/mechanics.md`) against an independent
//! implementation written here another way: the section's area, centroid, second moment and
//! farthest fibre by numerical integration and sampling over a polar grid of the material left
//! at a notch level (no closed forms), the stroke by summing small stroke steps through the
//! per-notch kinematics, the force from a moment balance. Run on the shipped joints, on other
//! tubes (a nitinol tube, a short notch where the outer corner is farthest) and on random
//! sections (proptest).

use std::f64::consts::PI;

use approx::assert_relative_eq;
use dlw_geometry::{CrossSection, FibreSide, Joint, Mechanics, NotchStyle};
use proptest::prelude::*;

/// Polar cells across the wall and round the tube: the integrals converge as 1/n² (midpoint
/// rule), so these give relative errors near 1e-6, far below the tolerances used.
const RADIAL_CELLS: usize = 60;
const ANGULAR_CELLS: usize = 7200;
/// Sub-samples per angular cell, to weigh the cells a notch edge cuts.
const ANGULAR_SUBSAMPLES: usize = 64;

/// The material left at a notch level: is the angle `phi` (from +y) on material?
fn on_material(style: NotchStyle, phi: f64, notch_rad: f64) -> bool {
    let from = |centre: f64| {
        let d = (phi - centre).rem_euclid(2.0 * PI);
        d.min(2.0 * PI - d)
    };
    match style {
        NotchStyle::Uan => from(PI) >= notch_rad / 2.0,
        NotchStyle::Bsn => from(PI) >= notch_rad / 2.0 && from(0.0) >= notch_rad / 2.0,
    }
}

/// Area, centroid `ȳ` and second moment about the centroid, by the midpoint rule on a polar
/// grid; a cell a notch edge cuts counts with the share of it on material.
struct Numeric {
    area: f64,
    y_bar: f64,
    second_moment: f64,
    farthest: f64,
    farthest_below: bool,
}

fn integrate(style: NotchStyle, ro: f64, ri: f64, sn: f64) -> Numeric {
    let notch_rad = sn / ro;
    let dr = (ro - ri) / RADIAL_CELLS as f64;
    let dphi = 2.0 * PI / ANGULAR_CELLS as f64;
    // Points and weights of the material cells.
    let mut cells = Vec::new();
    for k in 0..ANGULAR_CELLS {
        let phi = (k as f64 + 0.5) * dphi;
        // The share of the cell on material, from sub-samples: cells cut by a notch edge
        // count in part.
        let on = (0..ANGULAR_SUBSAMPLES)
            .filter(|&i| {
                let sub = (k as f64 + (i as f64 + 0.5) / ANGULAR_SUBSAMPLES as f64) * dphi;
                on_material(style, sub, notch_rad)
            })
            .count();
        if on == 0 {
            continue;
        }
        let share = on as f64 / ANGULAR_SUBSAMPLES as f64;
        for j in 0..RADIAL_CELLS {
            let r = ri + (j as f64 + 0.5) * dr;
            // Exact area of the annular cell, its centroid approximated by the midpoint.
            let w = 0.5 * ((r + dr / 2.0).powi(2) - (r - dr / 2.0).powi(2)) * dphi * share;
            cells.push((r * phi.cos(), w));
        }
    }
    let area: f64 = cells.iter().map(|(_, w)| w).sum();
    let y_bar = cells.iter().map(|(y, w)| y * w).sum::<f64>() / area;
    // Σ w·(y−ȳ)² plus each cell's own second moment is small; the grid is fine enough.
    let second_moment = cells.iter().map(|(y, w)| (y - y_bar).powi(2) * w).sum();
    // Farthest fibre: sample the material's boundary, the edges at r_i and r_o and the notch
    // faces, finely.
    let mut farthest = 0.0f64;
    let mut farthest_below = false;
    let samples = 20_000;
    for k in 0..=samples {
        let phi = 2.0 * PI * k as f64 / samples as f64;
        // Snap onto the notch edges so the corners themselves are sampled.
        for phi in [
            phi,
            PI - notch_rad / 2.0,
            PI + notch_rad / 2.0,
            notch_rad / 2.0,
        ] {
            if !on_material(style, phi, notch_rad - 1e-12) {
                continue;
            }
            for r in [ri, ro] {
                let d = r * phi.cos() - y_bar;
                if d.abs() > farthest + 1e-12 {
                    farthest = d.abs();
                    farthest_below = d < 0.0;
                }
            }
        }
    }
    Numeric {
        area,
        y_bar,
        second_moment,
        farthest,
        farthest_below,
    }
}

fn mechanics(style: NotchStyle, ro: f64, ri: f64, sn: f64, ss: f64, h: f64, n: u32) -> Mechanics {
    let c = 0.5;
    let length = f64::from(n) * h + f64::from(n - 1) * c;
    let joint = Joint::new(
        CrossSection::new(style, ro, ri, sn, ss).unwrap(),
        h,
        c,
        n,
        length,
    )
    .unwrap();
    Mechanics::new(joint, ri - 0.14).unwrap()
}

/// Joint angle from a stroke by walking it in small steps: each notch takes `δ/N` of the
/// step, its tendon side shortens by the step, the neutral plane keeps its length `h`
/// along the line `ȳ` (the angle of a notch is the stroke over the moment arm). Independent of
/// the closed form `θ = N·κ·s`.
fn angle_by_steps(m: &Mechanics, stroke_mm: f64) -> f64 {
    let steps = 1000;
    let y_bar = m.joint().section().neutral_axis_mm();
    let arm = m.tendon_offset_mm() + y_bar;
    let n = f64::from(m.joint().notch_count());
    (0..steps)
        .map(|_| (stroke_mm / steps as f64) / n / arm)
        .sum::<f64>()
        * n
}

/// The checks every tube gets.
fn check_tube(m: &Mechanics, expected_side: Option<FibreSide>) {
    let s = m.joint().section();
    let (ro, ri, sn) = (s.outer_radius_mm(), s.inner_radius_mm(), s.notch_arc_mm());
    let num = integrate(s.style(), ro, ri, sn);
    assert_relative_eq!(m.section_area_mm2(), num.area, max_relative = 1e-4);
    assert_relative_eq!(s.neutral_axis_mm(), num.y_bar, epsilon = 1e-4 * ro);
    assert_relative_eq!(
        m.second_moment_mm4(),
        num.second_moment,
        max_relative = 1e-3
    );
    let (d, side) = m.farthest_fibre();
    assert_relative_eq!(d, num.farthest, epsilon = 1e-4 * ro);
    if s.style() == NotchStyle::Uan {
        let below = matches!(side, FibreSide::NotchInnerEdge | FibreSide::NotchOuterEdge);
        assert_eq!(below, num.farthest_below, "{side:?}");
    }
    if let Some(want) = expected_side {
        assert_eq!(side, want);
    }
    // Stroke per degree: a 1° stroke bends 1°.
    let one_deg = m.stroke_per_deg_mm();
    assert_relative_eq!(
        angle_by_steps(m, one_deg).to_degrees(),
        1.0,
        max_relative = 1e-9
    );
    assert_relative_eq!(
        m.angle_from_stroke_rad(3.0 * one_deg).to_degrees(),
        3.0,
        max_relative = 1e-9
    );
    // Material strain at the limit angle: the farthest fibre at curvature θ_n/(N·h) effective.
    let lim = m.angle_at_material_strain_rad(0.03);
    let n = f64::from(m.joint().notch_count());
    let per_notch = lim / n;
    let kappa = per_notch / (m.joint().notch_width_mm() - per_notch * s.neutral_axis_mm());
    let eps = kappa * num.farthest / (1.0 + s.neutral_axis_mm() * kappa);
    assert_relative_eq!(eps, 0.03, max_relative = 1e-3);
    // Moment balance: tendon force × arm = E·I·κ_linear, κ_linear = θ_n/h.
    let e_pa = 2.5e9;
    let theta = 1f64.to_radians();
    let moment = e_pa * 1e-6 * num.second_moment * (theta / n) / m.joint().notch_width_mm();
    let force = moment / (m.tendon_offset_mm() + num.y_bar);
    assert_relative_eq!(m.tendon_force_per_deg_n(e_pa), force, max_relative = 2e-3);
}

#[test]
fn shipped_joints_match_the_independent_implementation() {
    let joints = [
        ("a", Some(FibreSide::NotchInnerEdge)),
        ("b", Some(FibreSide::NotchInnerEdge)),
        ("c", Some(FibreSide::NotchCorners)),
        ("d", Some(FibreSide::NotchInnerEdge)),
    ];
    for (name, side) in joints {
        let path = format!("{}/designs/joint-{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let design = dlw::design::Design::load(path.as_ref()).unwrap();
        check_tube(&design.mechanics, side);
    }
}

#[test]
fn other_tubes_match_the_independent_implementation() {
    // A nitinol-like 1.16/0.86 mm tube (York's wrist size), a thin polyimide tube with a short
    // notch (outer corner farthest), a deep notch on a thick tube, and a BSN on a large tube.
    check_tube(
        &mechanics(NotchStyle::Uan, 0.58, 0.43, 2.6, 0.3, 0.4, 6),
        None,
    );
    check_tube(
        &mechanics(NotchStyle::Uan, 1.0, 0.9, 0.6, 0.4, 0.5, 10),
        Some(FibreSide::NotchOuterEdge),
    );
    check_tube(
        &mechanics(NotchStyle::Uan, 1.5, 1.0, 7.0, 0.5, 0.6, 8),
        None,
    );
    check_tube(
        &mechanics(NotchStyle::Bsn, 1.25, 1.1, 2.0, 3.0, 0.3, 12),
        Some(FibreSide::NotchCorners),
    );
}

/// Joint D against the paper: the model's stroke per degree and the measured m_t.
#[test]
fn joint_d_model_against_the_papers_m_t() {
    let path = format!("{}/designs/joint-d.toml", env!("CARGO_MANIFEST_DIR"));
    let d = dlw::design::Design::load(path.as_ref()).unwrap();
    let model_deg_per_mm = 1.0 / d.mechanics.stroke_per_deg_mm();
    // (0.47 + 0.609011)·π/180 = 0.0188323 mm/°, 53.10 °/mm; the paper measured 35.49 °/mm, so
    // the bench took 1.50 times the model's stroke per degree.
    assert_relative_eq!(model_deg_per_mm, 53.10, epsilon = 0.01);
    let ratio = model_deg_per_mm / 35.49;
    assert!((ratio - 1.496).abs() < 0.001, "{ratio}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn random_uan_sections_match(
        ro in 0.4f64..2.0,
        wall_frac in 0.08f64..0.45,
        notch_frac in 0.1f64..0.85,
        h in 0.1f64..1.0,
        n in 1u32..30,
    ) {
        let ri = ro * (1.0 - wall_frac);
        prop_assume!(ri > 0.2);
        let sn = notch_frac * 2.0 * PI * ro;
        // A small sensor arc always sits on the backbone.
        let m = mechanics(NotchStyle::Uan, ro, ri, sn, 0.05 * ro, h, n);
        check_tube(&m, None);
        let (range, _) = m.usable_range_rad(0.02, 0.03);
        prop_assert!(range <= m.closing_angle_rad() + 1e-15);
        prop_assert!(range <= m.angle_at_material_strain_rad(0.03) + 1e-15);
        prop_assert!(range <= m.joint().angle_at_strain(0.02).abs() + 1e-15);
    }

    #[test]
    fn random_bsn_sections_match(
        ro in 0.4f64..2.0,
        wall_frac in 0.08f64..0.45,
        notch_frac in 0.05f64..0.45,
        n in 1u32..30,
    ) {
        let ri = ro * (1.0 - wall_frac);
        prop_assume!(ri > 0.2);
        let sn = notch_frac * 2.0 * PI * ro;
        let ss = (sn + PI * ro) / 2.0;
        let m = mechanics(NotchStyle::Bsn, ro, ri, sn, ss, 0.5, n);
        check_tube(&m, Some(FibreSide::NotchCorners));
    }
}

/// Values computed by hand (a calculator session, the formulas of docs/mechanics.md typed in
/// directly) for Joint A, Joint C and a nitinol tube of York's wrist size (r_o 0.58, r_i 0.43,
/// s_n 2.6 mm, h 0.4 mm, N 6, r_t 0.29 mm, E 75 GPa).
#[test]
fn hand_computed_values() {
    // (mechanics, E, stroke mm/°, d mm, material limit ° at 3 %, A mm², I mm⁴, F N/°)
    let load = |name: &str| {
        let path = format!("{}/designs/joint-{name}.toml", env!("CARGO_MANIFEST_DIR"));
        dlw::design::Design::load(path.as_ref()).unwrap().mechanics
    };
    let niti = mechanics(NotchStyle::Uan, 0.58, 0.43, 2.6, 0.3, 0.4, 6);
    let table = [
        (
            load("a"),
            2.5e9,
            0.0291564,
            0.377694,
            22.7548,
            0.678949,
            0.0150312,
            0.0785206,
        ),
        (
            load("c"),
            2.5e9,
            0.0082030,
            0.410997,
            20.9110,
            0.289089,
            0.0133919,
            0.248651,
        ),
        (
            niti,
            75e9,
            0.0127886,
            0.175515,
            23.5040,
            0.136382,
            0.000654128,
            0.486903,
        ),
    ];
    for (m, e, stroke, d, mat, area, i, f) in table {
        assert_relative_eq!(m.stroke_per_deg_mm(), stroke, max_relative = 1e-5);
        assert_relative_eq!(m.farthest_fibre().0, d, max_relative = 1e-5);
        assert_relative_eq!(
            m.angle_at_material_strain_rad(0.03).to_degrees(),
            mat,
            max_relative = 1e-5
        );
        assert_relative_eq!(m.section_area_mm2(), area, max_relative = 1e-5);
        assert_relative_eq!(m.second_moment_mm4(), i, max_relative = 1e-5);
        assert_relative_eq!(m.tendon_force_per_deg_n(e), f, max_relative = 1e-5);
    }
}
