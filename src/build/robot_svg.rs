//! A robot as an SVG sheet (`crate::robot`): the unrolled robot with each joint labelled
//! (number, design, style, rotation), every sensor's U-trace, leads and pads in a colour of
//! its own, and below it a side view of the straight robot with each joint's bending plane
//! marked in an end view. A robot of one joint is drawn as its joint ([`crate::drawing::svg::layout_svg`]).
//!
//! Frames: the unrolled view is the layout's (`x` right, `s` up, the window
//! `[seam, seam + C)`); the side view has the same `x`, and up is the tube's `+y` (the surface
//! line `s = 0`); the end views look from the distal end (the tip) toward the collet, `+y` up,
//! `φ` counter-clockwise, so a surface point at `s` lies at angle `s/r_o` from up.

use std::f64::consts::PI;

use crate::drawing::svg::annotate::{self, Table, SMALL_MM, TEXT_MM, THIN_MM};
use crate::drawing::svg::options::{Drawn, SvgOptions};
use crate::drawing::svg::palette;
use crate::drawing::svg::sheet::{fixed, Anchor, Sheet, TextStyle};
use crate::drawing::svg::SvgError;
use crate::layout::Layout;
use crate::robot::CheckedRobot;

/// The sheet's layers, bottom first.
const LAYERS: [&str; 9] = [
    "tube",
    "guides",
    "joints",
    "notches",
    "sensor",
    "leads-pads",
    "parting",
    "side",
    "labels",
];

/// One colour per sensor (robot-wide order), distinct from the notches' orange and from each
/// other in print; repeated past ten sensors.
pub const SENSOR_COLOURS: [&str; 10] = [
    "#1f5fd6", "#1e9e3a", "#8e2cc2", "#d6336c", "#0f8b8d", "#6b4f1d", "#4c6ef5", "#2b8a3e",
    "#c2255c", "#495057",
];

/// The colour of robot sensor `index`.
pub fn sensor_colour(index: usize) -> &'static str {
    SENSOR_COLOURS[index % SENSOR_COLOURS.len()]
}

/// The robot as an SVG document at the largest standard scale that fits A4 landscape.
///
/// # Errors
/// See [`robot_svg_with`].
pub fn robot_svg(robot: &CheckedRobot) -> Result<String, SvgError> {
    robot_svg_with(robot, &SvgOptions::default())
}

/// The robot as an SVG document.
///
/// # Errors
/// [`SvgError`] for a non-finite or non-positive layout value or an unusable print scale.
pub fn robot_svg_with(robot: &CheckedRobot, options: &SvgOptions) -> Result<String, SvgError> {
    if let [only] = robot.robot.joints.as_slice() {
        return crate::drawing::svg::layout_svg_with(&robot.layout, only.design(), options);
    }
    crate::drawing::svg::layout::check(&robot.layout)?;
    // The tube alone is `length` wide on the sheet: no scale above page width / length fits.
    let largest = crate::drawing::svg::options::PAGE_MM.0 / robot.layout.length_mm;
    options.draw_at_most(largest, |scale| draw(robot, scale))
}

fn draw(robot: &CheckedRobot, scale: f64) -> Drawn {
    let mut sheet = Sheet::new(scale, &LAYERS);
    tube(&mut sheet, &robot.layout);
    joints(&mut sheet, robot);
    cuts(&mut sheet, &robot.layout);
    let below = axes(&mut sheet, robot);
    let side_bottom = side_view(&mut sheet, robot, below);
    footer(&mut sheet, robot, side_bottom);
    let title = format!(
        "{} — unrolled robot, {} joints, scale {}",
        robot.robot.name,
        robot.robot.joints.len(),
        annotate::scale_ratio(scale)
    );
    let ((min_x, min_y), _) = sheet.extent();
    sheet.text_plain(
        "labels",
        (min_x, min_y - sheet.paper(4.0)),
        &title,
        TextStyle::new(4.0, palette::OUTLINE).bold(),
    );
    sheet.finish(&title, 6.0)
}

/// The unrolled view's sheet point of layout point `(x, s)`.
fn unrolled(layout: &Layout) -> impl Fn(f64, f64) -> (f64, f64) {
    let top = layout.seam_s_mm + layout.circumference_mm;
    move |x: f64, s: f64| (x, top - s)
}

/// The tube, unrolled.
fn tube(sheet: &mut Sheet, layout: &Layout) {
    let pt = unrolled(layout);
    let top = layout.seam_s_mm + layout.circumference_mm;
    let length = layout.length_mm;
    let outline = sheet.pen(palette::OUTLINE, 0.35, None);
    sheet.rect(
        "tube",
        pt(0.0, layout.seam_s_mm),
        pt(length, top),
        Some(palette::TUBE_FILL),
        Some(&outline),
        "tube",
    );
}

/// Each joint's +y line over its own stretch, its label, and its bracket below the tube.
fn joints(sheet: &mut Sheet, robot: &CheckedRobot) {
    let layout = &robot.layout;
    let c = layout.circumference_mm;
    let pt = unrolled(layout);
    let wrap = |s: f64| layout.seam_s_mm + (s - layout.seam_s_mm).rem_euclid(c);
    let guide = sheet.pen(palette::GUIDE, THIN_MM, Some(&[6.0, 1.5, 1.0, 1.5]));
    let bracket = sheet.pen(palette::OUTLINE, 0.25, None);
    let label = TextStyle::new(SMALL_MM, palette::OUTLINE).anchor(Anchor::Middle);
    for (i, j) in robot.robot.joints.iter().enumerate() {
        let d = &j.design().file;
        let (x0, x1) = (j.x_start_mm(), j.x_end_mm());
        let margin = d.fabrication.distal_margin_mm;
        let (_, y) = pt(0.0, wrap(j.rotation_s_mm()));
        sheet.line(
            "guides",
            (x0 - margin / 2.0, y),
            (x1 + margin / 2.0, y),
            &guide,
        );
        sheet.text(
            "labels",
            (x1 + margin / 2.0 + sheet.paper(1.0), y + sheet.paper(0.7)),
            &format!("+y_{{{}}}", i + 1),
            TextStyle::new(SMALL_MM, palette::GUIDE),
        );
        let yb = -sheet.paper(3.0);
        let tick = sheet.paper(1.5);
        sheet.path(
            "joints",
            &[(x0, yb + tick), (x0, yb), (x1, yb), (x1, yb + tick)],
            false,
            None,
            Some(&bracket),
            "joint",
        );
        sheet.text_plain(
            "labels",
            ((x0 + x1) / 2.0, yb - sheet.paper(1.2)),
            &format!(
                "joint {}: {} ({}), {}°",
                i + 1,
                d.name,
                j.style_name(),
                fixed(j.rotation_deg, 1)
            ),
            label,
        );
    }
}

/// Notches, then each sensor's traces in its colour, then the parting cut.
fn cuts(sheet: &mut Sheet, layout: &Layout) {
    let pt = unrolled(layout);
    let edge = sheet.pen(palette::NOTCH_EDGE, 0.15, None);
    for n in &layout.notches {
        for poly in &n.outline {
            let mut pts: Vec<(f64, f64)> = poly.exterior().coords().map(|p| pt(p.x, p.y)).collect();
            if pts.len() > 1 && pts.first() == pts.last() {
                pts.pop();
            }
            sheet.path(
                "notches",
                &pts,
                true,
                Some(palette::NOTCH_FILL),
                Some(&edge),
                "notch",
            );
        }
    }
    for (layer, class, traces) in [
        ("sensor", "sensor", &layout.sensors),
        ("leads-pads", "lead", &layout.leads),
        ("leads-pads", "pad", &layout.pads),
    ] {
        for t in traces {
            let pen = crate::drawing::svg::sheet::Pen {
                colour: sensor_colour(t.sensor),
                width: layout.trace_width_mm,
                dash: None,
            };
            for piece in &t.pieces {
                let pts: Vec<(f64, f64)> = piece.coords().map(|p| pt(p.x, p.y)).collect();
                sheet.path(layer, &pts, false, None, Some(&pen), class);
            }
        }
    }
    let parting = sheet.pen(palette::PARTING, 0.45, Some(&[3.0, 1.5]));
    for line in &layout.parting {
        let pts: Vec<(f64, f64)> = line.coords().map(|p| pt(p.x, p.y)).collect();
        sheet.path("parting", &pts, false, None, Some(&parting), "parting");
    }
}

/// x ticks under the tube, s ticks left of it; returns the sheet y below them.
fn axes(sheet: &mut Sheet, robot: &CheckedRobot) -> f64 {
    let layout = &robot.layout;
    let c = layout.circumference_mm;
    let length = layout.length_mm;
    let tick = sheet.pen(palette::GUIDE, THIN_MM, None);
    let small = TextStyle::new(SMALL_MM, palette::DIMENSION);
    let tick_len = sheet.paper(1.2);
    let step = [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0]
        .into_iter()
        .find(|s| s * sheet.scale() >= 10.0)
        .unwrap_or(50.0);
    let mut x = 0.0;
    while x <= length + 1e-9 {
        sheet.line("guides", (x, c), (x, c + tick_len), &tick);
        sheet.text(
            "labels",
            (x, c + tick_len + sheet.paper(SMALL_MM + 0.5)),
            &fixed(x, usize::from(step < 1.0)),
            small.anchor(Anchor::Middle),
        );
        x += step;
    }
    let (s0, s1) = (layout.seam_s_mm, layout.seam_s_mm + c);
    let s_step = [0.5, 1.0, 2.0, 5.0]
        .into_iter()
        .find(|s| s * sheet.scale() >= 8.0)
        .unwrap_or(5.0);
    let mut i = (s0 / s_step).ceil() as i64;
    while (i as f64) * s_step <= s1 + 1e-9 {
        let s = i as f64 * s_step;
        let y = s1 - s;
        sheet.line("guides", (0.0, y), (-tick_len, y), &tick);
        sheet.text(
            "labels",
            (-tick_len - sheet.paper(0.8), y + sheet.paper(0.7)),
            &fixed(s, 1),
            small.anchor(Anchor::End),
        );
        i += 1;
    }
    let y = c + sheet.paper(10.0);
    sheet.text(
        "labels",
        (length / 2.0, y),
        &format!(
            "x (mm) along the tube: distal end 0 → parting cut {}; s (mm, left) = r_{{o}}·φ round the tube, seam at s = {} mm (top and bottom edges)",
            fixed(length, 2),
            fixed(layout.seam_s_mm, 2)
        ),
        TextStyle::new(SMALL_MM, palette::DIMENSION).anchor(Anchor::Middle),
    );
    y + sheet.paper(4.0)
}

/// The straight robot seen from the side (up = `+y`, the line `s = 0`), notches projected,
/// with an end view of each joint's bending plane above it. Returns the sheet y below it.
fn side_view(sheet: &mut Sheet, robot: &CheckedRobot, top: f64) -> f64 {
    let layout = &robot.layout;
    let r_o = layout.outer_radius_mm;
    let length = layout.length_mm;
    let glyph = sheet.paper(5.0);
    let centre_y = top + sheet.paper(16.0) + 2.0 * glyph + r_o;
    let side = |x: f64, y: f64| (x, centre_y - y);
    let text = TextStyle::new(SMALL_MM, palette::DIMENSION);
    sheet.text(
        "labels",
        (0.0, top + sheet.paper(4.0)),
        "side view of the straight robot (up = +y, the surface line s = 0), notches projected; above each joint its bending plane, seen from the tip (+y up, φ counter-clockwise)",
        text,
    );
    let outline = sheet.pen(palette::OUTLINE, 0.35, None);
    sheet.rect(
        "side",
        side(0.0, -r_o),
        side(length, r_o),
        Some(palette::TUBE_FILL),
        Some(&outline),
        "side-tube",
    );
    let axis = sheet.pen(palette::GUIDE, THIN_MM, Some(&[6.0, 1.5, 1.0, 1.5]));
    sheet.line(
        "side",
        side(-sheet.paper(3.0), 0.0),
        side(length + sheet.paper(3.0), 0.0),
        &axis,
    );
    let edge = sheet.pen(palette::NOTCH_EDGE, 0.15, None);
    for n in &layout.notches {
        let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for poly in &n.outline {
            let ss: Vec<f64> = poly.exterior().coords().map(|p| p.y).collect();
            for p in poly.exterior().coords() {
                x0 = x0.min(p.x);
                x1 = x1.max(p.x);
            }
            let (a, b) = ss
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
                    (a.min(*s), b.max(*s))
                });
            // The height range of the arc [a, b] on the surface: cos over it.
            let (pa, pb) = (a / r_o, b / r_o);
            let mut ys = vec![pa.cos(), pb.cos()];
            let k0 = (pa / PI).ceil() as i64;
            let k1 = (pb / PI).floor() as i64;
            for k in k0..=k1 {
                ys.push((k as f64 * PI).cos());
            }
            for y in ys {
                lo = lo.min(r_o * y);
                hi = hi.max(r_o * y);
            }
        }
        if x0.is_finite() && lo.is_finite() {
            sheet.rect(
                "side",
                side(x0, lo),
                side(x1, hi),
                Some(palette::NOTCH_FILL),
                Some(&edge),
                "side-notch",
            );
        }
    }
    // The bending plane of each joint, seen from the tip.
    let ring = sheet.pen(palette::OUTLINE, 0.3, None);
    let plane = sheet.pen(palette::NEUTRAL, 0.35, None);
    let arrow = sheet.pen(palette::DIMENSION, 0.3, None);
    for (i, j) in robot.robot.joints.iter().enumerate() {
        let cx = (j.x_start_mm() + j.x_end_mm()) / 2.0;
        let cy = centre_y - r_o - sheet.paper(4.0) - glyph;
        let phi = j.rotation_rad();
        // Direction of the surface point at φ, seen from the tip: (−sin φ, cos φ), y up.
        let dir = |phi: f64| (-phi.sin(), -phi.cos());
        let (ux, uy) = dir(phi);
        sheet.circle(
            "side",
            (cx, cy),
            glyph,
            Some("#ffffff"),
            Some(&ring),
            "end-view",
        );
        sheet.line(
            "side",
            (cx - 1.3 * glyph * ux, cy - 1.3 * glyph * uy),
            (cx + 1.3 * glyph * ux, cy + 1.3 * glyph * uy),
            &plane,
        );
        sheet.circle(
            "side",
            (cx + glyph * ux, cy + glyph * uy),
            sheet.paper(0.6),
            Some(palette::SENSOR),
            None,
            "backbone",
        );
        let tip = (cx - 1.6 * glyph * ux, cy - 1.6 * glyph * uy);
        sheet.line("side", (cx, cy), tip, &arrow);
        sheet.arrowhead("side", tip, (-ux, -uy));
        sheet.text(
            "labels",
            (cx + 1.6 * glyph + sheet.paper(2.5), cy + sheet.paper(0.7)),
            &format!(
                "joint {}: plane at {}°, bends toward −y_{{{}}}",
                i + 1,
                fixed(j.rotation_deg, 0),
                i + 1
            ),
            text,
        );
    }
    centre_y + r_o + sheet.paper(6.0)
}

/// The legend (one colour per sensor, with what it reads) and the title block.
fn footer(sheet: &mut Sheet, robot: &CheckedRobot, top: f64) {
    let text = TextStyle::new(SMALL_MM, palette::DIMENSION);
    let row = sheet.paper(4.2);
    let mut y = top + sheet.paper(2.0);
    let sw = sheet.paper(5.0);
    for r in &robot.sensors {
        let pen = sheet.pen(sensor_colour(r.sensor.index), 0.8, None);
        let mid = y - sheet.paper(0.7);
        sheet.line("labels", (0.0, mid), (sw, mid), &pen);
        let others: Vec<String> = r
            .crosstalk
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != r.sensor.joint)
            .map(|(j, v)| format!("{} % of joint {}", fixed(v * 100.0, 1), j + 1))
            .collect();
        sheet.text_plain(
            "labels",
            (sw + sheet.paper(2.0), y),
            &format!(
                "sensor {} = {}: U-trace, leads and pads; trace {} mm; reads {}",
                r.sensor.index + 1,
                r.sensor,
                fixed(r.trace_length_mm, 2),
                if others.is_empty() {
                    "its own joint only".to_string()
                } else {
                    others.join(", ")
                }
            ),
            text,
        );
        y += row;
    }
    let notch_edge = sheet.pen(palette::NOTCH_EDGE, 0.15, None);
    let mid = y - sheet.paper(0.7);
    sheet.rect(
        "labels",
        (0.0, mid - sheet.paper(1.2)),
        (sw, mid + sheet.paper(1.2)),
        Some(palette::NOTCH_FILL),
        Some(&notch_edge),
        "legend",
    );
    sheet.text("labels", (sw + sheet.paper(2.0), y), "notch (cut)", text);
    y += row;
    let (_, below_bar) = annotate::scale_bar(sheet, "labels", (0.0, y));
    let r = &robot.robot;
    let mut rows = vec![
        (
            "tube".to_string(),
            format!(
                "r_{{o}} = {}, r_{{i}} = {} mm",
                fixed(r.outer_radius_mm(), 3),
                fixed(r.inner_radius_mm(), 3)
            ),
        ),
        (
            "part length".to_string(),
            format!("{} mm to the parting cut", fixed(robot.layout.length_mm, 2)),
        ),
    ];
    for (i, j) in r.joints.iter().enumerate() {
        rows.push((
            format!("joint {}", i + 1),
            format!(
                "{} ({}), {}°, x {} … {} mm",
                j.design().file.name.replace('{', "(").replace('}', ")"),
                j.style_name(),
                fixed(j.rotation_deg, 1),
                fixed(j.x_start_mm(), 2),
                fixed(j.x_end_mm(), 2)
            ),
        ));
    }
    rows.push((
        "pads".to_string(),
        format!(
            "{} row{} after the last joint's own",
            robot.pad_rows,
            if robot.pad_rows == 1 { "" } else { "s" }
        ),
    ));
    rows.push((
        "trace width, kerf".to_string(),
        format!(
            "{}, {} mm",
            fixed(robot.layout.trace_width_mm, 3),
            fixed(robot.layout.kerf_mm, 3)
        ),
    ));
    rows.push(("robot checksum".to_string(), r.checksum.clone()));
    let table = Table {
        heading: format!("{} — {} joints", r.name, r.joints.len()),
        rows,
    };
    let _ = TEXT_MM;
    let x = robot.layout.length_mm.max(sheet.paper(160.0)) - table.size(sheet).0;
    table.draw(
        sheet,
        "labels",
        (x.max(sheet.paper(150.0)), top + sheet.paper(2.0)),
    );
    let _ = below_bar;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn robot(name: &str) -> CheckedRobot {
        CheckedRobot::load(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("designs")
                .join(name),
        )
        .unwrap()
    }

    /// `docs/img/robot-bc.svg` is this code's output; rerun with `DLW_UPDATE_DOCS=1` to
    /// regenerate it after a deliberate change (and look at it: `docs/robots.md`).
    #[test]
    fn docs_robot_figure_is_current() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/img/robot-bc.svg");
        let svg = robot_svg(&robot("robot-bc.toml")).unwrap();
        if std::env::var_os("DLW_UPDATE_DOCS").is_some() {
            crate::output::write_atomic(&path, svg.as_bytes()).unwrap();
        }
        let on_disk = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("{}: {e}; run with DLW_UPDATE_DOCS=1", path.display()));
        assert!(
            on_disk == svg,
            "{} is stale; regenerate with DLW_UPDATE_DOCS=1 cargo test --lib drawing::svg::robot",
            path.display()
        );
    }

    #[test]
    fn the_sheet_names_the_robot() {
        let svg = robot_svg(&robot("robot-bc.toml")).unwrap();
        assert!(svg.contains("<title>Robot BC — unrolled robot, 2 joints, scale"));
    }
}
