//! Drawing annotations shared by both sheets: linear dimensions, the scale bar and the table
//! used for title blocks.

use super::palette;
use super::sheet::{fixed, Anchor, Sheet, TextStyle};

/// Dimension and label text height (paper mm).
pub(crate) const TEXT_MM: f64 = 2.5;
/// Smaller text: tick labels, notes (paper mm).
pub(crate) const SMALL_MM: f64 = 2.0;
/// Dimension line weight (paper mm).
pub(crate) const THIN_MM: f64 = 0.18;

/// Where a dimension's label goes when it does not fit between the arrows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Overflow {
    /// Before the smaller end (left of a horizontal dimension, below a vertical one).
    Before,
    /// Past the larger end (right of a horizontal dimension, above a vertical one).
    After,
}

/// A linear dimension between two positions along one sheet axis.
#[derive(Debug, Clone)]
pub(crate) struct Dimension {
    /// The two measured positions along the dimension's axis (user units).
    pub ends: (f64, f64),
    /// Where the dimension line runs, on the other axis.
    pub at: f64,
    /// Where each extension line starts on the other axis (the feature's edge); an extension
    /// line is left out when its feature is already on the dimension line.
    pub feature: (f64, f64),
    /// The label, with `_{…}`/`^{…}` markup.
    pub label: String,
    /// Where the label goes if it does not fit between the arrows.
    pub overflow: Overflow,
    /// For a vertical dimension: write the label upright, right of the line at mid-height,
    /// instead of along the line.
    pub beside: bool,
}

/// Draws a dimension measured along the sheet's x axis.
pub(crate) fn horizontal(sheet: &mut Sheet, layer: &'static str, d: &Dimension) {
    linear(sheet, layer, d, false);
}

/// Draws a dimension measured along the sheet's y axis; the label reads bottom-to-top.
pub(crate) fn vertical(sheet: &mut Sheet, layer: &'static str, d: &Dimension) {
    linear(sheet, layer, d, true);
}

fn linear(sheet: &mut Sheet, layer: &'static str, d: &Dimension, vertical: bool) {
    // `u` runs along the measurement, `v` across it; `pt` maps back to sheet coordinates.
    let pt = |u: f64, v: f64| if vertical { (v, u) } else { (u, v) };
    let (lo, hi) = (d.ends.0.min(d.ends.1), d.ends.0.max(d.ends.1));
    let feature_lo = if d.ends.0 <= d.ends.1 {
        d.feature.0
    } else {
        d.feature.1
    };
    let feature_hi = if d.ends.0 <= d.ends.1 {
        d.feature.1
    } else {
        d.feature.0
    };
    let guide = sheet.pen(palette::GUIDE, THIN_MM, None);
    let ink = sheet.pen(palette::DIMENSION, THIN_MM, None);
    let (gap, over) = (sheet.paper(0.8), sheet.paper(1.5));
    for (u, f) in [(lo, feature_lo), (hi, feature_hi)] {
        let span = d.at - f;
        if span.abs() > gap {
            let s = span.signum();
            sheet.line(layer, pt(u, f + s * gap), pt(u, d.at + s * over), &guide);
        }
    }
    let arrow = sheet.paper(2.2);
    let (a, b) = (pt(lo, d.at), pt(hi, d.at));
    let dir = if vertical { (0.0, 1.0) } else { (1.0, 0.0) };
    if hi - lo >= 2.0 * arrow + sheet.paper(1.0) {
        sheet.line(layer, a, b, &ink);
        sheet.arrowhead(layer, a, (-dir.0, -dir.1));
        sheet.arrowhead(layer, b, dir);
    } else {
        // Too short for arrows inside: arrows outside pointing in, on short leaders.
        let lead = sheet.paper(5.0);
        sheet.line(layer, pt(lo - lead, d.at), pt(hi + lead, d.at), &ink);
        sheet.arrowhead(layer, a, dir);
        sheet.arrowhead(layer, b, (-dir.0, -dir.1));
    }
    let style = TextStyle::new(TEXT_MM, palette::DIMENSION);
    if vertical && d.beside {
        let at = (d.at + sheet.paper(1.5), (lo + hi) / 2.0 + sheet.paper(0.9));
        sheet.text(layer, at, &d.label, style);
        return;
    }
    let style = if vertical { style.vertical() } else { style };
    let width = sheet.text_width(&d.label, style);
    let lift = sheet.paper(1.0);
    // Text sits on the side of the line with smaller sheet coordinates: above a horizontal
    // line, left of a vertical one (whose text reads upward). Outside the arrows, it moves
    // further out, then to the other end, until no line drawn so far strikes it.
    let candidates: Vec<((f64, f64), TextStyle)> = if width + sheet.paper(2.0) <= hi - lo {
        vec![(
            pt((lo + hi) / 2.0, d.at - lift),
            style.anchor(Anchor::Middle),
        )]
    } else {
        let beyond = sheet.paper(if hi - lo >= 2.0 * arrow { 1.0 } else { 5.5 });
        let step = sheet.paper(1.5);
        let other = match d.overflow {
            Overflow::Before => Overflow::After,
            Overflow::After => Overflow::Before,
        };
        let mut out = Vec::new();
        for overflow in [d.overflow, other] {
            // (start, outward direction, anchor)
            let (at, out_dir, anchor) = match (overflow, vertical) {
                // Along a vertical line `lo` is the top of the sheet, which the text runs toward.
                (Overflow::Before, false) => (lo - beyond, -1.0, Anchor::End),
                (Overflow::After, false) => (hi + beyond, 1.0, Anchor::Start),
                (Overflow::Before, true) => (hi + beyond, 1.0, Anchor::End),
                (Overflow::After, true) => (lo - beyond, -1.0, Anchor::Start),
            };
            for k in 0..=8 {
                let u = at + out_dir * f64::from(k) * step;
                out.push((pt(u, d.at - lift), style.anchor(anchor)));
            }
        }
        out
    };
    sheet.text_clear(layer, &candidates, &d.label);
}

/// A scale bar whose top-left corner is at `origin`, about 40 paper mm long, with the print
/// scale written after it. Returns its bottom-right corner.
pub(crate) fn scale_bar(sheet: &mut Sheet, layer: &'static str, origin: (f64, f64)) -> (f64, f64) {
    let scale = sheet.scale();
    let length = [
        0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0,
    ]
    .into_iter()
    .rev()
    .find(|l| l * scale <= 50.0)
    .unwrap_or(0.01);
    let (x, y) = origin;
    let h = sheet.paper(1.6);
    let pen = sheet.pen(palette::OUTLINE, THIN_MM, None);
    let segments = 4;
    let seg = length / f64::from(segments);
    for i in 0..segments {
        let x0 = x + f64::from(i) * seg;
        let fill = if i % 2 == 0 {
            palette::OUTLINE
        } else {
            "#ffffff"
        };
        sheet.rect(
            layer,
            (x0, y),
            (x0 + seg, y + h),
            Some(fill),
            Some(&pen),
            "scale-bar",
        );
    }
    let small = TextStyle::new(SMALL_MM, palette::DIMENSION).anchor(Anchor::Middle);
    let ty = y + h + sheet.paper(SMALL_MM + 0.8);
    let decimals = if length >= 1.0 { 0 } else { 2 };
    sheet.text(layer, (x, ty), "0", small);
    sheet.text(
        layer,
        (x + length / 2.0, ty),
        &fixed(length / 2.0, decimals + 1),
        small,
    );
    sheet.text(
        layer,
        (x + length, ty),
        &format!("{} mm", fixed(length, decimals)),
        small,
    );
    let caption = format!("scale {}", scale_ratio(scale));
    let text = TextStyle::new(TEXT_MM, palette::DIMENSION);
    let cx = x + length + sheet.paper(6.0);
    sheet.text(layer, (cx, y + h), &caption, text);
    (cx + sheet.text_width(&caption, text), ty)
}

/// `10:1`, `1:2` and so on.
pub(crate) fn scale_ratio(scale: f64) -> String {
    if scale >= 1.0 {
        format!("{}:1", super::sheet::num(scale))
    } else {
        format!("1:{}", super::sheet::num(1.0 / scale))
    }
}

/// A boxed two-column table (key, value) with an optional bold heading row.
pub(crate) struct Table {
    /// Heading, written across both columns.
    pub heading: String,
    /// Rows of (key, value), with markup.
    pub rows: Vec<(String, String)>,
}

impl Table {
    fn metrics(&self, sheet: &Sheet) -> (f64, f64, f64, f64) {
        let style = TextStyle::new(SMALL_MM, palette::DIMENSION);
        let pad = sheet.paper(1.5);
        let key_w = self
            .rows
            .iter()
            .map(|(k, _)| sheet.text_width(k, style))
            .fold(0.0, f64::max);
        let val_w = self
            .rows
            .iter()
            .map(|(_, v)| sheet.text_width(v, style))
            .fold(0.0, f64::max);
        let head_w = sheet.text_width(&self.heading, style.bold());
        let width = (key_w + val_w + 4.0 * pad).max(head_w + 2.0 * pad);
        let row_h = sheet.paper(SMALL_MM * 1.55);
        (width, row_h, key_w + 2.0 * pad, pad)
    }

    /// Width and height in user units.
    pub fn size(&self, sheet: &Sheet) -> (f64, f64) {
        let (w, row_h, _, _) = self.metrics(sheet);
        (w, row_h * (self.rows.len() + 1) as f64)
    }

    /// Draws the table with its top-left corner at `origin`.
    pub fn draw(&self, sheet: &mut Sheet, layer: &'static str, origin: (f64, f64)) {
        let (w, row_h, key_col, pad) = self.metrics(sheet);
        let (_, h) = self.size(sheet);
        let (x, y) = origin;
        let frame = sheet.pen(palette::OUTLINE, 0.35, None);
        let rule = sheet.pen(palette::GUIDE, THIN_MM, None);
        sheet.rect(
            layer,
            (x, y),
            (x + w, y + h),
            None,
            Some(&frame),
            "title-block",
        );
        let style = TextStyle::new(SMALL_MM, palette::DIMENSION);
        let drop = sheet.paper(SMALL_MM * 0.45);
        let base = |row: usize| y + row_h * (row as f64 + 1.0) - drop;
        let head_base = base(0);
        sheet.text_plain(layer, (x + pad, head_base), &self.heading, style.bold());
        sheet.line(layer, (x, y + row_h), (x + w, y + row_h), &frame);
        for (i, (k, v)) in self.rows.iter().enumerate() {
            let b = base(i + 1);
            sheet.text(layer, (x + pad, b), k, style);
            sheet.text(layer, (x + key_col + pad, b), v, style);
            if i + 1 < self.rows.len() {
                let ry = y + row_h * (i as f64 + 2.0);
                sheet.line(layer, (x, ry), (x + w, ry), &rule);
            }
        }
        sheet.line(layer, (x + key_col, y + row_h), (x + key_col, y + h), &rule);
    }
}
