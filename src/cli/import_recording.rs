//! `dlw import-recording --daq FILE --voltage CH[,CH2] --divider-ohm R[,R2] --supply-v V
//! --stroke CH --stroke-mm-per-v K --tracker FILE [--tool N] [--reference-tool M]
//! [--tracker-hz 40] -o REC [--force] [--json] [--report DIR]`: a DAQ's CSV export, TDMS or LVM file and an
//! NDI Aurora log become one recording folder (`docs/import.md`).

use std::path::PathBuf;

use anyhow::Context;
use dlw::import::report::report_page;
use dlw::import::{import, DaqFormat, ImportRequest, SyncMethod, TrackerMap};

/// Arguments of `dlw import-recording`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The DAQ file: a CSV export with a header row, NI TDMS, or a LabVIEW .lvm file.
    #[arg(long)]
    daq: PathBuf,
    /// The DAQ file's format: csv, tdms or lvm (default: from a .tdms or .lvm extension, else
    /// csv).
    #[arg(long)]
    daq_format: Option<String>,
    /// The sensor voltage channel(s) by header name (TDMS: Group/Channel or Channel), sensor 1
    /// first.
    #[arg(long, value_delimiter = ',', required = true)]
    voltage: Vec<String>,
    /// The divider's fixed resistor per sensor (Ω).
    #[arg(long, value_delimiter = ',', required = true)]
    divider_ohm: Vec<f64>,
    /// The divider supply (V).
    #[arg(long)]
    supply_v: f64,
    /// The stroke channel (V) by header name.
    #[arg(long)]
    stroke: String,
    /// The stroke sensor's scale (mm per V).
    #[arg(long, allow_hyphen_values = true)]
    stroke_mm_per_v: f64,
    /// The DAQ's time column, when it is not named time_s, time, Time or t.
    #[arg(long)]
    time_column: Option<String>,
    /// The DAQ's sample rate, when the file has no time column (Hz).
    #[arg(long)]
    daq_rate_hz: Option<f64>,
    /// The tracker log (CSV): NDI's own layout (NDI Track, the Combined API sample), or any
    /// lab's logger with --tracker-map.
    #[arg(long)]
    tracker: PathBuf,
    /// How to read a tracker log that is not in NDI's layout: a TOML file naming its header
    /// line, time columns, frame counter and each tool's quaternion columns (docs/import.md).
    #[arg(long, value_name = "MAP.toml")]
    tracker_map: Option<PathBuf>,
    /// The tip tool: the n-th tool block of the log (1-based).
    #[arg(long, default_value_t = 1)]
    tool: usize,
    /// A reference tool on the base: the angle is taken relative to it.
    #[arg(long)]
    reference_tool: Option<usize>,
    /// The tracker's frame rate (Hz; default: measured from the log's time columns against its
    /// frame counter, else 40).
    #[arg(long)]
    tracker_hz: Option<f64>,
    /// The still start the rest axis is averaged over (s).
    #[arg(long, default_value_t = 2.0)]
    rest_s: f64,
    /// How the clocks are aligned: auto (cross-correlation of the angle with sensor 1), or a DAQ
    /// channel carrying a TTL sync pulse that the tracker log also holds (--tracker-sync-column).
    #[arg(long, default_value = "auto")]
    sync: String,
    /// With --sync CH: the tracker log's column holding the same TTL level per frame.
    #[arg(long)]
    tracker_sync_column: Option<String>,
    /// The largest offset between the clocks --sync auto searches (s).
    #[arg(long, default_value_t = dlw::import::align::MAX_OFFSET_S)]
    max_offset_s: f64,
    /// The recording's sample rate (Hz; default: the DAQ's): the DAQ's channels are averaged
    /// down to it, or interpolated up (at most 10 times the DAQ's rate).
    #[arg(long)]
    rate_hz: Option<f64>,
    /// Output recording folder (must not exist or be empty, unless --force).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
    /// Write an HTML report with SVG plots into this folder: the lag between the clocks, the
    /// stroke and the angle before and after the alignment, the angle with its gaps marked.
    #[arg(long)]
    report: Option<PathBuf>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = std::iter::once(&args.output)
        .chain(&args.report)
        .map(|p| p.as_path())
        .collect();
    let inputs: Vec<&PathBuf> = [&args.daq, &args.tracker]
        .into_iter()
        .chain(&args.tracker_map)
        .collect();
    for folder in &outputs {
        dlw::output::claim_folder(folder, &inputs, args.force)?;
    }
    dlw::output::claim_all(&outputs, &inputs, args.force)?;
    let daq_format = match &args.daq_format {
        Some(name) => DaqFormat::from_name(name)?,
        None => DaqFormat::from_path(&args.daq),
    };
    let sync = match (args.sync.as_str(), &args.tracker_sync_column) {
        ("auto", None) => SyncMethod::Auto,
        ("auto", Some(_)) => {
            anyhow::bail!("--tracker-sync-column is for --sync CH (a sync pulse channel); --sync auto does not use it")
        }
        (channel, Some(column)) => SyncMethod::Pulse {
            daq_channel: channel.to_owned(),
            tracker_column: column.clone(),
        },
        (channel, None) => anyhow::bail!(
            "--sync {channel:?} needs --tracker-sync-column NAME: the tracker log's column holding the same TTL pulse (NDI's own logs have none; docs/import.md)"
        ),
    };
    let map = args
        .tracker_map
        .as_ref()
        .map(|path| -> anyhow::Result<TrackerMap> {
            let text = dlw::output::read_limited(path, dlw::limits::MAX_TEXT_INPUT_BYTES)
                .with_context(|| format!("reading {}", path.display()))?;
            TrackerMap::from_toml(&text).with_context(|| format!("{}", path.display()))
        })
        .transpose()?;
    let daq_bytes = dlw::output::read_limited_bytes(&args.daq, MAX_INPUT_BYTES)
        .with_context(|| format!("reading {}", args.daq.display()))?;
    let tracker_text = dlw::output::read_limited(&args.tracker, MAX_INPUT_BYTES)
        .with_context(|| format!("reading {}", args.tracker.display()))?;
    let (daq_path, tracker_path) = (
        args.daq.display().to_string(),
        args.tracker.display().to_string(),
    );
    let request = ImportRequest {
        daq: (&daq_path, &daq_bytes),
        daq_format,
        voltage_channels: args.voltage.clone(),
        divider_ohm: args.divider_ohm.clone(),
        supply_v: args.supply_v,
        stroke: (args.stroke.clone(), args.stroke_mm_per_v),
        time_column: args.time_column.clone(),
        daq_rate_hz: args.daq_rate_hz,
        tracker: (&tracker_path, &tracker_text),
        tracker_map: map.as_ref(),
        tool: args.tool,
        reference_tool: args.reference_tool,
        tracker_hz: args.tracker_hz,
        rest_s: args.rest_s,
        sync,
        max_offset_s: args.max_offset_s,
        rate_hz: args.rate_hz,
    };
    let (recording, summary) = import(&request)?;
    dlw::finite::check(&summary)?;
    let report = args
        .report
        .as_ref()
        .map(|_| report_page(&recording, &summary).files())
        .transpose()
        .context("drawing the report")?;
    // Everything is computed: both folders are staged (the recording read back through the
    // recording's reader) before either is put in place, so a failure leaves neither.
    let staged = recording
        .stage_checked(&args.output, args.force)
        .with_context(|| format!("writing recording {}", args.output.display()))?;
    let staged_report = match (&args.report, report) {
        (Some(dir), Some(files)) => Some(dlw::output::stage_folder(dir, &files)?),
        _ => None,
    };
    staged
        .commit()
        .with_context(|| format!("writing recording {}", args.output.display()))?;
    if let Some(report) = staged_report {
        report.commit().with_context(|| {
            format!(
                "the recording {} is written, but not the report",
                args.output.display()
            )
        })?;
    }
    for w in &summary.warnings {
        eprintln!("warning: {w}");
    }
    if args.json {
        let mut json = serde_json::to_value(&summary)?;
        json["recording"] = serde_json::Value::String(args.output.display().to_string());
        println!("{}", dlw::finite::to_json(&json)?);
    } else {
        let a = &summary.alignment;
        println!(
            "wrote {}: {} samples over {:.1} s; clocks: offset {:.4} ± {:.4} s, drift {:.1} ± {:.1} ppm ({}{}); checked in {} windows (worst {:.2}° RMS, limit {:.2}°); tracker: {} frames, {} missing, {} gaps, out of plane {:.2}° RMS; {} rows without a tracker angle (tracker_valid = 0)",
            args.output.display(),
            summary.samples,
            summary.duration_s,
            a.offset_s,
            a.offset_uncertainty_s,
            a.drift_ppm,
            a.drift_uncertainty_ppm,
            match (a.correlation, a.sync_edges) {
                (Some(r), _) => format!("r = {r:.3}"),
                (None, Some(n)) => format!("{n} sync edges"),
                (None, None) => String::new(),
            },
            if a.stretches.len() > 1 {
                format!(
                    "; {} stretches of the DAQ's clock, each aligned on its own",
                    a.stretches.len()
                )
            } else {
                String::new()
            },
            summary.check.windows,
            summary.check.worst.rms_deg,
            summary.check.worst.limit_deg,
            summary.tracker.frames,
            summary.tracker.missing_frames,
            summary.tracker.gaps,
            summary.tracker.out_of_plane_rms_deg,
            summary.invalid_rows
        );
    }
    Ok(())
}

/// The largest DAQ or tracker file read (bytes): hours of a bench's logging stay far below.
const MAX_INPUT_BYTES: u64 = 4 << 30;
