//! The cross-section through a notch (the paper's Fig. 3) as an SVG sheet.

use std::f64::consts::PI;

use dlw_geometry::{CrossSection, NotchStyle};

use super::annotate::{self, Dimension, Overflow, Table, SMALL_MM, TEXT_MM, THIN_MM};
use super::error::SvgError;
use super::layout::style_name;
use super::options::{Drawn, SvgOptions};
use super::palette;
use super::sheet::{fixed, Anchor, Sheet, TextStyle};
use crate::design::Design;

/// The sheet's layers, bottom first.
const LAYERS: [&str; 6] = [
    "section",
    "guides",
    "planes",
    "sensor",
    "dimensions",
    "labels",
];

/// An angular range `(φ0, φ1)` of the section (rad from `+y`).
type Sector = (f64, f64);

/// Arc flattening step (rad): half a degree keeps the chord within 1e-5·r of the circle.
const ARC_STEP_RAD: f64 = PI / 360.0;

/// The cross-section through a notch level as an SVG document, at the largest standard scale
/// at which the sheet fits A4 landscape. See [`section_svg_with`].
///
/// # Errors
/// See [`section_svg_with`].
pub fn section_svg(design: &Design) -> Result<String, SvgError> {
    section_svg_with(design, &SvgOptions::default())
}

/// The cross-section through a notch level as an SVG document (the paper's Fig. 3).
///
/// Drawn in the `dlw_geometry` cross-section frame: origin on the tube axis, `y` up toward the
/// UAN backbone, `φ` measured from `+y`. It shows the annulus `r_i … r_o` with the material the
/// notch removes (an angular sector of `φ_n = s_n/r_o`, centred at `φ = π` for UAN, at `φ = 0`
/// and `π` for BSN) in pale orange, the neutral plane `ȳ` (Eq. 2), the sensor arms at
/// `φ = ±φ_s/2` (and `π ± φ_s/2` for BSN's sensor 2) with the sensor plane `y_s` (Eq. 1), and
/// the offset `Δy = y_s − ȳ` (Eq. 3) as a dimension; for BSN also `Δy^(1,2) = 2·y_s`, the
/// distance between the sensor planes in the two-sensor angle (the paper's Eq. 7).
/// Every number comes from `dlw_geometry`.
///
/// # Errors
/// [`SvgError::BadScale`] for an unusable print scale. A validated [`Design`] always draws.
pub fn section_svg_with(design: &Design, options: &SvgOptions) -> Result<String, SvgError> {
    options.draw(|scale| draw(design, scale))
}

fn draw(design: &Design, scale: f64) -> Drawn {
    let sec = design.joint.section();
    let mut sheet = Sheet::new(scale, &LAYERS);
    draw_material(&mut sheet, sec);
    draw_centre_lines(&mut sheet, sec.outer_radius_mm());
    let columns = Columns::place(&sheet, sec);
    let lowest_plane = draw_planes(&mut sheet, sec, &columns);
    draw_sensor_arms(&mut sheet, sec, design.file.fabrication.trace_width_mm);
    draw_arm_labels(&mut sheet, sec);
    draw_offsets(&mut sheet, sec, columns);
    let radius_label_end = draw_radii(&mut sheet, sec);
    draw_numbers(&mut sheet, design, lowest_plane, radius_label_end);
    let notch_y = draw_notch_name(&mut sheet, sec);
    // The scale bar under everything.
    let ((min_x, _), _) = sheet.extent();
    let bar_y = notch_y + sheet.paper(5.0);
    annotate::scale_bar(&mut sheet, "labels", (min_x, bar_y));
    let title = draw_title(&mut sheet, design, scale);
    sheet.finish(&title, 6.0)
}

/// The material and the notch cut, as annular sectors `[φ0, φ1]`: the cut in pale orange
/// under the kept material.
fn draw_material(sheet: &mut Sheet, sec: &CrossSection) {
    let (ro, ri) = (sec.outer_radius_mm(), sec.inner_radius_mm());
    let phi_n = sec.notch_angle_rad();
    let (kept, cut): (Vec<Sector>, Vec<Sector>) = match sec.style() {
        NotchStyle::Uan => {
            let alpha = PI - phi_n / 2.0;
            (vec![(-alpha, alpha)], vec![(alpha, 2.0 * PI - alpha)])
        }
        NotchStyle::Bsn => (
            vec![
                (phi_n / 2.0, PI - phi_n / 2.0),
                (PI + phi_n / 2.0, 2.0 * PI - phi_n / 2.0),
            ],
            vec![
                (-phi_n / 2.0, phi_n / 2.0),
                (PI - phi_n / 2.0, PI + phi_n / 2.0),
            ],
        ),
    };
    let outline = sheet.pen(palette::OUTLINE, 0.35, None);
    let ghost_edge = sheet.pen(palette::NOTCH_EDGE, 0.2, Some(&[1.5, 1.0]));
    for (a, b) in &cut {
        let pts = annular_sector(ro, ri, *a, *b);
        sheet.path(
            "section",
            &pts,
            true,
            Some(palette::NOTCH_GHOST),
            Some(&ghost_edge),
            "notch-cut",
        );
    }
    for (a, b) in &kept {
        let pts = annular_sector(ro, ri, *a, *b);
        sheet.path(
            "section",
            &pts,
            true,
            Some(palette::SECTION_FILL),
            Some(&outline),
            "material",
        );
    }
}

/// Centre lines through the tube's axis, and the `+y` axis (`φ = 0`) as an arrow.
fn draw_centre_lines(sheet: &mut Sheet, ro: f64) {
    let r_ext = ro + sheet.paper(5.0);
    let centre = sheet.pen(palette::GUIDE, THIN_MM, Some(&[6.0, 1.5, 1.0, 1.5]));
    sheet.line("guides", (-r_ext, 0.0), (r_ext, 0.0), &centre);
    sheet.line("guides", (0.0, r_ext), (0.0, -r_ext), &centre);
    let axis = sheet.pen(palette::DIMENSION, THIN_MM, None);
    let y_tip = -(ro + sheet.paper(10.0));
    sheet.line("guides", (0.0, -r_ext), (0.0, y_tip), &axis);
    sheet.arrowhead("guides", (0.0, y_tip), (0.0, -1.0));
    let label = TextStyle::new(TEXT_MM, palette::DIMENSION);
    sheet.text(
        "labels",
        (sheet.paper(1.5), y_tip + sheet.paper(2.5)),
        "y (φ = 0)",
        label,
    );
    sheet.text(
        "labels",
        (sheet.paper(1.5), r_ext),
        "φ = 180°",
        TextStyle::new(SMALL_MM, palette::GUIDE),
    );
    sheet.circle(
        "guides",
        (0.0, 0.0),
        sheet.paper(0.6),
        Some(palette::DIMENSION),
        None,
        "axis",
    );
}

/// Where the offset dimensions stand right of the section. `Δy`'s label stands upright right
/// of its line, so `Δy^(1,2)` goes right of that label.
struct Columns {
    /// `Δy = y_s − ȳ`'s label.
    dy_label: String,
    /// x of `Δy`'s dimension line.
    col1: f64,
    /// x of `Δy^(1,2)`'s dimension line (BSN).
    col2: f64,
}

impl Columns {
    fn place(sheet: &Sheet, sec: &CrossSection) -> Self {
        let dy_label = format!("Δy = y_{{s}} − ȳ = {} mm", fixed(sec.offset_mm(), 3));
        let col1 = sec.outer_radius_mm() + sheet.paper(10.0);
        let col2 = col1
            + sheet.paper(5.0)
            + sheet.text_width(&dy_label, TextStyle::new(TEXT_MM, palette::DIMENSION));
        Self {
            dy_label,
            col1,
            col2,
        }
    }
}

/// The planes `ȳ`, `y_s` and, for BSN, `−y_s`, as lines running from their labels left of the
/// section to past the dimensions; returns the lowest plane's sheet y.
fn draw_planes(sheet: &mut Sheet, sec: &CrossSection, columns: &Columns) -> f64 {
    let ro = sec.outer_radius_mm();
    let style = sec.style();
    let y_bar = sec.neutral_axis_mm();
    let y_s = sec.sensor_plane_mm();
    let Columns { col1, col2, .. } = *columns;
    let x_right = match style {
        NotchStyle::Uan => col1,
        NotchStyle::Bsn => col2,
    } + sheet.paper(3.0);
    let x_left = -(ro + sheet.paper(6.0));
    let mut planes = vec![(
        y_bar,
        format!("neutral plane ȳ = {} mm", fixed(y_bar, 3)),
        palette::NEUTRAL,
        "neutral-plane",
    )];
    let sensor_names = match style {
        NotchStyle::Uan => ["sensor plane", ""],
        NotchStyle::Bsn => ["sensor 1 plane", "sensor 2 plane"],
    };
    planes.push((
        y_s,
        format!("{} y_{{s}} = {} mm", sensor_names[0], fixed(y_s, 3)),
        palette::SENSOR,
        "sensor-plane",
    ));
    if style == NotchStyle::Bsn {
        planes.push((
            -y_s,
            format!("{} −y_{{s}} = {} mm", sensor_names[1], fixed(-y_s, 3)),
            palette::SENSOR,
            "sensor-plane",
        ));
    }
    let text = TextStyle::new(TEXT_MM, palette::DIMENSION).anchor(Anchor::End);
    let wanted: Vec<f64> = planes.iter().map(|(y, ..)| -y).collect();
    let placed = spread(&wanted, sheet.paper(TEXT_MM * 1.6));
    for ((y, label, colour, class), ty) in planes.iter().zip(placed) {
        let pen = sheet.pen(colour, 0.3, Some(&[3.0, 1.5]));
        sheet.path(
            "planes",
            // ȳ only reaches Δy's column, so it stays clear of Δy^(1,2)'s label.
            &[
                (x_left, -y),
                (
                    if *class == "neutral-plane" {
                        col1 + sheet.paper(3.0)
                    } else {
                        x_right
                    },
                    -y,
                ),
            ],
            false,
            None,
            Some(&pen),
            class,
        );
        let tx = x_left - sheet.paper(2.0);
        if (ty - -y).abs() > 1e-9 {
            let lead = sheet.pen(colour, THIN_MM, None);
            sheet.line("planes", (tx + sheet.paper(0.5), ty), (x_left, -y), &lead);
        }
        sheet.text("labels", (tx, ty + sheet.paper(0.9)), label, text);
    }
    planes
        .iter()
        .map(|(y, ..)| -y)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The sensor arms on the outer surface at `φ = ±φ_s/2` (and `π ± φ_s/2` for BSN), as dots at
/// least the trace's width across.
fn draw_sensor_arms(sheet: &mut Sheet, sec: &CrossSection, trace_width_mm: f64) {
    let ro = sec.outer_radius_mm();
    let phi_s = sec.sensor_angle_rad();
    let arm_r = (trace_width_mm / 2.0).max(sheet.paper(0.9));
    let mut arms = vec![-phi_s / 2.0, phi_s / 2.0];
    if sec.style() == NotchStyle::Bsn {
        arms.extend([PI - phi_s / 2.0, PI + phi_s / 2.0]);
    }
    for phi in &arms {
        sheet.circle(
            "sensor",
            polar(ro, *phi),
            arm_r,
            Some(palette::SENSOR),
            None,
            "sensor-arm",
        );
    }
}

/// The sensor arms' labels on leaders, above or below the section.
fn draw_arm_labels(sheet: &mut Sheet, sec: &CrossSection) {
    let ro = sec.outer_radius_mm();
    let phi_s = sec.sensor_angle_rad();
    let arm_labels: Vec<(f64, String)> = match sec.style() {
        NotchStyle::Uan => vec![(
            phi_s / 2.0,
            format!(
                "sensor arms at φ = ±φ_{{s}}/2, s_{{s}} = {} mm (φ_{{s}} = {:.1}°)",
                fixed(sec.sensor_arc_mm(), 2),
                phi_s.to_degrees()
            ),
        )],
        NotchStyle::Bsn => vec![
            (
                phi_s / 2.0,
                format!(
                    "sensor 1 (tension at θ > 0): φ = ±φ_{{s}}/2, s_{{s}} = {} mm (φ_{{s}} = {:.1}°)",
                    fixed(sec.sensor_arc_mm(), 2),
                    phi_s.to_degrees()
                ),
            ),
            (
                PI - phi_s / 2.0,
                "sensor 2 (compression at θ > 0): φ = π ± φ_{s}/2".to_string(),
            ),
        ],
    };
    let leader = sheet.pen(palette::SENSOR, THIN_MM, None);
    for (phi, label) in arm_labels {
        let (ax, ay) = polar(ro, phi);
        let up = ay < 0.0;
        let ty = if up {
            -(ro + sheet.paper(9.0))
        } else {
            ro + sheet.paper(9.0)
        };
        let tx = ax.max(0.0) + sheet.paper(12.0);
        sheet.line("sensor", (ax, ay), (tx - sheet.paper(1.0), ty), &leader);
        sheet.text(
            "labels",
            (tx, ty + sheet.paper(0.9)),
            &label,
            TextStyle::new(TEXT_MM, palette::SENSOR),
        );
    }
}

/// `Δy` (and, for BSN, `Δy^(1,2)`) as dimensions right of the section.
fn draw_offsets(sheet: &mut Sheet, sec: &CrossSection, columns: Columns) {
    let y_bar = sec.neutral_axis_mm();
    let y_s = sec.sensor_plane_mm();
    let Columns {
        dy_label,
        col1,
        col2,
    } = columns;
    annotate::vertical(
        sheet,
        "dimensions",
        &Dimension {
            ends: (-y_s, -y_bar),
            at: col1,
            feature: (col1, col1),
            label: dy_label,
            overflow: Overflow::After,
            beside: true,
        },
    );
    if let Some(dy12) = sec.two_sensor_offset_mm() {
        annotate::vertical(
            sheet,
            "dimensions",
            &Dimension {
                ends: (-y_s, y_s),
                at: col2,
                feature: (col2, col2),
                label: format!("Δy^{{(1,2)}} = 2y_{{s}} = {} mm", fixed(dy12, 3)),
                overflow: Overflow::After,
                beside: true,
            },
        );
    }
}

/// The radii `r_o` and `r_i` on leaders below the centre line, away from the plane labels;
/// returns where `r_o`'s label ends (sheet x).
fn draw_radii(sheet: &mut Sheet, sec: &CrossSection) -> f64 {
    let (ro, ri) = (sec.outer_radius_mm(), sec.inner_radius_mm());
    let radius_pen = sheet.pen(palette::DIMENSION, THIN_MM, None);
    let mut radius_label_end: f64 = 0.0;
    for (r, phi, label, right) in [
        (
            ro,
            PI * 5.0 / 6.0,
            format!("r_{{o}} = {}", fixed(ro, 3)),
            true,
        ),
        (
            ri,
            -PI * 5.0 / 6.0,
            format!("r_{{i}} = {}", fixed(ri, 3)),
            false,
        ),
    ] {
        let tip = polar(r, phi);
        let elbow = polar(ro + sheet.paper(10.0), phi);
        let shoulder = sheet.paper(4.0);
        let end = (elbow.0 + if right { shoulder } else { -shoulder }, elbow.1);
        sheet.path(
            "dimensions",
            &[(0.0, 0.0), elbow, end],
            false,
            None,
            Some(&radius_pen),
            "radius",
        );
        sheet.arrowhead("dimensions", tip, tip);
        let anchor = if right { Anchor::Start } else { Anchor::End };
        let tx = end.0
            + if right {
                sheet.paper(1.0)
            } else {
                -sheet.paper(1.0)
            };
        let style = TextStyle::new(TEXT_MM, palette::DIMENSION).anchor(anchor);
        if right {
            radius_label_end = tx + sheet.text_width(&label, style);
        }
        sheet.text("labels", (tx, end.1 + sheet.paper(0.9)), &label, style);
    }
    radius_label_end
}

/// The table of numbers right of the section, below the planes and clear of `r_o`'s label.
fn draw_numbers(sheet: &mut Sheet, design: &Design, lowest_plane: f64, radius_label_end: f64) {
    let ro = design.joint.section().outer_radius_mm();
    let table = numbers(design, sheet);
    let table_x = (ro + sheet.paper(12.0)).max(radius_label_end + sheet.paper(4.0));
    // Bottom-aligned with the section unless the planes reach lower.
    let (_, table_h) = table.size(sheet);
    let table_y = (lowest_plane + sheet.paper(6.0)).max(ro - table_h);
    table.draw(sheet, "labels", (table_x, table_y));
}

/// The notch, named below everything drawn so far; returns the name's sheet y.
fn draw_notch_name(sheet: &mut Sheet, sec: &CrossSection) -> f64 {
    let phi_n = sec.notch_angle_rad();
    let notch_label = match sec.style() {
        NotchStyle::Uan => format!(
            "notch (pale orange): s_{{n}} = {} mm, φ_{{n}} = s_{{n}}/r_{{o}} = {:.1}°, centred at φ = 180°",
            fixed(sec.notch_arc_mm(), 2),
            phi_n.to_degrees()
        ),
        NotchStyle::Bsn => format!(
            "notches (pale orange): s_{{n}} = {} mm each, φ_{{n}} = {:.1}°, centred at φ = 0° and 180°",
            fixed(sec.notch_arc_mm(), 2),
            phi_n.to_degrees()
        ),
    };
    let ((_, _), (_, max_y)) = sheet.extent();
    let notch_y = max_y + sheet.paper(6.0);
    sheet.text(
        "labels",
        (0.0, notch_y),
        &notch_label,
        TextStyle::new(TEXT_MM, palette::NOTCH_EDGE).anchor(Anchor::Middle),
    );
    notch_y
}

/// The sheet's title above everything; returns it.
fn draw_title(sheet: &mut Sheet, design: &Design, scale: f64) -> String {
    let title = format!(
        "{} — section through a notch ({}), scale {}",
        design.file.name,
        style_name(design.joint.section().style()),
        annotate::scale_ratio(scale)
    );
    let ((min_x, min_y), _) = sheet.extent();
    sheet.text_plain(
        "labels",
        (min_x, min_y - sheet.paper(4.0)),
        &title,
        TextStyle::new(4.0, palette::OUTLINE).bold(),
    );
    title
}

fn numbers(design: &Design, sheet: &Sheet) -> Table {
    let j = &design.joint;
    let s = j.section();
    let mut rows = vec![
        (
            "neutral plane (Eq. 2)".to_string(),
            format!("ȳ = {} mm", fixed(s.neutral_axis_mm(), 3)),
        ),
        (
            "sensor plane (Eq. 1)".to_string(),
            format!(
                "y_{{s}} = r_{{o}}·cos(φ_{{s}}/2) = {} mm",
                fixed(s.sensor_plane_mm(), 3)
            ),
        ),
        (
            "offset (Eq. 3)".to_string(),
            format!("Δy = {} mm", fixed(s.offset_mm(), 3)),
        ),
    ];
    if let Some(dy12) = s.two_sensor_offset_mm() {
        rows.push((
            "two sensors (Eq. 7)".to_string(),
            format!("Δy^{{(1,2)}} = {} mm", fixed(dy12, 3)),
        ));
    }
    rows.extend([
        (
            "sensitivity".to_string(),
            format!(
                "dε/dθ = Δy/L = {} %/° (L = {} mm)",
                fixed(j.strain_per_deg() * 100.0, 4),
                fixed(j.length_mm(), 2)
            ),
        ),
        (
            "scale, units".to_string(),
            format!("{}, mm", annotate::scale_ratio(sheet.scale())),
        ),
    ]);
    Table {
        heading: format!(
            "{} — {} cross-section",
            design.file.name,
            style_name(s.style())
        ),
        rows,
    }
}

/// A point at radius `r` and angle `φ` from `+y`, in sheet coordinates (`y` down).
fn polar(r: f64, phi: f64) -> (f64, f64) {
    (r * phi.sin(), -r * phi.cos())
}

/// The outline of the annular sector `φ0 … φ1` between radii `ri` and `ro`.
fn annular_sector(ro: f64, ri: f64, phi0: f64, phi1: f64) -> Vec<(f64, f64)> {
    let n = (((phi1 - phi0).abs() / ARC_STEP_RAD).ceil() as usize).max(1);
    let at = |i: usize| phi0 + (phi1 - phi0) * i as f64 / n as f64;
    let outer = (0..=n).map(|i| polar(ro, at(i)));
    let inner = (0..=n).rev().map(|i| polar(ri, at(i)));
    outer.chain(inner).collect()
}

/// Positions for labels wanted at `ys` (sheet y), moved apart to at least `gap`, keeping
/// their order and staying as close to where they were wanted as a simple sweep allows.
fn spread(ys: &[f64], gap: f64) -> Vec<f64> {
    let mut order: Vec<usize> = (0..ys.len()).collect();
    order.sort_by(|a, b| ys[*a].total_cmp(&ys[*b]));
    let mut out = ys.to_vec();
    // Sweep down pushing labels apart, then centre each cluster on where it was wanted.
    let mut placed: Vec<f64> = Vec::new();
    for &i in &order {
        let y = match placed.last() {
            Some(prev) if ys[i] < prev + gap => prev + gap,
            _ => ys[i],
        };
        placed.push(y);
    }
    let wanted: Vec<f64> = order.iter().map(|&i| ys[i]).collect();
    let mut start = 0;
    while start < placed.len() {
        let mut end = start + 1;
        while end < placed.len() && placed[end] - placed[end - 1] <= gap + 1e-12 {
            end += 1;
        }
        let shift = (wanted[start..end].iter().sum::<f64>()
            - placed[start..end].iter().sum::<f64>())
            / (end - start) as f64;
        for p in &mut placed[start..end] {
            *p += shift;
        }
        start = end;
    }
    for (k, &i) in order.iter().enumerate() {
        out[i] = placed[k];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_keeps_far_labels_and_separates_near_ones() {
        assert_eq!(spread(&[0.0, 10.0], 3.0), vec![0.0, 10.0]);
        let s = spread(&[5.0, 5.5, 20.0], 3.0);
        assert!((s[1] - s[0] - 3.0).abs() < 1e-12, "{s:?}");
        assert!(((s[0] + s[1]) / 2.0 - 5.25).abs() < 1e-12, "{s:?}");
        assert_eq!(s[2], 20.0);
    }

    #[test]
    fn sectors_close_on_the_right_radii() {
        let pts = annular_sector(2.0, 1.0, -0.5, 0.5);
        let r: Vec<f64> = pts.iter().map(|(x, y)| x.hypot(*y)).collect();
        let half = pts.len() / 2;
        assert!(r[..half].iter().all(|v| (v - 2.0).abs() < 1e-12));
        assert!(r[half..].iter().all(|v| (v - 1.0).abs() < 1e-12));
        // φ = 0 is +y, which is up on the sheet.
        let (x, y) = polar(1.0, 0.0);
        assert!(x.abs() < 1e-15 && (y + 1.0).abs() < 1e-15);
    }
}
