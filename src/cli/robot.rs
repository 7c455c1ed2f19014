//! The robot side of the commands that take a design (`docs/robots.md`): each of them, given
//! a robot file ([`dlw::robot::is_robot_file`]), comes here.

use std::path::Path;

use dlw::build::CheckedRobotDrawing;
use dlw::robot::{CheckedRobot, RobotInspection};

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

/// `dlw import-dxf DRAWING --design ROBOT`: what the drawing read back holds.
pub(crate) fn print_drawing(
    dxf_path: &Path,
    robot: &CheckedRobot,
    drawing: &CheckedRobotDrawing,
) -> anyhow::Result<()> {
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
