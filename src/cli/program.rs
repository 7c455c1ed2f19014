//! `dlw program DESIGN [--machine PROFILE] -o FILE [--sheet FILE.md]` and
//! `dlw program --from-dxf DRAWING.dxf --design DESIGN -o FILE …`.

use std::path::PathBuf;

use anyhow::bail;
use dlw::build::{JointInputs, RobotInputs};
use dlw::output::write_all_atomic;

use super::import_dxf::DrawingOptions;
use super::written::Output;

/// Arguments of `dlw program`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file (`docs/robots.md`).
    #[arg(value_name = "DESIGN")]
    design: Option<PathBuf>,
    /// Design file, when the layout comes from `--from-dxf` (same as the positional DESIGN).
    #[arg(long = "design", value_name = "DESIGN", conflicts_with = "design")]
    design_flag: Option<PathBuf>,
    /// Take the layout from this DXF (dlw's layer convention, e.g. a drawing from `dlw draw`
    /// that a designer edited and saved again) instead of laying the design out. The drawing
    /// must be of the design and keep every design rule; the design gives the radii, kerf,
    /// trace width, materials and process sets, and the program header and setup sheet name
    /// the drawing and list how it differs from the design's own layout.
    #[arg(long, value_name = "DRAWING.dxf")]
    from_dxf: Option<PathBuf>,
    /// Machine profile: a name looked for in `machines/` next to the design, then among the
    /// built-in profiles, or a path to a `.toml`. Default: linuxcnc-reference.
    #[arg(long, value_name = "PROFILE")]
    machine: Option<String>,
    /// `-o FILE`: the program file to write.
    #[command(flatten)]
    out: Output,
    /// Also write the operator's setup sheet (Markdown) here.
    #[arg(long, value_name = "FILE.md")]
    sheet: Option<PathBuf>,
    /// How to read the `--from-dxf` drawing.
    #[command(flatten)]
    drawing: DrawingOptions,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let machine = args.machine.as_deref();
    let read: Vec<PathBuf> = args
        .design
        .iter()
        .chain(&args.design_flag)
        .flat_map(|d| dlw::robot::design_inputs(d))
        .flat_map(|d| dlw::job::input_files(&d, machine))
        .chain(args.from_dxf.iter().cloned())
        .collect();
    let sheet: Vec<&std::path::Path> = args.sheet.iter().map(|p| p.as_path()).collect();
    args.out.claim_with(&sheet, &read)?;
    if args.from_dxf.is_none() && args.drawing.units.is_some() {
        bail!("--units is for reading a drawing: give it with --from-dxf DRAWING.dxf");
    }
    let Some(design_path) = args.design.or(args.design_flag) else {
        bail!("give the design file: dlw program DESIGN -o FILE (or --from-dxf DRAWING.dxf --design DESIGN)");
    };
    let output = &args.out.output;
    let program_file = output.file_name().map_or_else(
        || output.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let reading = args.drawing.reading();
    let from_dxf = args.from_dxf.as_deref().map(|p| (p, &reading));
    let job = if dlw::robot::is_robot_file(&design_path) {
        let inputs = RobotInputs::resolve(&design_path, from_dxf, machine)?;
        super::print_warnings(&inputs.warnings);
        inputs.job(&program_file)?
    } else {
        let inputs = JointInputs::resolve(&design_path, from_dxf, machine)?;
        super::print_warnings(&inputs.warnings);
        inputs.job(&program_file)?
    };
    // Everything is made before anything is written, and the files are staged together, so a
    // failure leaves no file behind.
    let mut files = vec![(output.clone(), job.program.into_bytes())];
    if let Some(sheet) = &args.sheet {
        files.push((sheet.clone(), job.sheet.into_bytes()));
    }
    write_all_atomic(&files)?;
    for (path, _) in &files {
        println!("wrote {}", path.display());
    }
    Ok(())
}
