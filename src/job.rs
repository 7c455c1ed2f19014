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

/// Every file a job for the design at `design_path` reads: the design, the process sets it
/// names from the `process/` folder beside it, and the machine profile (`machine`, or the
/// default) from `machines/` or a path. A command claims its outputs against all of them, so
/// that no output replaces a file the design includes (`docs/outputs.md`). A design that
/// cannot be read yields itself alone (reading it later gives the error).
pub fn input_files(
    design_path: &std::path::Path,
    machine: Option<&str>,
) -> Vec<std::path::PathBuf> {
    let mut files = vec![design_path.to_path_buf()];
    if let Ok(design) = crate::design::DesignFile::read(design_path) {
        files.extend(crate::process::ProcessLibrary::beside(design_path).files(&design.process));
    }
    files.extend(crate::machine::MachineLibrary::beside(design_path).file(machine));
    files
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

/// [`make_job_from`] for any [`Part`] (a robot's; `crate::build::robot_job`), with the sheet written
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

#[cfg(test)]
mod tests {
    // The setup sheet's text as a job writes it for a shipped design (the sheet's own tests,
    // in `sheet::setup`, cover its parts).
    use super::*;

    fn sheet_for(design: &str) -> String {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("designs")
            .join(design);
        let file = crate::design::DesignFile::read(&path).unwrap();
        let checked = crate::rules::check_file(file).unwrap();
        let sets = crate::process::ProcessLibrary::beside(&path)
            .resolve(&checked.design.file.process)
            .unwrap();
        let profile = crate::machine::MachineLibrary::beside(&path)
            .find(None)
            .unwrap();
        make_job(&checked.design, &checked.layout, &sets, &profile, "x.ngc")
            .unwrap()
            .sheet
    }

    #[test]
    fn text_matches_the_joints_style_and_names_both_lengths() {
        let c = sheet_for("joint-c.toml");
        assert!(c.contains("This is a BSN joint"), "{c}");
        assert!(!c.contains("UAN"), "a BSN sheet mentions UAN:\n{c}");
        assert!(c.contains("two backbones run along A90 and A270"));
        let a = sheet_for("joint-a.toml");
        assert!(a.contains("(this is a UAN joint)"), "{a}");
        assert!(!a.contains("BSN"), "a UAN sheet mentions BSN:\n{a}");
        for sheet in [&a, &c] {
            assert!(
                sheet.contains("part length 13.3 mm beside bending length L = 9.5 mm"),
                "{sheet}"
            );
            assert!(sheet.contains("## Laser safety"));
            assert!(sheet.contains("a dwell of 5 s"));
        }
    }
}
