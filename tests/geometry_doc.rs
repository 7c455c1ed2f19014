//! The worked numbers in `docs/geometry.md`, recomputed with the geometry crate: every figure
//! quoted there must be what the code gives, formatted as the page prints it.

use std::f64::consts::PI;
use std::path::Path;

use dlw::design::Design;
use dlw_geometry::Divider;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn design(stem: &str) -> Design {
    Design::load(&root().join("designs").join(format!("{stem}.toml"))).unwrap()
}

fn page() -> String {
    std::fs::read_to_string(root().join("docs/geometry.md")).unwrap()
}

/// The figures for one joint, as the page writes them.
fn figures(stem: &str, peak_deg: f64, gauge_factor: f64, r0_ohm: f64) -> Vec<String> {
    let d = design(stem);
    let j = &d.joint;
    let s = j.section();
    let divider = Divider::new(99.6e3, 5.0).unwrap();
    let close = j.closing_angle_rad();
    let mut out = vec![
        format!(
            "{:.4} rad ({:.2}°)",
            s.notch_angle_rad(),
            s.notch_angle_rad().to_degrees()
        ),
        format!(
            "{:.4} rad ({:.2}°)",
            s.sensor_angle_rad(),
            s.sensor_angle_rad().to_degrees()
        ),
        format!("{:.5} mm", s.sensor_plane_mm()),
        format!("{:.5} mm", s.offset_mm()),
        format!(
            "{:.6} /rad = {:.6} %/°",
            j.strain_per_rad(),
            j.strain_per_deg() * 100.0
        ),
        format!(
            "{peak_deg:.0}°: **{:.4} %**",
            j.strain(peak_deg.to_radians()) * 100.0
        ),
        format!("{close:.4} rad ({:.2}°)", close.to_degrees()),
        format!("{:.2} %", j.strain_at_closing() * 100.0),
        format!(
            "{:.5} mm, {:.2} %",
            s.backbone_reach_mm(),
            j.backbone_strain(close) * 100.0
        ),
        format!("{:.3} V", divider.voltage(r0_ohm)),
    ];
    let ratio = j.resistance_ratio_per_deg(gauge_factor) * 100.0;
    out.push(if ratio >= 0.1 {
        format!("{ratio:.4} %/°")
    } else {
        format!("{ratio:.5} %/°")
    });
    let mv = j.voltage_per_deg(gauge_factor, r0_ohm, &divider) * 1e3;
    out.push(if mv >= 1.0 {
        format!("{mv:.2} mV/°")
    } else {
        format!("{mv:.3} mV/°")
    });
    out
}

#[test]
fn joint_a_figures_match_the_page() {
    let page = page();
    let d = design("joint-a");
    let s = d.joint.section();
    let alpha = PI - s.notch_angle_rad() / 2.0;
    let mut wanted = figures("joint-a", 26.0, 15.3, 215e3);
    wanted.push(format!("{alpha:.5} rad ({:.2}°)", alpha.to_degrees()));
    wanted.push(format!(
        "ȳ = 2·0.77042·1.23670/(3·0.87950·0.77198) = {:.5} mm",
        s.neutral_axis_mm()
    ));
    for w in wanted {
        assert!(page.contains(&w), "docs/geometry.md lacks {w:?}");
    }
    // The step-by-step intermediate values.
    assert!((alpha.sin() - 0.77042).abs() < 5e-6);
    assert!((1.24f64.powi(3) - 0.875f64.powi(3) - 1.23670).abs() < 5e-6);
    assert!((1.24f64.powi(2) - 0.875f64.powi(2) - 0.77198).abs() < 5e-6);
    // The headline: ε(26°) ≈ 1.38 %.
    assert!((d.joint.strain(26f64.to_radians()) * 100.0 - 1.3774).abs() < 5e-5);
}

#[test]
fn joint_c_figures_match_the_page() {
    let page = page();
    let d = design("joint-c");
    let s = d.joint.section();
    let mut wanted = figures("joint-c", 40.0, 1.28, 74.0e3);
    wanted.push(format!("{:.5} mm |", s.two_sensor_offset_mm().unwrap()));
    for w in wanted {
        assert!(page.contains(&w), "docs/geometry.md lacks {w:?}");
    }
    assert_eq!(s.neutral_axis_mm(), 0.0);
    assert!((d.joint.strain(40f64.to_radians()) * 100.0 - 1.3949).abs() < 5e-5);
}

#[test]
fn the_figure_on_the_page_exists() {
    let page = page();
    assert!(page.contains("](img/joint-a-section.svg)"));
    assert!(root().join("docs/img/joint-a-section.svg").is_file());
    assert!(page.contains("[`docs/frames.md`](frames.md)"));
}
