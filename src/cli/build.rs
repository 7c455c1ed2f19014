//! `dlw build DESIGN -o DIR [--machine PROFILE]`: everything for one joint in one folder — the
//! DXF drawing, the SVG sheets (layout and cross-section), the laser program and the setup
//! sheet. The folder is written in a temporary folder beside it and renamed into place, so it
//! never exists half-written. An existing non-empty folder is refused unless `--force` (as in
//! `dlw simulate`), so a build never silently replaces another design's files.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use dlw::build::{joint_build_files, JointInputs, RobotInputs};
use dlw::output::write_folder_atomic;

use super::written::Output;

/// Arguments of `dlw build`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file (`docs/robots.md`).
    design: PathBuf,
    /// `-o DIR`: the folder to write (must not exist or be empty, unless --force).
    #[command(flatten)]
    out: Output,
    /// Machine profile: a name or a path (default: linuxcnc-reference).
    #[arg(long, value_name = "PROFILE")]
    machine: Option<String>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let machine = args.machine.as_deref();
    let read: Vec<PathBuf> = dlw::robot::design_inputs(&args.design)
        .iter()
        .flat_map(|d| dlw::job::input_files(d, machine))
        .collect();
    args.out.claim_folder(&read)?;
    let robot = dlw::robot::is_robot_file(&args.design);
    let stem = args.design.file_stem().map_or_else(
        || if robot { "robot" } else { "joint" }.to_string(),
        |s| s.to_string_lossy().into_owned(),
    );
    let files = if robot {
        let inputs = RobotInputs::resolve(&args.design, None, machine)?;
        super::print_warnings(&inputs.warnings);
        inputs.build_files(&stem)?
    } else {
        let inputs = JointInputs::resolve(&args.design, None, machine)?;
        super::print_warnings(&inputs.warnings);
        joint_build_files(&inputs, &stem)?
    };
    write_folder(&args.out.output, &files)?;
    for (name, _) in &files {
        println!("wrote {}", args.out.output.join(name).display());
    }
    Ok(())
}

/// Writes `files` into a fresh temporary folder next to `dir`, then puts it in `dir`'s place,
/// making `dir`'s parent folders first. An existing non-empty `dir` is replaced only if it was
/// claimed with `--force` (`output::claim` and `write_folder_atomic` check that); a file in its
/// place never is.
fn write_folder(dir: &Path, files: &[(String, Vec<u8>)]) -> anyhow::Result<()> {
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if std::fs::symlink_metadata(dir).is_ok() && !dir.is_dir() {
        bail!(
            "output {} exists and is not a folder; give a folder",
            dir.display()
        );
    }
    std::fs::create_dir_all(&parent)
        .with_context(|| format!("cannot create {}", parent.display()))?;
    write_folder_atomic(dir, files)?;
    Ok(())
}
