//! `dlw fluoro-render --recording REC [--fps 2] [--size 512] [--offset-deg 0] -o FRAMES`:
//! synthetic fluoroscopy frames of a recording's angle, for trying `dlw fluoro` without an
//! X-ray machine.

use std::path::PathBuf;

use anyhow::Context;
use dlw::fluoro::render::{png_bytes, PinScene, RecordedAngle};
use dlw::fluoro::StagedFolder;
use dlw::sim::Recording;

/// The most frames one run writes.
const MAX_FRAMES: usize = 100_000;

use super::written::Output;

/// Arguments of `dlw fluoro-render`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Recording folder whose angle_deg column the pin follows.
    #[arg(long)]
    recording: PathBuf,
    /// Frame rate (frames per second); frame k shows the angle at the first sample's time +
    /// k/fps, interpolated.
    #[arg(long, allow_hyphen_values = true, default_value_t = 2.0)]
    fps: f64,
    /// Frame width and height (px).
    #[arg(long, default_value_t = 512)]
    size: u32,
    /// Bits per pixel: 8 or 16.
    #[arg(long, default_value_t = 16)]
    bits: u32,
    /// The pin's angle in the image at zero joint angle (°, counter-clockwise as displayed):
    /// the mounting offset `dlw fluoro`'s baseline removes.
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    offset_deg: f64,
    /// Seed of the frames' noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Noise-free, unblurred frames without the distracting blob.
    #[arg(long)]
    clean: bool,
    #[command(flatten)]
    out: Output,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    dlw::output::claim_folder(&args.out.output, [&args.recording], args.out.force)?;
    dlw::limits::within(
        "--fps",
        args.fps,
        dlw::limits::MIN_FPS,
        dlw::limits::MAX_FPS,
        "frames per second",
    )
    .map_err(anyhow::Error::msg)?;
    if !(32..=8192).contains(&args.size) {
        anyhow::bail!("--size {} is out of range (32 to 8192 px)", args.size);
    }
    if args.bits != 8 && args.bits != 16 {
        anyhow::bail!("--bits {} is out of range (8 or 16)", args.bits);
    }
    if !args.offset_deg.is_finite() {
        anyhow::bail!("--offset-deg {} is not a finite angle", args.offset_deg);
    }
    let rec = Recording::read(&args.recording)?;
    let film = RecordedAngle {
        time_s: &rec.samples.time_s,
        angle_deg: &rec.samples.angle_deg,
        fps: args.fps,
        offset_deg: args.offset_deg,
        seed: args.seed,
    };
    let (t0, t1) = film.span_s();
    let frames = film.frames();
    if frames > MAX_FRAMES {
        anyhow::bail!(
            "{frames} frames ({} s at {} fps) is more than {MAX_FRAMES}; lower --fps or shorten the recording",
            t1 - t0,
            args.fps
        );
    }
    let mut scene = PinScene::standard(args.size);
    scene.bits = args.bits;
    if args.clean {
        scene.blur_px = 0.0;
        scene.photons = 0.0;
        scene.distractor = None;
    }
    let folder = StagedFolder::create(&args.out.output, args.out.force)?;
    for k in 0..frames {
        let name = RecordedAngle::name(k);
        let bytes = png_bytes(&film.render(&scene, k)).map_err(|message| {
            dlw::fluoro::FluoroError::Encode {
                name: name.clone(),
                message,
            }
        })?;
        folder.add_bytes(&name, &bytes)?;
    }
    folder
        .finish()
        .with_context(|| format!("writing frames {}", args.out.output.display()))?;
    println!(
        "wrote {}: {frames} frames ({}×{} px, {}-bit) at {} fps from {t0} s, pin at the recording's angle + {}°",
        args.out.output.display(),
        args.size,
        args.size,
        args.bits,
        args.fps,
        args.offset_deg
    );
    Ok(())
}
