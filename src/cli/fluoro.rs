//! `dlw fluoro FRAMES_DIR [--fps 2] [--crop x,y,w,h] [--threshold otsu|VALUE] [--invert]
//! [--smooth 8] [--baseline-s T] -o angles.csv [--json] [--overlay DIR]`.

use std::path::PathBuf;

use anyhow::Context;
use dlw::fluoro::{
    analyze_folder, angles_csv_bytes, BaselineRule, Crop, Series, SeriesSettings, Settings,
    StagedFolder, Summary, Threshold,
};
use dlw::output::write_atomic;

/// Arguments of `dlw fluoro`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Folder of frames (PNG or TIFF, 8- or 16-bit greyscale), read in file-name order.
    frames: PathBuf,
    /// Frame rate (frames per second); frame k is at start-s + k/fps.
    #[arg(long, allow_hyphen_values = true, default_value_t = 2.0)]
    fps: f64,
    /// Time of the first frame (s), to line the frames up with a recording.
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    start_s: f64,
    /// Region searched for the pin, x,y,w,h in pixels from the top-left corner. Crop around
    /// the pin's sweep: Otsu over a whole frame tends to split the background instead.
    #[arg(long, value_parser = parse_crop)]
    crop: Option<Crop>,
    /// `otsu`, or a fixed grey level in the frames' units (0-255 or 0-65535); pixels at or
    /// below it are the pin.
    #[arg(long, default_value = "otsu")]
    threshold: Threshold,
    /// The pin is bright on a dark background.
    #[arg(long)]
    invert: bool,
    /// Moving-average width (frames, centred); 1 for none.
    #[arg(long, default_value_t = 8)]
    smooth: usize,
    /// Baseline: the mean over the first T seconds is subtracted (0: no baseline). Without
    /// it, the mean of the frames before motion is detected (see --motion-deg).
    #[arg(long, allow_hyphen_values = true)]
    baseline_s: Option<f64>,
    /// Motion starts at the first frame whose angle departs from the first frame's by more
    /// than this (°); used without --baseline-s.
    #[arg(long, allow_hyphen_values = true, default_value_t = 2.0)]
    motion_deg: f64,
    /// Smallest plausible pin (pixels); a smaller largest component is skipped.
    #[arg(long, default_value_t = 20)]
    min_area_px: u32,
    /// Smallest plausible major/minor axis ratio; a rounder component is skipped.
    #[arg(long, allow_hyphen_values = true, default_value_t = 1.5)]
    min_axis_ratio: f64,
    /// Output CSV: time_s,angle_deg,raw_deg,area_px,axis_ratio,flags.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Write each frame with the fitted ellipse and axis drawn on it into this folder.
    #[arg(long)]
    overlay: Option<PathBuf>,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

fn parse_crop(s: &str) -> Result<Crop, String> {
    s.parse()
        .map_err(|e: dlw::fluoro::FluoroError| e.to_string())
}

/// A skipped frame in the JSON summary.
pub fn run(args: Args) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = std::iter::once(&args.output)
        .chain(&args.overlay)
        .map(|p| p.as_path())
        .collect();
    dlw::output::claim_all(&outputs, [&args.frames], args.force)?;
    let settings = Settings {
        crop: args.crop,
        threshold: args.threshold,
        invert: args.invert,
        min_area_px: args.min_area_px,
        min_axis_ratio: args.min_axis_ratio,
    };
    let baseline = match args.baseline_s {
        Some(t) if !(t.is_finite() && t >= 0.0) => {
            anyhow::bail!("--baseline-s {t} is out of range (finite and at least 0)")
        }
        Some(0.0) => BaselineRule::Off,
        Some(t) => BaselineRule::Seconds(t),
        None if !(args.motion_deg.is_finite() && args.motion_deg > 0.0) => {
            anyhow::bail!(
                "--motion-deg {} is out of range (finite and greater than 0)",
                args.motion_deg
            )
        }
        None => BaselineRule::UntilMotion {
            threshold_deg: args.motion_deg,
        },
    };
    let series_settings = SeriesSettings {
        fps: args.fps,
        start_s: args.start_s,
        smooth: args.smooth,
        baseline,
    };
    dlw::limits::within(
        "--fps",
        args.fps,
        dlw::limits::MIN_FPS,
        dlw::limits::MAX_FPS,
        "frames per second",
    )
    .map_err(anyhow::Error::msg)?;
    dlw::limits::within(
        "--start-s",
        args.start_s,
        -dlw::limits::MAX_ABS_START_S,
        dlw::limits::MAX_ABS_START_S,
        "s",
    )
    .map_err(anyhow::Error::msg)?;
    // The CSV is written last, after the overlay folder is in place: check its folder first so
    // that a typo there cannot leave overlays without angles.
    let csv_dir = match args.output.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    if !csv_dir.is_dir() {
        anyhow::bail!(
            "cannot write {}: folder {} does not exist",
            args.output.display(),
            csv_dir.display()
        );
    }
    let overlay = args
        .overlay
        .as_deref()
        .map(|dir| StagedFolder::create(dir, args.force))
        .transpose()?;
    let folder = analyze_folder(&args.frames, &settings, overlay.as_ref())
        .with_context(|| format!("analyzing frames in {}", args.frames.display()))?;
    let series = Series::from_fits(
        &folder.fits,
        &series_settings,
        settings.min_area_px,
        settings.min_axis_ratio,
    )
    .with_context(|| format!("analyzing frames in {}", args.frames.display()))?;
    if let Some(o) = overlay {
        o.finish()?;
    }
    write_atomic(&args.output, &angles_csv_bytes(&series))?;

    let summary = Summary::of(&folder, &series, args.output.clone(), args.overlay.clone());
    let b = series.baseline;
    let (lo, hi) = (summary.angle_min_deg, summary.angle_max_deg);
    if args.json {
        println!("{}", dlw::finite::to_json(&summary)?);
        return Ok(());
    }
    for s in &summary.skipped {
        eprintln!(
            "warning: frame {} (t = {:.3} s) skipped: {}",
            s.frame, s.time_s, s.flags
        );
    }
    println!("{}", args.frames.display());
    println!(
        "  frames              {} ({}×{} px, {}-bit), {} fitted, {} skipped",
        summary.frames,
        summary.width_px,
        summary.height_px,
        summary.bits,
        summary.fitted,
        summary.skipped.len()
    );
    match series_settings.baseline {
        BaselineRule::Off => println!("  baseline            none"),
        _ => println!(
            "  baseline            {:.3}° (mean of {} frame(s){})",
            b.mean_deg,
            b.frames,
            b.end_s
                .map_or_else(String::new, |t| format!(" before {t:.3} s"))
        ),
    }
    println!("  angle               {lo:.2}° to {hi:.2}°");
    println!("  angles              {}", args.output.display());
    if let Some(o) = &args.overlay {
        println!("  overlays            {}", o.display());
    }
    Ok(())
}
