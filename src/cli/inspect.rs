//! `dlw inspect DESIGN [--json]`.

use std::path::PathBuf;

use dlw::design::DesignFile;
use dlw::rules;
use serde::Serialize;

/// Arguments of `dlw inspect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML).
    design: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// What `inspect` reports; the JSON keys are part of the interface.
#[derive(Debug, Serialize)]
struct Report {
    name: String,
    style: dlw_geometry::NotchStyle,
    neutral_axis_mm: f64,
    sensor_plane_mm: f64,
    offset_mm: f64,
    strain_per_deg: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    two_sensor_offset_mm: Option<f64>,
    closing_angle_deg: f64,
    strain_at_closing: f64,
    warnings: Vec<String>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let checked = rules::check_file(DesignFile::read(&args.design)?)?;
    let design = &checked.design;
    let joint = &design.joint;
    let section = joint.section();
    let report = Report {
        name: design.file.name.clone(),
        style: joint.style(),
        neutral_axis_mm: section.neutral_axis_mm(),
        sensor_plane_mm: section.sensor_plane_mm(),
        offset_mm: section.offset_mm(),
        strain_per_deg: joint.strain_per_deg(),
        two_sensor_offset_mm: section.two_sensor_offset_mm(),
        closing_angle_deg: joint.closing_angle_rad().to_degrees(),
        strain_at_closing: joint.strain_at_closing(),
        warnings: checked.warnings.iter().map(ToString::to_string).collect(),
    };
    if args.json {
        println!("{}", dlw::finite::to_json(&report)?);
    } else {
        println!("{}", report.name);
        println!("  style               {:?}", report.style);
        println!("  neutral plane ȳ     {:.4} mm", report.neutral_axis_mm);
        println!("  sensor plane y_s    {:.4} mm", report.sensor_plane_mm);
        println!("  offset Δy           {:.4} mm", report.offset_mm);
        if let Some(dy) = report.two_sensor_offset_mm {
            println!("  two-sensor Δy(1,2)  {dy:.4} mm");
        }
        println!(
            "  strain per degree   {:.4} %",
            report.strain_per_deg * 100.0
        );
        println!("  notches close at    {:.1}°", report.closing_angle_deg);
        println!(
            "  strain at closing   {:.2} %",
            report.strain_at_closing * 100.0
        );
        for w in &report.warnings {
            println!("warning: {w}");
        }
    }
    Ok(())
}
