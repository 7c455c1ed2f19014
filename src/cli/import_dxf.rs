//! `dlw import-dxf FILE [--design DESIGN] [--units mm|um|in] [--join-tolerance MM]`: reads a
//! drawing in dlw's DXF convention, as CAD tools save it, and summarizes it; with a design, also
//! checks it against the design and lists every difference from the design's own layout.

use std::path::PathBuf;

use dlw::build::{read_design_drawing, read_drawing, read_robot_drawing, DrawingReading};
use dlw::design::DesignFile;
use dlw::drawing::{DrawingUnits, DEFAULT_JOIN_TOLERANCE_MM};
use dlw::robot::CheckedRobot;
use dlw::rules::{self, RulesError};

/// How to read a drawing that does not say everything itself (shared with `dlw program`).
#[derive(Debug, Clone, clap::Args)]
pub struct DrawingOptions {
    /// The drawing's unit when it has no $INSUNITS (R12 files cannot store it): mm, um or in.
    #[arg(long, value_name = "mm|um|in", value_parser = parse_units)]
    pub units: Option<DrawingUnits>,
    /// Ends of LINEs and ARCs on NOTCHES closer than this are joined into one outline (mm);
    /// also the chord error of arcs.
    #[arg(long, value_name = "MM", default_value_t = DEFAULT_JOIN_TOLERANCE_MM)]
    join_tolerance: f64,
}

fn parse_units(s: &str) -> Result<DrawingUnits, String> {
    DrawingUnits::from_name(s).ok_or_else(|| format!("unknown unit {s:?}: use mm, um or in"))
}

impl DrawingOptions {
    /// The library's reading of a drawing.
    pub fn reading(&self) -> DrawingReading {
        DrawingReading {
            units: self.units,
            join_tolerance_mm: self.join_tolerance,
        }
    }
}

/// Arguments of `dlw import-dxf`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// DXF drawing in dlw's layer convention, e.g. written by `dlw draw --dxf` and edited.
    dxf: PathBuf,
    /// Check the drawing against this design or robot file (and take the layout's numbers from
    /// it when the drawing lost dlw's XDATA).
    #[arg(long, value_name = "DESIGN")]
    design: Option<PathBuf>,
    #[command(flatten)]
    drawing: DrawingOptions,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let reading = args.drawing.reading();
    if let Some(robot) = args
        .design
        .as_deref()
        .filter(|p| dlw::robot::is_robot_file(p))
    {
        let robot = CheckedRobot::load(robot)?;
        super::print_warnings(&robot.warnings);
        let (read, drawing) = read_robot_drawing(&args.dxf, &reading, &robot)?;
        super::print_warnings(&read.warnings);
        super::print_warnings(&drawing.warnings);
        return super::robot::print_drawing(&args.dxf, &robot, &drawing);
    }
    let (imported, layout, clearance_mm, drawing) = match &args.design {
        Some(design) => {
            let checked = rules::check_file(DesignFile::read(design)?)?;
            let (read, d) = read_design_drawing(&args.dxf, &reading, &checked)?;
            super::print_warnings(&read.warnings);
            let clearance = checked.design.file.fabrication.clearance_mm();
            (read.imported, d.layout.clone(), clearance, Some(d))
        }
        None => {
            let read = read_drawing(&args.dxf, &reading, None)?;
            super::print_warnings(&read.warnings);
            let layout = read.imported.layout.clone();
            let clearance = read.imported.clearance_mm;
            (read.imported, layout, clearance, None)
        }
    };
    println!("{} (read from {})", layout.name, args.dxf.display());
    let counts: Vec<String> = imported
        .layer_counts
        .iter()
        .map(|(layer, n)| format!("{layer} {n}"))
        .collect();
    println!("  entities per layer  {}", counts.join(", "));
    let (units, _) = imported.units;
    println!(
        "  file                AutoCAD {}, read in {}",
        imported.version,
        units.name()
    );
    let pieces: usize = layout.notches.iter().map(|n| n.outline.len()).sum();
    println!(
        "  features            {} notches ({pieces} pieces), {} sensor traces, {} leads, {} pads, {} parting pieces",
        layout.notches.len(),
        layout.sensors.len(),
        layout.leads.len(),
        layout.pads.len(),
        layout.parting.len()
    );
    println!("  notch area          {:.6} mm²", layout.notch_area_mm2());
    if let Some(ext) = layout.extents() {
        println!(
            "  extents             x {:.4} .. {:.4} mm, s {:.4} .. {:.4} mm",
            ext.min().x,
            ext.max().x,
            ext.min().y,
            ext.max().y
        );
    }
    println!(
        "  frame               r_o {} mm, circumference {:.4} mm, seam at s = {:.4} mm, length {:.4} mm",
        layout.outer_radius_mm, layout.circumference_mm, layout.seam_s_mm, layout.length_mm
    );
    if imported.untagged > 0 {
        println!(
            "  untagged entities   {} (read from their geometry alone)",
            imported.untagged
        );
    }
    if imported.joined_outlines > 0 {
        println!(
            "  joined outlines     {} notch outlines joined from LINEs, ARCs or open polylines",
            imported.joined_outlines
        );
    }
    if let Some(d) = &drawing {
        for w in &d.warnings {
            eprintln!("warning: {w}");
        }
        for line in d.provenance.lines() {
            println!("  {line}");
        }
        println!(
            "  design rules        kept on the drawing (clearance {clearance_mm:.3} mm, kerf {} mm)",
            layout.kerf_mm
        );
        return Ok(());
    }
    let violations = rules::check_layout(&layout, clearance_mm);
    if violations.is_empty() {
        println!("  design rules        clearance {clearance_mm:.3} mm kept everywhere");
        Ok(())
    } else {
        Err(RulesError {
            name: layout.name.clone(),
            violations,
        }
        .into())
    }
}
