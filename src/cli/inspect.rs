//! `dlw inspect DESIGN [--json]`.

use std::path::PathBuf;

use dlw::design::DesignFile;
use dlw::rules;

/// Arguments of `dlw inspect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file (`docs/robots.md`).
    design: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    if dlw::robot::is_robot_file(&args.design) {
        return super::robot::inspect(&args.design, args.json);
    }
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
        print_mechanics(&report);
        for w in &report.warnings {
            println!("warning: {w}");
        }
    }
    Ok(())
}

/// The mechanics lines of the text report (`docs/mechanics.md`).
fn print_mechanics(r: &rules::Inspection) {
    println!("  mechanics (friction ignored; docs/mechanics.md)");
    println!("  tendon offset r_t   {:.4} mm", r.tendon_offset_mm);
    println!(
        "  stroke per degree   {:.5} mm/° ({:.2} °/mm)",
        r.stroke_per_deg_mm, r.deg_per_stroke_mm
    );
    println!(
        "  closing per notch   {:.2}°",
        r.closing_angle_per_notch_deg
    );
    println!(
        "  tube material       {} (E = {:.3} GPa, strain limit {:.2} %)",
        r.tube_material,
        r.youngs_modulus_pa / 1e9,
        r.material_strain_limit * 100.0
    );
    println!(
        "  farthest fibre      {:.4} mm from ȳ ({})",
        r.farthest_fibre_mm,
        r.farthest_fibre_side.describe()
    );
    println!(
        "  material strain     {:.4} % per degree, limit reached at {:.1}°",
        r.material_strain_per_deg * 100.0,
        r.material_limit_deg
    );
    println!("  sensor saturates at {:.1}°", r.saturation_limit_deg);
    println!(
        "  usable range        {:.1}° (limited by {})",
        r.usable_range_deg,
        r.range_limited_by.describe()
    );
    println!("  section area        {:.5} mm²", r.section_area_mm2);
    println!("  second moment I     {:.6} mm⁴", r.second_moment_mm4);
    println!("  moment per degree   {:.5} N·mm", r.moment_per_deg_nmm);
    println!("  tendon force per °  {:.5} N", r.tendon_force_per_deg_n);
}
