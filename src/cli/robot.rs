//! The robot side of the commands that take a design (`docs/robots.md`): each of them, given
//! a robot file ([`dlw::robot::is_robot_file`]), comes here.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use dlw::drawing::svg::section_svg;
use dlw::drawing::{LayoutNumbers, Provenance};
use dlw::job::Job;
use dlw::layout::Layout;
use dlw::machine::{MachineLibrary, MachineProfile};
use dlw::process::{ProcessLibrary, ProcessSets};
use dlw::robot::robot_svg;
use dlw::robot::{check_robot_drawing, CheckedRobot, RobotInspection};

use super::import_dxf::{read, DrawingOptions};

/// Reads and checks a robot, printing its warnings.
pub(crate) fn load(path: &Path) -> anyhow::Result<CheckedRobot> {
    let robot = CheckedRobot::load(path)?;
    for w in &robot.warnings {
        eprintln!("warning: {w}");
    }
    Ok(robot)
}

/// `dlw inspect ROBOT [--json]`.
pub(crate) fn inspect(path: &Path, json: bool) -> anyhow::Result<()> {
    let robot = CheckedRobot::load(path)?;
    let report = RobotInspection::of(&robot);
    if json {
        println!("{}", dlw::finite::to_json(&report)?);
        return Ok(());
    }
    println!("{} (robot, checksum {})", report.name, report.checksum);
    println!(
        "  part length         {:.4} mm, {} pad row(s) after the last joint's own",
        report.length_mm, report.pad_rows
    );
    for (i, j) in report.joints.iter().enumerate() {
        println!(
            "  joint {}             {} ({:?}), rotated {}°, notched x {:.4} … {:.4} mm, ȳ {:.4} mm, Δy {:.4} mm",
            i + 1,
            j.design.name,
            j.design.style,
            j.rotation_deg,
            j.x_start_mm,
            j.x_end_mm,
            j.design.neutral_axis_mm,
            j.design.offset_mm
        );
    }
    for (i, s) in report.sensors.iter().enumerate() {
        let c: Vec<String> = s
            .crosstalk
            .iter()
            .map(|v| format!("{:.2} %", v * 100.0))
            .collect();
        println!(
            "  sensor {}            joint {} sensor {}, trace {:.3} mm, crosstalk [{}]",
            i + 1,
            s.joint,
            s.sensor,
            s.trace_length_mm,
            c.join(", ")
        );
    }
    for w in &report.warnings {
        println!("warning: {w}");
    }
    Ok(())
}

/// The robot's DXF of `layout`.
pub(crate) fn dxf(robot: &CheckedRobot, layout: &Layout) -> anyhow::Result<Vec<u8>> {
    dlw::robot::files::dxf(robot, layout).context("drawing the DXF")
}

/// `dlw draw ROBOT …`: the files to write (outputs already claimed).
pub(crate) fn draw(
    path: &Path,
    dxf_path: Option<PathBuf>,
    svg_path: Option<PathBuf>,
    section_path: Option<PathBuf>,
) -> anyhow::Result<Vec<(PathBuf, Vec<u8>)>> {
    let robot = load(path)?;
    let mut out = Vec::new();
    if let Some(p) = dxf_path {
        out.push((p, dxf(&robot, &robot.layout)?));
    }
    if let Some(p) = svg_path {
        let svg = robot_svg(&robot).context("drawing the robot SVG")?;
        out.push((p, svg.into_bytes()));
    }
    if let Some(p) = section_path {
        let [only] = robot.robot.joints.as_slice() else {
            bail!(
                "--section draws one joint's cross-section, and {:?} has {} joints: draw each joint's design with --section, or dlw build the robot (one section sheet per joint)",
                robot.robot.name,
                robot.robot.joints.len()
            );
        };
        let svg = section_svg(only.design()).context("drawing the section SVG")?;
        out.push((p, svg.into_bytes()));
    }
    Ok(out)
}

/// What a robot's job is made from, resolved and checked.
pub(crate) struct RobotInputs {
    pub robot: CheckedRobot,
    pub layout: Layout,
    pub sets: ProcessSets,
    pub profile: MachineProfile,
    pub provenance: Option<Provenance>,
}

/// Reads and checks the robot, takes its layout or its drawing's (checked against it), finds
/// the process sets and the machine profile beside the robot file.
pub(crate) fn resolve(
    path: &Path,
    from_dxf: Option<(&Path, &DrawingOptions)>,
    machine: Option<&str>,
) -> anyhow::Result<RobotInputs> {
    let robot = load(path)?;
    let (layout, provenance) = match from_dxf {
        None => (robot.layout.clone(), None),
        Some((dxf_path, options)) => {
            let drawing = read_robot_drawing(dxf_path, options, &robot)?;
            (drawing.layout, Some(drawing.provenance))
        }
    };
    let sets =
        ProcessLibrary::beside(path).resolve(&robot.robot.joints[0].design().file.process)?;
    let profile = MachineLibrary::beside(path).find(machine)?;
    Ok(RobotInputs {
        robot,
        layout,
        sets,
        profile,
        provenance,
    })
}

/// Reads a robot's drawing and checks it against the robot.
pub(crate) fn read_robot_drawing(
    dxf_path: &Path,
    options: &DrawingOptions,
    robot: &CheckedRobot,
) -> anyhow::Result<dlw::robot::CheckedRobotDrawing> {
    let numbers = LayoutNumbers::of(&robot.layout, robot.robot.clearance_mm());
    let (imported, bytes) = read(dxf_path, options, Some(numbers))?;
    let file_name = dxf_path.file_name().map_or_else(
        || dxf_path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let drawing = check_robot_drawing(robot, &imported, &file_name, &bytes)
        .with_context(|| format!("drawing {} checked against the robot", dxf_path.display()))?;
    for w in &drawing.warnings {
        eprintln!("warning: {w}");
    }
    Ok(drawing)
}

/// Makes the robot's job, naming the program `program_file` on the sheet.
pub(crate) fn job(inputs: &RobotInputs, program_file: &str) -> anyhow::Result<Job> {
    dlw::robot::job::make_job(
        &inputs.robot,
        &inputs.layout,
        &inputs.sets,
        &inputs.profile,
        program_file,
        inputs.provenance.clone(),
    )
    .with_context(|| format!("planning the laser job for {:?}", inputs.robot.robot.name))
}

/// `dlw build ROBOT -o DIR`: the files to write.
pub(crate) fn build_files(
    path: &Path,
    stem: &str,
    machine: Option<&str>,
) -> anyhow::Result<Vec<(String, Vec<u8>)>> {
    let inputs = resolve(path, None, machine)?;
    dlw::robot::files::build_files(&inputs.robot, stem, &inputs.sets, &inputs.profile)
        .with_context(|| format!("building {:?}", inputs.robot.robot.name))
}

/// `dlw import-dxf DRAWING --design ROBOT`.
pub(crate) fn import_dxf(
    dxf_path: &Path,
    robot_path: &Path,
    options: &DrawingOptions,
) -> anyhow::Result<()> {
    let robot = load(robot_path)?;
    let drawing = read_robot_drawing(dxf_path, options, &robot)?;
    let layout = &drawing.layout;
    println!("{} (robot, read from {})", layout.name, dxf_path.display());
    let pieces: usize = layout.notches.iter().map(|n| n.outline.len()).sum();
    println!(
        "  features            {} notches ({pieces} pieces) in {} joints, {} sensor traces, {} leads, {} pads, {} parting pieces",
        layout.notches.len(),
        robot.robot.joints.len(),
        layout.sensors.len(),
        layout.leads.len(),
        layout.pads.len(),
        layout.parting.len()
    );
    for line in drawing.provenance.lines() {
        println!("  {line}");
    }
    println!(
        "  design rules        kept on the drawing (clearance {:.3} mm, kerf {} mm), and the router's property",
        robot.robot.clearance_mm(),
        layout.kerf_mm
    );
    Ok(())
}

/// `dlw estimator-config ROBOT --joint N`: joint `N`'s design, and a note saying what the
/// config leaves out (the other joints' bending its sensors read).
pub(crate) fn joint_for_estimator(
    path: &Path,
    joint: Option<usize>,
) -> anyhow::Result<(dlw::design::Design, Option<String>)> {
    let robot = load(path)?;
    let r = &robot.robot;
    let list = r
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| format!("{} = {}", i + 1, j.design().file.name))
        .collect::<Vec<_>>()
        .join(", ");
    let Some(n) = joint else {
        bail!(
            "{} is a robot of {} joints ({list}): give --joint N for the nominal config of joint N's own sensors alone, or no --joint for the robot's own config",
            path.display(),
            r.joints.len()
        );
    };
    if n == 0 || n > r.joints.len() {
        bail!(
            "--joint {n} must be from 1 to {}, the robot's joints ({list})",
            r.joints.len()
        );
    }
    let mut lines = vec![format!(
        "Joint {n} of the robot {:?} (robot checksum {}); its sensors alone, as if the other joints did not bend.",
        r.name, r.checksum
    )];
    for s in robot.sensors.iter().filter(|s| s.sensor.joint == n - 1) {
        let others: Vec<String> = s
            .crosstalk
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != n - 1)
            .map(|(j, v)| format!("{:.2} % of joint {}", v * 100.0, j + 1))
            .collect();
        if !others.is_empty() {
            lines.push(format!(
                "Its sensor {} also reads {} (crosstalk, docs/robots.md).",
                s.sensor.sensor + 1,
                others.join(", ")
            ));
        }
    }
    Ok((r.joints[n - 1].design().clone(), Some(lines.join("\n"))))
}
