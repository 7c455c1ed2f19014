//! DXF round trip: export, import, same layout to 1e-9 mm; and the import's refusals.

use crate::common;
use common::designs as common_designs;

use dlw::design::{Design, DesignFile};
use dlw::drawing::{layout_from_dxf, layout_to_dxf, DxfImportError};
use dlw::layout::Layout;
use dlw::rules;

const TOLERANCE_MM: f64 = 1e-9;

fn checked(file: DesignFile) -> Layout {
    rules::check_file(file).unwrap().layout
}

fn round_trip(layout: &Layout) {
    let bytes = layout_to_dxf(layout, 0.08).unwrap();
    let back = layout_from_dxf(&bytes).unwrap();
    assert_eq!(back.untagged, 0);
    assert_eq!(back.clearance_mm, 0.08);
    let diff = layout
        .max_difference_mm(&back.layout)
        .unwrap_or_else(|e| panic!("{}: {e}", layout.name));
    assert!(
        diff <= TOLERANCE_MM,
        "{}: differs by {diff:e} mm",
        layout.name
    );
}

#[test]
fn shipped_designs_round_trip() {
    for path in common_designs::shipped() {
        round_trip(&checked(DesignFile::read(&path).unwrap()));
    }
}

#[test]
fn generated_designs_round_trip() {
    for text in [common_designs::BSN_WIDE, common_designs::UAN_THREE] {
        let layout = checked(DesignFile::from_toml(text).unwrap());
        round_trip(&layout);
    }
}

#[test]
fn traces_split_at_the_seam_round_trip() {
    // Pads wider than the tube: no seam misses the traces, so the U-trace's bridge is split.
    // (The rules refuse this design; the drawing must still read back exactly.)
    let text = common_designs::UAN_THREE
        .replace("outer_radius_mm = 0.6", "outer_radius_mm = 0.35")
        .replace("inner_radius_mm = 0.45", "inner_radius_mm = 0.25")
        .replace("notch_arc_mm = 2.4", "notch_arc_mm = 1.2")
        .replace("pad_turns = 3", "pad_turns = 6");
    let layout = Layout::from_design(&Design::from_toml(&text).unwrap()).unwrap();
    assert!(
        layout.sensors[0].pieces.len() > 1,
        "{:?}",
        layout.sensors[0]
    );
    round_trip(&layout);
}

fn joint_a_dxf() -> String {
    let layout = checked(DesignFile::read(&common_designs::shipped()[0]).unwrap());
    String::from_utf8(layout_to_dxf(&layout, 0.08).unwrap()).unwrap()
}

#[test]
fn inch_drawings_are_scaled_and_other_units_refused() {
    let text = joint_a_dxf();
    let inches = text.replacen(
        "$INSUNITS\r\n 70\r\n     4",
        "$INSUNITS\r\n 70\r\n     1",
        1,
    );
    assert_ne!(inches, text);
    let back = layout_from_dxf(inches.as_bytes()).unwrap();
    // The numbers are in inches now: Joint A's first notch starts 1 inch from the free end.
    let x0 = back.layout.notches[0].outline[0].exterior().0[0].x;
    assert!((x0 - 25.4).abs() < 1e-9, "{x0}");
    let feet = text.replacen(
        "$INSUNITS\r\n 70\r\n     4",
        "$INSUNITS\r\n 70\r\n     2",
        1,
    );
    let err = layout_from_dxf(feet.as_bytes()).unwrap_err();
    assert!(
        matches!(err, DxfImportError::Units { insunits: 2, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("$INSUNITS = 2 (feet)"), "{err}");
}

#[test]
fn unknown_layers_are_ignored_and_counted() {
    let text = joint_a_dxf().replacen("  8\r\nSENSOR\r\n", "  8\r\nTRACES\r\n", 1);
    let back = layout_from_dxf(text.as_bytes()).unwrap();
    assert_eq!(back.ignored.get("TRACES"), Some(&1));
    assert!(back.layout.sensors.is_empty());
    assert_eq!(
        back.ignored_warnings(),
        vec!["ignored 1 entity on layer \"TRACES\", which is not a dlw layer (dlw reads NOTCHES, SENSOR, LEADS_PADS, PARTING and ANNOTATION)"]
    );
}

#[test]
fn open_notch_contours_are_refused() {
    let text = joint_a_dxf();
    let at = text.find("  8\r\nNOTCHES\r\n").unwrap();
    let flag = at + text[at..].find(" 70\r\n     1\r\n").unwrap();
    let open = format!("{} 70\r\n     0\r\n{}", &text[..flag], &text[flag + 14..]);
    let err = layout_from_dxf(open.as_bytes()).unwrap_err().to_string();
    assert!(
        err.starts_with("NOTCHES outline does not close: its end at x = 1.0000 mm, s = 6.7006 mm is 5.6100 mm from the nearest other end, at x = 1.0000 mm, s = 1.0906 mm"),
        "{err}"
    );
}

#[test]
fn missing_layout_numbers_are_refused() {
    let text = joint_a_dxf().replacen("1000\r\nlayout\r\n", "1000\r\nsomething\r\n", 1);
    let err = layout_from_dxf(text.as_bytes()).unwrap_err().to_string();
    assert!(
        err.starts_with("no dlw layout numbers: none found"),
        "{err}"
    );
}

#[test]
fn garbage_is_refused() {
    let err = layout_from_dxf(b"hello\r\nworld\r\n").unwrap_err();
    assert!(matches!(err, DxfImportError::NotDxf { .. }), "{err}");
    assert!(err.to_string().starts_with("not a DXF file: "), "{err}");
}
