//! Every drawing read back with ezdxf (`tests/scripts/dxf_check.py`): audit clean, layers and
//! colours, entity counts per layer, total notch area; and files ezdxf itself wrote read back.
//!
//! Needs `python3` with `ezdxf` (installed by `scripts/test.sh`); without them these tests fail.

use crate::common;
use common::designs as common_designs;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use dlw::design::DesignFile;
use dlw::drawing::layout_from_dxf;
use dlw::layout::Layout;
use dlw::rules;
use geo::MapCoordsInPlace;

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scripts/dxf_check.py")
}

fn python(args: &[&str]) -> Output {
    Command::new("python3")
        .arg(script())
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run python3 ({e}): these checks need python3 with ezdxf (scripts/test.sh installs it)"))
}

fn assert_ok(out: &Output, what: &str) {
    assert!(
        out.status.success(),
        "{what}: exit {:?}\nstdout: {}\nstderr: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Draws `design` with the real binary into `dir`, returning the DXF path and the layout.
fn draw(design: &Path, dir: &Path) -> (PathBuf, Layout, DesignFile) {
    let stem = design.file_stem().unwrap().to_string_lossy();
    let dxf = dir.join(format!("{stem}.dxf"));
    let out = Command::new(env!("CARGO_BIN_EXE_dlw"))
        .arg("draw")
        .arg(design)
        .arg("--dxf")
        .arg(&dxf)
        .output()
        .unwrap();
    assert_ok(&out, &format!("dlw draw {}", design.display()));
    let file = DesignFile::read(design).unwrap();
    let layout = rules::check_file(file.clone()).unwrap().layout;
    (dxf, layout, file)
}

/// What ezdxf must find: entity counts per layer from the layout, and the notch area from the
/// design's own numbers, `N·h·s_n` per side.
fn expectation(layout: &Layout, file: &DesignFile) -> String {
    let pieces =
        |traces: &[dlw::layout::Trace]| traces.iter().map(|t| t.pieces.len()).sum::<usize>();
    let notches: usize = layout.notches.iter().map(|n| n.outline.len()).sum();
    let sides = match file.style {
        dlw_geometry::NotchStyle::Uan => 1.0,
        dlw_geometry::NotchStyle::Bsn => 2.0,
    };
    let area = f64::from(file.notch_count) * file.notch_width_mm * file.notch_arc_mm * sides;
    // Title, frame, scale, scale bar, its label; and the note when the seam splits notches.
    // TUBE: the outline, two seam lines, two seam labels.
    let annotation = 5 + usize::from(layout.notches.iter().any(|n| n.outline.len() > 1));
    format!(
        r#"{{"layers": {{"NOTCHES": {notches}, "SENSOR": {}, "LEADS_PADS": {}, "PARTING": {}, "ANNOTATION": {annotation}, "TUBE": 5}}, "notch_area_mm2": {area}}}"#,
        pieces(&layout.sensors),
        pieces(&layout.leads) + pieces(&layout.pads),
        layout.parting.len()
    )
}

fn audit(design: &Path) {
    let dir = tempfile::tempdir().unwrap();
    let (dxf, layout, file) = draw(design, dir.path());
    let out = python(&["audit", dxf.to_str().unwrap(), &expectation(&layout, &file)]);
    assert_ok(&out, &format!("ezdxf audit of {}", design.display()));
    let out = python(&["tube", dxf.to_str().unwrap(), &tube_expectation(&layout)]);
    assert_ok(&out, &format!("ezdxf TUBE layer of {}", design.display()));
}

/// The tube outline and seam the `TUBE` layer must show, and whether the split note is due.
fn tube_expectation(layout: &Layout) -> String {
    format!(
        r#"{{"seam": {}, "circumference": {}, "length": {}, "split": {}}}"#,
        layout.seam_s_mm,
        layout.circumference_mm,
        layout.length_mm,
        layout.notches.iter().any(|n| n.outline.len() > 1)
    )
}

/// Joints B and D (UAN, split at the seam) carry the note; A and C (nothing split) do not; and
/// the check fails when the expectation is wrong, so it can fail.
#[test]
fn the_tube_layer_and_the_split_note() {
    let shipped = common_designs::shipped();
    let dir = tempfile::tempdir().unwrap();
    for (design, split) in shipped.iter().zip([false, true, false, true]) {
        let (dxf, layout, _) = draw(design, dir.path());
        assert_eq!(
            layout.notches.iter().any(|n| n.outline.len() > 1),
            split,
            "{}",
            design.display()
        );
        let text = String::from_utf8(std::fs::read(&dxf).unwrap()).unwrap();
        assert_eq!(
            text.contains("cross the seam"),
            split,
            "{}",
            design.display()
        );
        let wrong = tube_expectation(&layout).replace(
            &format!("\"split\": {split}"),
            &format!("\"split\": {}", !split),
        );
        let out = python(&["tube", dxf.to_str().unwrap(), &wrong]);
        assert_eq!(out.status.code(), Some(1), "{}", design.display());
    }
    // The imported layout ignores the TUBE layer: the drawing still reads back exactly.
    let again = tempfile::tempdir().unwrap();
    let (dxf, layout, _) = draw(&shipped[1], again.path());
    let back = layout_from_dxf(&std::fs::read(&dxf).unwrap()).unwrap();
    assert!(layout.max_difference_mm(&back.layout).unwrap() <= 1e-9);
}

#[test]
fn shipped_drawings_pass_ezdxf() {
    for design in common_designs::shipped() {
        audit(&design);
    }
}

#[test]
fn drawings_of_designs_outside_the_paper_pass_ezdxf() {
    for text in [common_designs::BSN_WIDE, common_designs::UAN_THREE] {
        let dir = tempfile::tempdir().unwrap();
        let design = dir.path().join("design.toml");
        std::fs::write(&design, text).unwrap();
        audit(&design);
    }
}

#[test]
fn the_audit_catches_a_wrong_area() {
    // The check itself must be able to fail.
    let dir = tempfile::tempdir().unwrap();
    let (dxf, layout, file) = draw(&common_designs::shipped()[0], dir.path());
    let wrong = expectation(&layout, &file)
        .replace("\"notch_area_mm2\": 28.05", "\"notch_area_mm2\": 28.06");
    let out = python(&["audit", dxf.to_str().unwrap(), &wrong]);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("notch area 28.050000000"));
}

#[test]
fn a_notch_moved_in_ezdxf_is_read_where_it_was_moved() {
    let dir = tempfile::tempdir().unwrap();
    let (dxf, layout, _) = draw(&common_designs::shipped()[0], dir.path());
    let moved = dir.path().join("moved.dxf");
    let out = python(&[
        "resave",
        dxf.to_str().unwrap(),
        moved.to_str().unwrap(),
        "--move-notch",
        "0",
        "0.05",
    ]);
    assert_ok(&out, "ezdxf resave");
    let back = layout_from_dxf(&std::fs::read(&moved).unwrap()).unwrap();
    let mut expected = layout.clone();
    for piece in &mut expected.notches[0].outline {
        piece.map_coords_in_place(|c| geo::Coord {
            x: c.x,
            y: c.y + 0.05,
        });
    }
    let diff = expected.max_difference_mm(&back.layout).unwrap();
    assert!(diff <= 1e-9, "differs by {diff:e} mm");
    assert!(layout.max_difference_mm(&back.layout).unwrap() > 0.049);
}

#[test]
fn drawings_without_dlw_xdata_are_read_from_their_geometry() {
    // Joint A (nothing split), B (notches split at the seam), C (BSN, two sensors).
    for design in &common_designs::shipped()[..3] {
        let dir = tempfile::tempdir().unwrap();
        let (dxf, layout, _) = draw(design, dir.path());
        let bare = dir.path().join("bare.dxf");
        let out = python(&[
            "resave",
            dxf.to_str().unwrap(),
            bare.to_str().unwrap(),
            "--strip-xdata",
        ]);
        assert_ok(&out, "ezdxf resave without xdata");
        let back = layout_from_dxf(&std::fs::read(&bare).unwrap()).unwrap();
        assert!(back.untagged > 0);
        let diff = layout
            .max_difference_mm(&back.layout)
            .unwrap_or_else(|e| panic!("{}: {e}", design.display()));
        assert!(diff <= 1e-9, "{}: differs by {diff:e} mm", design.display());
    }
}
