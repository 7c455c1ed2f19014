//! The unrolled layout as an SVG sheet: features in the paper's Fig. 1 colours, dimensions
//! measured from the drawn geometry, axes, a title block and a scale bar.

use std::f64::consts::PI;

use dlw_geometry::NotchStyle;
use geo::{BoundingRect, LineString, Polygon};

use super::annotate::{self, Dimension, Overflow, Table, SMALL_MM, TEXT_MM, THIN_MM};
use super::error::SvgError;
use super::options::{Drawn, SvgOptions};
use super::palette;
use super::sheet::{fixed, Anchor, Sheet, TextStyle};
use crate::design::Design;
use crate::layout::{Layout, Notch, Trace};

/// The sheet's layers, bottom first.
const LAYERS: [&str; 8] = [
    "tube",
    "guides",
    "dimensions",
    "notches",
    "sensor",
    "leads-pads",
    "parting",
    "labels",
];

/// The unrolled layout as an SVG document, at the largest standard scale at which the sheet
/// fits A4 landscape. See [`layout_svg_with`].
///
/// # Errors
/// See [`layout_svg_with`].
pub fn layout_svg(layout: &Layout, design: &Design) -> Result<String, SvgError> {
    layout_svg_with(layout, design, &SvgOptions::default())
}

/// The unrolled layout as an SVG document.
///
/// The sheet shows the tube's outer surface cut open at the seam and laid flat: `x` (along the
/// tube from the distal end) to the right, `s` (arc length, the layout's window
/// `[seam_s_mm, seam_s_mm + circumference_mm)`) upward, both in mm of the part; the top and
/// bottom edges of the tube are the seam. Notches are filled orange, the sensor is blue, leads
/// and pads are green, all traces drawn with their real width; the parting cut is dark grey
/// and dashed. Dimensions (notch width `h`, spacing `c`, notch arc `s_n`, sensor arc `s_s`,
/// joint and notched length, circumference, length to the parting cut) are measured from the
/// drawn geometry; the title block lists the design's values and the geometry of
/// `dlw_geometry` (`ȳ`, `y_s`, `Δy`, sensitivity, closing angle).
///
/// User units are mm of the part; `width`/`height` are in mm at the print scale, so the file
/// prints to scale.
///
/// # Errors
/// [`SvgError::NotFinite`] when a layout coordinate is not finite,
/// [`SvgError::NotPositive`] when the layout's length, radius, circumference or trace width
/// is not positive, [`SvgError::BadScale`] for an unusable print scale.
pub fn layout_svg_with(
    layout: &Layout,
    design: &Design,
    options: &SvgOptions,
) -> Result<String, SvgError> {
    check(layout)?;
    options.draw(|scale| draw(layout, design, scale))
}

fn draw(layout: &Layout, design: &Design, scale: f64) -> Drawn {
    let (x_min, x_max) = x_range(layout);
    let mut sheet = Sheet::new(scale, &LAYERS);
    let frame = Frame {
        top_s_mm: layout.seam_s_mm + layout.circumference_mm,
    };
    draw_tube(&mut sheet, layout, &frame);
    draw_features(&mut sheet, layout, &frame);
    let right_edge = draw_dimensions(&mut sheet, layout, design, &frame);
    let below = draw_axes(&mut sheet, layout, x_min, x_max);
    draw_line_labels(&mut sheet, layout, &frame);
    let title = format!(
        "{} — unrolled layout ({}), scale {}",
        design.file.name,
        style_name(design.file.style),
        annotate::scale_ratio(scale)
    );
    draw_footer(&mut sheet, layout, design, below, right_edge);
    let ((min_x, min_y), _) = sheet.extent();
    sheet.text_plain(
        "labels",
        (min_x, min_y - sheet.paper(4.0)),
        &title,
        TextStyle::new(4.0, palette::OUTLINE).bold(),
    );
    sheet.finish(&title, 6.0)
}

/// Maps the layout's `(x, s)` to sheet coordinates: `x` right, `s` up.
struct Frame {
    top_s_mm: f64,
}

impl Frame {
    fn pt(&self, x: f64, s: f64) -> (f64, f64) {
        (x, self.top_s_mm - s)
    }
}

/// Uppercase style name.
pub(crate) fn style_name(style: NotchStyle) -> &'static str {
    match style {
        NotchStyle::Uan => "UAN",
        NotchStyle::Bsn => "BSN",
    }
}

pub(crate) fn check(layout: &Layout) -> Result<(), SvgError> {
    for (what, value) in [
        ("layout length_mm", layout.length_mm),
        ("layout outer_radius_mm", layout.outer_radius_mm),
        ("layout circumference_mm", layout.circumference_mm),
        ("layout trace_width_mm", layout.trace_width_mm),
    ] {
        if !value.is_finite() {
            return Err(SvgError::NotFinite {
                what: what.to_string(),
                value,
            });
        }
        if value <= 0.0 {
            return Err(SvgError::NotPositive { what, value });
        }
    }
    if !layout.seam_s_mm.is_finite() {
        return Err(SvgError::NotFinite {
            what: "layout seam_s_mm".into(),
            value: layout.seam_s_mm,
        });
    }
    let finite = |what: String, line: &LineString<f64>| -> Result<(), SvgError> {
        for p in line.coords() {
            for (axis, value) in [("x", p.x), ("s", p.y)] {
                if !value.is_finite() {
                    return Err(SvgError::NotFinite {
                        what: format!("{what} {axis}"),
                        value,
                    });
                }
            }
        }
        Ok(())
    };
    for (i, n) in layout.notches.iter().enumerate() {
        for poly in &n.outline {
            finite(format!("notch {i} outline"), poly.exterior())?;
        }
    }
    for (kind, traces) in [
        ("sensor", &layout.sensors),
        ("lead", &layout.leads),
        ("pad", &layout.pads),
    ] {
        for (i, t) in traces.iter().enumerate() {
            for piece in &t.pieces {
                finite(format!("{kind} {i} point"), piece)?;
            }
        }
    }
    for line in &layout.parting {
        finite("parting line point".into(), line)?;
    }
    Ok(())
}

/// Axis-aligned extent in the layout's `(x, s)`.
#[derive(Debug, Clone, Copy)]
struct Extent {
    x0: f64,
    x1: f64,
    s0: f64,
    s1: f64,
}

fn extent<'a>(lines: impl Iterator<Item = &'a LineString<f64>>) -> Option<Extent> {
    lines
        .filter_map(|l| l.bounding_rect())
        .map(|r| Extent {
            x0: r.min().x,
            x1: r.max().x,
            s0: r.min().y,
            s1: r.max().y,
        })
        .reduce(|a, b| Extent {
            x0: a.x0.min(b.x0),
            x1: a.x1.max(b.x1),
            s0: a.s0.min(b.s0),
            s1: a.s1.max(b.s1),
        })
}

/// The extent of each piece of a notch (one unless the seam splits it).
fn notch_pieces(n: &Notch) -> Vec<Extent> {
    n.outline
        .iter()
        .filter_map(|p| extent(std::iter::once(p.exterior())))
        .collect()
}

/// The extent of each piece of a trace (one unless the seam splits it).
fn trace_pieces(t: &Trace) -> Vec<Extent> {
    t.pieces
        .iter()
        .filter_map(|p| extent(std::iter::once(p)))
        .collect()
}

fn x_range(layout: &Layout) -> (f64, f64) {
    let lines = layout
        .notches
        .iter()
        .flat_map(|n| n.outline.iter().map(Polygon::exterior))
        .chain(
            [&layout.sensors, &layout.leads, &layout.pads]
                .into_iter()
                .flat_map(|ts| ts.iter().flat_map(|t| t.pieces.iter())),
        )
        .chain(layout.parting.iter());
    match extent(lines) {
        Some(e) => (e.x0.min(0.0), e.x1.max(layout.length_mm)),
        None => (0.0, layout.length_mm),
    }
}

fn draw_tube(sheet: &mut Sheet, layout: &Layout, f: &Frame) {
    let outline = sheet.pen(palette::OUTLINE, 0.35, None);
    let (a, b) = (
        f.pt(0.0, layout.seam_s_mm),
        f.pt(layout.length_mm, f.top_s_mm),
    );
    sheet.rect(
        "tube",
        a,
        b,
        Some(palette::TUBE_FILL),
        Some(&outline),
        "tube",
    );
    // Centre lines of the cross-section's +y (φ = 0) and −y (φ = 180°) directions; their
    // labels are written last ([`draw_line_labels`]), clear of every line.
    let centre = sheet.pen(palette::GUIDE, THIN_MM, Some(&[6.0, 1.5, 1.0, 1.5]));
    for (_, s) in phi_lines(layout) {
        let (_, y) = f.pt(0.0, s);
        sheet.line("guides", (0.0, y), (layout.length_mm, y), &centre);
    }
}

/// The φ = 0 and φ = 180° centre lines: `(φ in degrees, s in the window)`.
fn phi_lines(layout: &Layout) -> [(f64, f64); 2] {
    [(0.0, 0.0), (180.0, PI * layout.outer_radius_mm)].map(|(phi, s)| (phi, wrap(s, layout)))
}

/// The labels of lines that run across the sheet (the φ centre lines, the parting cut), written
/// after every line so each is placed where no line strikes it: level with the end of its
/// line if that is clear, else moved just off it.
fn draw_line_labels(sheet: &mut Sheet, layout: &Layout, f: &Frame) {
    let label = TextStyle::new(SMALL_MM, palette::GUIDE);
    for (phi_deg, s) in phi_lines(layout) {
        let (_, y) = f.pt(0.0, s);
        let x = layout.length_mm + sheet.paper(1.5);
        // Centred on the line's height first, then 1, 2, … paper mm above and below it.
        let mut candidates = vec![((x, y + sheet.paper(0.7)), label)];
        for k in 1..=6 {
            let d = sheet.paper(f64::from(k));
            candidates.push(((x, y + sheet.paper(0.7) - d), label));
            candidates.push(((x, y + sheet.paper(0.7) + d), label));
        }
        sheet.text_clear("labels", &candidates, &format!("φ = {phi_deg:.0}°"));
    }
    if layout.parting.is_empty() {
        return;
    }
    // Above the tube at the parting line: centred on it, else beside the extension line that
    // marks the same x.
    let x = layout.length_mm;
    let y = -sheet.paper(1.5);
    let style = TextStyle::new(SMALL_MM, palette::PARTING);
    let gap = sheet.paper(1.0);
    sheet.text_clear(
        "labels",
        &[
            ((x, y), style.anchor(Anchor::Middle)),
            ((x - gap, y), style.anchor(Anchor::End)),
            ((x + gap, y), style.anchor(Anchor::Start)),
        ],
        "parting cut",
    );
}

/// `s` moved into the drawing's window by whole turns.
fn wrap(s: f64, layout: &Layout) -> f64 {
    layout.seam_s_mm + (s - layout.seam_s_mm).rem_euclid(layout.circumference_mm)
}

fn draw_features(sheet: &mut Sheet, layout: &Layout, f: &Frame) {
    let edge = sheet.pen(palette::NOTCH_EDGE, 0.15, None);
    for n in &layout.notches {
        for poly in &n.outline {
            let mut pts: Vec<(f64, f64)> =
                poly.exterior().coords().map(|p| f.pt(p.x, p.y)).collect();
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
    let trace = |colour| super::sheet::Pen {
        colour,
        width: layout.trace_width_mm,
        dash: None,
    };
    for (layer, class, colour, traces) in [
        ("sensor", "sensor", palette::SENSOR, &layout.sensors),
        ("leads-pads", "lead", palette::LEADS_PADS, &layout.leads),
        ("leads-pads", "pad", palette::LEADS_PADS, &layout.pads),
    ] {
        let pen = trace(colour);
        for t in traces {
            for piece in &t.pieces {
                let pts: Vec<(f64, f64)> = piece.coords().map(|p| f.pt(p.x, p.y)).collect();
                sheet.path(layer, &pts, false, None, Some(&pen), class);
            }
        }
    }
    let parting = sheet.pen(palette::PARTING, 0.45, Some(&[3.0, 1.5]));
    for line in &layout.parting {
        let pts: Vec<(f64, f64)> = line.coords().map(|p| f.pt(p.x, p.y)).collect();
        sheet.path("parting", &pts, false, None, Some(&parting), "parting");
    }
}

/// Draws the dimensions; returns the sheet x of the rightmost annotation column.
///
/// The outermost dimensions are drawn first, so that the labels of the inner ones are placed
/// clear of the outer ones' extension lines, which cross the inner rows and columns.
fn draw_dimensions(sheet: &mut Sheet, layout: &Layout, design: &Design, f: &Frame) -> f64 {
    let length = layout.length_mm;
    let k = sheet.paper(1.0);
    let row = |i: f64| -k * (6.0 + 8.0 * i);
    let mut next_row = 0.0;
    // Horizontal dimensions above the tube, innermost row first.
    let mut rows: Vec<Dimension> = Vec::new();
    let h_and_c = h_and_c_notches(layout);
    if let Some((a, b)) = h_and_c {
        let at = row(0.0);
        let top_a = f.pt(0.0, a.s1).1;
        rows.push(Dimension {
            ends: (a.x0, a.x1),
            at,
            feature: (top_a, top_a),
            label: format!("h = {}", fixed(a.x1 - a.x0, 2)),
            overflow: Overflow::Before,
            beside: false,
        });
        if let Some(b) = b {
            rows.push(Dimension {
                ends: (a.x1, b.x0),
                at,
                feature: (top_a, f.pt(0.0, b.s1).1),
                label: format!("c = {}", fixed(b.x0 - a.x1, 2)),
                overflow: Overflow::After,
                beside: false,
            });
        }
        next_row = 1.0;
    }
    // Notched length and the joint length L, from the first notch.
    let notched = extent(
        layout
            .notches
            .iter()
            .flat_map(|n| n.outline.iter().map(Polygon::exterior)),
    );
    let joint_l = design.file.joint_length_mm;
    if let Some(e) = notched {
        let span = e.x1 - e.x0;
        let same = (span - joint_l).abs() < 1e-6;
        let label = if same {
            format!("L = N·h + (N−1)·c = {}", fixed(span, 2))
        } else {
            format!("notched length N·h + (N−1)·c = {}", fixed(span, 2))
        };
        rows.push(Dimension {
            ends: (e.x0, e.x1),
            at: row(next_row),
            feature: (0.0, 0.0),
            label,
            overflow: Overflow::After,
            beside: false,
        });
        next_row += 1.0;
        if !same {
            rows.push(Dimension {
                ends: (e.x0, e.x0 + joint_l),
                at: row(next_row),
                feature: (0.0, 0.0),
                label: format!("L = {} (sensor gauge length)", fixed(joint_l, 2)),
                overflow: Overflow::After,
                beside: false,
            });
            next_row += 1.0;
        }
    }
    rows.push(Dimension {
        ends: (0.0, length),
        at: row(next_row),
        feature: (0.0, 0.0),
        label: format!("to parting cut {}", fixed(length, 2)),
        overflow: Overflow::After,
        beside: false,
    });
    for d in rows.iter().rev() {
        annotate::horizontal(sheet, "dimensions", d);
    }
    // Vertical dimensions right of the tube: s_s, s_n, circumference; drawn outermost first.
    let phi_label = sheet.text_width("φ = 180°", TextStyle::new(SMALL_MM, palette::GUIDE));
    let mut col = length + phi_label + sheet.paper(9.0);
    let step = sheet.paper(TEXT_MM + 5.5);
    let mut arcs: Vec<(f64, Vec<Extent>, &str)> = Vec::new();
    if let Some(sensor) = layout.sensors.first() {
        arcs.push((col, trace_pieces(sensor), "s_{s}"));
        col += step;
    }
    // The last notch of side 0, whose extension lines cross the least.
    let notch = layout
        .notches
        .iter()
        .filter(|n| n.side == 0)
        .max_by_key(|n| n.level);
    if let Some(n) = notch {
        arcs.push((col, notch_pieces(n), "s_{n}"));
        col += step;
    }
    annotate::vertical(
        sheet,
        "dimensions",
        &Dimension {
            ends: (0.0, layout.circumference_mm),
            at: col,
            feature: (length, length),
            label: format!("2πr_{{o}} = {}", fixed(layout.circumference_mm, 2)),
            overflow: Overflow::After,
            beside: false,
        },
    );
    for (at, pieces, symbol) in arcs.iter().rev() {
        arc_dimension(sheet, f, *at, pieces, symbol);
    }
    col
}

/// The two lowest-level notches of the side whose notches reach highest on the sheet (so the
/// extension lines up to the `h`/`c` row cross the least), as whole-notch extents.
fn h_and_c_notches(layout: &Layout) -> Option<(Extent, Option<Extent>)> {
    let whole = |n: &Notch| extent(n.outline.iter().map(Polygon::exterior));
    // The side's highest piece top, measured in the window.
    let side_top = |side: usize| {
        layout
            .notches
            .iter()
            .filter(|n| n.side == side)
            .filter_map(|n| notch_pieces(n).first().map(|e| e.s1))
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let side = [0, 1]
        .into_iter()
        .filter(|s| layout.notches.iter().any(|n| n.side == *s))
        .max_by(|a, b| side_top(*a).total_cmp(&side_top(*b)))?;
    let mut ns: Vec<&Notch> = layout.notches.iter().filter(|n| n.side == side).collect();
    ns.sort_by_key(|n| n.level);
    // A split notch's pieces share its x extent; its top on the sheet is the window's top.
    let a = whole(ns.first()?)?;
    let b = ns.get(1).and_then(|n| whole(n));
    Some((a, b))
}

/// A vertical dimension of an arc in `s` (notch arc, sensor arc) at sheet x `col`, with
/// extension lines from the feature's proximal end. A feature the seam splits gets one
/// dimension per piece, each labelled as its share of the whole.
fn arc_dimension(sheet: &mut Sheet, f: &Frame, col: f64, pieces: &[Extent], symbol: &str) {
    let total: f64 = pieces.iter().map(|e| e.s1 - e.s0).sum();
    let lowest = pieces.iter().map(|e| e.s0).fold(f64::INFINITY, f64::min);
    for e in pieces {
        let (y0, y1) = (f.pt(0.0, e.s0).1, f.pt(0.0, e.s1).1);
        let label = if pieces.len() == 1 {
            format!("{symbol} = {}", fixed(total, 2))
        } else {
            format!("{symbol}: {} of {}", fixed(e.s1 - e.s0, 2), fixed(total, 2))
        };
        annotate::vertical(
            sheet,
            "dimensions",
            &Dimension {
                ends: (y1, y0),
                at: col,
                feature: (e.x1, e.x1),
                label,
                // A lower piece writes below itself, clear of the piece above.
                overflow: if pieces.len() > 1 && e.s0 <= lowest {
                    Overflow::Before
                } else {
                    Overflow::After
                },
                beside: false,
            },
        );
    }
}

/// A tick step from `candidates` whose ticks are at least `min_mm` apart on paper.
fn tick_step(scale: f64, min_mm: f64) -> f64 {
    [0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0]
        .into_iter()
        .find(|s| s * scale >= min_mm)
        .unwrap_or(100.0)
}

fn decimals(step: f64) -> usize {
    if step >= 1.0 {
        0
    } else {
        1
    }
}

/// Draws the x and s axes; returns the sheet y below the x axis title.
fn draw_axes(sheet: &mut Sheet, layout: &Layout, x_min: f64, x_max: f64) -> f64 {
    let c = layout.circumference_mm;
    let tick = sheet.pen(palette::GUIDE, THIN_MM, None);
    let small = TextStyle::new(SMALL_MM, palette::DIMENSION);
    let tick_len = sheet.paper(1.2);
    // x along the bottom edge.
    let step = tick_step(sheet.scale(), 10.0);
    let mut i = (x_min / step).ceil() as i64;
    while (i as f64) * step <= x_max + 1e-9 {
        let x = i as f64 * step;
        sheet.line("guides", (x, c), (x, c + tick_len), &tick);
        sheet.text(
            "labels",
            (x, c + tick_len + sheet.paper(SMALL_MM + 0.5)),
            &fixed(x, decimals(step)),
            small.anchor(Anchor::Middle),
        );
        i += 1;
    }
    let x_title_y = c + sheet.paper(11.0);
    sheet.text(
        "labels",
        ((x_min + x_max) / 2.0, x_title_y),
        &format!(
            "x (mm) along the tube: distal end 0 → parting cut {}",
            fixed(layout.length_mm, 2)
        ),
        TextStyle::new(TEXT_MM, palette::DIMENSION).anchor(Anchor::Middle),
    );
    // s up the left edge: the window [seam, seam + C), s = r_o·φ with φ from +y.
    let step = tick_step(sheet.scale(), 8.0);
    let (s0, s1) = (layout.seam_s_mm, layout.seam_s_mm + c);
    let mut i = (s0 / step).ceil() as i64;
    let mut widest: f64 = 0.0;
    while (i as f64) * step <= s1 + 1e-9 {
        let s = i as f64 * step;
        let y = s1 - s;
        sheet.line("guides", (0.0, y), (-tick_len, y), &tick);
        let label = fixed(s, decimals(step));
        widest = widest.max(sheet.text_width(&label, small));
        sheet.text(
            "labels",
            (-tick_len - sheet.paper(0.8), y + sheet.paper(0.7)),
            &label,
            small.anchor(Anchor::End),
        );
        i += 1;
    }
    sheet.text(
        "labels",
        (-tick_len - widest - sheet.paper(3.0), c / 2.0),
        "s (mm)",
        TextStyle::new(TEXT_MM, palette::DIMENSION)
            .anchor(Anchor::Middle)
            .vertical(),
    );
    let seam_deg = (s0 / layout.outer_radius_mm).to_degrees();
    sheet.text(
        "labels",
        ((x_min + x_max) / 2.0, x_title_y + sheet.paper(5.0)),
        &format!(
            "s = r_{{o}}·φ: arc length on the outer surface from +y (φ = 0). \
             The top and bottom edges are the seam, s = {} mm (φ = {}°).",
            fixed(s0, 2),
            fixed(seam_deg, 1)
        ),
        TextStyle::new(SMALL_MM, palette::DIMENSION).anchor(Anchor::Middle),
    );
    x_title_y + sheet.paper(9.0)
}

fn draw_footer(sheet: &mut Sheet, layout: &Layout, design: &Design, top: f64, right: f64) {
    // Below everything drawn so far, including labels that overflowed downward.
    let ((_, _), (_, bottom)) = sheet.extent();
    let origin = (0.0, top.max(bottom) + sheet.paper(2.0));
    let (_, below_bar) = annotate::scale_bar(sheet, "labels", origin);
    // Legend: one swatch per feature kind.
    let sw = sheet.paper(5.0);
    let row_h = sheet.paper(4.2);
    let text = TextStyle::new(SMALL_MM, palette::DIMENSION);
    let mut y = below_bar + sheet.paper(4.0);
    let notch_edge = sheet.pen(palette::NOTCH_EDGE, 0.15, None);
    let entries = [
        ("notch (cut)", palette::NOTCH_FILL),
        ("sensor (DLW graphene)", palette::SENSOR),
        ("leads and contact pads (DLW)", palette::LEADS_PADS),
        ("parting cut", palette::PARTING),
    ];
    for (label, colour) in entries {
        let mid = y - sheet.paper(0.7);
        if colour == palette::NOTCH_FILL {
            sheet.rect(
                "labels",
                (0.0, mid - sheet.paper(1.2)),
                (sw, mid + sheet.paper(1.2)),
                Some(colour),
                Some(&notch_edge),
                "legend",
            );
        } else if colour == palette::PARTING {
            let pen = sheet.pen(colour, 0.45, Some(&[3.0, 1.5]));
            sheet.line("labels", (0.0, mid), (sw, mid), &pen);
        } else {
            let pen = sheet.pen(colour, 0.6, None);
            sheet.line("labels", (0.0, mid), (sw, mid), &pen);
        }
        sheet.text("labels", (sw + sheet.paper(2.0), y), label, text);
        y += row_h;
    }
    sheet.text(
        "labels",
        (0.0, y + sheet.paper(1.0)),
        &format!(
            "traces drawn at their real width, {} mm",
            fixed(layout.trace_width_mm, 3)
        ),
        text,
    );
    let table = title_block(sheet, layout, design);
    let (w, _) = table.size(sheet);
    let x = (right - w).max(sheet.paper(80.0));
    table.draw(sheet, "labels", (x, origin.1));
}

fn title_block(sheet: &Sheet, layout: &Layout, design: &Design) -> Table {
    let d = &design.file;
    let j = &design.joint;
    let s = j.section();
    let mut rows = vec![
        (
            "tube".to_string(),
            format!(
                "r_{{o}} = {}, r_{{i}} = {} mm",
                fixed(d.outer_radius_mm, 3),
                fixed(d.inner_radius_mm, 3)
            ),
        ),
        (
            "notches".to_string(),
            format!(
                "N = {}{}, s_{{n}} = {} (φ_{{n}} = {:.1}°), h = {}, c = {} mm",
                d.notch_count,
                if d.style == NotchStyle::Bsn {
                    " per side"
                } else {
                    ""
                },
                fixed(d.notch_arc_mm, 2),
                s.notch_angle_rad().to_degrees(),
                fixed(d.notch_width_mm, 2),
                fixed(d.notch_spacing_mm, 2)
            ),
        ),
        (
            "joint, sensor".to_string(),
            format!(
                "L = {}, s_{{s}} = {} mm",
                fixed(d.joint_length_mm, 2),
                fixed(d.sensor_arc_mm, 2)
            ),
        ),
        (
            "planes (Eqs. 1-2)".to_string(),
            format!(
                "ȳ = {}, y_{{s}} = {}, Δy = {} mm",
                fixed(s.neutral_axis_mm(), 3),
                fixed(s.sensor_plane_mm(), 3),
                fixed(s.offset_mm(), 3)
            ),
        ),
        (
            "sensitivity (Eq. 3)".to_string(),
            format!("dε/dθ = {} %/°", fixed(j.strain_per_deg() * 100.0, 4)),
        ),
        (
            "notches close at".to_string(),
            format!(
                "θ = {:.1}°, ε = {} %",
                j.closing_angle_rad().to_degrees(),
                fixed(j.strain_at_closing() * 100.0, 2)
            ),
        ),
    ];
    if let Some(dy12) = s.two_sensor_offset_mm() {
        rows.insert(
            4,
            (
                "two sensors (Eq. 7)".to_string(),
                format!("Δy^{{(1,2)}} = {} mm", fixed(dy12, 3)),
            ),
        );
    }
    rows.extend([
        (
            "trace width, kerf".to_string(),
            format!(
                "{}, {} mm",
                fixed(layout.trace_width_mm, 3),
                fixed(layout.kerf_mm, 3)
            ),
        ),
        (
            "s window".to_string(),
            format!(
                "[{}, {}) mm",
                fixed(layout.seam_s_mm, 2),
                fixed(layout.seam_s_mm + layout.circumference_mm, 2)
            ),
        ),
        (
            "scale, units".to_string(),
            format!("{}, mm", annotate::scale_ratio(sheet.scale())),
        ),
        ("design checksum".to_string(), design.checksum.clone()),
    ]);
    Table {
        heading: format!("{} — {}", d.name, style_name(d.style)),
        rows,
    }
}
