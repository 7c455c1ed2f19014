//! `dlw program DESIGN [--machine PROFILE] -o FILE [--sheet FILE.md]` and
//! `dlw program --from-dxf DRAWING.dxf --design DESIGN -o FILE …`.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use dlw::design::{Design, DesignFile};
use dlw::drawing::layout_from_dxf;
use dlw::job::{make_job, Job};
use dlw::layout::Layout;
use dlw::machine::{MachineLibrary, MachineProfile};
use dlw::output::write_all_atomic;
use dlw::process::{ProcessLibrary, ProcessSets};
use dlw::rules::{self, RulesError, Warning};

/// Arguments of `dlw program`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML).
    #[arg(value_name = "DESIGN")]
    design: Option<PathBuf>,
    /// Design file, when the layout comes from `--from-dxf` (same as the positional DESIGN).
    #[arg(long = "design", value_name = "DESIGN", conflicts_with = "design")]
    design_flag: Option<PathBuf>,
    /// Take the layout from this DXF (dlw's layer convention, e.g. a drawing from `dlw draw`
    /// that a designer edited) instead of laying the design out; the design still gives the
    /// radii, materials and process sets.
    #[arg(long, value_name = "DRAWING.dxf")]
    from_dxf: Option<PathBuf>,
    /// Machine profile: a name looked for in `machines/` next to the design, then among the
    /// built-in profiles, or a path to a `.toml`. Default: linuxcnc-reference.
    #[arg(long, value_name = "PROFILE")]
    machine: Option<String>,
    /// Program file to write.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Also write the operator's setup sheet (Markdown) here.
    #[arg(long, value_name = "FILE.md")]
    sheet: Option<PathBuf>,
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
}

/// Reads and checks the design (every design rule), takes its layout or the DXF's, finds the
/// process sets and the machine profile.
pub(crate) fn resolve_inputs(
    design_path: &Path,
    from_dxf: Option<&Path>,
    machine: Option<&str>,
) -> anyhow::Result<Inputs> {
    let checked = rules::check_file(DesignFile::read(design_path)?)?;
    let design = checked.design;
    let mut clearance_mm = design.file.fabrication.clearance_mm();
    let layout = match from_dxf {
        None => checked.layout,
        Some(dxf) => {
            let bytes = std::fs::read(dxf)
                .with_context(|| format!("cannot read drawing {}", dxf.display()))?;
            let imported =
                layout_from_dxf(&bytes).with_context(|| format!("reading {}", dxf.display()))?;
            let layout = imported.layout;
            let r_design = design.file.outer_radius_mm;
            if (layout.outer_radius_mm - r_design).abs() > 1e-9 {
                bail!(
                    "drawing {} is for r_o = {} mm but design {} has outer_radius_mm = {}",
                    dxf.display(),
                    layout.outer_radius_mm,
                    design_path.display(),
                    r_design
                );
            }
            clearance_mm = imported.clearance_mm;
            let violations = rules::check_layout(&layout, clearance_mm);
            if !violations.is_empty() {
                return Err(RulesError {
                    name: layout.name.clone(),
                    violations,
                })
                .with_context(|| format!("drawing {}", dxf.display()));
            }
            layout
        }
    };
    let sets = ProcessLibrary::beside(design_path).resolve(&design.file.process)?;
    let profile = MachineLibrary::beside(design_path).find(machine)?;
    Ok(Inputs {
        design,
        layout,
        sets,
        profile,
        warnings: checked.warnings,
        clearance_mm,
    })
}

/// Makes the job, naming the program `program_file` on the sheet.
pub(crate) fn job(inputs: &Inputs, program_file: &str) -> anyhow::Result<Job> {
    let job = make_job(
        &inputs.design,
        &inputs.layout,
        &inputs.sets,
        &inputs.profile,
        program_file,
    )
    .with_context(|| format!("planning the laser job for {:?}", inputs.design.file.name))?;
    Ok(job)
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let Some(design_path) = args.design.or(args.design_flag) else {
        bail!("give the design file: dlw program DESIGN -o FILE (or --from-dxf DRAWING.dxf --design DESIGN)");
    };
    let inputs = resolve_inputs(
        &design_path,
        args.from_dxf.as_deref(),
        args.machine.as_deref(),
    )?;
    for w in &inputs.warnings {
        eprintln!("warning: {w}");
    }
    let program_file = args.output.file_name().map_or_else(
        || args.output.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let job = job(&inputs, &program_file)?;
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
