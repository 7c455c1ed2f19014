//! `dlw build DESIGN -o DIR [--machine PROFILE]`: everything for one joint in one folder — the
//! DXF drawing, the SVG sheets (layout and cross-section), the laser program and the setup
//! sheet. The folder is written in a temporary folder beside it and renamed into place, so it
//! never exists half-written.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use dlw::drawing::layout_to_dxf;
use dlw::drawing::svg::{layout_svg, section_svg};
use dlw::job::program_file_name;

use super::program::{job, resolve_inputs};

/// Arguments of `dlw build`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML).
    design: PathBuf,
    /// Folder to write (created; an existing one may only hold files a previous build wrote).
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// Machine profile: a name or a path (default: linuxcnc-reference).
    #[arg(long, value_name = "PROFILE")]
    machine: Option<String>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
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

/// Writes `files` into a fresh temporary folder next to `dir`, then puts it in `dir`'s place.
/// An existing `dir` is replaced only if every file in it is one this build writes, so a
/// build never deletes anything else.
fn write_folder(dir: &Path, files: &[(String, Vec<u8>)]) -> anyhow::Result<()> {
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if dir.exists() {
        if !dir.is_dir() {
            bail!("{} exists and is not a folder", dir.display());
        }
        let entries =
            std::fs::read_dir(dir).with_context(|| format!("cannot list {}", dir.display()))?;
        for entry in entries {
            let entry = entry.with_context(|| format!("cannot list {}", dir.display()))?;
            let name = entry.file_name().to_string_lossy().into_owned();
            if !files.iter().any(|(n, _)| *n == name) {
                bail!(
                    "{} already holds {name:?}, which this build would not write; give an empty or new folder",
                    dir.display()
                );
            }
        }
    }
    std::fs::create_dir_all(&parent)
        .with_context(|| format!("cannot create {}", parent.display()))?;
    let tmp = tempfile::Builder::new()
        .prefix(".dlw-build-")
        .tempdir_in(&parent)
        .with_context(|| format!("cannot create a folder in {}", parent.display()))?;
    for (name, bytes) in files {
        let path = tmp.path().join(name);
        std::fs::write(&path, bytes).with_context(|| format!("cannot write {}", path.display()))?;
    }
    // A temporary folder is private (0700); the build folder is an ordinary one.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(tmp.path(), std::fs::Permissions::from_mode(0o755))
            .with_context(|| format!("cannot set permissions on {}", tmp.path().display()))?;
    }
    let staged = tmp.keep();
    if dir.exists() {
        let old = tempfile::Builder::new()
            .prefix(".dlw-old-")
            .tempdir_in(&parent)
            .with_context(|| format!("cannot create a folder in {}", parent.display()))?
            .keep();
        std::fs::rename(dir, old.join("old"))
            .with_context(|| format!("cannot move {} aside", dir.display()))?;
        if let Err(e) = std::fs::rename(&staged, dir) {
            // Put the old folder back so nothing is lost.
            let _ = std::fs::rename(old.join("old"), dir);
            let _ = std::fs::remove_dir_all(&staged);
            return Err(e)
                .with_context(|| format!("cannot move the new build into {}", dir.display()));
        }
        let _ = std::fs::remove_dir_all(&old);
    } else if let Err(e) = std::fs::rename(&staged, dir) {
        let _ = std::fs::remove_dir_all(&staged);
        return Err(e).with_context(|| format!("cannot create {}", dir.display()));
    }
    Ok(())
}
