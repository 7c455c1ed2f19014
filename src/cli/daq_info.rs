//! `dlw daq-info FILE [--daq-format F] [--json]` and `dlw daq-info --tracker FILE
//! [--tracker-map MAP] [--json]`: what a DAQ file or a tracker log holds, before importing it
//! (`docs/import.md`).

use std::path::PathBuf;

use anyhow::Context;
use dlw::import::info::{daq_info, tracker_info};
use dlw::import::{DaqFormat, TrackerMap};

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

/// The largest file read (bytes), as `import-recording` reads it.
const MAX_INPUT_BYTES: u64 = dlw::limits::MAX_RECORDING_BYTES;

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
    let bytes = dlw::output::read_limited_bytes(path, MAX_INPUT_BYTES)
        .with_context(|| format!("reading {}", path.display()))?;
    let info = daq_info(&bytes, format, args.time_column.as_deref())
        .with_context(|| format!("{}", path.display()))?;
    if args.json {
        println!("{}", dlw::finite::to_json(&info)?);
        return Ok(());
    }
    println!(
        "{}: {} file, {} channel(s)",
        path.display(),
        info.format,
        info.channels.len()
    );
    for c in &info.channels {
        let list = |v: &[serde_json::Value]| {
            v.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        };
        println!(
            "  {}: {}, {} values{}{}; first {}; last {}",
            c.name,
            c.kind.as_deref().unwrap_or("no data"),
            c.length,
            c.unit
                .as_ref()
                .map_or(String::new(), |u| format!(", unit {u}")),
            c.increment_s
                .map_or(String::new(), |s| format!(", every {s} s")),
            list(&c.first),
            list(&c.last)
        );
    }
    for w in &info.warnings {
        println!("warning: {w}");
    }
    Ok(())
}

fn tracker(args: &Args, path: &std::path::Path) -> anyhow::Result<()> {
    let map = args
        .tracker_map
        .as_ref()
        .map(|p| -> anyhow::Result<TrackerMap> {
            let text = dlw::output::read_limited(p, dlw::limits::MAX_TEXT_INPUT_BYTES)
                .with_context(|| format!("reading {}", p.display()))?;
            TrackerMap::from_toml(&text).with_context(|| format!("{}", p.display()))
        })
        .transpose()?;
    let text = dlw::output::read_limited(path, MAX_INPUT_BYTES)
        .with_context(|| format!("reading {}", path.display()))?;
    let info = tracker_info(&text, map.as_ref(), args.tracker_hz)
        .with_context(|| format!("{}", path.display()))?;
    if args.json {
        println!("{}", dlw::finite::to_json(&info)?);
        return Ok(());
    }
    println!(
        "{}: {} layout, {} frames over {:.3} s at {:.3} Hz ({}), {} gap(s)",
        path.display(),
        info.format,
        info.frames,
        info.span_s,
        info.rate_hz,
        match info.rate_source {
            dlw::import::tracker::RateSource::Given => "--tracker-hz",
            dlw::import::tracker::RateSource::Measured => "measured from its time columns",
            dlw::import::tracker::RateSource::Default => "the Aurora's default",
        },
        info.gaps.len()
    );
    for t in &info.tools {
        println!(
            "  tool {}: seen in {} frames, missing in {}",
            t.tool, t.seen, t.missing
        );
    }
    for g in &info.gaps {
        println!(
            "  gap before line {}: {:.3} s, {:.0} frames absent",
            g.line, g.seconds, g.frames
        );
    }
    for w in &info.warnings {
        println!("warning: {w}");
    }
    Ok(())
}
