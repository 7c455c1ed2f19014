//! The import's report (`dlw import-recording --report DIR`): the lag between the clocks
//! against the tracker's time with the fitted line, the stroke and the angle overlaid before
//! and after the alignment, and the recorded angle with the rows the tracker did not measure
//! marked. Every sentence is built from the numbers it states.

use crate::recording::Recording;
use crate::report::{Chart, Legend, Page, Series, Table};

use super::ImportSummary;

/// The stretch of the recording the before/after overlay shows (s): short enough that an
/// offset of tens of milliseconds is visible, long enough to hold a ramp of the stroke.
pub const OVERLAY_WINDOW_S: f64 = 8.0;

const BLUE: (u8, u8, u8) = (31, 119, 180);
const ORANGE: (u8, u8, u8) = (255, 127, 14);
const GREY: (u8, u8, u8) = (120, 120, 120);
const RED: (u8, u8, u8) = (214, 39, 40);

/// The report page of an import: `recording` as written and the `summary` that came with it.
pub fn report_page(recording: &Recording, summary: &ImportSummary) -> Page {
    let mut page = Page::new("Bench recording import");
    page.text(overview(summary));
    page.table(alignment_table(summary));
    page.heading("The clocks");
    page.figure("lag", lag_chart(summary), lag_caption(summary));
    page.heading("Stroke and angle, before and after the alignment");
    let gain = stroke_gain(recording);
    let window = overlay_window(recording);
    page.figure(
        "before",
        overlay_chart(recording, summary, gain, window, false),
        format!(
            "The tracker's angle placed at its own time τ (as if the clocks agreed), over the stroke scaled by {gain:.2} °/mm (the least-squares gain over the measured rows), {:.1} s to {:.1} s of DAQ time.",
            window.0, window.1
        ),
    );
    page.figure(
        "after",
        overlay_chart(recording, summary, gain, window, true),
        format!(
            "The same stretch with the tracker's frames at t = {:.4} s + τ·(1 {} {:.1}·10⁻⁶). The joint lags the stroke (relaxation, backlash, the tendon's stretch), so the two need not meet exactly.",
            summary.alignment.offset_s,
            if summary.alignment.drift_ppm < 0.0 { "−" } else { "+" },
            summary.alignment.drift_ppm.abs()
        ),
    );
    page.heading("The recorded angle");
    page.figure(
        "angle",
        angle_chart(recording),
        angle_caption(recording, summary),
    );
    page
}

/// One paragraph: what was imported and how much the tracker missed.
fn overview(summary: &ImportSummary) -> String {
    format!(
        "{} samples over {:.1} s. The tracker logged {} frames, {} of them without the tool; {} rows ({:.2} %) have no tracker angle (tracker_valid = 0). Out of the bending plane: {:.2}° RMS, {:.2}° at most.",
        summary.samples,
        summary.duration_s,
        summary.tracker.frames,
        summary.tracker.missing_frames,
        summary.invalid_rows,
        100.0 * summary.invalid_rows as f64 / summary.samples.max(1) as f64,
        summary.tracker.out_of_plane_rms_deg,
        summary.tracker.out_of_plane_max_deg
    )
}

/// The alignment's figures as a table.
fn alignment_table(summary: &ImportSummary) -> Table {
    let a = &summary.alignment;
    let mut t = Table::new(["figure", "value", "standard error"]);
    t.row([
        "offset (ms)".to_owned(),
        format!("{:.2}", a.offset_s * 1e3),
        format!("{:.2}", a.offset_uncertainty_s * 1e3),
    ]);
    t.row([
        "drift (ppm)".to_owned(),
        format!("{:.1}", a.drift_ppm),
        format!("{:.1}", a.drift_uncertainty_ppm),
    ]);
    t.row(["method".to_owned(), a.method.to_owned(), String::new()]);
    t
}

/// The measured lags (ms) against the tracker's time, and the line `offset + drift·τ`.
fn lag_chart(summary: &ImportSummary) -> Chart {
    let a = &summary.alignment;
    let line = |tau: f64| (a.offset_s + a.drift_ppm * 1e-6 * tau) * 1e3;
    let measured: Vec<(f64, f64)> = a.lags.iter().map(|&(t, l)| (t, l * 1e3)).collect();
    let end = summary.trace.tau_s.last().copied().unwrap_or(0.0);
    let mut chart = Chart::new(
        "Lag between the clocks",
        "tracker time τ (s)",
        "lag t_daq − τ (ms)",
    )
    .with(Series::dots(
        if a.method == "pulse" {
            "sync edge pairs"
        } else {
            "windows (cross-correlation)"
        },
        measured,
        BLUE,
    ))
    .with(Series::reference(
        "fitted line",
        vec![(0.0, line(0.0)), (end, line(end))],
        ORANGE,
    ));
    chart.legend = Legend::LowerRight;
    chart
}

/// The lag chart's caption, from the alignment's numbers.
fn lag_caption(summary: &ImportSummary) -> String {
    let a = &summary.alignment;
    let residual_ms = rms(a
        .lags
        .iter()
        .map(|&(t, l)| (l - a.offset_s - a.drift_ppm * 1e-6 * t) * 1e3));
    format!(
        "{} measured lags; the line t_daq − τ = {:.2} ms + {:.1} ppm·τ leaves {:.2} ms RMS. {}",
        a.lags.len(),
        a.offset_s * 1e3,
        a.drift_ppm,
        residual_ms,
        if a.method == "pulse" {
            "Each point is a sync pulse's rising edge seen in both files."
        } else {
            "Each point is a window's best lag of sensor 1's voltage against the angle; the line drawn is the final fit on every frame at once."
        }
    )
}

/// The root mean square of `values` (0 for none).
fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let (ss, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1));
    if n == 0 {
        0.0
    } else {
        (ss / n as f64).sqrt()
    }
}

/// The least-squares gain (°/mm) from the stroke's departure from its first value to the
/// angle, over the measured rows: it puts the stroke on the angle's axis. 1 when the stroke
/// never moves.
fn stroke_gain(recording: &Recording) -> f64 {
    let s = &recording.samples;
    let base = s.stroke_mm.first().copied().unwrap_or(0.0);
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for i in s.valid_angle_rows() {
        let x = s.stroke_mm[i] - base;
        sxy += x * s.angle_deg[i];
        sxx += x * x;
    }
    let gain = sxy / sxx;
    if gain.is_finite() && gain != 0.0 {
        gain
    } else {
        1.0
    }
}

/// The overlay's stretch of DAQ time (s): [`OVERLAY_WINDOW_S`] from the middle of the
/// recording, or all of a shorter one.
fn overlay_window(recording: &Recording) -> (f64, f64) {
    let end = recording.samples.time_s.last().copied().unwrap_or(0.0);
    if end <= OVERLAY_WINDOW_S {
        return (0.0, end);
    }
    let start = (end / 2.0 - OVERLAY_WINDOW_S / 2.0).max(0.0);
    (start, start + OVERLAY_WINDOW_S)
}

/// The scaled stroke and the tracker's frames over `window` of DAQ time, the frames at their
/// own time `τ` (`aligned` false) or mapped onto the DAQ's clock.
fn overlay_chart(
    recording: &Recording,
    summary: &ImportSummary,
    gain: f64,
    window: (f64, f64),
    aligned: bool,
) -> Chart {
    let s = &recording.samples;
    let base = s.stroke_mm.first().copied().unwrap_or(0.0);
    let inside = |t: f64| t >= window.0 && t <= window.1;
    let stroke: Vec<(f64, f64)> = s
        .time_s
        .iter()
        .zip(&s.stroke_mm)
        .filter(|(t, _)| inside(**t))
        .map(|(t, x)| (*t, gain * (x - base)))
        .collect();
    let a = &summary.alignment;
    let place = |tau: f64| {
        if aligned {
            a.offset_s + tau * (1.0 + a.drift_ppm * 1e-6)
        } else {
            tau
        }
    };
    let frames: Vec<(f64, f64)> = summary
        .trace
        .tau_s
        .iter()
        .zip(&summary.trace.angle_deg)
        .filter_map(|(tau, angle)| Some((place(*tau), (*angle)?)))
        .filter(|(t, _)| inside(*t))
        .collect();
    let title = if aligned {
        "After the alignment"
    } else {
        "Before the alignment"
    };
    Chart::new(title, "DAQ time (s)", "angle (°)")
        .with(Series::line(
            format!("stroke × {gain:.2} °/mm"),
            stroke,
            GREY,
        ))
        .with(Series::dots("tracker angle (frames)", frames, BLUE))
}

/// The recorded angle on the measured rows, and a mark below it on each row without one.
fn angle_chart(recording: &Recording) -> Chart {
    let s = &recording.samples;
    let rows = s.valid_angle_rows();
    let measured: Vec<(f64, f64)> = rows
        .iter()
        .map(|&i| (s.time_s[i], s.angle_deg[i]))
        .collect();
    let (lo, hi) = measured
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
    let mark = if lo.is_finite() {
        lo - 0.05 * (hi - lo).max(1.0)
    } else {
        0.0
    };
    let missing: Vec<(f64, f64)> = (0..s.time_s.len())
        .filter(|&i| !s.angle_valid(i))
        .map(|i| (s.time_s[i], mark))
        .collect();
    let mut chart = Chart::new("The recorded angle", "DAQ time (s)", "angle (°)").with(
        Series::line("tracker angle (measured rows)", measured, BLUE),
    );
    if !missing.is_empty() {
        chart.push(Series::dots(
            "no tracker angle (tracker_valid = 0)",
            missing,
            RED,
        ));
    }
    chart.legend = Legend::UpperLeft;
    chart
}

/// The angle chart's caption: the missing stretches counted and the longest named.
fn angle_caption(recording: &Recording, summary: &ImportSummary) -> String {
    let s = &recording.samples;
    let mut stretches = 0;
    let mut longest = (0.0_f64, 0.0_f64);
    let mut start: Option<usize> = None;
    for i in 0..=s.time_s.len() {
        let missing = i < s.time_s.len() && !s.angle_valid(i);
        match (start, missing) {
            (None, true) => start = Some(i),
            (Some(a), false) => {
                stretches += 1;
                let (t0, t1) = (s.time_s[a], s.time_s[i - 1]);
                if t1 - t0 >= longest.1 - longest.0 {
                    longest = (t0, t1);
                }
                start = None;
            }
            _ => {}
        }
    }
    if stretches == 0 {
        return "The tracker measured every row.".to_owned();
    }
    format!(
        "The angle on the {} rows the tracker measured (a line joins them across the gaps); the {} rows without a tracker angle, in {} stretches, are marked in red below it. The longest stretch runs from {:.3} s to {:.3} s. {} tracker frames were missing.",
        s.time_s.len() - summary.invalid_rows,
        summary.invalid_rows,
        stretches,
        longest.0,
        longest.1,
        summary.tracker.missing_frames
    )
}
