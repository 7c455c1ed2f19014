//! `dlw draw DESIGN [--dxf F] [--svg F] [--section F]`.

use std::path::PathBuf;

use anyhow::Context;
use dlw::design::DesignFile;
use dlw::drawing::layout_to_dxf;
use dlw::drawing::svg::{layout_svg, section_svg};
use dlw::output::write_all_atomic;
use dlw::rules;

/// Arguments of `dlw draw`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file (`docs/robots.md`).
    design: PathBuf,
    /// Write the unrolled layout as an AutoCAD DXF (mm) for designers.
    #[arg(long, value_name = "FILE")]
    dxf: Option<PathBuf>,
    /// Write the unrolled layout as an SVG sheet, with dimensions and a scale bar.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Write the cross-section through a notch (the paper's Fig. 3) as an SVG sheet.
    #[arg(long, value_name = "FILE")]
    section: Option<PathBuf>,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = args
        .dxf
        .iter()
        .chain(&args.svg)
        .chain(&args.section)
        .map(|p| p.as_path())
        .collect();
    dlw::output::claim_all(
        &outputs,
        dlw::robot::design_inputs(&args.design),
        args.force,
    )?;
    if args.dxf.is_none() && args.svg.is_none() && args.section.is_none() {
        anyhow::bail!("nothing to draw: give --dxf, --svg and/or --section FILE");
    }
    if dlw::robot::is_robot_file(&args.design) {
        let outputs = super::robot::draw(&args.design, args.dxf, args.svg, args.section)?;
        write_all_atomic(&outputs)?;
        for (path, _) in &outputs {
            println!("wrote {}", path.display());
        }
        return Ok(());
    }
    let checked = rules::check_file(DesignFile::read(&args.design)?)?;
    for w in &checked.warnings {
        eprintln!("warning: {w}");
    }
    // Make every drawing before writing any, so a failure leaves no file behind.
    let (design, layout) = (&checked.design, &checked.layout);
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(path) = args.dxf {
        let clearance_mm = design.file.fabrication.clearance_mm();
        let bytes = layout_to_dxf(layout, clearance_mm).context("drawing the DXF")?;
        outputs.push((path, bytes));
    }
    if let Some(path) = args.svg {
        let svg = layout_svg(layout, design).context("drawing the layout SVG")?;
        outputs.push((path, svg.into_bytes()));
    }
    if let Some(path) = args.section {
        let svg = section_svg(design).context("drawing the section SVG")?;
        outputs.push((path, svg.into_bytes()));
    }
    write_all_atomic(&outputs)?;
    for (path, _) in &outputs {
        println!("wrote {}", path.display());
    }
    Ok(())
}
