//! `dlw draw DESIGN [--dxf F] [--svg F] [--section F]`.

use std::path::PathBuf;

use dlw::build::{joint_drawings, robot_drawings, Drawings};
use dlw::design::DesignFile;
use dlw::output::write_all_atomic;
use dlw::robot::CheckedRobot;
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
    let wanted = Drawings {
        dxf: args.dxf,
        svg: args.svg,
        section: args.section,
    };
    let outputs: Vec<&std::path::Path> = [&wanted.dxf, &wanted.svg, &wanted.section]
        .into_iter()
        .flatten()
        .map(|p| p.as_path())
        .collect();
    dlw::output::claim_all(
        &outputs,
        dlw::robot::design_inputs(&args.design),
        args.force,
    )?;
    if wanted.is_empty() {
        anyhow::bail!("nothing to draw: give --dxf, --svg and/or --section FILE");
    }
    // Every drawing is made before any is written, so a failure leaves no file behind.
    let files = if dlw::robot::is_robot_file(&args.design) {
        let robot = CheckedRobot::load(&args.design)?;
        super::print_warnings(&robot.warnings);
        robot_drawings(&robot, &wanted)?
    } else {
        let checked = rules::check_file(DesignFile::read(&args.design)?)?;
        super::print_warnings(&checked.warnings);
        joint_drawings(&checked, &wanted)?
    };
    write_all_atomic(&files)?;
    for (path, _) in &files {
        println!("wrote {}", path.display());
    }
    Ok(())
}
