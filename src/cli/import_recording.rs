//! `dlw import-recording --daq FILE --voltage CH[,CH2] --divider-ohm R[,R2] --supply-v V
//! --stroke CH --stroke-mm-per-v K --tracker FILE [--tool N] [--reference-tool M]
//! [--tracker-hz 40] -o REC [--force] [--json] [--report DIR]`: a DAQ's CSV export, TDMS or LVM file and an
//! NDI Aurora log become one recording folder (`docs/import.md`). With `--design ROBOT.toml`
//! and one `--joint-tool K=TOOL` per joint (`--voltage` per sensor, `--stroke` per joint), a
//! robot recording (`docs/robots.md`).

use std::path::PathBuf;

use anyhow::Context;
use dlw::import::files::ImportFiles;
use dlw::import::report::report_page;
use dlw::import::robot::{import_robot, tool_by_name, RobotImportRequest, TIP_TOOL_REFUSAL};
use dlw::import::{import, DaqFormat, ImportRequest, SyncMethod};
use dlw::recording::Recording;

use super::written::Written;

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
    /// The stroke channel (V) by header name; a robot's: one per joint, joint 1 first
    /// (repeat the option or separate by commas).
    #[arg(long, value_delimiter = ',', required = true)]
    stroke: Vec<String>,
    /// The stroke sensor's scale (mm per V); a robot's: one for every joint, or one per joint.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    stroke_mm_per_v: Vec<f64>,
    /// A robot file: import a robot recording, one tracker tool per joint (--joint-tool).
    #[arg(long, value_name = "ROBOT.toml")]
    design: Option<PathBuf>,
    /// With --design ROBOT: joint K's tool (K 1-based, joint 1 distal, as `dlw inspect
    /// ROBOT --json` numbers them; TOOL the tool's number in the log's order, as --tool, or in
    /// NDI's layout its port handle, e.g. Port:3), one per joint.
    #[arg(long, value_name = "K=TOOL")]
    joint_tool: Vec<String>,
    /// With --design ROBOT: a tip tool alone. Refused: its positions cannot be put in the
    /// robot's base frame from the log alone (docs/robots.md).
    #[arg(long, value_name = "TOOL")]
    tip_tool: Option<String>,
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
    /// The tip tool: the n-th tool block of the log (1-based; default 1).
    #[arg(long)]
    tool: Option<usize>,
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
    #[command(flatten)]
    out: Written,
    /// Write an HTML report with SVG plots into this folder: the lag between the clocks, the
    /// stroke and the angle before and after the alignment, the angle with its gaps marked.
    #[arg(long)]
    report: Option<PathBuf>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    if let Some(robot) = &args.design {
        return run_robot(&args, robot);
    }
    if !args.joint_tool.is_empty() || args.tip_tool.is_some() {
        anyhow::bail!("--joint-tool and --tip-tool are a robot's: they need --design ROBOT.toml");
    }
    if args.stroke.len() != 1 || args.stroke_mm_per_v.len() != 1 {
        anyhow::bail!(
            "--stroke names {} channels and --stroke-mm-per-v {} scales; a joint has one of each (several are a robot's, with --design ROBOT.toml)",
            args.stroke.len(),
            args.stroke_mm_per_v.len()
        );
    }
    claim(&args)?;
    let (daq_format, sync) = (daq_format(&args)?, sync_method(&args)?);
    let files = read_files(&args)?;
    let request = request(&files, &args, daq_format, sync);
    let (recording, mut summary) = import(&request)?;
    dlw::finite::check(&summary)?;
    let report = args
        .report
        .as_ref()
        .map(|_| report_page(&recording, &summary).files())
        .transpose()
        .context("drawing the report")?;
    write(&args, &recording, report)?;
    summary.recording = Some(args.out.output.display().to_string());
    for w in &summary.warnings {
        eprintln!("warning: {w}");
    }
    if args.out.json {
        println!("{}", dlw::finite::to_json(&summary.to_json()?)?);
    } else {
        print!("{}", summary.summary());
    }
    Ok(())
}

/// Claims the recording folder and the report's (docs/outputs.md).
fn claim(args: &Args) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = std::iter::once(&args.out.output)
        .chain(&args.report)
        .map(|p| p.as_path())
        .collect();
    let designs: Vec<PathBuf> = args
        .design
        .iter()
        .flat_map(|d| dlw::robot::design_inputs(d))
        .collect();
    let inputs: Vec<&PathBuf> = [&args.daq, &args.tracker]
        .into_iter()
        .chain(&args.tracker_map)
        .chain(&designs)
        .collect();
    for folder in &outputs {
        dlw::output::claim_folder(folder, &inputs, args.out.force)?;
    }
    dlw::output::claim_all(&outputs, &inputs, args.out.force)?;
    Ok(())
}

/// `--daq`, `--tracker` and `--tracker-map`, read.
fn read_files(args: &Args) -> anyhow::Result<ImportFiles> {
    Ok(ImportFiles::read(
        &args.daq,
        &args.tracker,
        args.tracker_map.as_deref(),
    )?)
}

/// `--daq-format`, else the DAQ file's extension.
fn daq_format(args: &Args) -> anyhow::Result<DaqFormat> {
    Ok(match &args.daq_format {
        Some(name) => DaqFormat::from_name(name)?,
        None => DaqFormat::from_path(&args.daq),
    })
}

/// `--sync` with `--tracker-sync-column`.
fn sync_method(args: &Args) -> anyhow::Result<SyncMethod> {
    Ok(match (args.sync.as_str(), &args.tracker_sync_column) {
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
    })
}

/// The import's request: the files read and the command line's settings.
fn request<'a>(
    files: &'a ImportFiles,
    args: &Args,
    daq_format: DaqFormat,
    sync: SyncMethod,
) -> ImportRequest<'a> {
    ImportRequest {
        daq: (&files.daq_name, &files.daq_bytes),
        daq_format,
        voltage_channels: args.voltage.clone(),
        divider_ohm: args.divider_ohm.clone(),
        supply_v: args.supply_v,
        stroke: (args.stroke[0].clone(), args.stroke_mm_per_v[0]),
        time_column: args.time_column.clone(),
        daq_rate_hz: args.daq_rate_hz,
        tracker: (&files.tracker_name, &files.tracker_text),
        tracker_map: files.map.as_ref(),
        tool: args.tool.unwrap_or(1),
        reference_tool: args.reference_tool,
        tracker_hz: args.tracker_hz,
        rest_s: args.rest_s,
        sync,
        max_offset_s: args.max_offset_s,
        rate_hz: args.rate_hz,
    }
}
/// Writes the recording and the report's files. Everything is computed: both folders are
/// staged (the recording read back through the recording's reader) before either is put in
/// place, so a failure leaves neither.
fn write(
    args: &Args,
    recording: &Recording,
    report: Option<Vec<(String, Vec<u8>)>>,
) -> anyhow::Result<()> {
    let staged = recording
        .stage_checked(&args.out.output, args.out.force)
        .with_context(|| format!("writing recording {}", args.out.output.display()))?;
    let staged_report = match (&args.report, report) {
        (Some(dir), Some(files)) => Some(dlw::output::stage_folder(dir, &files)?),
        _ => None,
    };
    staged
        .commit()
        .with_context(|| format!("writing recording {}", args.out.output.display()))?;
    if let Some(report) = staged_report {
        report.commit().with_context(|| {
            format!(
                "the recording {} is written, but not the report",
                args.out.output.display()
            )
        })?;
    }
    Ok(())
}

/// `--design ROBOT`: the robot's import, written as a robot recording.
fn run_robot(args: &Args, robot_path: &std::path::Path) -> anyhow::Result<()> {
    if args.tip_tool.is_some() {
        anyhow::bail!("{TIP_TOOL_REFUSAL}");
    }
    if args.report.is_some() {
        anyhow::bail!("--report draws a joint's import; a robot's import has none yet");
    }
    if let Some(tool) = args.tool {
        anyhow::bail!("--tool {tool} is a joint's tip tool; a robot's tools are --joint-tool K=TOOL, one per joint");
    }
    let robot = dlw::robot::Robot::load(robot_path)
        .with_context(|| format!("reading robot {}", robot_path.display()))?;
    let joints = robot.joints.len();
    let joint_tools = joint_tools(&args.joint_tool, joints)?;
    let scales = match args.stroke_mm_per_v.len() {
        1 => vec![args.stroke_mm_per_v[0]; joints],
        n if n == joints => args.stroke_mm_per_v.clone(),
        n => anyhow::bail!(
            "--stroke-mm-per-v gives {n} scales; the robot has {joints} joints (one for all, or one per joint)"
        ),
    };
    claim(args)?;
    let (daq_format, sync) = (daq_format(args)?, sync_method(args)?);
    let files = read_files(args)?;
    let joint_tools = joint_tools
        .iter()
        .map(|name| tool_by_name(&files.tracker_text, files.map.as_ref(), name))
        .collect::<Result<Vec<usize>, _>>()
        .with_context(|| args.tracker.display().to_string())?;
    let mut base = request(&files, args, daq_format, sync);
    base.tool = joint_tools[0];
    let request = RobotImportRequest {
        base,
        strokes: args.stroke.iter().cloned().zip(scales).collect(),
        joint_tools,
        sensors: robot.sensors().len(),
    };
    let (recording, mut summary) = import_robot(&request)?;
    dlw::finite::check(&summary)?;
    recording
        .write(&args.out.output, args.out.force)
        .with_context(|| format!("writing recording {}", args.out.output.display()))?;
    summary.import.recording = Some(args.out.output.display().to_string());
    for w in &summary.import.warnings {
        eprintln!("warning: {w}");
    }
    if args.out.json {
        println!(
            "{}",
            dlw::finite::to_json(&serde_json::to_value(&summary)?)?
        );
    } else {
        print!("{}", summary.summary());
    }
    Ok(())
}

/// `--joint-tool K=TOOL` for a robot of `joints` joints: each joint's tool as named, joint 1
/// first.
fn joint_tools(given: &[String], joints: usize) -> anyhow::Result<Vec<String>> {
    let mut tools: Vec<Option<String>> = vec![None; joints];
    for g in given {
        let parsed = g
            .split_once('=')
            .and_then(|(k, t)| Some((k.trim().parse::<usize>().ok()?, t.trim().to_owned())));
        let Some((k, tool)) = parsed.filter(|(_, t)| !t.is_empty() && t != "0") else {
            anyhow::bail!("--joint-tool {g:?} is not K=TOOL (a joint number from 1 and a tool: its number from 1, or its port handle; e.g. 1=2 or 1=Port:2)");
        };
        if !(1..=joints).contains(&k) {
            anyhow::bail!(
                "--joint-tool {g:?}: joint {k} is out of range; the robot has joints 1 to {joints}"
            );
        }
        if let Some(before) = tools[k - 1].replace(tool) {
            anyhow::bail!(
                "--joint-tool {g:?}: joint {k} already has tool {before}; one tool per joint"
            );
        }
    }
    tools
        .iter()
        .enumerate()
        .map(|(k, t)| {
            t.clone().ok_or_else(|| {
                anyhow::anyhow!(
                    "joint {} has no --joint-tool; the robot has {joints} joints and each needs its own tool (K=TOOL)",
                    k + 1
                )
            })
        })
        .collect()
}
