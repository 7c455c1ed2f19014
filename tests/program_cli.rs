//! `dlw program` and `dlw build` through the binary: what they write, and that bad input gets a
//! clear error, a non-zero exit and no file.

use crate::common;
use common::dlw;

use common::designs as common_designs;

use std::path::{Path, PathBuf};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A folder with a design (Joint B plus `extra` appended), `process/` and `machines/`.
fn workspace(extra: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("process")).unwrap();
    std::fs::create_dir_all(dir.path().join("machines")).unwrap();
    let text = std::fs::read_to_string(&common_designs::shipped()[1]).unwrap();
    let design = dir.path().join("design.toml");
    std::fs::write(&design, format!("{text}\n{extra}\n")).unwrap();
    (dir, design)
}

fn machine(dir: &Path, name: &str, edit: impl Fn(String) -> String) {
    let text = include_str!("../designs/machines/linuxcnc-reference.toml").to_string();
    std::fs::write(dir.join(format!("machines/{name}.toml")), edit(text)).unwrap();
}

/// Runs `dlw program` expecting failure; returns stderr and checks no file was written.
fn refused(dir: &Path, args: &[&str]) -> String {
    let out = dir.join("out.ngc");
    let sheet = dir.join("out.md");
    let mut all = vec!["program"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", s(&out), "--sheet", s(&sheet)]);
    let o = dlw(&all);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success(), "dlw {all:?} succeeded");
    assert!(err.contains("dlw: error:"), "{err}");
    assert!(
        !out.exists() && !sheet.exists(),
        "a file was written despite: {err}"
    );
    let leftovers: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".tmp") || n.starts_with(".dlw"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
    err
}

#[test]
fn writes_program_and_sheet() {
    let (dir, design) = workspace("");
    let out = dir.path().join("b.ngc");
    let sheet = dir.path().join("b.md");
    let o = dlw(&["program", s(&design), "-o", s(&out), "--sheet", s(&sheet)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let program = std::fs::read_to_string(&out).unwrap();
    let sheet = std::fs::read_to_string(&sheet).unwrap();
    let checksum = dlw::design::Design::load(&design).unwrap().checksum;
    assert!(program.contains(&format!("design checksum {checksum}")));
    assert!(program.contains("(dlw laser program for design \"Joint B\")"));
    assert!(sheet.contains(&format!("`{checksum}`")) && sheet.contains("Program `b.ngc`"));
    // The sheet tells the operator how to fix the tube and run the job.
    for needle in [
        "OD 1.6 mm",
        "1.2 mm machine-steel rod",
        "Glue end = collet end",
        "Collet end",
        "Free end",
        "X0 at the tube's free end face",
        "A0 at s = 0",
        "Z: focus on the top of the tube",
        "| sensor | `sensor` | 1030 nm | 160 mW | 1 mm/s | 200 kHz | 550 fs | 1 |",
        "| notches | `notches` | 1030 nm | 2000 mW | 25 mm/s | 60 kHz | 215 fs | 32 |",
        "silver epoxy",
        "Parylene-C",
        "about 5 µm",
        "Sand the parylene off",
        "hot-melt",
        "0.28 mm",
    ] {
        assert!(
            sheet.contains(needle),
            "setup sheet lacks {needle:?}:\n{sheet}"
        );
    }
}

#[test]
fn aerobasic_profile_writes_an_aerobasic_program() {
    let (dir, design) = workspace("");
    let out = dir.path().join("b.pgm");
    let o = dlw(&[
        "program",
        s(&design),
        "--machine",
        "aerotech-aerobasic",
        "-o",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let program = std::fs::read_to_string(&out).unwrap();
    assert!(
        program.contains("G76 // feeds in units per second") && program.ends_with("END PROGRAM\n")
    );
    assert!(!program.contains("G93") && !program.contains("repeat"));
}

#[test]
fn refuses_a_design_that_breaks_a_rule() {
    let (dir, design) = workspace("");
    let text = std::fs::read_to_string(&design)
        .unwrap()
        .replace("notch_width_mm = 0.5", "notch_width_mm = 0.02");
    std::fs::write(&design, text).unwrap();
    let err = refused(dir.path(), &[s(&design)]);
    assert!(
        err.contains("breaks") && err.contains("notch_width_mm = 0.02") && err.contains("kerf"),
        "{err}"
    );
}

#[test]
fn refuses_a_speed_beyond_the_stage() {
    let (dir, design) = workspace("");
    machine(dir.path(), "slow", |t| {
        t.replace("a_speed_max_deg_s = 3600.0", "a_speed_max_deg_s = 360.0")
    });
    let err = refused(dir.path(), &[s(&design), "--machine", "slow"]);
    // 25 mm/s on r_o = 0.8 mm is 1790.5 deg/s.
    assert!(
        err.contains("notches: notch")
            && err.contains("move")
            && err.contains("needs A at 1790.5 deg/s")
            && err.contains("limit of 360 deg/s"),
        "{err}"
    );
    machine(dir.path(), "slowx", |t| {
        t.replace("x_speed_max_mm_s = 100.0", "x_speed_max_mm_s = 10.0")
    });
    let err = refused(dir.path(), &[s(&design), "--machine", "slowx"]);
    assert!(
        err.contains("needs X at 25.0 mm/s") && err.contains("limit of 10 mm/s"),
        "{err}"
    );
}

#[test]
fn refuses_unknown_profile_keys_and_missing_profiles() {
    let (dir, design) = workspace("");
    machine(dir.path(), "typo", |t| {
        t.replace("max_power_mw = 2500.0", "max_power_w = 2.5")
    });
    let err = refused(dir.path(), &[s(&design), "--machine", "typo"]);
    assert!(
        err.contains("max_power_w") && err.contains("typo.toml"),
        "{err}"
    );
    let err = refused(dir.path(), &[s(&design), "--machine", "nonesuch"]);
    assert!(
        err.contains("\"nonesuch\" not found") && err.contains("linuxcnc-reference"),
        "{err}"
    );
}

#[test]
fn refuses_a_missing_process_set() {
    let (dir, design) = workspace("[process]\nsensor = \"engrave\"");
    let err = refused(dir.path(), &[s(&design)]);
    assert!(
        err.contains("process set \"engrave\" not found") && err.contains("engrave.toml"),
        "{err}"
    );
}

#[test]
fn refuses_power_travel_and_focus_beyond_the_machine() {
    let (dir, design) = workspace("");
    machine(dir.path(), "weak", |t| {
        t.replace("max_power_mw = 2500.0", "max_power_mw = 1000.0")
    });
    let err = refused(dir.path(), &[s(&design), "--machine", "weak"]);
    assert!(
        err.contains("2000 mW, above the machine's maximum of 1000 mW"),
        "{err}"
    );
    machine(dir.path(), "short", |t| {
        t.replace("x_max_mm = 150.0", "x_max_mm = 10.0")
    });
    let err = refused(dir.path(), &[s(&design), "--machine", "short"]);
    assert!(
        err.contains("outside the machine's X travel -5 mm to 10 mm"),
        "{err}"
    );
    let deep = include_str!("../designs/process/notches.toml")
        .replace("# z_step_mm = 0.0", "z_step_mm = 0.01");
    std::fs::write(dir.path().join("process/deep.toml"), deep).unwrap();
    let text = std::fs::read_to_string(&design).unwrap();
    std::fs::write(&design, format!("{text}\n[process]\nnotches = \"deep\"\n")).unwrap();
    let err = refused(dir.path(), &[s(&design)]);
    assert!(
        err.contains("lowers the focus 0.31 mm") && err.contains("0.19"),
        "{err}"
    );
}

#[test]
fn refuses_loops_the_post_cannot_write() {
    let (dir, design) = workspace("");
    let aero = include_str!("../designs/machines/aerotech-aerobasic.toml")
        .replace("\"unroll\"", "\"loop\"");
    std::fs::write(dir.path().join("machines/aeroloop.toml"), aero).unwrap();
    let err = refused(dir.path(), &[s(&design), "--machine", "aeroloop"]);
    assert!(
        err.contains("not supported by the aerobasic post") && err.contains("unroll"),
        "{err}"
    );
}

/// When the temporary folder cannot be made beside the output, the message names the parent
/// folder and why (`dlw simulate` writes straight through `output::write_folder_atomic`).
#[test]
fn staging_failure_names_the_parent_folder() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("plain");
    std::fs::write(&file, "x").unwrap();
    let out = file.join("rec");
    let o = dlw(&[
        "simulate",
        "--design",
        s(&common_designs::shipped()[3]),
        "--protocol",
        "random",
        "--duration-s",
        "1",
        "-o",
        s(&out),
        // Past the recording's own check of the destination, to the staging folder.
        "--force",
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(&format!(
            "cannot make a temporary staging folder in {}",
            file.display()
        )) && err.contains("Not a directory"),
        "{err}"
    );
    assert_eq!(
        err.matches("Not a directory").count(),
        1,
        "said once: {err}"
    );
}

#[test]
fn build_writes_everything_or_nothing() {
    let (dir, design) = workspace("");
    let out = dir.path().join("out/joint");
    let o = dlw(&["build", s(&design), "-o", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "design-layout.svg",
            "design-section.svg",
            "design-setup.md",
            "design.dxf",
            "design.ngc"
        ]
    );
    // Again over the same folder: refused without --force, whatever it holds (it may be
    // another design's build), and left as it was.
    let before = std::fs::read(out.join("design.ngc")).unwrap();
    std::fs::write(out.join("design.ngc"), "another design's program").unwrap();
    let o = dlw(&["build", s(&design), "-o", s(&out)]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("already exists and is not empty") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("design.ngc")).unwrap(),
        "another design's program"
    );
    // With --force: replaced whole, nothing left behind, someone else's file included.
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let o = dlw(&["build", s(&design), "-o", s(&out), "--force"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(out.join("design.ngc")).unwrap(), before);
    assert!(!out.join("notes.txt").exists());
    let parent: Vec<_> = std::fs::read_dir(dir.path().join("out")).unwrap().collect();
    assert_eq!(parent.len(), 1, "only the build folder is left");
    // An empty folder is fine without --force.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let o = dlw(&["build", s(&design), "-o", s(&empty)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // A file where the folder should be is never replaced, even with --force.
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let o = dlw(&["build", s(&design), "-o", s(&file), "--force"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("is not a folder"));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "x");
    // A bad design: no folder at all.
    machine(dir.path(), "slow", |t| {
        t.replace("a_speed_max_deg_s = 3600.0", "a_speed_max_deg_s = 360.0")
    });
    let fresh = dir.path().join("fresh");
    let o = dlw(&["build", s(&design), "-o", s(&fresh), "--machine", "slow"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("limit of 360 deg/s"));
    assert!(!fresh.exists());
}
