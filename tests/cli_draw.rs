//! `dlw inspect` and `dlw draw` on the shipped designs and on designs outside the paper, through
//! the real binary.

use crate::common;
use common::dlw;

use common::designs as common_designs;

use std::path::{Path, PathBuf};

fn designs(dir: &Path) -> Vec<PathBuf> {
    let mut all = common_designs::shipped();
    for (i, text) in [common_designs::BSN_WIDE, common_designs::UAN_THREE]
        .iter()
        .enumerate()
    {
        let path = dir.join(format!("generated-{i}.toml"));
        std::fs::write(&path, text).unwrap();
        all.push(path);
    }
    all
}

#[test]
fn inspect_and_draw_every_design() {
    let dir = tempfile::tempdir().unwrap();
    for design in designs(dir.path()) {
        let out = dlw(&["inspect".as_ref(), design.as_os_str(), "--json".as_ref()]);
        assert!(
            out.status.success(),
            "{}: {}",
            design.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(json["strain_per_deg"].as_f64().unwrap() > 0.0);
        assert!(json["warnings"].is_array());
        let out = dlw(&["inspect".as_ref(), design.as_os_str()]);
        assert!(out.status.success());

        let stem = design.file_stem().unwrap().to_string_lossy().to_string();
        let files = ["dxf", "svg", "section"].map(|k| dir.path().join(format!("{stem}-{k}.out")));
        let out = dlw(&[
            "draw".as_ref(),
            design.as_os_str(),
            "--dxf".as_ref(),
            files[0].as_os_str(),
            "--svg".as_ref(),
            files[1].as_os_str(),
            "--section".as_ref(),
            files[2].as_os_str(),
        ]);
        assert!(
            out.status.success(),
            "{}: {}",
            design.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        let dxf = std::fs::read(&files[0]).unwrap();
        let back = dlw::drawing::layout_from_dxf(&dxf).unwrap();
        assert!(!back.layout.notches.is_empty());
        for svg in &files[1..] {
            let text = std::fs::read_to_string(svg).unwrap();
            roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", svg.display()));
        }
    }
}

#[test]
fn draw_without_an_output_is_refused() {
    let design = &common_designs::shipped()[0];
    let out = dlw(&["draw".as_ref(), design.as_os_str()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("nothing to draw"));
}

#[test]
fn a_failed_output_leaves_no_other_file() {
    // The SVG's folder does not exist: the DXF, planned first, must not be written either.
    let dir = tempfile::tempdir().unwrap();
    let design = &common_designs::shipped()[0];
    let dxf = dir.path().join("a.dxf");
    let svg = dir.path().join("missing/a.svg");
    let out = dlw(&[
        "draw".as_ref(),
        design.as_os_str(),
        "--svg".as_ref(),
        svg.as_os_str(),
        "--dxf".as_ref(),
        dxf.as_os_str(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("a.svg"));
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "left files behind"
    );
}

/// Under `SOURCE_DATE_EPOCH` a drawing is the same bytes every time (its dates are that instant
/// and its GUIDs a digest of it); without it, the GUIDs are random; a value that is not whole
/// seconds is refused and nothing is written.
#[test]
fn source_date_epoch_makes_the_dxf_reproducible() {
    let dir = tempfile::tempdir().unwrap();
    let design = common_designs::shipped()[0].clone();
    let draw = |name: &str, epoch: Option<&str>| {
        let path = dir.path().join(name);
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_dlw"));
        c.arg("draw").arg(&design).arg("--dxf").arg(&path);
        match epoch {
            Some(e) => c.env("SOURCE_DATE_EPOCH", e),
            None => c.env_remove("SOURCE_DATE_EPOCH"),
        };
        (c.output().unwrap(), path)
    };
    let (o1, a) = draw("a.dxf", Some("1764115200"));
    let (o2, b) = draw("b.dxf", Some("1764115200"));
    assert!(o1.status.success() && o2.status.success());
    let (a, b) = (std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
    assert_eq!(a, b, "two drawings under one SOURCE_DATE_EPOCH differ");
    let text = String::from_utf8(a).unwrap();
    // 2025-11-26 00:00 UTC, as the dxf crate writes a Julian date.
    assert!(
        text.contains("$TDUCREATE\r\n 40\r\n2461006.0\r\n"),
        "no epoch date"
    );
    let (_, c) = draw("c.dxf", None);
    let (_, d) = draw("d.dxf", None);
    assert_ne!(std::fs::read(c).unwrap(), std::fs::read(d).unwrap());
    let (bad, path) = draw("bad.dxf", Some("yesterday"));
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("SOURCE_DATE_EPOCH = \"yesterday\""));
    assert!(!path.exists());
}
