//! `dlw import-dxf FILE`: reads a drawing in dlw's DXF convention and summarizes it.

use std::path::PathBuf;

use anyhow::Context;
use dlw::drawing::layout_from_dxf;
use dlw::rules::{self, RulesError};

/// Arguments of `dlw import-dxf`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// DXF drawing (mm) in dlw's layer convention, e.g. written by `dlw draw --dxf` and edited.
    dxf: PathBuf,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let bytes = std::fs::read(&args.dxf)
        .with_context(|| format!("cannot read drawing {}", args.dxf.display()))?;
    let imported =
        layout_from_dxf(&bytes).with_context(|| format!("reading {}", args.dxf.display()))?;
    let layout = &imported.layout;
    println!("{} (read from {})", layout.name, args.dxf.display());
    let counts: Vec<String> = imported
        .layer_counts
        .iter()
        .map(|(layer, n)| format!("{layer} {n}"))
        .collect();
    println!("  entities per layer  {}", counts.join(", "));
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
    let violations = rules::check_layout(layout, imported.clearance_mm);
    if violations.is_empty() {
        println!(
            "  design rules        clearance {:.3} mm kept everywhere",
            imported.clearance_mm
        );
        Ok(())
    } else {
        Err(RulesError {
            name: layout.name.clone(),
            violations,
        }
        .into())
    }
}
