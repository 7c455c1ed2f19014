//! Where a channel's model disagrees with the measurement: the residual's RMS in named
//! situations, relative to its RMS over all held-out samples.

use serde::Serialize;

use super::data::Data;

/// One situation and how much of the disagreement sits there.
#[derive(Debug, Clone, Serialize)]
pub struct Place {
    /// `reversals`, `holds`, `high strain`, `high rate`, `late` (growing with time).
    pub situation: &'static str,
    /// Share of the held-out samples in the situation.
    pub share: f64,
    /// RMS of the residual there over the RMS everywhere.
    pub ratio: f64,
}

/// Window around a reversal of the stroke (s).
const REVERSAL_S: f64 = 1.0;
/// "Holds": the stroke's rate below this fraction of its peak |rate| (dimensionless).
const STILL_RATE_FRACTION: f64 = 0.02;
/// "High strain": |felt strain| above this fraction of its peak (dimensionless).
const HIGH_STRAIN_FRACTION: f64 = 0.7;
/// "High rate": the stroke's |rate| above this fraction of its peak (dimensionless).
const HIGH_RATE_FRACTION: f64 = 0.5;
/// "Late": after this fraction of the recording's duration (dimensionless).
const LATE_FRACTION: f64 = 2.0 / 3.0;

/// The residual's RMS in each situation over its RMS on `mask`, sorted by ratio.
pub fn locate(data: &Data, residual: &[f64], mask: &[bool]) -> Vec<Place> {
    let n = data.len();
    let rate: Vec<f64> = (0..n)
        .map(|i| {
            if i == 0 {
                0.0
            } else {
                (data.stroke_mm[i] - data.stroke_mm[i - 1]) / data.dt_s
            }
        })
        .collect();
    let span_rate = rate.iter().fold(0.0_f64, |m, r| m.max(r.abs()));
    let still = |i: usize| rate[i].abs() < STILL_RATE_FRACTION * span_rate;
    // Reversals: where the sign of the stroke's motion changes (holds skipped over).
    let mut near_reversal = vec![false; n];
    let window = (REVERSAL_S / data.dt_s) as usize;
    let mut last_sign = 0.0;
    for i in 0..n {
        if still(i) {
            continue;
        }
        let sign = rate[i].signum();
        if last_sign != 0.0 && sign != last_sign {
            for flag in &mut near_reversal[i.saturating_sub(window)..(i + window).min(n)] {
                *flag = true;
            }
        }
        last_sign = sign;
    }
    let peak = data.strain.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
    let end = data.time_s.last().copied().unwrap_or(0.0);
    let start = data.time_s.first().copied().unwrap_or(0.0);
    type Pick<'a> = Box<dyn Fn(usize) -> bool + 'a>;
    let situations: [(&'static str, Pick); 5] = [
        ("reversals", Box::new(|i| near_reversal[i])),
        ("holds", Box::new(still)),
        (
            "high strain",
            Box::new(|i| data.strain[i].abs() > HIGH_STRAIN_FRACTION * peak),
        ),
        (
            "high rate",
            Box::new(|i| rate[i].abs() > HIGH_RATE_FRACTION * span_rate),
        ),
        (
            "late (last third)",
            Box::new(|i| data.time_s[i] > start + LATE_FRACTION * (end - start)),
        ),
    ];
    let rms = |pick: &dyn Fn(usize) -> bool| {
        let (mut s, mut k) = (0.0, 0usize);
        for i in 0..n {
            if mask[i] && pick(i) {
                s += residual[i] * residual[i];
                k += 1;
            }
        }
        (if k > 0 { (s / k as f64).sqrt() } else { 0.0 }, k)
    };
    let (all, total) = rms(&|_| true);
    let mut places: Vec<Place> = situations
        .iter()
        .map(|(name, pick)| {
            let (r, k) = rms(pick.as_ref());
            Place {
                situation: name,
                share: k as f64 / total.max(1) as f64,
                ratio: if all > 0.0 { r / all } else { 0.0 },
            }
        })
        .collect();
    places.sort_by(|a, b| b.ratio.total_cmp(&a.ratio));
    places
}
