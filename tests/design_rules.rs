//! Every design rule refuses a bad design through the real binary: non-zero exit, the rule's
//! message (parameter, value, limit), and no output file.

use crate::common;
use common::dlw as run;

use std::path::Path;
use std::process::Output;

const JOINT_A: &str = include_str!("../designs/joint-a.toml");
const JOINT_C: &str = include_str!("../designs/joint-c.toml");

/// A design: Joint A or C with some lines replaced, or with lines appended to `[fabrication]`
/// or `[materials]`.
enum Edit {
    A(&'static [(&'static str, &'static str)]),
    C(&'static [(&'static str, &'static str)]),
    Fabrication(&'static str),
    /// Joint C with lines in `[fabrication]`.
    FabricationC(&'static str),
    Materials(&'static str),
}

impl Edit {
    fn text(&self) -> String {
        let replace = |base: &str, edits: &[(&str, &str)]| {
            edits.iter().fold(base.to_string(), |t, (from, to)| {
                assert!(
                    t.contains(from),
                    "test table: {from:?} not in the base design"
                );
                t.replace(from, to)
            })
        };
        match self {
            Edit::A(e) => replace(JOINT_A, e),
            Edit::C(e) => replace(JOINT_C, e),
            Edit::Fabrication(lines) => format!("{JOINT_A}\n[fabrication]\n{lines}\n"),
            Edit::FabricationC(lines) => format!("{JOINT_C}\n[fabrication]\n{lines}\n"),
            Edit::Materials(lines) => format!("{JOINT_A}\n[materials]\n{lines}\n"),
        }
    }
}

/// (rule, bad design, every fragment the refusal must contain)
const RULES: &[(&str, Edit, &[&str])] = &[
    ("r_i < r_o", Edit::A(&[("inner_radius_mm = 0.875", "inner_radius_mm = 1.3")]),
        &["inner_radius_mm = 1.3 must be smaller than outer_radius_mm = 1.24"]),
    ("r_i = r_o", Edit::A(&[("inner_radius_mm = 0.875", "inner_radius_mm = 1.24")]),
        &["inner_radius_mm = 1.24 must be smaller than outer_radius_mm = 1.24"]),
    ("s_n < 2π·r_o", Edit::A(&[("notch_arc_mm = 5.61", "notch_arc_mm = 8.0")]),
        &["notch_arc_mm = 8 must be less than the circumference 2π·r_o = 7.7911 mm"]),
    ("BSN pair must not overlap", Edit::C(&[("notch_arc_mm = 1.65", "notch_arc_mm = 2.6")]),
        &["notch_arc_mm = 2.6 makes the BSN notch pair overlap: each notch must be shorter than half the circumference π·r_o = 2.5133 mm"]),
    ("sensor arms on the backbone (UAN)", Edit::A(&[("sensor_arc_mm = 0.4", "sensor_arc_mm = 3.0")]),
        &["sensor_arc_mm = 3 must lie strictly between 0.0000 and 2.1811 mm so both arms sit on the backbone"]),
    ("sensor arms on the backbone (BSN)", Edit::C(&[("sensor_arc_mm = 2.13", "sensor_arc_mm = 1.5")]),
        &["sensor_arc_mm = 1.5 must lie strictly between 1.6500 and 2.5133 mm"]),
    ("N ≥ 1", Edit::A(&[("notch_count = 10", "notch_count = 0")]),
        &["notch_count = 0 must be at least 1"]),
    ("N at most 10000", Edit::A(&[("notch_count = 10", "notch_count = 4000000000")]),
        &["notch_count = 4000000000 must be at most 10000"]),
    ("N ≤ 10000, written as a float", Edit::A(&[("notch_count = 10", "notch_count = 1e9")]),
        &["notch_count = 1000000000 must be at most 10000"]),
    ("pads fit round the tube", Edit::Fabrication("pad_turns = 4000000000"),
        &["pads of pad_turns = 4000000000 at pad_pitch_mm = 0.1 are 800000000.0000 mm wide (2·turns·pitch)", "so each may be at most 3.5956 mm"]),
    ("outer radius positive", Edit::A(&[("outer_radius_mm = 1.24", "outer_radius_mm = -1.24")]),
        &["outer_radius_mm = -1.24 must be a finite number greater than 0"]),
    ("notch width positive", Edit::A(&[("notch_width_mm = 0.5", "notch_width_mm = 0.0")]),
        &["notch_width_mm = 0 must be a finite number greater than 0"]),
    ("notch spacing positive", Edit::A(&[("notch_spacing_mm = 0.5", "notch_spacing_mm = -0.5")]),
        &["notch_spacing_mm = -0.5 must be a finite number greater than 0"]),
    ("notch arc finite", Edit::A(&[("notch_arc_mm = 5.61", "notch_arc_mm = nan")]),
        &["notch_arc_mm = NaN must be a finite number greater than 0"]),
    ("notch width larger than the kerf", Edit::A(&[("notch_width_mm = 0.5", "notch_width_mm = 0.02"), ("joint_length_mm = 9.5", "joint_length_mm = 4.7")]),
        &["notch_width_mm = 0.02 must be larger than the kerf kerf_mm = 0.03"]),
    ("notch spacing larger than the kerf", Edit::A(&[("notch_spacing_mm = 0.5", "notch_spacing_mm = 0.03"), ("joint_length_mm = 9.5", "joint_length_mm = 5.27")]),
        &["notch_spacing_mm = 0.03 must be larger than the kerf kerf_mm = 0.03"]),
    ("L = N·h + (N−1)·c", Edit::A(&[("joint_length_mm = 9.5", "joint_length_mm = 9.6")]),
        &["joint_length_mm = 9.6 does not match N·h + (N−1)·c = 9.5000 mm", "must agree to 0.001 mm"]),
    ("trace width positive", Edit::Fabrication("trace_width_mm = 0.0"),
        &["trace_width_mm = 0 must be a finite number greater than 0"]),
    ("kerf positive", Edit::Fabrication("kerf_mm = -0.03"),
        &["kerf_mm = -0.03 must be a finite number greater than 0"]),
    ("clearance positive", Edit::Fabrication("clearance_mm = 0.0"),
        &["clearance_mm = 0 must be a finite number greater than 0"]),
    ("distal margin positive", Edit::Fabrication("distal_margin_mm = 0.0"),
        &["distal_margin_mm = 0 must be a finite number greater than 0"]),
    ("lead length positive", Edit::Fabrication("lead_length_mm = -1.0"),
        &["lead_length_mm = -1 must be a finite number greater than 0"]),
    ("pad gap positive", Edit::Fabrication("pad_gap_mm = 0.0"),
        &["pad_gap_mm = 0 must be a finite number greater than 0"]),
    ("proximal margin positive", Edit::Fabrication("proximal_margin_mm = 0.0"),
        &["proximal_margin_mm = 0 must be a finite number greater than 0"]),
    ("pad pitch positive", Edit::Fabrication("pad_pitch_mm = 0.0"),
        &["pad_pitch_mm = 0 must be a finite number greater than 0"]),
    ("at least one pad turn", Edit::Fabrication("pad_turns = 0"),
        &["pad_turns = 0 must be at least 1"]),
    ("saturation strain positive", Edit::Materials("sensor_saturation_strain = 0.0"),
        &["sensor_saturation_strain = 0 must be a finite number greater than 0"]),
    ("backbone limit positive", Edit::Materials("backbone_strain_limit = -0.03"),
        &["backbone_strain_limit = -0.03 must be a finite number greater than 0"]),
    ("tendon in the lumen", Edit::A(&[("sensor_arc_mm = 0.4", "sensor_arc_mm = 0.4\ntendon_offset_mm = 0.9")]),
        &["tendon_offset_mm = 0.9 must be at most the inner radius inner_radius_mm = 0.875 (the tendon runs in the lumen)"]),
    ("tendon offset positive", Edit::A(&[("sensor_arc_mm = 0.4", "sensor_arc_mm = 0.4\ntendon_offset_mm = -0.1")]),
        &["tendon_offset_mm = -0.1 must be greater than 0"]),
    ("spiral pitch ≥ trace width", Edit::Fabrication("pad_pitch_mm = 0.04"),
        &["pad_pitch_mm = 0.04 must be at least the trace width trace_width_mm = 0.05"]),
    ("clearance: arm to notch", Edit::A(&[("sensor_arc_mm = 0.4", "sensor_arc_mm = 2.0")]),
        &["sensor 1 arm at x = ", "mm is 0.066 mm from notch 1 (clearance 0.080 mm required)", "from notch 10 (clearance 0.080 mm required)"]),
    ("clearance: arm to arm", Edit::A(&[("sensor_arc_mm = 0.4", "sensor_arc_mm = 0.1")]),
        &["sensor 1 arm at x = ", "is 0.050 mm from sensor 1 arm (clearance 0.080 mm required)"]),
    ("clearance: bridge to distal end", Edit::Fabrication("distal_margin_mm = 0.1"),
        &["sensor 1 bridge at x = 0.05 mm, s = 0.20 mm is 0.025 mm from the distal end (x = 0) (clearance 0.080 mm required)"]),
    ("clearance: bridge to notch (BSN: the bridge passes notch side 1)", Edit::FabricationC("distal_margin_mm = 0.1"),
        &["sensor 1 bridge at x = 0.05 mm", "is 0.025 mm from notch 1 (side 1) (clearance 0.080 mm required)"]),
    ("clearance: pad to parting cut", Edit::Fabrication("proximal_margin_mm = 0.05"),
        &["sensor 1 pad at x = 12.80 mm", "is 0.025 mm from the parting cut (clearance 0.080 mm required)"]),
    ("clearance: pad to pad (BSN)", Edit::FabricationC("pad_gap_mm = 0.1"),
        &["sensor 1 pad at x = 12.00 mm", "is 0.050 mm from sensor 2 pad (clearance 0.080 mm required)"]),
    ("pads fit round the tube (BSN)", Edit::C(&[("outer_radius_mm = 0.800", "outer_radius_mm = 0.6"), ("inner_radius_mm = 0.610", "inner_radius_mm = 0.45"), ("notch_arc_mm = 1.65", "notch_arc_mm = 1.2"), ("sensor_arc_mm = 2.13", "sensor_arc_mm = 1.6")]),
        &["pads of pad_turns = 4 at pad_pitch_mm = 0.1 are 0.8000 mm wide (2·turns·pitch); 4 of them with pad_gap_mm between must fit round the circumference 2π·r_o = 3.7699 mm, so each may be at most 0.6425 mm"]),
    ("clearance: written arm overlapping a notch", Edit::A(&[("sensor_arc_mm = 0.4", "sensor_arc_mm = 2.15"), ("notch_arc_mm = 5.61", "notch_arc_mm = 5.62")]),
        &["sensor 1 arm at x = 1.00 mm, s = 1.08 mm overlaps notch 1 by 0.014 mm (clearance 0.080 mm required)"]),
    ("clearance: lead to lead", Edit::A(&[("sensor_arc_mm = 0.4", "sensor_arc_mm = 0.12\n[fabrication]\npad_gap_mm = 0.06")]),
        &["sensor 1 lead at x = ", "is 0.070 mm from sensor 1 lead (clearance 0.080 mm required)"]),
    ("clearance: set explicitly", Edit::Fabrication("clearance_mm = 0.9"),
        &["sensor 1 arm at x = ", "is 0.866 mm from notch 1 (clearance 0.900 mm required)"]),
];

fn refused(out: &Output, rule: &str, fragments: &[&str]) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{rule}: accepted\n{stderr}");
    assert!(
        stderr.starts_with("dlw: error: design \"Joint "),
        "{rule}: {stderr}"
    );
    for f in fragments {
        assert!(stderr.contains(f), "{rule}: no {f:?} in\n{stderr}");
    }
}

#[test]
fn every_rule_refuses_a_bad_design_and_writes_nothing() {
    for (rule, edit, fragments) in RULES {
        let dir = tempfile::tempdir().unwrap();
        let design = dir.path().join("bad.toml");
        std::fs::write(&design, edit.text()).unwrap();
        let dxf = dir.path().join("out.dxf");
        let out = run(&[
            "draw".as_ref(),
            design.as_os_str(),
            "--dxf".as_ref(),
            dxf.as_os_str(),
        ]);
        refused(&out, rule, fragments);
        assert!(!dxf.exists(), "{rule}: wrote {}", dxf.display());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "{rule}: left files behind"
        );
        // inspect runs the same rules.
        let out = run(&["inspect".as_ref(), design.as_os_str(), "--json".as_ref()]);
        refused(&out, rule, fragments);
        assert!(out.stdout.is_empty(), "{rule}: inspect printed a report");
    }
}

#[test]
fn every_violation_is_listed_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let design = dir.path().join("bad.toml");
    let text = JOINT_A
        .replace("inner_radius_mm = 0.875", "inner_radius_mm = 1.3")
        .replace("joint_length_mm = 9.5", "joint_length_mm = 9.6");
    std::fs::write(
        &design,
        format!("{text}\n[fabrication]\npad_pitch_mm = 0.04\n"),
    )
    .unwrap();
    let out = run(&["inspect".as_ref(), design.as_os_str()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("dlw: error: design \"Joint A\" breaks 3 design rules:\n  - "),
        "{stderr}"
    );
}

#[test]
fn warnings_are_printed_and_do_not_block() {
    let design = Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    let out = run(&["inspect".as_ref(), design.as_os_str(), "--json".as_ref()]);
    assert!(out.status.success());
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let warnings = json["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(warnings[0]
        .as_str()
        .unwrap()
        .contains("past sensor_saturation_strain = 2.00 %: the sensor saturates from 37.8° on"));
    assert!(warnings[1].as_str().unwrap().contains(
        "past backbone_strain_limit = 3.00 %: the backbone passes its limit from 22.8° on"
    ));
    let dir = tempfile::tempdir().unwrap();
    let dxf = dir.path().join("a.dxf");
    let out = run(&[
        "draw".as_ref(),
        design.as_os_str(),
        "--dxf".as_ref(),
        dxf.as_os_str(),
    ]);
    assert!(out.status.success());
    assert!(dxf.exists());
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning: sensor strain reaches 6.98 %"));
}

#[test]
fn import_dxf_runs_the_clearance_rules() {
    // A layout that breaks the clearance (arms next to the notches), drawn through the library
    // because `dlw draw` refuses it.
    let text = JOINT_A.replace("sensor_arc_mm = 0.4", "sensor_arc_mm = 2.0");
    let design = dlw::design::Design::from_toml(&text).unwrap();
    let layout = dlw::layout::Layout::from_design(&design).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let dxf = dir.path().join("bad.dxf");
    std::fs::write(&dxf, dlw::drawing::layout_to_dxf(&layout, 0.08).unwrap()).unwrap();
    let out = run(&["import-dxf".as_ref(), dxf.as_os_str()]);
    refused(
        &out,
        "import-dxf clearance",
        &["is 0.066 mm from notch 1 (clearance 0.080 mm required)"],
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("notch area          28.050000 mm²"));
}

#[test]
fn import_dxf_refuses_bad_drawings_with_one_message() {
    let dir = tempfile::tempdir().unwrap();
    let dxf = dir.path().join("x.dxf");
    std::fs::write(&dxf, "hello\r\nworld\r\n").unwrap();
    let out = run(&["import-dxf".as_ref(), dxf.as_os_str()]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("dlw: error: reading ") && stderr.contains("not a DXF file"),
        "{stderr}"
    );
}

/// `notch_count` as a float gets the integer's message and limit, also where a `u32` cannot
/// hold it (then the parser refuses it, with the same words).
#[test]
fn notch_counts_written_as_floats_name_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let design = dir.path().join("n.toml");
    for (count, want) in [
        ("1e9", "notch_count = 1000000000 must be at most 10000"),
        ("100000", "notch_count = 100000 must be at most 10000"),
        ("1e12", "notch_count = 1000000000000 must be at most 10000"),
        (
            "1000000000000",
            "notch_count = 1000000000000 must be at most 10000",
        ),
        (
            "2.5",
            "notch_count = 2.5 must be a whole number from 1 to 10000",
        ),
        ("-1", "notch_count = -1 must be at least 1"),
    ] {
        std::fs::write(
            &design,
            JOINT_A.replace("notch_count = 10", &format!("notch_count = {count}")),
        )
        .unwrap();
        let out = run(&["inspect".as_ref(), design.as_os_str()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{count}: accepted");
        assert!(stderr.contains(want), "{count}: {stderr}");
    }
}

/// A wall thinner than the notch set's `min_wall_mm` is refused by `dlw program` and
/// `dlw build`, naming the wall, the radii and the set's minimum; nothing is written. A set made
/// for thin walls (its own `min_wall_mm`) is accepted.
#[test]
fn thin_walls_are_refused_for_cutting() {
    let dir = tempfile::tempdir().unwrap();
    let design = dir.path().join("thin.toml");
    std::fs::write(
        &design,
        JOINT_C.replace("inner_radius_mm = 0.610", "inner_radius_mm = 0.780"),
    )
    .unwrap();
    let program = dir.path().join("thin.ngc");
    let build = dir.path().join("build");
    for args in [
        vec![
            "program".as_ref(),
            design.as_os_str(),
            "-o".as_ref(),
            program.as_os_str(),
        ],
        vec![
            "build".as_ref(),
            design.as_os_str(),
            "-o".as_ref(),
            build.as_os_str(),
        ],
    ] {
        let out = run(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "accepted: {stderr}");
        assert!(
            stderr.contains(
                "tube wall r_o − r_i = 0.0200 mm (outer_radius_mm = 0.8, inner_radius_mm = 0.78) is thinner than min_wall_mm = 0.1 mm of process set \"notches\""
            ),
            "{stderr}"
        );
    }
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "wrote nothing"
    );
    // A set that declares it cuts 0.02 mm walls.
    std::fs::create_dir(dir.path().join("process")).unwrap();
    std::fs::write(
        dir.path().join("process/thin-wall.toml"),
        format!(
            "{}\nmin_wall_mm = 0.02\n",
            include_str!("../designs/process/notches.toml")
        ),
    )
    .unwrap();
    let text = std::fs::read_to_string(&design).unwrap();
    std::fs::write(
        &design,
        format!("{text}\n[process]\nnotches = \"thin-wall\"\n"),
    )
    .unwrap();
    let out = run(&[
        "program".as_ref(),
        design.as_os_str(),
        "-o".as_ref(),
        program.as_os_str(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
