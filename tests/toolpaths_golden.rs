//! `toolpaths/` holds the programs and setup sheets of the four shipped designs, one folder per
//! design. This regenerates them through the binary and fails on any difference.
//!
//! To regenerate after an intended change: `DLW_REGENERATE=1 cargo test --test toolpaths_golden`,
//! then review the diff (`git diff toolpaths/`) before committing.

mod canon;

use std::path::Path;
use std::process::Command;

/// The files of one design's folder, and the `dlw program` arguments (after the design) that
/// write each program; `out` is the folder to write into.
fn runs(stem: &str, out: &Path) -> Vec<Vec<String>> {
    let o = |f: String| out.join(f).to_string_lossy().into_owned();
    vec![
        vec![
            "-o".into(),
            o(format!("{stem}.ngc")),
            "--sheet".into(),
            o(format!("{stem}-setup.md")),
        ],
        vec![
            "--machine".into(),
            "aerotech-aerobasic".into(),
            "-o".into(),
            o(format!("{stem}.pgm")),
        ],
    ]
}

fn files(stem: &str) -> [String; 3] {
    [
        format!("{stem}.ngc"),
        format!("{stem}-setup.md"),
        format!("{stem}.pgm"),
    ]
}

#[test]
fn toolpaths_folder_is_up_to_date() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let regenerate = std::env::var_os("DLW_REGENERATE").is_some();
    let mut stale = Vec::new();
    for j in ["a", "b", "c", "d"] {
        let stem = format!("joint-{j}");
        let tmp = tempfile::tempdir().unwrap();
        for args in runs(&stem, tmp.path()) {
            // From the repository root with a relative design path, as a user would, so the
            // profile's source reads `designs/machines/…` on every machine.
            let o = Command::new(env!("CARGO_BIN_EXE_dlw"))
                .current_dir(root)
                .arg("program")
                .arg(format!("designs/{stem}.toml"))
                .args(&args)
                .output()
                .unwrap();
            assert!(
                o.status.success(),
                "{stem}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
        let folder = root.join("toolpaths").join(&stem);
        for file in files(&stem) {
            let fresh = std::fs::read_to_string(tmp.path().join(&file)).unwrap();
            let kept_path = folder.join(&file);
            let kept = std::fs::read_to_string(&kept_path).unwrap_or_default();
            if fresh != kept {
                if regenerate {
                    std::fs::create_dir_all(&folder).unwrap();
                    std::fs::write(&kept_path, &fresh).unwrap();
                } else {
                    stale.push(format!("toolpaths/{stem}/{file}"));
                }
            }
        }
    }
    assert!(
        stale.is_empty(),
        "generated programs differ from the committed ones: {}\nregenerate with \
         `DLW_REGENERATE=1 cargo test --test toolpaths_golden` and review `git diff toolpaths/`",
        stale.join(", ")
    );
}

/// The committed programs themselves pass LinuxCNC's interpreter.
#[test]
fn committed_programs_run_in_rs274() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for j in ["a", "b", "c", "d"] {
        let file = root.join(format!("toolpaths/joint-{j}/joint-{j}.ngc"));
        assert!(file.is_file(), "{} is missing", file.display());
        let canon = canon::parse(&canon::run_rs274(&file));
        assert_eq!(canon.operations, ["sensor", "notches", "parting"]);
    }
}
