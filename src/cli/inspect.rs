//! `dlw inspect DESIGN [--json]`.

use std::path::PathBuf;

use dlw::design::DesignFile;
use dlw::rules;

/// Arguments of `dlw inspect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML).
    design: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let checked = rules::check_file(DesignFile::read(&args.design)?)?;
    let report = rules::Inspection::of(&checked);
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
