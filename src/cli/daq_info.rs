//! `dlw daq-info FILE [--daq-format F] [--json]` and `dlw daq-info --tracker FILE
//! [--tracker-map MAP] [--json]`: what a DAQ file or a tracker log holds, before importing it
//! (`docs/import.md`).

use std::path::PathBuf;

use anyhow::Context;
use dlw::import::files::read_map;
use dlw::import::info::{daq_info, tracker_info};
use dlw::import::DaqFormat;
use dlw::limits::MAX_RECORDING_BYTES;

/// Arguments of `dlw daq-info`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The DAQ file: a CSV export, NI TDMS or a LabVIEW .lvm file.
    #[arg(required_unless_present = "tracker", conflicts_with = "tracker")]
    file: Option<PathBuf>,
    /// The DAQ file's format: csv, tdms or lvm (default: from a .tdms or .lvm extension, else
    /// csv).
    #[arg(long)]
    daq_format: Option<String>,
    /// A CSV's time column, when it is not named time_s, time, Time or t.
    #[arg(long)]
    time_column: Option<String>,
    /// A tracker log instead: its tools, frames, span, rate and gaps.
    #[arg(long)]
    tracker: Option<PathBuf>,
    /// How to read a tracker log that is not in NDI's layout (docs/import.md).
    #[arg(long, value_name = "MAP.toml", requires = "tracker")]
    tracker_map: Option<PathBuf>,
    /// The tracker's frame rate (Hz; default: measured from the log's time columns against its
    /// frame counter, else 40).
    #[arg(long, requires = "tracker")]
    tracker_hz: Option<f64>,
    /// Print JSON: `format`, `channels` (`name`, `type`, `length`, `unit`, `increment_s`,
    /// `first`, `last`), `warnings`; for a tracker log `format`, `tools`, `frames`, `span_s`,
    /// `rate_hz`, `rate_source`, `gaps`, `warnings`.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    if let Some(path) = &args.tracker {
        return tracker(&args, path);
    }
    let Some(path) = &args.file else {
        anyhow::bail!("give a DAQ file, or --tracker FILE");
    };
    let format = match &args.daq_format {
        Some(name) => DaqFormat::from_name(name)?,
        None => DaqFormat::from_path(path),
    };
    let bytes = dlw::output::read_limited_bytes(path, MAX_RECORDING_BYTES)
        .with_context(|| format!("reading {}", path.display()))?;
    let info = daq_info(&bytes, format, args.time_column.as_deref())
        .with_context(|| format!("{}", path.display()))?;
    if args.json {
        println!("{}", dlw::finite::to_json(&info)?);
    } else {
        print!("{}", info.summary(&path.display().to_string()));
    }
    Ok(())
}

fn tracker(args: &Args, path: &std::path::Path) -> anyhow::Result<()> {
    let map = args.tracker_map.as_deref().map(read_map).transpose()?;
    let text = dlw::output::read_limited(path, MAX_RECORDING_BYTES)
        .with_context(|| format!("reading {}", path.display()))?;
    let info = tracker_info(&text, map.as_ref(), args.tracker_hz)
        .with_context(|| format!("{}", path.display()))?;
    if args.json {
        println!("{}", dlw::finite::to_json(&info)?);
    } else {
        print!("{}", info.summary(&path.display().to_string()));
    }
    Ok(())
}
