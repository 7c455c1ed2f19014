//! A drawing sheet: geometry in part millimetres, annotation sizes in paper millimetres.
//!
//! SVG user units are millimetres of the part; the root `width`/`height` are the viewBox times
//! the print scale, in mm, so the file prints to scale. Text heights, arrow sizes and line
//! weights are given in paper millimetres and divided by the scale, so they read the same at
//! any scale. The sheet tracks the extent of everything drawn (text by an estimate of its
//! width) and sizes the viewBox to it, so nothing is clipped.

use std::fmt::Write as _;

use svg::node::element::{Circle, Group, Path, Rectangle, Title};
use svg::node::Blob;
use svg::{Document, Node};

use super::options::Drawn;

/// Where a text sits relative to its anchor point (SVG `text-anchor`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Anchor {
    /// The text starts at the point.
    Start,
    /// The text is centred on the point.
    Middle,
    /// The text ends at the point.
    End,
}

/// How a text is set: height in paper mm, anchor, orientation and colour.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TextStyle {
    /// Font size in paper millimetres.
    pub size_mm: f64,
    /// Horizontal anchor along the text's own direction.
    pub anchor: Anchor,
    /// Runs bottom-to-top (rotated −90°) when true.
    pub vertical: bool,
    /// Bold weight.
    pub bold: bool,
    /// Fill colour.
    pub colour: &'static str,
}

impl TextStyle {
    /// Upright text of `size_mm`, anchored at its start.
    pub fn new(size_mm: f64, colour: &'static str) -> Self {
        Self {
            size_mm,
            anchor: Anchor::Start,
            vertical: false,
            bold: false,
            colour,
        }
    }

    /// The same style with another anchor.
    pub fn anchor(mut self, anchor: Anchor) -> Self {
        self.anchor = anchor;
        self
    }

    /// The same style, running bottom-to-top.
    pub fn vertical(mut self) -> Self {
        self.vertical = true;
        self
    }

    /// The same style in bold.
    pub fn bold(mut self) -> Self {
        self.bold = true;
        self
    }
}

/// A stroke: colour, width in user units (part mm) and an optional dash pattern.
#[derive(Debug, Clone)]
pub(crate) struct Pen {
    /// Stroke colour.
    pub colour: &'static str,
    /// Stroke width (part mm).
    pub width: f64,
    /// Dash and gap lengths (part mm); `None` for a solid line.
    pub dash: Option<Vec<f64>>,
}

/// A label's box in user units: `(x0, y0, x1, y1)`.
pub(crate) type Rect = (f64, f64, f64, f64);

/// A stroked straight segment and half its stroke width (user units).
pub(crate) type Segment = ((f64, f64), (f64, f64), f64);

/// The layers of a sheet, drawn in the order given; each becomes a `<g id=…>`.
pub(crate) struct Sheet {
    scale: f64,
    layers: Vec<(&'static str, Group)>,
    min: (f64, f64),
    max: (f64, f64),
    /// Every stroked segment drawn so far, so labels can be placed clear of them.
    segments: Vec<Segment>,
}

impl Sheet {
    /// An empty sheet at `scale` paper mm per part mm with the given layers, bottom first.
    pub fn new(scale: f64, layers: &[&'static str]) -> Self {
        Self {
            scale,
            layers: layers
                .iter()
                .map(|id| (*id, Group::new().set("id", *id)))
                .collect(),
            min: (f64::INFINITY, f64::INFINITY),
            max: (f64::NEG_INFINITY, f64::NEG_INFINITY),
            segments: Vec::new(),
        }
    }

    /// The print scale (paper mm per part mm).
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// A length given on paper (mm), in user units.
    pub fn paper(&self, mm: f64) -> f64 {
        mm / self.scale
    }

    /// A pen whose width and dashes are given in paper mm.
    pub fn pen(&self, colour: &'static str, width_mm: f64, dash_mm: Option<&[f64]>) -> Pen {
        Pen {
            colour,
            width: self.paper(width_mm),
            dash: dash_mm.map(|d| d.iter().map(|v| self.paper(*v)).collect()),
        }
    }

    /// Extends the sheet's extent to cover a point.
    pub fn cover(&mut self, x: f64, y: f64) {
        if x.is_finite() && y.is_finite() {
            self.min = (self.min.0.min(x), self.min.1.min(y));
            self.max = (self.max.0.max(x), self.max.1.max(y));
        }
    }

    /// The extent covered so far, `(min, max)` in user units.
    pub fn extent(&self) -> ((f64, f64), (f64, f64)) {
        (self.min, self.max)
    }

    fn add(&mut self, layer: &'static str, node: impl Into<Box<dyn Node>>) {
        if let Some((_, g)) = self.layers.iter_mut().find(|(id, _)| *id == layer) {
            g.append(node);
        } else {
            // Layers are fixed by the drawing code; an unknown one goes on top rather than lost.
            let mut g = Group::new().set("id", layer);
            g.append(node);
            self.layers.push((layer, g));
        }
    }

    /// A polyline (or, when `closed`, a polygon) through `points`, with an optional fill and
    /// stroke. `class` names the feature kind for readers and tests.
    pub fn path(
        &mut self,
        layer: &'static str,
        points: &[(f64, f64)],
        closed: bool,
        fill: Option<&'static str>,
        pen: Option<&Pen>,
        class: &str,
    ) {
        let Some(((x0, y0), rest)) = points.split_first() else {
            return;
        };
        let mut d = format!("M{} {}", num(*x0), num(*y0));
        for (x, y) in rest {
            let _ = write!(d, " L{} {}", num(*x), num(*y));
        }
        if closed {
            d.push_str(" Z");
        }
        let pad = pen.map_or(0.0, |p| p.width / 2.0);
        for (x, y) in points {
            self.cover(x - pad, y - pad);
            self.cover(x + pad, y + pad);
        }
        if pen.is_some() {
            for w in points.windows(2) {
                self.segments.push((w[0], w[1], pad));
            }
            if closed && points.len() > 2 {
                self.segments
                    .push((points[points.len() - 1], points[0], pad));
            }
        }
        let mut path = Path::new().set("d", d).set("fill", fill.unwrap_or("none"));
        if !class.is_empty() {
            path = path.set("class", class);
        }
        path = stroke(path, pen);
        self.add(layer, path);
    }

    /// A straight line from `a` to `b`.
    pub fn line(&mut self, layer: &'static str, a: (f64, f64), b: (f64, f64), pen: &Pen) {
        self.path(layer, &[a, b], false, None, Some(pen), "");
    }

    /// A rectangle with corners `a` and `b`.
    pub fn rect(
        &mut self,
        layer: &'static str,
        a: (f64, f64),
        b: (f64, f64),
        fill: Option<&'static str>,
        pen: Option<&Pen>,
        class: &str,
    ) {
        let (x0, x1) = (a.0.min(b.0), a.0.max(b.0));
        let (y0, y1) = (a.1.min(b.1), a.1.max(b.1));
        self.path(
            layer,
            &[(x0, y0), (x1, y0), (x1, y1), (x0, y1)],
            true,
            fill,
            pen,
            class,
        );
    }

    /// A circle.
    pub fn circle(
        &mut self,
        layer: &'static str,
        centre: (f64, f64),
        radius: f64,
        fill: Option<&'static str>,
        pen: Option<&Pen>,
        class: &str,
    ) {
        let pad = radius + pen.map_or(0.0, |p| p.width / 2.0);
        self.cover(centre.0 - pad, centre.1 - pad);
        self.cover(centre.0 + pad, centre.1 + pad);
        let mut c = Circle::new()
            .set("cx", num(centre.0))
            .set("cy", num(centre.1))
            .set("r", num(radius))
            .set("fill", fill.unwrap_or("none"));
        if !class.is_empty() {
            c = c.set("class", class);
        }
        self.add(layer, stroke(c, pen));
    }

    /// A filled arrowhead with its tip at `tip`, pointing along `dir` (need not be unit).
    pub fn arrowhead(&mut self, layer: &'static str, tip: (f64, f64), dir: (f64, f64)) {
        let len = dir.0.hypot(dir.1);
        if len <= 0.0 || !len.is_finite() {
            return;
        }
        let (ux, uy) = (dir.0 / len, dir.1 / len);
        let (l, w) = (self.paper(2.2), self.paper(0.75));
        let back = (tip.0 - ux * l, tip.1 - uy * l);
        let pts = [
            tip,
            (back.0 - uy * w, back.1 + ux * w),
            (back.0 + uy * w, back.1 - ux * w),
        ];
        self.path(
            layer,
            &pts,
            true,
            Some(super::palette::DIMENSION),
            None,
            "arrow",
        );
    }

    /// A text with light markup: `_{…}` sets a subscript and `^{…}` a superscript. Everything
    /// else is literal, so names from design files go through unchanged unless they contain
    /// `_{` or `^{` (use [`Sheet::text_plain`] for those).
    pub fn text(&mut self, layer: &'static str, at: (f64, f64), markup: &str, style: TextStyle) {
        let spans = parse_markup(markup);
        self.emit_text(layer, at, &spans, style);
    }

    /// A literal text, no markup.
    pub fn text_plain(
        &mut self,
        layer: &'static str,
        at: (f64, f64),
        text: &str,
        style: TextStyle,
    ) {
        self.emit_text(layer, at, &[(text.to_string(), Shift::None)], style);
    }

    /// The box a text covers on the sheet (user units): its estimated advance, from the cap
    /// height (0.7 em above the baseline) to the descenders (0.2 em below), turned with the
    /// text when it runs upward.
    pub fn text_box(&self, at: (f64, f64), markup: &str, style: TextStyle) -> Rect {
        let size = self.paper(style.size_mm);
        let w = self.text_width(markup, style);
        let (before, after) = match style.anchor {
            Anchor::Start => (0.0, w),
            Anchor::Middle => (w / 2.0, w / 2.0),
            Anchor::End => (w, 0.0),
        };
        let (up, down) = (0.7 * size, 0.2 * size);
        if style.vertical {
            (at.0 - up, at.1 - after, at.0 + down, at.1 + before)
        } else {
            (at.0 - before, at.1 - up, at.0 + after, at.1 + down)
        }
    }

    /// Whether no line drawn so far passes within `margin` (user units) of `rect`.
    pub fn is_clear(&self, rect: Rect, margin: f64) -> bool {
        self.segments.iter().all(|(a, b, half)| {
            let m = margin + half;
            !crosses(*a, *b, (rect.0 - m, rect.1 - m, rect.2 + m, rect.3 + m))
        })
    }

    /// Writes `markup` at the first of `candidates` (anchor point and style) whose box no line
    /// drawn so far strikes, keeping a 0.3 paper-mm gap; at the first candidate if none is
    /// clear. Returns whether the chosen place is clear. Lines drawn later are not seen, so
    /// draw labels after the lines they must avoid.
    pub fn text_clear(
        &mut self,
        layer: &'static str,
        candidates: &[((f64, f64), TextStyle)],
        markup: &str,
    ) -> bool {
        let margin = self.paper(0.3);
        let pick = candidates
            .iter()
            .find(|(at, style)| self.is_clear(self.text_box(*at, markup, *style), margin));
        match pick.or(candidates.first()) {
            Some(&(at, style)) => {
                self.text(layer, at, markup, style);
                pick.is_some()
            }
            None => false,
        }
    }

    /// Estimated advance of a text in user units (for layout and the extent).
    pub fn text_width(&self, markup: &str, style: TextStyle) -> f64 {
        text_width_mm(&parse_markup(markup), style) / self.scale
    }

    fn emit_text(
        &mut self,
        layer: &'static str,
        at: (f64, f64),
        spans: &[(String, Shift)],
        style: TextStyle,
    ) {
        let size = self.paper(style.size_mm);
        let w = text_width_mm(spans, style) / self.scale;
        let (before, after) = match style.anchor {
            Anchor::Start => (0.0, w),
            Anchor::Middle => (w / 2.0, w / 2.0),
            Anchor::End => (w, 0.0),
        };
        let (ascent, descent) = (0.8 * size, 0.3 * size);
        if style.vertical {
            self.cover(at.0 - ascent, at.1 + before);
            self.cover(at.0 + descent, at.1 - after);
        } else {
            self.cover(at.0 - before, at.1 - ascent);
            self.cover(at.0 + after, at.1 + descent);
        }
        let anchor = match style.anchor {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let (x, y) = (num(at.0), num(at.1));
        let mut s = format!(
            r#"<text x="{x}" y="{y}" font-size="{}" text-anchor="{anchor}" fill="{}""#,
            num(size),
            style.colour
        );
        if style.bold {
            s.push_str(r#" font-weight="bold""#);
        }
        if style.vertical {
            let _ = write!(s, r#" transform="rotate(-90 {x} {y})""#);
        }
        s.push('>');
        // Written by hand rather than through `svg::node::element::Text`, whose writer puts a
        // newline before every `<tspan>`: inside `<text>` that newline would render as a space
        // between a symbol and its subscript.
        for (t, shift) in spans {
            match shift {
                Shift::None => s.push_str(&escape(t)),
                Shift::Sub => {
                    let _ = write!(
                        s,
                        r#"<tspan baseline-shift="sub" font-size="70%">{}</tspan>"#,
                        escape(t)
                    );
                }
                Shift::Sup => {
                    let _ = write!(
                        s,
                        r#"<tspan baseline-shift="super" font-size="70%">{}</tspan>"#,
                        escape(t)
                    );
                }
            }
        }
        s.push_str("</text>");
        self.add(layer, Blob::new(s));
    }

    /// The finished SVG document: a white background, the layers in order, a `<title>`, and
    /// a viewBox `margin_mm` (paper) larger than everything drawn.
    pub fn finish(self, title: &str, margin_mm: f64) -> Drawn {
        let m = self.paper(margin_mm);
        let (min, max) = if self.min.0.is_finite() {
            (self.min, self.max)
        } else {
            ((0.0, 0.0), (1.0, 1.0))
        };
        let (x, y) = (min.0 - m, min.1 - m);
        let (w, h) = (max.0 - min.0 + 2.0 * m, max.1 - min.1 + 2.0 * m);
        let mut doc = Document::new()
            .set("version", "1.1")
            .set(
                "viewBox",
                format!("{} {} {} {}", num(x), num(y), num(w), num(h)),
            )
            .set("width", format!("{}mm", num(w * self.scale)))
            .set("height", format!("{}mm", num(h * self.scale)))
            .set("font-family", "DejaVu Sans, Arial, Helvetica, sans-serif")
            .add(Title::new(title))
            .add(
                Rectangle::new()
                    .set("x", num(x))
                    .set("y", num(y))
                    .set("width", num(w))
                    .set("height", num(h))
                    .set("fill", "#ffffff"),
            );
        for (_, g) in self.layers {
            doc = doc.add(g);
        }
        Drawn {
            svg: format!("{doc}\n"),
            size_mm: (w * self.scale, h * self.scale),
        }
    }
}

/// Whether segment `a`-`b` passes through `r` (Liang–Barsky clipping).
pub(crate) fn crosses(a: (f64, f64), b: (f64, f64), r: Rect) -> bool {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a.0 - r.0),
        (dx, r.2 - a.0),
        (-dy, a.1 - r.1),
        (dy, r.3 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

fn stroke<T: Node>(mut node: T, pen: Option<&Pen>) -> T {
    match pen {
        None => node.assign("stroke", "none"),
        Some(p) => {
            node.assign("stroke", p.colour);
            node.assign("stroke-width", num(p.width));
            node.assign("stroke-linecap", "round");
            node.assign("stroke-linejoin", "round");
            if let Some(d) = &p.dash {
                let d: Vec<String> = d.iter().map(|v| num(*v)).collect();
                node.assign("stroke-dasharray", d.join(" "));
                node.assign("stroke-linecap", "butt");
            }
        }
    }
    node
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shift {
    None,
    Sub,
    Sup,
}

fn parse_markup(markup: &str) -> Vec<(String, Shift)> {
    let mut spans = Vec::new();
    let mut rest = markup;
    while !rest.is_empty() {
        let next = [("_{", Shift::Sub), ("^{", Shift::Sup)]
            .iter()
            .filter_map(|(tag, shift)| rest.find(tag).map(|i| (i, *shift)))
            .min_by_key(|(i, _)| *i);
        let Some((i, shift)) = next else {
            spans.push((rest.to_string(), Shift::None));
            break;
        };
        let Some(close) = rest[i + 2..].find('}') else {
            spans.push((rest.to_string(), Shift::None));
            break;
        };
        if i > 0 {
            spans.push((rest[..i].to_string(), Shift::None));
        }
        spans.push((rest[i + 2..i + 2 + close].to_string(), shift));
        rest = &rest[i + 3 + close..];
    }
    spans
}

/// Advance estimate in paper mm: DejaVu Sans averages about 0.6 em per character.
fn text_width_mm(spans: &[(String, Shift)], style: TextStyle) -> f64 {
    let em = if style.bold { 0.66 } else { 0.6 };
    spans
        .iter()
        .map(|(t, shift)| {
            let k = if *shift == Shift::None { 1.0 } else { 0.7 };
            t.chars().count() as f64 * k
        })
        .sum::<f64>()
        * em
        * style.size_mm
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A coordinate as written to the file: at most 4 decimals (0.1 µm), no trailing zeros, no
/// `-0`.
pub(crate) fn num(v: f64) -> String {
    let mut s = format!("{v:.4}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" {
        s = "0".into();
    }
    s
}

/// A value for a label with a fixed number of decimals, with a typographic minus (U+2212)
/// and never `−0.00`.
pub(crate) fn fixed(v: f64, decimals: usize) -> String {
    let s = crate::fixed::fixed(v, decimals);
    match s.strip_prefix('-') {
        Some(abs) => format!("−{abs}"),
        None => s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_never_negative_zero() {
        let table = [
            (0.0, "0"),
            (-0.0, "0"),
            (-0.00001, "0"),
            (1.5, "1.5"),
            (2.0, "2"),
            (-1.234567, "-1.2346"),
            (1e-3, "0.001"),
        ];
        for (v, s) in table {
            assert_eq!(num(v), s, "{v}");
        }
        assert_eq!(fixed(-0.001, 2), "0.00");
        assert_eq!(fixed(-0.5, 2), "−0.50");
        assert_eq!(fixed(9.5, 2), "9.50");
    }

    #[test]
    fn markup_splits_sub_and_superscripts() {
        assert_eq!(
            parse_markup("Δy^{(1,2)} = y_{s}"),
            vec![
                ("Δy".to_string(), Shift::None),
                ("(1,2)".to_string(), Shift::Sup),
                (" = y".to_string(), Shift::None),
                ("s".to_string(), Shift::Sub),
            ]
        );
        assert_eq!(
            parse_markup("joint_a {x}"),
            vec![("joint_a {x}".to_string(), Shift::None)]
        );
        assert_eq!(
            parse_markup("open_{brace"),
            vec![("open_{brace".to_string(), Shift::None)]
        );
    }

    #[test]
    fn text_is_escaped_and_extends_the_sheet() {
        let mut sheet = Sheet::new(10.0, &["a"]);
        sheet.text_plain("a", (0.0, 0.0), "a<b & \"c\"", TextStyle::new(2.5, "#000"));
        let svg = sheet.finish("t", 1.0).svg;
        assert!(svg.contains("a&lt;b &amp; &quot;c&quot;"), "{svg}");
        roxmltree::Document::parse(&svg).unwrap();
    }
}
