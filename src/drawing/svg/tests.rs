//! Structural tests: every drawing is parsed back as XML and checked for its features, colours,
//! extent and numbers.

use std::f64::consts::PI;

use roxmltree::{Document, Node};

use super::fixture::{design, layout_for, outside_design};
use super::palette;
use super::sheet::fixed;
use super::*;
use crate::design::Design;
use crate::layout::Layout;

/// A shipped design and its layout from the layout generator.
fn sample(stem: &str) -> (Design, Layout) {
    let d = design(stem);
    let l = Layout::from_design(&d).unwrap();
    (d, l)
}

fn parse(svg: &str) -> Document<'_> {
    Document::parse(svg).unwrap_or_else(|e| panic!("not XML: {e}"))
}

fn view_box(doc: &Document) -> [f64; 4] {
    let vb: Vec<f64> = doc
        .root_element()
        .attribute("viewBox")
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    [vb[0], vb[1], vb[2], vb[3]]
}

fn mm_attr(doc: &Document, name: &str) -> f64 {
    let v = doc.root_element().attribute(name).unwrap();
    v.strip_suffix("mm")
        .unwrap_or_else(|| panic!("{name}={v} not in mm"))
        .parse()
        .unwrap()
}

fn with_class<'a>(doc: &'a Document, class: &str) -> Vec<Node<'a, 'a>> {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some(class))
        .collect()
}

/// Every `<text>` as the string a reader sees (sub/superscripts run in).
fn texts(doc: &Document) -> Vec<String> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| {
            n.descendants()
                .filter(|d| d.is_text())
                .filter_map(|d| d.text())
                .collect()
        })
        .collect()
}

fn has_text(doc: &Document, needle: &str) -> bool {
    texts(doc).iter().any(|t| t.contains(needle))
}

/// All numbers in a path's `d`, as (x, y) pairs.
fn path_points(n: &Node) -> Vec<(f64, f64)> {
    let d = n.attribute("d").unwrap();
    let nums: Vec<f64> = d
        .split(|c: char| c.is_ascii_alphabetic() || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| t.parse().unwrap())
        .collect();
    nums.chunks(2).map(|c| (c[0], c[1])).collect()
}

fn assert_clean(svg: &str) {
    for bad in ["NaN", "inf", "undefined"] {
        assert!(!svg.contains(bad), "SVG contains {bad}");
    }
}

#[test]
fn joint_a_layout_has_every_feature_in_fig1_colours() {
    let (d, l) = sample("joint-a");
    let svg = layout_svg(&l, &d).unwrap();
    assert_clean(&svg);
    let doc = parse(&svg);
    let notches = with_class(&doc, "notch");
    let pieces: usize = l.notches.iter().map(|n| n.outline.len()).sum();
    assert_eq!(notches.len(), pieces);
    assert_eq!(notches.len(), 10);
    for n in &notches {
        assert_eq!(n.attribute("fill"), Some(palette::NOTCH_FILL));
        assert!(n.attribute("d").unwrap().ends_with('Z'), "notch not closed");
    }
    let tw = fixed(l.trace_width_mm, 4);
    for (class, colour, count) in [
        ("sensor", palette::SENSOR, 1),
        ("lead", palette::LEADS_PADS, 2),
        ("pad", palette::LEADS_PADS, 2),
    ] {
        let found = with_class(&doc, class);
        assert_eq!(found.len(), count, "{class}");
        for n in found {
            assert_eq!(n.attribute("stroke"), Some(colour), "{class}");
            assert_eq!(n.attribute("fill"), Some("none"), "{class}");
            let w: f64 = n.attribute("stroke-width").unwrap().parse().unwrap();
            assert_eq!(fixed(w, 4), tw, "{class} drawn at its real width");
        }
    }
    let parting = with_class(&doc, "parting");
    assert_eq!(parting.len(), 1);
    assert_eq!(parting[0].attribute("stroke"), Some(palette::PARTING));
    assert!(parting[0].attribute("stroke-dasharray").is_some());
    for needle in [
        "h = 0.50",
        "c = 0.50",
        "L = N·h + (N−1)·c = 9.50",
        "sn = 5.61",
        "ss = 0.40",
        "2πro = 7.79",
        "Joint A — unrolled layout (UAN), scale 10:1",
        "ȳ = 0.936, ys = 1.224, Δy = 0.288 mm",
        &format!("to parting cut {}", fixed(l.length_mm, 2)),
        &format!(
            "The top and bottom edges are the seam, s = {} mm",
            fixed(l.seam_s_mm, 2)
        ),
    ] {
        assert!(
            has_text(&doc, needle),
            "missing {needle:?} in {:?}",
            texts(&doc)
        );
    }
}

#[test]
fn layout_prints_to_scale_and_covers_the_tube() {
    for stem in ["joint-a", "joint-b", "joint-c", "joint-d"] {
        let (d, l) = sample(stem);
        let svg = layout_svg(&l, &d).unwrap();
        let doc = parse(&svg);
        let [x, y, w, h] = view_box(&doc);
        // The tube is drawn at x ∈ [0, length], sheet y ∈ [0, C].
        assert!(x < 0.0 && x + w > l.length_mm, "{stem}: {x} {w}");
        assert!(y < 0.0 && y + h > l.circumference_mm, "{stem}: {y} {h}");
        let scale = mm_attr(&doc, "width") / w;
        assert!((mm_attr(&doc, "height") / h - scale).abs() < 1e-3, "{stem}");
        assert!((scale - 10.0).abs() < 1e-3, "{stem}: scale {scale}");
        // Fits A4 landscape, as the automatic scale promises.
        assert!(mm_attr(&doc, "width") <= 297.0 && mm_attr(&doc, "height") <= 210.0);
        // Every notch corner lies inside the tube rectangle on the sheet.
        for n in with_class(&doc, "notch") {
            for (px, py) in path_points(&n) {
                assert!(px > 0.0 && px < l.length_mm, "{stem}: x {px}");
                assert!(
                    py >= -1e-9 && py <= l.circumference_mm + 1e-9,
                    "{stem}: y {py}"
                );
            }
        }
    }
}

#[test]
fn notches_are_drawn_where_the_layout_puts_them() {
    let (d, l) = sample("joint-a");
    let svg = layout_svg(&l, &d).unwrap();
    let doc = parse(&svg);
    let top = l.seam_s_mm + l.circumference_mm;
    for (n, drawn) in l.notches.iter().zip(with_class(&doc, "notch")) {
        let want: Vec<(f64, f64)> = n.outline[0]
            .exterior()
            .coords()
            .map(|c| (c.x, top - c.y))
            .collect();
        let got = path_points(&drawn);
        assert_eq!(got.len(), want.len() - 1, "closing point dropped, Z closes");
        for (g, w) in got.iter().zip(&want) {
            assert!((g.0 - w.0).abs() < 1e-4 && (g.1 - w.1).abs() < 1e-4);
        }
    }
}

#[test]
fn joint_c_layout_has_both_sides_and_both_sensors() {
    let (d, l) = sample("joint-c");
    let svg = layout_svg(&l, &d).unwrap();
    assert_clean(&svg);
    let doc = parse(&svg);
    assert_eq!(with_class(&doc, "notch").len(), 20);
    assert_eq!(with_class(&doc, "sensor").len(), 2);
    assert_eq!(with_class(&doc, "pad").len(), 4);
    for needle in ["sn = 1.65", "ss = 2.13", "Δy(1,2) = 0.380 mm", "BSN"] {
        assert!(
            has_text(&doc, needle),
            "missing {needle:?} in {:?}",
            texts(&doc)
        );
    }
}

#[test]
fn a_design_outside_the_paper_shows_l_and_the_notched_length_apart() {
    let d = outside_design();
    let l = Layout::from_design(&d).unwrap();
    let svg = layout_svg(&l, &d).unwrap();
    assert_clean(&svg);
    let doc = parse(&svg);
    assert_eq!(with_class(&doc, "notch").len(), 14);
    for needle in [
        "notched length N·h + (N−1)·c = 13.30",
        "L = 14.00 (sensor gauge length)",
        "h = 0.30",
        "c = 0.70",
    ] {
        assert!(
            has_text(&doc, needle),
            "missing {needle:?} in {:?}",
            texts(&doc)
        );
    }
    let w: f64 = with_class(&doc, "sensor")[0]
        .attribute("stroke-width")
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(w, 0.08);
}

#[test]
fn features_split_at_the_seam_are_drawn_piece_by_piece() {
    let d = design("joint-a");
    // The seam through the middle of the notches: every notch in two pieces.
    let l = layout_for(&d, -PI * d.file.outer_radius_mm);
    assert!(l.notches.iter().all(|n| n.outline.len() == 2));
    let svg = layout_svg(&l, &d).unwrap();
    assert_clean(&svg);
    let doc = parse(&svg);
    assert_eq!(with_class(&doc, "notch").len(), 20);
    // h and c still measured (a split notch keeps its x extent); s_n in two shares.
    for needle in ["h = 0.50", "c = 0.50"] {
        assert!(
            has_text(&doc, needle),
            "missing {needle:?} in {:?}",
            texts(&doc)
        );
    }
    let shares: Vec<f64> = texts(&doc)
        .iter()
        .filter_map(|t| {
            t.strip_prefix("sn: ")?
                .strip_suffix(" of 5.61")?
                .parse()
                .ok()
        })
        .collect();
    assert_eq!(shares.len(), 2, "{:?}", texts(&doc));
    assert!(
        (shares.iter().sum::<f64>() - 5.61).abs() < 0.011,
        "{shares:?}"
    );
}

#[test]
fn explicit_scale_sets_the_printed_size() {
    let (d, l) = sample("joint-b");
    let svg = layout_svg_with(
        &l,
        &d,
        &SvgOptions {
            print_scale: Some(5.0),
        },
    )
    .unwrap();
    let doc = parse(&svg);
    let [_, _, w, _] = view_box(&doc);
    assert!((mm_attr(&doc, "width") - 5.0 * w).abs() < 1e-3);
    assert!(has_text(&doc, "scale 5:1"));
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e4] {
        let err = layout_svg_with(
            &l,
            &d,
            &SvgOptions {
                print_scale: Some(bad),
            },
        )
        .unwrap_err();
        assert!(matches!(err, SvgError::BadScale { .. }), "{bad}: {err}");
        assert!(err.to_string().contains("1000"), "{err}");
    }
}

#[test]
fn bad_layouts_are_refused_with_the_value() {
    let (d, l) = sample("joint-a");
    let mut nan = l.clone();
    nan.sensors[0].pieces[0].0[1].y = f64::NAN;
    let err = layout_svg(&nan, &d).unwrap_err().to_string();
    assert_eq!(err, "sensor 0 point s = NaN is not a finite number");
    let mut short = l.clone();
    short.length_mm = 0.0;
    let err = layout_svg(&short, &d).unwrap_err().to_string();
    assert_eq!(err, "layout length_mm = 0 mm must be greater than 0");
    let mut wide = l;
    wide.trace_width_mm = f64::INFINITY;
    assert!(matches!(
        layout_svg(&wide, &d),
        Err(SvgError::NotFinite { .. })
    ));
}

/// The cross-section: sectors, planes at the geometry crate's heights, arms, Δy arrows.
fn check_section(stem: &str) {
    let d = design(stem);
    let s = d.joint.section();
    let svg = section_svg(&d).unwrap();
    assert_clean(&svg);
    let doc = parse(&svg);
    // Prints to scale on A4 landscape, the whole section inside the viewBox.
    let [x, y, w, h] = view_box(&doc);
    let scale = mm_attr(&doc, "width") / w;
    assert!((mm_attr(&doc, "height") / h - scale).abs() < 1e-3);
    assert!(mm_attr(&doc, "width") <= super::options::PAGE_MM.0);
    assert!(mm_attr(&doc, "height") <= super::options::PAGE_MM.1);
    let ro = s.outer_radius_mm();
    assert!(x < -ro && x + w > ro && y < -ro && y + h > ro, "{stem}");
    let bsn = s.style() == dlw_geometry::NotchStyle::Bsn;
    let sides = if bsn { 2 } else { 1 };
    assert_eq!(with_class(&doc, "material").len(), sides);
    assert_eq!(with_class(&doc, "notch-cut").len(), sides);
    assert_eq!(with_class(&doc, "sensor-arm").len(), 2 * sides);
    for n in with_class(&doc, "notch-cut") {
        assert_eq!(n.attribute("fill"), Some(palette::NOTCH_GHOST));
    }
    // Arms on the outer surface at φ = ±φ_s/2 (+ π), i.e. at height ±y_s.
    for arm in with_class(&doc, "sensor-arm") {
        let x: f64 = arm.attribute("cx").unwrap().parse().unwrap();
        let y: f64 = arm.attribute("cy").unwrap().parse().unwrap();
        assert!((x.hypot(y) - s.outer_radius_mm()).abs() < 1e-4);
        assert!((y.abs() - s.sensor_plane_mm()).abs() < 1e-4, "{y}");
    }
    // Planes as dashed horizontal lines at sheet y = −ȳ and ∓y_s.
    let neutral = with_class(&doc, "neutral-plane");
    assert_eq!(neutral.len(), 1);
    assert!(neutral[0].attribute("stroke-dasharray").is_some());
    for (_, y) in path_points(&neutral[0]) {
        assert!((y + s.neutral_axis_mm()).abs() < 1e-4, "ȳ line at {y}");
    }
    let planes = with_class(&doc, "sensor-plane");
    assert_eq!(planes.len(), sides);
    for (p, sign) in planes.iter().zip([1.0, -1.0]) {
        for (_, y) in path_points(p) {
            assert!(
                (y + sign * s.sensor_plane_mm()).abs() < 1e-4,
                "y_s line at {y}"
            );
        }
    }
    // Δy: an arrow tip on each plane.
    let tips: Vec<(f64, f64)> = with_class(&doc, "arrow")
        .iter()
        .map(|a| path_points(a)[0])
        .collect();
    for y in [-s.neutral_axis_mm(), -s.sensor_plane_mm()] {
        assert!(
            tips.iter()
                .any(|t| (t.1 - y).abs() < 1e-4 && t.0 > s.outer_radius_mm()),
            "no Δy arrow at {y}: {tips:?}"
        );
    }
    let mut needles = vec![
        format!("ȳ = {} mm", fixed(s.neutral_axis_mm(), 3)),
        format!("ys = {} mm", fixed(s.sensor_plane_mm(), 3)),
        format!("Δy = ys − ȳ = {} mm", fixed(s.offset_mm(), 3)),
        format!("ro = {}", fixed(s.outer_radius_mm(), 3)),
        format!("ri = {}", fixed(s.inner_radius_mm(), 3)),
        format!("sn = {} mm", fixed(s.notch_arc_mm(), 2)),
    ];
    if let Some(dy12) = s.two_sensor_offset_mm() {
        needles.push(format!("Δy(1,2) = 2ys = {} mm", fixed(dy12, 3)));
        assert!(tips
            .iter()
            .any(|t| (t.1 - s.sensor_plane_mm()).abs() < 1e-4));
    }
    for needle in needles {
        assert!(
            has_text(&doc, &needle),
            "missing {needle:?} in {:?}",
            texts(&doc)
        );
    }
}

#[test]
fn joint_a_section_marks_the_planes_and_delta_y() {
    check_section("joint-a");
    let doc_svg = section_svg(&design("joint-a")).unwrap();
    let doc = parse(&doc_svg);
    assert!(has_text(&doc, "scale 50:1"), "{:?}", texts(&doc));
    assert!(has_text(&doc, "ȳ = 0.936 mm"));
    assert!(has_text(&doc, "Δy = ys − ȳ = 0.288 mm"));
}

#[test]
fn joint_c_section_has_two_notches_two_sensors_and_delta_y_12() {
    check_section("joint-c");
    let doc_svg = section_svg(&design("joint-c")).unwrap();
    let doc = parse(&doc_svg);
    assert!(has_text(&doc, "ȳ = 0.000 mm"));
    assert!(has_text(&doc, "Δy(1,2) = 2ys = 0.380 mm"));
}

#[test]
fn sections_of_other_designs_draw() {
    check_section("joint-b");
    let d = outside_design();
    let svg = section_svg(&d).unwrap();
    assert_clean(&svg);
    parse(&svg);
}

/// `docs/img/joint-a-section.svg` is this code's output; rerun with `DLW_UPDATE_DOCS=1` to
/// regenerate it after a deliberate change.
#[test]
fn docs_section_figure_is_current() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/img/joint-a-section.svg");
    let svg = section_svg(&design("joint-a")).unwrap();
    if std::env::var_os("DLW_UPDATE_DOCS").is_some() {
        crate::output::write_atomic(&path, svg.as_bytes()).unwrap();
    }
    let on_disk = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e}; run with DLW_UPDATE_DOCS=1", path.display()));
    assert!(
        on_disk == svg,
        "{} is stale; regenerate with DLW_UPDATE_DOCS=1 cargo test -p dlw --lib drawing::svg",
        path.display()
    );
}

#[test]
fn snapshots() {
    let (d, l) = sample("joint-a");
    insta::assert_snapshot!("joint_a_layout", layout_svg(&l, &d).unwrap());
    insta::assert_snapshot!("joint_c_section", section_svg(&design("joint-c")).unwrap());
}

/// Writes sample drawings to `$DLW_SVG_SAMPLES` (when set) for looking at in a browser.
#[test]
fn write_samples_when_asked() {
    let Some(dir) = std::env::var_os("DLW_SVG_SAMPLES") else {
        return;
    };
    let dir = std::path::PathBuf::from(dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut designs: Vec<(String, Design)> = ["joint-a", "joint-b", "joint-c"]
        .iter()
        .map(|s| (s.to_string(), design(s)))
        .collect();
    designs.push(("outside".into(), outside_design()));
    for (stem, d) in designs {
        let l = Layout::from_design(&d).unwrap();
        let layout = layout_svg(&l, &d).unwrap();
        let section = section_svg(&d).unwrap();
        parse(&layout);
        parse(&section);
        std::fs::write(dir.join(format!("{stem}-layout.svg")), layout).unwrap();
        std::fs::write(dir.join(format!("{stem}-section.svg")), section).unwrap();
    }
    let d = design("joint-a");
    let split = layout_for(&d, -PI * d.file.outer_radius_mm);
    std::fs::write(
        dir.join("joint-a-split-layout.svg"),
        layout_svg(&split, &d).unwrap(),
    )
    .unwrap();
}
