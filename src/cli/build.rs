//! `dlw build DESIGN -o DIR [--machine PROFILE]`: everything for one joint in one folder — the
//! DXF drawing, the SVG sheets (layout and cross-section), the laser program and the setup
//! sheet. The folder is written in a temporary folder beside it and renamed into place, so it
//! never exists half-written. An existing non-empty folder is refused unless `--force` (as in
//! `dlw simulate`), so a build never silently replaces another design's files.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use dlw::drawing::layout_to_dxf;
use dlw::drawing::svg::{layout_svg, section_svg};
use dlw::job::program_file_name;
use dlw::output::write_folder_atomic;

use super::program::{job, resolve_inputs};

/// Arguments of `dlw build`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file (`docs/robots.md`).
    design: PathBuf,
    /// Folder to write (must not exist or be empty, unless --force).
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
    /// Machine profile: a name or a path (default: linuxcnc-reference).
    #[arg(long, value_name = "PROFILE")]
    machine: Option<String>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    if dlw::robot::is_robot_file(&args.design) {
        let read: Vec<_> = dlw::robot::design_inputs(&args.design)
            .iter()
            .flat_map(|d| dlw::job::input_files(d, args.machine.as_deref()))
            .collect();
        dlw::output::claim_folder(&args.output, &read, args.force)?;
        let stem = args
            .design
            .file_stem()
            .map_or_else(|| "robot".to_string(), |s| s.to_string_lossy().into_owned());
        let files = super::robot::build_files(&args.design, &stem, args.machine.as_deref())?;
        write_folder(&args.output, &files)?;
        for (name, _) in &files {
            println!("wrote {}", args.output.join(name).display());
        }
        return Ok(());
    }
    let read = dlw::job::input_files(&args.design, args.machine.as_deref());
    dlw::output::claim_folder(&args.output, &read, args.force)?;
    let inputs = resolve_inputs(&args.design, None, args.machine.as_deref())?;
    for w in &inputs.warnings {
        eprintln!("warning: {w}");
    }
    let stem = args
        .design
        .file_stem()
        .map_or_else(|| "joint".to_string(), |s| s.to_string_lossy().into_owned());
    let program_file = program_file_name(&stem, &inputs.profile);
    let job = job(&inputs, &program_file)?;
    let files: Vec<(String, Vec<u8>)> = vec![
        (
            format!("{stem}.dxf"),
            layout_to_dxf(&inputs.layout, inputs.clearance_mm).context("drawing the DXF")?,
        ),
        (
            format!("{stem}-layout.svg"),
            layout_svg(&inputs.layout, &inputs.design)
                .context("drawing the layout SVG")?
                .into_bytes(),
        ),
        (
            format!("{stem}-section.svg"),
            section_svg(&inputs.design)
                .context("drawing the section SVG")?
                .into_bytes(),
        ),
        (program_file, job.program.into_bytes()),
        (format!("{stem}-setup.md"), job.sheet.into_bytes()),
    ];
    write_folder(&args.output, &files)?;
    for (name, _) in &files {
        println!("wrote {}", args.output.join(name).display());
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
