//! `dlw draw DESIGN [--dxf F]`.

use std::path::PathBuf;

use anyhow::Context;
use dlw::design::DesignFile;
use dlw::drawing::layout_to_dxf;
use dlw::output::write_atomic;
use dlw::rules;

/// Arguments of `dlw draw`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML).
    design: PathBuf,
    /// Write the unrolled layout as an AutoCAD DXF (mm) for designers.
    #[arg(long, value_name = "FILE")]
    dxf: Option<PathBuf>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    if args.dxf.is_none() {
        anyhow::bail!("nothing to draw: give --dxf FILE");
    }
    let checked = rules::check_file(DesignFile::read(&args.design)?)?;
    for w in &checked.warnings {
        eprintln!("warning: {w}");
    }
    // Plan every output before writing any, so a failure leaves no file behind.
    let clearance_mm = checked.design.file.fabrication.clearance_mm();
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(path) = args.dxf {
        let bytes = layout_to_dxf(&checked.layout, clearance_mm).context("drawing the DXF")?;
        outputs.push((path, bytes));
    }
    for (path, bytes) in outputs {
        write_atomic(&path, &bytes)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
