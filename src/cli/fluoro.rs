//! `dlw fluoro FRAMES_DIR [--fps 2] [--crop x,y,w,h] [--threshold otsu|VALUE] [--invert]
//! [--smooth 8] [--baseline-s T] -o angles.csv [--json] [--overlay DIR]`.

use super::written::Written;
use std::path::PathBuf;

use dlw::fluoro::{fluoro, BaselineRule, Crop, FluoroRequest, SeriesSettings, Settings, Threshold};

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
    #[command(flatten)]
    out: Written,
    /// Write each frame with the fitted ellipse and axis drawn on it into this folder.
    #[arg(long)]
    overlay: Option<PathBuf>,
}

fn parse_crop(s: &str) -> Result<Crop, String> {
    s.parse()
        .map_err(|e: dlw::fluoro::FluoroError| e.to_string())
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let overlay: Vec<&std::path::Path> = args.overlay.iter().map(|p| p.as_path()).collect();
    args.out.claim_with(&overlay, [&args.frames])?;
    let request = FluoroRequest {
        frames: &args.frames,
        settings: Settings {
            crop: args.crop,
            threshold: args.threshold,
            invert: args.invert,
            min_area_px: args.min_area_px,
            min_axis_ratio: args.min_axis_ratio,
        },
        series: SeriesSettings {
            fps: args.fps,
            start_s: args.start_s,
            smooth: args.smooth,
            baseline: BaselineRule::from_options(args.baseline_s, args.motion_deg)?,
        },
        output: &args.out.output,
        overlay: args.overlay.as_deref(),
        force: args.out.force,
    };
    let result = fluoro(&request)?;
    if args.out.json {
        println!("{}", dlw::finite::to_json(&result)?);
        return Ok(());
    }
    for w in result.warnings() {
        eprintln!("warning: {w}");
    }
    print!("{}", result.text());
    Ok(())
}
