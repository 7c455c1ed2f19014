//! `dlw inspect` and `dlw draw` on the shipped designs and on designs outside the paper, through
//! the real binary.

mod common;
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
