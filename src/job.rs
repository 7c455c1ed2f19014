//! A laser job: a checked design and its layout, planned and written as a program and a setup
//! sheet for one machine.
//!
//! # Examples
//! ```
//! use dlw::{design::DesignFile, job, machine::MachineLibrary, process::ProcessLibrary, rules};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/designs/joint-a.toml"));
//! let checked = rules::check_file(DesignFile::read(path)?)?;
//! let sets = ProcessLibrary::beside(path).resolve(&checked.design.file.process)?;
//! let profile = MachineLibrary::beside(path).find(None)?;
//! let file = job::program_file_name("joint-a", &profile);
//! let job = job::make_job(&checked.design, &checked.layout, &sets, &profile, &file)?;
//! assert!(job.program.contains("G93"));
//! assert_eq!(job.program_file, "joint-a.ngc");
//! # Ok(()) }
//! ```

use crate::design::Design;
use crate::drawing::Provenance;
use crate::layout::Layout;
use crate::machine::MachineProfile;
use crate::post::{post_for, write_program, PostError};
use crate::process::ProcessSets;
use crate::sheet::{setup_sheet, SheetContext};
use crate::toolpath::{plan, plan_part, Part, Plan, PlanOptions, ToolpathError};

/// Everything one `dlw program` writes.
#[derive(Debug, Clone)]
pub struct Job {
    /// The plan the program was written from.
    pub plan: Plan,
    /// The program's text.
    pub program: String,
    /// The program's file name, as the sheet names it.
    pub program_file: String,
    /// The setup sheet (Markdown).
    pub sheet: String,
}

/// `stem` plus the usual extension of the profile's dialect: `joint-a.ngc`, `joint-a.pgm`.
pub fn program_file_name(stem: &str, profile: &MachineProfile) -> String {
    format!("{stem}.{}", post_for(profile.dialect).extension())
}

/// Why a job could not be made.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    /// The planner refused the layout or a safety invariant.
    #[error(transparent)]
    Toolpath(#[from] ToolpathError),
    /// The post-processor cannot write what the profile asks.
    #[error(transparent)]
    Post(#[from] PostError),
}

/// Plans `layout` and writes the program and the setup sheet for `profile`; `program_file` is
/// the name the sheet tells the operator to load (see [`program_file_name`]).
///
/// # Errors
/// [`JobError`] from the planner or the post-processor; nothing is written here.
pub fn make_job(
    design: &Design,
    layout: &Layout,
    sets: &ProcessSets,
    profile: &MachineProfile,
    program_file: &str,
) -> Result<Job, JobError> {
    make_job_from(design, layout, sets, profile, program_file, None)
}

/// [`make_job`] for a layout read from a drawing: the program header and the setup sheet say
/// where it came from (`provenance`).
///
/// # Errors
/// [`JobError`] from the planner or the post-processor; nothing is written here.
pub fn make_job_from(
    design: &Design,
    layout: &Layout,
    sets: &ProcessSets,
    profile: &MachineProfile,
    program_file: &str,
    provenance: Option<Provenance>,
) -> Result<Job, JobError> {
    let mut plan = plan(design, layout, sets, profile, &PlanOptions::default())?;
    plan.provenance = provenance;
    let post = post_for(profile.dialect);
    let program = write_program(&plan, profile, post.as_ref())?;
    let program_file = program_file.to_string();
    let sheet = setup_sheet(
        &plan,
        &SheetContext {
            profile,
            program_file: &program_file,
        },
    );
    Ok(Job {
        plan,
        program,
        program_file,
        sheet,
    })
}

/// [`make_job_from`] for any [`Part`] (a robot's; `crate::robot::job`), with the sheet written
/// by `sheet` (the caller has checked the wall against the sets, [`crate::rules::check_wall`]).
///
/// # Errors
/// [`JobError`] from the planner or the post-processor; nothing is written here.
pub fn make_part_job(
    part: &Part,
    layout: &Layout,
    sets: &ProcessSets,
    profile: &MachineProfile,
    program_file: &str,
    provenance: Option<Provenance>,
    sheet: &dyn Fn(&Plan, &SheetContext) -> String,
) -> Result<Job, JobError> {
    let mut plan = plan_part(part, layout, sets, profile, &PlanOptions::default())?;
    plan.provenance = provenance;
    let post = post_for(profile.dialect);
    let program = write_program(&plan, profile, post.as_ref())?;
    let program_file = program_file.to_string();
    let sheet = sheet(
        &plan,
        &SheetContext {
            profile,
            program_file: &program_file,
        },
    );
    Ok(Job {
        plan,
        program,
        program_file,
        sheet,
    })
}
