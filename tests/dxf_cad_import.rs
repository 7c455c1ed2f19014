//! Drawings as CAD tools write them (issue 11, sections 1 and 2): dlw's drawings edited by ezdxf
//! (`tests/scripts/dxf_cad_edit.py`) — saved as R12, R2000 and R2018, rebuilt through ezdxf's
//! `Importer` (no XDATA), notches redrawn as LINEs and ARCs, title blocks on other layers,
//! inches — read back by `dlw`; drawings that do not match their design, or break a rule, are
//! refused without writing a file; programs made from edited drawings run through LinuxCNC's
//! `rs274` and cut what the drawing shows, and say where their layout came from.
//!
//! Needs `python3` with `ezdxf` and `rs274` (both installed by `scripts/test.sh`); without them
//! these tests fail.

use crate::canon;
use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use canon::checks::{check, expected};
use canon::{parse, run_rs274};
use common::designs::shipped;
use common::dlw;
use dlw::design::DesignFile;
use dlw::drawing::{
    read_dxf, DrawingUnits, DxfImportError, ImportOptions, ImportedDxf, LayoutNumbers,
};
use dlw::layout::Layout;
use dlw::rules;
use geo::{Area, BoundingRect};

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scripts/dxf_cad_edit.py")
}

fn text(out: &Output) -> String {
    format!(
        "exit {:?}\nstdout: {}\nstderr: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

/// Applies `edits` (words of `dxf_cad_edit.py`) to `input`, writing `output`.
fn ezdxf_edit(input: &Path, output: &Path, edits: &[&str]) {
    let out = Command::new("python3")
        .arg(script())
        .arg(input)
        .arg(output)
        .args(edits)
        .output()
        .unwrap_or_else(|e| panic!("cannot run python3 ({e}): these tests need python3 with ezdxf (scripts/test.sh installs it)"));
    assert!(out.status.success(), "ezdxf {edits:?}: {}", text(&out));
}

fn sha256_by_python(file: &Path) -> String {
    let out = Command::new("python3")
        .arg(script())
        .arg(file)
        .arg("-")
        .arg("sha256")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out));
    String::from_utf8_lossy(&out.stdout).trim().to_string()
}

/// Joint `j` (a, b, c, d): its design path, its layout, its clearance, and its drawing by
/// `dlw draw` in `dir`.
struct Joint {
    design: PathBuf,
    layout: Layout,
    clearance_mm: f64,
    dxf: PathBuf,
}

fn joint(j: char, dir: &Path) -> Joint {
    let design = shipped()[(j as u8 - b'a') as usize].clone();
    let checked = rules::check_file(DesignFile::read(&design).unwrap()).unwrap();
    let dxf = dir.join(format!("joint-{j}.dxf"));
    let out = dlw(&[
        "draw".as_ref(),
        design.as_os_str(),
        "--dxf".as_ref(),
        dxf.as_os_str(),
    ]);
    assert!(out.status.success(), "{}", text(&out));
    Joint {
        design,
        clearance_mm: checked.design.file.fabrication.clearance_mm(),
        layout: checked.layout,
        dxf,
    }
}

fn read(file: &Path, units: Option<DrawingUnits>, numbers: Option<LayoutNumbers>) -> ImportedDxf {
    try_read(file, units, numbers).unwrap_or_else(|e| panic!("{}: {e}", file.display()))
}

fn try_read(
    file: &Path,
    units: Option<DrawingUnits>,
    numbers: Option<LayoutNumbers>,
) -> Result<ImportedDxf, DxfImportError> {
    read_dxf(
        &std::fs::read(file).unwrap(),
        &ImportOptions {
            units,
            numbers,
            ..ImportOptions::default()
        },
    )
}

/// Per notch (in layout order): its `x` range, total `s` extent and area.
fn notch_shapes(layout: &Layout) -> Vec<[f64; 4]> {
    layout
        .notches
        .iter()
        .map(|n| {
            let boxes: Vec<_> = n.outline.iter().filter_map(|p| p.bounding_rect()).collect();
            [
                boxes
                    .iter()
                    .map(|r| r.min().x)
                    .fold(f64::INFINITY, f64::min),
                boxes
                    .iter()
                    .map(|r| r.max().x)
                    .fold(f64::NEG_INFINITY, f64::max),
                boxes.iter().map(|r| r.height()).sum(),
                n.outline.iter().map(|p| p.unsigned_area()).sum(),
            ]
        })
        .collect()
}

fn assert_same_notches(a: &Layout, b: &Layout, tol: f64, what: &str) {
    let (sa, sb) = (notch_shapes(a), notch_shapes(b));
    assert_eq!(sa.len(), sb.len(), "{what}: notch count");
    for (i, (p, q)) in sa.iter().zip(&sb).enumerate() {
        for k in 0..4 {
            assert!(
                (p[k] - q[k]).abs() <= tol,
                "{what}: notch {i} {p:?} vs {q:?}"
            );
        }
    }
}

#[test]
fn r12_r2000_and_r2018_saves_read_back_as_drawn() {
    let dir = tempfile::tempdir().unwrap();
    // A (plain UAN), B (notches split at the seam), C (BSN, two sensors).
    for j in ['a', 'b', 'c'] {
        let joint = joint(j, dir.path());
        for (version, edits) in [
            ("R12", vec!["r12"]),
            ("R2000", vec!["resave", "R2000"]),
            ("R2018", vec!["resave", "R2018"]),
        ] {
            let file = dir.path().join(format!("{j}-{version}.dxf"));
            ezdxf_edit(&joint.dxf, &file, &edits);
            let units = (version == "R12").then_some(DrawingUnits::Mm);
            let back = read(&file, units, None);
            assert_eq!(back.version, version, "{j} {version}");
            let diff = joint
                .layout
                .max_difference_mm(&back.layout)
                .unwrap_or_else(|e| panic!("joint {j} {version}: {e}"));
            assert!(diff <= 1e-9, "joint {j} {version}: differs by {diff:e} mm");
        }
    }
}

#[test]
fn an_r12_drawing_without_units_asks_for_them() {
    let dir = tempfile::tempdir().unwrap();
    let joint = joint('a', dir.path());
    let r12 = dir.path().join("a-r12.dxf");
    ezdxf_edit(&joint.dxf, &r12, &["r12"]);
    let err = try_read(&r12, None, None).unwrap_err().to_string();
    assert!(
        err.contains(
            "$INSUNITS is missing; R12 files cannot store it): give them with --units mm|um|in"
        ),
        "{err}"
    );
    // Through the binary, with and without --units.
    let out = dlw(&["import-dxf".as_ref(), r12.as_os_str()]);
    assert!(!out.status.success() && text(&out).contains("--units mm|um|in"));
    let out = dlw(&[
        "import-dxf".as_ref(),
        r12.as_os_str(),
        "--units".as_ref(),
        "mm".as_ref(),
    ]);
    assert!(out.status.success(), "{}", text(&out));
}

#[test]
fn inch_drawings_are_read_in_mm() {
    let dir = tempfile::tempdir().unwrap();
    let joint = joint('c', dir.path());
    let inches = dir.path().join("c-in.dxf");
    ezdxf_edit(&joint.dxf, &inches, &["inches"]);
    let back = read(&inches, None, None);
    assert_eq!(back.units.0, DrawingUnits::In);
    let diff = joint.layout.max_difference_mm(&back.layout).unwrap();
    assert!(diff <= 1e-9, "differs by {diff:e} mm");
    // The same in R12, with the unit given; and the wrong unit given is refused.
    let r12 = dir.path().join("c-in-r12.dxf");
    ezdxf_edit(&joint.dxf, &r12, &["inches", "+", "r12"]);
    let back = read(&r12, Some(DrawingUnits::In), None);
    assert!(joint.layout.max_difference_mm(&back.layout).unwrap() <= 1e-9);
    let err = try_read(&inches, Some(DrawingUnits::Mm), None).unwrap_err();
    assert!(
        matches!(err, DxfImportError::UnitsConflict { insunits: 1, .. }),
        "{err}"
    );
}

#[test]
fn drawings_rebuilt_by_the_importer_take_their_numbers_from_the_design() {
    let dir = tempfile::tempdir().unwrap();
    for j in ['b', 'c'] {
        let joint = joint(j, dir.path());
        let rebuilt = dir.path().join(format!("{j}-importer.dxf"));
        ezdxf_edit(&joint.dxf, &rebuilt, &["importer", "R2018"]);
        let err = try_read(&rebuilt, None, None).unwrap_err().to_string();
        assert!(
            err.starts_with("no dlw layout numbers: none found") && err.contains("--design"),
            "{err}"
        );
        let numbers = LayoutNumbers::of(&joint.layout, joint.clearance_mm);
        let back = read(&rebuilt, None, Some(numbers));
        assert!(!back.numbers_from_xdata && back.untagged > 0);
        let diff = joint.layout.max_difference_mm(&back.layout).unwrap();
        assert!(diff <= 1e-9, "joint {j}: differs by {diff:e} mm");
        // The binary, given the design.
        let out = dlw(&[
            "import-dxf".as_ref(),
            rebuilt.as_os_str(),
            "--design".as_ref(),
            joint.design.as_os_str(),
        ]);
        assert!(out.status.success(), "{}", text(&out));
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            stdout.contains("layout numbers from the design (the drawing has no dlw XDATA)")
                && stdout.contains("differences from the design's own layout: none"),
            "{stdout}"
        );
    }
}

#[test]
fn notches_redrawn_as_lines_are_joined_into_outlines() {
    let dir = tempfile::tempdir().unwrap();
    for j in ['a', 'b', 'c'] {
        let joint = joint(j, dir.path());
        for (name, edits) in [
            ("lines", vec!["lines"]),
            ("lines-r12", vec!["lines", "+", "r12"]),
        ] {
            let file = dir.path().join(format!("{j}-{name}.dxf"));
            ezdxf_edit(&joint.dxf, &file, &edits);
            let back = read(&file, Some(DrawingUnits::Mm), None);
            let pieces: usize = joint.layout.notches.iter().map(|n| n.outline.len()).sum();
            assert_eq!(back.joined_outlines, pieces, "joint {j} {name}");
            assert_same_notches(&joint.layout, &back.layout, 1e-9, &format!("{j} {name}"));
            let levels_sides: Vec<_> = back
                .layout
                .notches
                .iter()
                .map(|n| (n.level, n.side))
                .collect();
            let expected: Vec<_> = joint
                .layout
                .notches
                .iter()
                .map(|n| (n.level, n.side))
                .collect();
            assert_eq!(levels_sides, expected, "joint {j} {name}");
        }
    }
}

#[test]
fn exploded_drawings_read_back_as_drawn() {
    // EXPLODE turns every polyline into LINEs: notches, U-traces, leads, the pads' spirals and
    // the parting cut; leads and pads are told apart again where the lead meets the spiral.
    let dir = tempfile::tempdir().unwrap();
    for j in ['a', 'b', 'c'] {
        let joint = joint(j, dir.path());
        for (name, edits) in [
            ("exploded", vec!["explode"]),
            ("exploded-r12", vec!["explode", "+", "r12"]),
        ] {
            let file = dir.path().join(format!("{j}-{name}.dxf"));
            ezdxf_edit(&joint.dxf, &file, &edits);
            let back = read(&file, Some(DrawingUnits::Mm), None);
            let diff = joint
                .layout
                .max_difference_mm(&back.layout)
                .unwrap_or_else(|e| panic!("joint {j} {name}: {e}"));
            assert!(diff <= 1e-9, "joint {j} {name}: differs by {diff:e} mm");
        }
    }
}

#[test]
fn an_arc_edge_is_read_within_the_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    let joint = joint('a', dir.path());
    let file = dir.path().join("a-arc.dxf");
    ezdxf_edit(&joint.dxf, &file, &["arc-edge", "0.1"]);
    let back = read(&file, None, None);
    let (design, drawn) = (notch_shapes(&joint.layout), notch_shapes(&back.layout));
    // The distal edge bulges 0.1 mm towards the free end; flattened with chords at most 1 µm
    // inside the arc.
    let x_min = drawn[0][0];
    assert!(
        x_min <= design[0][0] - 0.1 + 1e-3 && x_min >= design[0][0] - 0.1 - 1e-12,
        "{x_min}"
    );
    // The circular segment added: chord 2a = s_n, sagitta h: area = r²·asin(a/r) − a·(r − h).
    let (a, h) = (design[0][2] / 2.0, 0.1);
    let r = (a * a + h * h) / (2.0 * h);
    let segment = r * r * (a / r).asin() - a * (r - h);
    let added = drawn[0][3] - design[0][3];
    assert!(
        added <= segment && added >= segment - 1e-3 * 2.0 * a,
        "added {added} mm², segment {segment} mm²"
    );
}

#[test]
fn an_outline_that_does_not_close_names_the_gap() {
    let dir = tempfile::tempdir().unwrap();
    let joint = joint('a', dir.path());
    let file = dir.path().join("a-gap.dxf");
    ezdxf_edit(&joint.dxf, &file, &["gap", "0.02"]);
    let err = try_read(&file, None, None).unwrap_err().to_string();
    assert!(
        err.starts_with("NOTCHES outline does not close: its end at x = ")
            && err.contains("is 0.0200 mm from the nearest other end")
            && err.ends_with("(ends within 0.001 mm are joined)"),
        "{err}"
    );
    // A wider tolerance joins it.
    let out = dlw(&[
        "import-dxf".as_ref(),
        file.as_os_str(),
        "--join-tolerance".as_ref(),
        "0.025".as_ref(),
    ]);
    assert!(out.status.success(), "{}", text(&out));
}

#[test]
fn other_layers_are_ignored_with_a_count_and_tube_silently() {
    let dir = tempfile::tempdir().unwrap();
    let joint = joint('b', dir.path());
    let file = dir.path().join("b-extras.dxf");
    ezdxf_edit(&joint.dxf, &file, &["extras"]);
    let back = read(&file, None, None);
    assert!(joint.layout.max_difference_mm(&back.layout).unwrap() <= 1e-9);
    assert_eq!(
        back.ignored.into_iter().collect::<Vec<_>>(),
        vec![("0".to_string(), 1), ("TITLE".to_string(), 2)]
    );
    let out = dlw(&["import-dxf".as_ref(), file.as_os_str()]);
    assert!(out.status.success(), "{}", text(&out));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("ignored 2 entities on layer \"TITLE\", which is not a dlw layer")
            && stderr.contains("ignored 1 entity on layer \"0\""),
        "{stderr}"
    );
    assert!(!stderr.contains("TUBE"), "{stderr}");
}

#[test]
fn empty_foreign_and_truncated_files_get_their_own_messages() {
    let dir = tempfile::tempdir().unwrap();
    let joint = joint('a', dir.path());
    let whole = std::fs::read(&joint.dxf).unwrap();
    let cases: [(&str, Vec<u8>, &str); 3] = [
        ("empty.dxf", Vec::new(), "the file is empty (0 bytes)"),
        (
            "photo.dxf",
            b"\x89PNG\r\n\x1a\n....".to_vec(),
            "not a DXF file: a DXF starts with the group code 0 and SECTION",
        ),
        (
            "cut.dxf",
            whole[..whole.len() * 2 / 3].to_vec(),
            "the DXF is truncated: it ends after",
        ),
    ];
    for (name, bytes, message) in cases {
        let file = dir.path().join(name);
        std::fs::write(&file, &bytes).unwrap();
        let ngc = dir.path().join(format!("{name}.ngc"));
        let out = dlw(&[
            "program".as_ref(),
            "--from-dxf".as_ref(),
            file.as_os_str(),
            "--design".as_ref(),
            joint.design.as_os_str(),
            "-o".as_ref(),
            ngc.as_os_str(),
        ]);
        assert!(!out.status.success(), "{name}: {}", text(&out));
        assert!(text(&out).contains(message), "{name}: {}", text(&out));
        assert!(!ngc.exists(), "{name}: a program was written");
    }
}

/// `dlw program --from-dxf FILE --design DESIGN -o OUT --sheet SHEET` and its output.
fn program_from(
    file: &Path,
    design: &Path,
    dir: &Path,
    extra: &[&str],
) -> (Output, PathBuf, PathBuf) {
    let stem = file.file_stem().unwrap().to_string_lossy().into_owned();
    let ngc = dir.join(format!("{stem}.ngc"));
    let sheet = dir.join(format!("{stem}-setup.md"));
    let mut args: Vec<&std::ffi::OsStr> = vec![
        "program".as_ref(),
        "--from-dxf".as_ref(),
        file.as_os_str(),
        "--design".as_ref(),
        design.as_os_str(),
        "-o".as_ref(),
        ngc.as_os_str(),
        "--sheet".as_ref(),
        sheet.as_os_str(),
    ];
    args.extend(extra.iter().map(std::ffi::OsStr::new));
    (dlw(&args), ngc, sheet)
}

#[test]
fn a_joint_b_drawing_with_joint_c_design_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let b = joint('b', dir.path());
    let c_design = shipped()[2].clone();
    let rebuilt = dir.path().join("b-importer.dxf");
    ezdxf_edit(&b.dxf, &rebuilt, &["importer", "R2000"]);
    for file in [&b.dxf, &rebuilt] {
        let (out, ngc, sheet) = program_from(file, &c_design, dir.path(), &[]);
        assert!(!out.status.success(), "{}", text(&out));
        let t = text(&out);
        assert!(
            t.contains(
                "the drawing's notch style is UAN (notches on one side) but the design's is BSN"
            ) && t.contains("the drawing's sensor count is 1 but the design's is 2"),
            "{t}"
        );
        assert!(!ngc.exists() && !sheet.exists());
    }
    // With its XDATA, the drawing's name gives it away too.
    let (out, _, _) = program_from(&b.dxf, &c_design, dir.path(), &[]);
    assert!(
        text(&out).contains("the drawing's name is \"Joint B\" but the design's is \"Joint C\"")
    );
}

#[test]
fn a_notch_moved_past_the_free_end_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let a = joint('a', dir.path());
    let moved = dir.path().join("a-free-end.dxf");
    // Joint A's first notch starts 1 mm from the free end.
    ezdxf_edit(&a.dxf, &moved, &["move", "0", "-1.185", "0"]);
    let (out, ngc, sheet) = program_from(&moved, &a.design, dir.path(), &[]);
    assert!(!out.status.success(), "{}", text(&out));
    assert!(
        text(&out).contains(
            "notch 1 reaches x = -0.1850 mm, 0.1850 mm past the free end x = 0 (every cut must lie inside the joint"
        ),
        "{}",
        text(&out)
    );
    assert!(!ngc.exists() && !sheet.exists());
    // Moved onto its neighbour: the overlap is named.
    let onto = dir.path().join("a-overlap.dxf");
    ezdxf_edit(&a.dxf, &onto, &["move", "1", "-0.7", "0"]);
    let (out, ngc, _) = program_from(&onto, &a.design, dir.path(), &[]);
    assert!(
        !out.status.success() && text(&out).contains("notch 1 overlaps notch 2 at x = "),
        "{}",
        text(&out)
    );
    assert!(!ngc.exists());
}

/// The program made from `file` runs through rs274 and cuts the drawing's notches; its header
/// and sheet name the drawing, its SHA-256 and `differences`.
fn check_program(file: &Path, design: &Path, dir: &Path, extra: &[&str], differences: &[&str]) {
    let (out, ngc, sheet) = program_from(file, design, dir, extra);
    assert!(out.status.success(), "{}: {}", file.display(), text(&out));
    let units = extra
        .windows(2)
        .find(|w| w[0] == "--units")
        .and_then(|w| DrawingUnits::from_name(w[1]));
    let checked = rules::check_file(DesignFile::read(design).unwrap()).unwrap();
    let numbers = LayoutNumbers::of(&checked.layout, 0.08);
    let mut e = expected(design, None);
    e.layout = read(file, units, Some(numbers)).layout;
    check(&parse(&run_rs274(&ngc)), &e, &file.display().to_string());
    let program = std::fs::read_to_string(&ngc).unwrap();
    let sheet = std::fs::read_to_string(&sheet).unwrap();
    let name = file.file_name().unwrap().to_string_lossy();
    let sha = sha256_by_python(file);
    // The program carries the lines as comments, in which LinuxCNC allows no parentheses.
    let as_comment = |s: &str| s.replace('(', "[").replace(')', "]");
    for (text, say) in [
        (&program, &as_comment as &dyn Fn(&str) -> String),
        (&sheet, &|s: &str| s.to_string()),
    ] {
        assert!(
            text.contains(&format!("layout from drawing {name}")),
            "{text}"
        );
        assert!(text.contains(&format!("drawing SHA-256 {sha}")), "{text}");
        for d in differences {
            assert!(text.contains(&say(d)), "{d:?} missing:\n{text}");
        }
        let heading = if differences.is_empty() {
            "differences from the design's own layout: none".to_string()
        } else {
            format!(
                "differences from the design's own layout ({}):",
                differences.len()
            )
        };
        assert!(
            text.contains(&say(&heading)),
            "{heading:?} missing:\n{text}"
        );
    }
}

#[test]
fn programs_from_edited_drawings_pass_rs274_and_say_where_they_came_from() {
    let dir = tempfile::tempdir().unwrap();
    let a = joint('a', dir.path());
    let b = joint('b', dir.path());
    let c = joint('c', dir.path());
    let edit = |j: &Joint, name: &str, edits: &[&str]| {
        let file = dir.path().join(name);
        ezdxf_edit(&j.dxf, &file, edits);
        file
    };
    // Re-saved as R12 (BSN, two sensors), with its unit given.
    let c12 = edit(&c, "c-r12.dxf", &["r12"]);
    check_program(&c12, &c.design, dir.path(), &["--units", "mm"], &[]);
    // Rebuilt without XDATA, notches as LINEs, with a title block: read as designed.
    let b_lines = edit(
        &b,
        "b-lines.dxf",
        &["importer", "R2018", "+", "lines", "+", "extras"],
    );
    check_program(&b_lines, &b.design, dir.path(), &[], &[]);
    // Every polyline exploded into LINEs (BSN, two sensors).
    let c_exploded = edit(&c, "c-exploded.dxf", &["explode"]);
    check_program(&c_exploded, &c.design, dir.path(), &[], &[]);
    // A notch moved 0.05 mm round the tube.
    let a_moved = edit(
        &a,
        "a-moved.dxf",
        &["move", "3", "0", "0.05", "+", "resave", "R2018"],
    );
    check_program(
        &a_moved,
        &a.design,
        dir.path(),
        &[],
        &["notch 4 moved by dx = +0.0000 mm, ds = +0.0500 mm"],
    );
}

#[test]
fn derived_numbers_come_from_the_drawn_notches() {
    let dir = tempfile::tempdir().unwrap();
    let a = joint('a', dir.path());
    let fewer = dir.path().join("a-nine.dxf");
    ezdxf_edit(&a.dxf, &fewer, &["delete", "9"]);
    let (out, ngc, _) = program_from(&fewer, &a.design, dir.path(), &[]);
    assert!(out.status.success(), "{}", text(&out));
    let program = std::fs::read_to_string(&ngc).unwrap();
    let checked = rules::check_file(DesignFile::read(&a.design).unwrap()).unwrap();
    let closing = checked.design.joint.closing_angle_rad().to_degrees();
    // Nine notches of ten close at nine tenths of the angle.
    assert!(
        program.contains(&format!(
            "(as drawn: 9 notch levels [9 notches], mean h = 0.5000 mm, c = 0.5000 mm, s_n = {:.4} mm, closing angle {:.1} deg)\n(as designed: 10 notch levels",
            checked.design.file.notch_arc_mm,
            0.9 * closing
        )),
        "{program}"
    );
    assert!(
        program.contains("- notch 10 removed [was at x 10.0000..10.5000 mm"),
        "{program}"
    );
    // The strain warnings are for the drawn joint's closing angle.
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!("at the notch-closing angle {:.1}°", 0.9 * closing)),
        "{stderr}"
    );
    run_rs274(&ngc);
}
