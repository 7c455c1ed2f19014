//! `dlw program DESIGN [--machine PROFILE] -o FILE [--sheet FILE.md]` and
//! `dlw program --from-dxf DRAWING.dxf --design DESIGN -o FILE …`.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use dlw::design::{Design, DesignFile};
use dlw::drawing::Provenance;
use dlw::job::{make_job_from, Job};
use dlw::layout::Layout;
use dlw::machine::{MachineLibrary, MachineProfile};
use dlw::output::write_all_atomic;
use dlw::process::{ProcessLibrary, ProcessSets};
use dlw::rules::{self, Warning};

use super::import_dxf::{read_for_design, DrawingOptions};

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
    /// Program file to write.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
    /// Also write the operator's setup sheet (Markdown) here.
    #[arg(long, value_name = "FILE.md")]
    sheet: Option<PathBuf>,
    /// How to read the `--from-dxf` drawing.
    #[command(flatten)]
    drawing: DrawingOptions,
}

/// What a job is made from, resolved and checked.
pub(crate) struct Inputs {
    pub design: Design,
    pub layout: Layout,
    pub sets: ProcessSets,
    pub profile: MachineProfile,
    pub warnings: Vec<Warning>,
    /// The clearance the layout was checked with (mm).
    pub clearance_mm: f64,
    /// The drawing the layout was read from (`--from-dxf`).
    pub provenance: Option<Provenance>,
}

/// Reads and checks the design (every design rule), takes its layout or the DXF's (checked
/// against the design), finds the process sets and the machine profile.
pub(crate) fn resolve_inputs(
    design_path: &Path,
    from_dxf: Option<(&Path, &DrawingOptions)>,
    machine: Option<&str>,
) -> anyhow::Result<Inputs> {
    let checked = rules::check_file(DesignFile::read(design_path)?)?;
    let clearance_mm = checked.design.file.fabrication.clearance_mm();
    let (layout, warnings, provenance) = match from_dxf {
        None => (checked.layout, checked.warnings, None),
        Some((dxf, options)) => {
            let (_, drawing) = read_for_design(dxf, options, &checked)?;
            (drawing.layout, drawing.warnings, Some(drawing.provenance))
        }
    };
    let design = checked.design;
    let sets = ProcessLibrary::beside(design_path).resolve(&design.file.process)?;
    let profile = MachineLibrary::beside(design_path).find(machine)?;
    Ok(Inputs {
        design,
        layout,
        sets,
        profile,
        warnings,
        clearance_mm,
        provenance,
    })
}

/// Makes the job, naming the program `program_file` on the sheet.
pub(crate) fn job(inputs: &Inputs, program_file: &str) -> anyhow::Result<Job> {
    let job = make_job_from(
        &inputs.design,
        &inputs.layout,
        &inputs.sets,
        &inputs.profile,
        program_file,
        inputs.provenance.clone(),
    )
    .with_context(|| format!("planning the laser job for {:?}", inputs.design.file.name))?;
    Ok(job)
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = std::iter::once(&args.output)
        .chain(&args.sheet)
        .map(|p| p.as_path())
        .collect();
    let read: Vec<PathBuf> = args
        .design
        .iter()
        .chain(&args.design_flag)
        .flat_map(|d| dlw::robot::design_inputs(d))
        .flat_map(|d| dlw::job::input_files(&d, args.machine.as_deref()))
        .chain(args.from_dxf.iter().cloned())
        .collect();
    dlw::output::claim_all(&outputs, &read, args.force)?;
    if args.from_dxf.is_none() && args.drawing.units.is_some() {
        bail!("--units is for reading a drawing: give it with --from-dxf DRAWING.dxf");
    }
    let Some(design_path) = args.design.or(args.design_flag) else {
        bail!("give the design file: dlw program DESIGN -o FILE (or --from-dxf DRAWING.dxf --design DESIGN)");
    };
    let program_file = args.output.file_name().map_or_else(
        || args.output.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let from_dxf = args.from_dxf.as_deref().map(|p| (p, &args.drawing));
    let job = if dlw::robot::is_robot_file(&design_path) {
        let inputs = super::robot::resolve(&design_path, from_dxf, args.machine.as_deref())?;
        super::robot::job(&inputs, &program_file)?
    } else {
        let inputs = resolve_inputs(&design_path, from_dxf, args.machine.as_deref())?;
        for w in &inputs.warnings {
            eprintln!("warning: {w}");
        }
        job(&inputs, &program_file)?
    };
    // Everything is made before anything is written, and the files are staged together, so a
    // failure leaves no file behind.
    let mut files = vec![(args.output.clone(), job.program.into_bytes())];
    if let Some(sheet) = &args.sheet {
        files.push((sheet.clone(), job.sheet.into_bytes()));
    }
    write_all_atomic(&files)?;
    for (path, _) in &files {
        println!("wrote {}", path.display());
    }
    Ok(())
}
