//! No label struck by a line: every `<text>`'s box, estimated as the sheet estimates it
//! (0.6 em per character, 0.66 bold, 70 % for sub- and superscripts; cap height 0.7 em above
//! the baseline, descenders 0.2 em below), against every stroked segment of every `<path>`
//! (widened by half its stroke). Read from the finished SVG, so it checks what a reader sees.

use roxmltree::{Document, Node};

use super::sheet::crosses;

use super::sheet::{Rect, Segment};

/// One label and the box it covers.
#[derive(Debug, Clone)]
pub(super) struct Label {
    pub text: String,
    pub rect: Rect,
}

fn attr(n: &Node, name: &str) -> f64 {
    n.attribute(name)
        .and_then(|v| v.parse().ok())
        .unwrap_or(0.0)
}

/// Every `<text>` with its box.
pub(super) fn labels(doc: &Document) -> Vec<Label> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| {
            let size = attr(&n, "font-size");
            let bold = n.attribute("font-weight") == Some("bold");
            let mut chars = 0.0;
            let mut text = String::new();
            for d in n.descendants().filter(|d| d.is_text()) {
                let t = d.text().unwrap_or("");
                let small = d.parent().is_some_and(|p| p.has_tag_name("tspan"));
                chars += t.chars().count() as f64 * if small { 0.7 } else { 1.0 };
                text.push_str(t);
            }
            let w = chars * if bold { 0.66 } else { 0.6 } * size;
            let (before, after) = match n.attribute("text-anchor") {
                Some("middle") => (w / 2.0, w / 2.0),
                Some("end") => (w, 0.0),
                _ => (0.0, w),
            };
            let (x, y) = (attr(&n, "x"), attr(&n, "y"));
            let (up, down) = (0.7 * size, 0.2 * size);
            let vertical = n
                .attribute("transform")
                .is_some_and(|t| t.starts_with("rotate(-90"));
            let rect = if vertical {
                (x - up, y - after, x + down, y + before)
            } else {
                (x - before, y - up, x + after, y + down)
            };
            Label { text, rect }
        })
        .collect()
}

/// Every stroked segment: `((x0, y0), (x1, y1), half width)`.
pub(super) fn segments(doc: &Document) -> Vec<Segment> {
    let mut out = Vec::new();
    for n in doc.descendants().filter(|n| n.has_tag_name("path")) {
        if matches!(n.attribute("stroke"), None | Some("none")) {
            continue;
        }
        let half = attr(&n, "stroke-width") / 2.0;
        let d = n.attribute("d").unwrap_or("");
        let closed = d.trim_end().ends_with('Z');
        let nums: Vec<f64> = d
            .split(|c: char| c.is_ascii_alphabetic() || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .filter_map(|t| t.parse().ok())
            .collect();
        let mut pts: Vec<(f64, f64)> = nums.chunks(2).map(|c| (c[0], c[1])).collect();
        if closed && pts.len() > 2 {
            pts.push(pts[0]);
        }
        for w in pts.windows(2) {
            out.push((w[0], w[1], half));
        }
    }
    out
}

/// Every label a line strikes, as `label: segment` descriptions.
pub(super) fn struck(svg: &str) -> Vec<String> {
    let doc = Document::parse(svg).expect("the SVG is XML");
    let segs = segments(&doc);
    let mut out = Vec::new();
    for l in labels(&doc) {
        for (a, b, half) in &segs {
            let r = (
                l.rect.0 - half,
                l.rect.1 - half,
                l.rect.2 + half,
                l.rect.3 + half,
            );
            if crosses(*a, *b, r) {
                out.push(format!(
                    "{:?} (box {:.3?}) struck by the line {:.3?} → {:.3?}",
                    l.text, l.rect, a, b
                ));
                break;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::fixture::{design, outside_design};
    use super::super::{layout_svg, section_svg};
    use super::*;
    use crate::layout::Layout;

    #[test]
    fn the_check_finds_a_struck_label_and_passes_a_clear_one() {
        let svg = |line: &str| {
            format!(
                r##"<svg xmlns="http://www.w3.org/2000/svg"><text x="10" y="10" font-size="2" text-anchor="middle" fill="#000">parting cut</text>{line}</svg>"##
            )
        };
        // "parting cut": 11 characters, 13.2 wide, centred on x = 10; cap height 1.4.
        let through = r##"<path d="M10 0 L10 20" stroke="#000" stroke-width="0.1" fill="none"/>"##;
        assert_eq!(struck(&svg(through)).len(), 1);
        let under =
            r##"<path d="M0 10.6 L20 10.6" stroke="#000" stroke-width="0.1" fill="none"/>"##;
        assert!(struck(&svg(under)).is_empty(), "{:?}", struck(&svg(under)));
        let beside = r##"<path d="M17 0 L17 20" stroke="#000" stroke-width="0.1" fill="none"/>"##;
        assert!(struck(&svg(beside)).is_empty());
        let unstroked = r##"<path d="M10 0 L10 20" stroke="none" fill="#000"/>"##;
        assert!(struck(&svg(unstroked)).is_empty());
        let vertical = r##"<svg xmlns="http://www.w3.org/2000/svg"><text x="10" y="10" font-size="2" fill="#000" transform="rotate(-90 10 10)">sn</text><path d="M0 9 L20 9" stroke="#000" stroke-width="0.1"/></svg>"##;
        assert_eq!(struck(vertical).len(), 1, "a rotated label runs upward");
    }

    #[test]
    fn no_label_is_struck_on_the_shipped_and_other_drawings() {
        let mut found = Vec::new();
        for stem in ["joint-a", "joint-b", "joint-c", "joint-d"] {
            let d = design(stem);
            let l = Layout::from_design(&d).unwrap();
            for s in struck(&layout_svg(&l, &d).unwrap()) {
                found.push(format!("{stem} layout: {s}"));
            }
            for s in struck(&section_svg(&d).unwrap()) {
                found.push(format!("{stem} section: {s}"));
            }
        }
        let d = outside_design();
        let l = Layout::from_design(&d).unwrap();
        for s in struck(&layout_svg(&l, &d).unwrap()) {
            found.push(format!("outside layout: {s}"));
        }
        assert!(found.is_empty(), "{}", found.join("\n"));
    }
}
