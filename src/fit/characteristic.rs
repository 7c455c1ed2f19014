//! The characteristic points of a resistance–strain loop (Section IV-A1, Table III): the
//! centre `(ε_c, R_c)` with its slope `m_c`, and the peak `(ε_peak, R_peak)`.

use serde::Serialize;

use super::{min_max, FitError};
use crate::signal::Cycle;
use crate::stats::slope;

/// The points the PI procedure starts from. JSON keys are part of `dlw fit --json`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Characteristic {
    /// Strain at the centre `ε_c` (fraction).
    pub center_strain: f64,
    /// Resistance at the centre `R_c` (Ω).
    pub center_ohm: f64,
    /// Steepest slope of the first loading phase `m_c` (Ω per unit strain).
    pub center_slope_ohm: f64,
    /// Largest resistance `R_peak` (Ω).
    pub peak_ohm: f64,
    /// Largest strain `ε_peak` (fraction).
    pub peak_strain: f64,
}

/// The paper's procedure:
///
/// - `R_c` is the resistance where the slope `dR/dε` is greatest during the loading phase of
///   the first cycle, `m_c` that slope. The slope is a least-squares line over a window of a
///   tenth of the phase (at least 5 samples), so one noisy pair of samples cannot set it, and
///   only over windows where the strain moves by at least [`MIN_WINDOW_SPAN`] of the phase's
///   span (not in a rest the phase begins with).
/// - `ε_c` is the mean of the strain there and the strain where the last cycle's unloading
///   phase passes `R_c`.
/// - `R_peak` and `ε_peak` are the largest resistance and strain of the recording.
///
/// # Errors
/// [`FitError::TooFewCycles`] without a cycle; [`FitError::NotIncreasing`] when no window of
/// the first loading phase rises.
pub fn characteristic(
    strain: &[f64],
    ohm: &[f64],
    cycles: &[Cycle],
) -> Result<Characteristic, FitError> {
    let (Some(first), Some(last)) = (cycles.first(), cycles.last()) else {
        return Err(FitError::TooFewCycles {
            found: 0,
            min: 1,
            model: "pi",
        });
    };
    let load = first.loading.start..=first.loading.end;
    let len = load.end() - load.start() + 1;
    let w = (len / 10).max(5).min(len);
    let mut best: Option<(f64, f64, f64)> = None; // (slope, R, ε)
    let (lo, hi) = min_max(&strain[load.clone()]);
    let min_span = MIN_WINDOW_SPAN * (hi - lo);
    let mut start = *load.start();
    while start + w <= load.end() + 1 {
        let (x, y) = (&strain[start..start + w], &ohm[start..start + w]);
        // A window where the strain barely moves (the rest a recording starts with, which the
        // first loading phase takes in) has a slope of noise over noise: skip it.
        let (a, b) = min_max(x);
        if b - a < min_span {
            start += 1;
            continue;
        }
        if let Some(slope) = slope(x, y) {
            if best.map_or(true, |b| slope > b.0) {
                let n = w as f64;
                best = Some((slope, y.iter().sum::<f64>() / n, x.iter().sum::<f64>() / n));
            }
        }
        start += 1;
    }
    let (m_c, r_c, e_load) = match best {
        Some(b) if b.0 > 0.0 => b,
        _ => {
            return Err(FitError::NotIncreasing {
                slope_ohm_per_strain: best.map_or(0.0, |b| b.0),
                r2: 0.0,
                min_r2: 0.0,
            })
        }
    };
    let unload = last.unloading.start..=last.unloading.end;
    let e_unload = unload
        .min_by(|&a, &b| (ohm[a] - r_c).abs().total_cmp(&(ohm[b] - r_c).abs()))
        .map_or(e_load, |i| strain[i]);
    let peak_ohm = ohm.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let peak_strain = strain.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Ok(Characteristic {
        center_strain: 0.5 * (e_load + e_unload),
        center_ohm: r_c,
        center_slope_ohm: m_c,
        peak_ohm,
        peak_strain,
    })
}

/// A window for `m_c` must span at least this fraction of the first loading phase's strain.
pub const MIN_WINDOW_SPAN: f64 = 0.03;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::signal::{cycles, phases};
    use approx::assert_relative_eq;

    #[test]
    fn finds_the_steepest_point_of_a_tanh_loop() {
        // Two cycles 0 → 1.35 % → 0 of R = R_c + A·tanh(k(ε − ε_c)), no hysteresis: the
        // steepest point is the centre, where the slope is A·k.
        let (rc, a, k, ec) = (224e3, 26e3, 200.0, 0.00307);
        let mut strain = Vec::new();
        for _ in 0..2 {
            strain.extend((0..=400).map(|i| 0.0135 * i as f64 / 400.0));
            strain.extend((0..400).rev().map(|i| 0.0135 * i as f64 / 400.0));
        }
        let ohm: Vec<f64> = strain
            .iter()
            .map(|e| rc + a * (k * (e - ec)).tanh())
            .collect();
        let c = cycles(&phases(&strain, 0.001));
        assert_eq!(c.len(), 2);
        let ch = characteristic(&strain, &ohm, &c).unwrap();
        assert_relative_eq!(ch.center_ohm, rc, max_relative = 0.01);
        assert_relative_eq!(ch.center_strain, ec, max_relative = 0.05);
        assert_relative_eq!(ch.center_slope_ohm, a * k, max_relative = 0.02);
        assert_relative_eq!(ch.peak_strain, 0.0135, max_relative = 1e-12);
    }

    /// A recording that starts at rest: the first loading phase takes the rest in, where the
    /// strain is noise around zero and any slope is noise over noise. The centre is still the
    /// tanh's.
    #[test]
    fn a_rest_before_the_first_loading_does_not_set_the_centre() {
        let (rc, a, k, ec) = (224e3, 26e3, 200.0, 0.00307);
        let mut seed = 99u64;
        let mut noise = move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut strain: Vec<f64> = (0..300).map(|_| 2e-6 * noise()).collect();
        for _ in 0..2 {
            strain.extend((0..=400).map(|i| 0.0135 * i as f64 / 400.0));
            strain.extend((0..400).rev().map(|i| 0.0135 * i as f64 / 400.0));
        }
        let ohm: Vec<f64> = strain
            .iter()
            .map(|e| rc + a * (k * (e - ec)).tanh() + 20.0 * noise())
            .collect();
        let c = cycles(&phases(&strain, 0.001));
        let ch = characteristic(&strain, &ohm, &c).unwrap();
        assert_relative_eq!(ch.center_strain, ec, max_relative = 0.1);
        assert_relative_eq!(ch.center_slope_ohm, a * k, max_relative = 0.05);
    }
}
