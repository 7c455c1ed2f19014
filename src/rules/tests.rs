//! Rule tests on in-memory designs; `tests/design_rules.rs` runs every rule through the binary.

use super::*;

const JOINT_A: &str = include_str!("../../designs/joint-a.toml");

fn file(edit: impl FnOnce(&mut DesignFile)) -> DesignFile {
    let mut f = DesignFile::from_toml(JOINT_A).unwrap();
    edit(&mut f);
    f
}

fn messages(f: DesignFile) -> Vec<String> {
    match check_file(f) {
        Ok(_) => Vec::new(),
        Err(e) => e.violations.iter().map(ToString::to_string).collect(),
    }
}

#[test]
fn shipped_designs_pass_every_rule() {
    for name in ["a", "b", "c", "d"] {
        let path = format!("{}/designs/joint-{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let f = DesignFile::read(path.as_ref()).unwrap();
        let checked = check_file(f).unwrap_or_else(|e| panic!("joint {name}: {e}"));
        // The paper's joints bend far past 2 % sensor strain before their notches close (Joint
        // A's close at 131.7°): both warnings are real for every Table I joint.
        assert_eq!(
            checked.warnings.len(),
            2,
            "joint {name}: {:?}",
            checked.warnings
        );
        assert!(matches!(
            checked.warnings[0],
            Warning::SensorSaturates { .. }
        ));
        assert!(matches!(
            checked.warnings[1],
            Warning::BackboneStrain { .. }
        ));
    }
}

#[test]
fn every_problem_is_listed_at_once() {
    let f = file(|f| {
        f.inner_radius_mm = 2.0;
        f.notch_count = 0;
        f.fabrication.pad_pitch_mm = 0.01;
    });
    let m = messages(f);
    assert_eq!(m.len(), 3, "{m:?}");
    assert!(m[0].contains("notch_count = 0"), "{m:?}");
    assert!(m[1].contains("inner_radius_mm = 2 must be smaller than outer_radius_mm = 1.24"));
    assert!(
        m[2].contains("pad_pitch_mm = 0.01 must be at least the trace width trace_width_mm = 0.05")
    );
}

#[test]
fn arm_too_close_to_a_notch_names_both_and_the_gap() {
    // Joint A's arms at ±1.0 mm, the notch edge at π·1.24 − 2.805 = 1.0906 mm: the centre line is
    // 0.0906 mm from the notch, the written edge 0.0656 mm (clearance 0.08 mm).
    let m = messages(file(|f| f.sensor_arc_mm = 2.0));
    let hit = m
        .iter()
        .find(|m| m.contains("notch 1 "))
        .expect("notch 1 reported");
    assert!(hit.starts_with("sensor 1 arm at x = "), "{hit}");
    assert!(
        hit.contains(" mm is 0.066 mm from notch 1 (clearance 0.080 mm required)"),
        "{hit}"
    );
    assert!(
        hit.contains("s = -1.00 mm") || hit.contains("s = 1.00 mm"),
        "{hit}"
    );
    // Every notch level is reported once.
    assert_eq!(
        m.iter()
            .filter(|m| m.contains("sensor 1 arm") && m.contains("notch"))
            .count(),
        10,
        "{m:?}"
    );
}

#[test]
fn arms_closer_than_the_clearance_short_the_sensor() {
    // s_s = 0.1 mm: centre lines 0.1 apart, edges 0.05 apart.
    let m = messages(file(|f| f.sensor_arc_mm = 0.1));
    assert!(
        m.iter()
            .any(|m| m.contains("sensor 1 arm") && m.contains("is 0.050 mm from sensor 1 arm")),
        "{m:?}"
    );
}

#[test]
fn bsn_pads_that_do_not_fit_are_refused_before_layout() {
    // Joint C shrunk: four 0.8 mm pads cannot fit round a 0.6 mm tube.
    let path = format!("{}/designs/joint-c.toml", env!("CARGO_MANIFEST_DIR"));
    let mut f = DesignFile::read(path.as_ref()).unwrap();
    f.outer_radius_mm = 0.6;
    f.inner_radius_mm = 0.45;
    f.notch_arc_mm = 1.2;
    f.sensor_arc_mm = 1.6;
    let m = messages(f.clone());
    assert_eq!(m.len(), 1, "{m:?}");
    assert!(m[0].contains("so each may be at most 0.6425 mm"), "{m:?}");
    // With room for the pads but a small gap, the clearance rule sees the pads of the two
    // sensors 0.1 mm apart, centre line to centre line of their outer turns.
    let mut f = DesignFile::read(path.as_ref()).unwrap();
    f.fabrication.pad_gap_mm = 0.1;
    let m = messages(f);
    assert!(
        m.iter()
            .any(|m| m.contains("sensor 1 pad") && m.contains("is 0.050 mm from sensor 2 pad")),
        "{m:?}"
    );
}

#[test]
fn length_must_match_the_notches() {
    let m = messages(file(|f| f.joint_length_mm = 9.6));
    assert_eq!(m.len(), 1);
    assert!(
        m[0].contains("joint_length_mm = 9.6 does not match N·h + (N−1)·c = 9.5000 mm"),
        "{m:?}"
    );
    assert!(messages(file(|f| f.joint_length_mm = 9.5 + 0.9e-3)).is_empty());
}

#[test]
fn saturation_and_backbone_warnings_give_the_angle() {
    let path = format!("{}/designs/joint-a.toml", env!("CARGO_MANIFEST_DIR"));
    let mut f = DesignFile::read(path.as_ref()).unwrap();
    f.materials.sensor_saturation_strain = 0.01;
    f.materials.backbone_strain_limit = 0.01;
    let checked = check_file(f).unwrap();
    let j = &checked.design.joint;
    let w: Vec<String> = checked.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(w.len(), 2, "{w:?}");
    let sat = format!("{:.1}°", j.angle_at_strain(0.01).to_degrees());
    assert!(
        w[0].contains("past sensor_saturation_strain = 1.00 %")
            && w[0].ends_with(&format!("from {sat} on")),
        "{w:?}"
    );
    let bb = format!(
        "{:.1}°",
        checked
            .design
            .mechanics
            .angle_at_material_strain_rad(0.01)
            .to_degrees()
    );
    assert!(
        w[1].contains("past backbone_strain_limit = 1.00 %")
            && w[1].ends_with(&format!("from {bb} on")),
        "{w:?}"
    );
}

#[test]
fn rules_error_lists_every_violation() {
    let e = check_file(file(|f| {
        f.notch_width_mm = 0.02;
        f.notch_spacing_mm = 0.03;
    }))
    .unwrap_err();
    let text = e.to_string();
    assert!(text.starts_with("design \"Joint A\" breaks "), "{text}");
    assert!(
        text.contains("\n  - notch_width_mm = 0.02 must be larger than the kerf kerf_mm = 0.03"),
        "{text}"
    );
    assert!(
        text.contains("\n  - notch_spacing_mm = 0.03 must be larger than the kerf kerf_mm = 0.03"),
        "{text}"
    );
}
