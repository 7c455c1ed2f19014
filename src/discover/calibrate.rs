//! Names calibrated on the recording they are given: a parametric bootstrap of the test that
//! names them.
//!
//! A fixed threshold in nats was tuned on the tests' generators, and coloured noise inflates
//! evidence in ways the correlation-time correction only partly removes. Instead, before an
//! effect is named, the recording's own channel is simulated without it, [`COPIES`] times, and
//! the same test is run on each copy:
//!
//! - **The world without the effect**: the channel's current model, fitted to the recording, on
//!   the recording's own input (the stroke for the plant, the measured and smoothed angle for a
//!   sensor), plus noise from [`CopyNoise`]. Each channel is its own regression, so the other
//!   channels' fitted effects do not enter its likelihood; a sensor's copies keep the
//!   recording's measured angle, so they never see the plant model either.
//! - **The noise**: an AR process fitted (Levinson-Durbin, order by AIC up to the correlation
//!   window) to the residual of the fuller model, the one with the effect, over every moving
//!   sample, less a smooth baseline in time ([`without_slow_baseline`]: wander over a minute
//!   or more is a drift, not noise). The frozen noise model whitens, as on the recording; but a copy made with that
//!   same model would whiten to white noise and miss the colour (slow wander during motion)
//!   that inflates evidence on the recording. The fuller model's residual estimates the noise
//!   whether or not the effect is real (Hall & Wilson 1991, "Two guidelines for bootstrap
//!   hypothesis testing": resample the alternative's residuals).
//! - **The test on each copy**: every candidate of the channel scored as on the recording
//!   (best grid shape on the training blocks, held-out evidence over the correlation time),
//!   and the largest kept, since the name goes to the largest: the null is that of the whole
//!   search of the round, not of one effect.
//! - **The rule** ([`Calibration`]): name when the observed evidence clears the fast screen
//!   ([`SCREEN_NATS`]), exceeds every copy, and exceeds the one-sided prediction bound
//!   `mean + t(1 − α, B − 1)·sd·√(1 + 1/B)` of the copies at the stated false-name rate
//!   `α` = [`FALSE_NAME_RATE`]. With `B` = 20 copies, the copies' largest alone is the 95th
//!   percentile at best; the prediction bound carries the rate to 1 % under a normal tail, and
//!   the largest guards a heavier one. When the observation falls close to the bound (within
//!   a standard deviation of the copies), [`MORE_COPIES`] are drawn and the rule applied again.
//!   Fewer than [`COPIES`] usable copies: nothing is named ("cannot tell").
//!
//! **Rival names** ([`Rivalry`]): when another candidate also beats the null, each is the world
//! the other must be told from. From the recording's model with the rival `B` (fitted), copies
//! are drawn and the evidence of `A` added after `B` is measured on each: when the recording's
//! `A`-after-`B` exceeds that null by the rule, `B` cannot produce what was seen. `A` is named
//! only when every rival is excluded so; when a rival cannot be excluded and `A` cannot be
//! excluded from the rival's side either, the channel is `ambiguous`, with both names, the
//! evidence for each and what data would separate them ([`separating_data`]).

use nalgebra::{DMatrix, DVector};
use rand_chacha::ChaCha8Rng;
use rand_core::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;
use serde::Serialize;

use super::data::Data;
use super::model::{correlation_time_white, fit, relaxation_signs, Stage, StageModel};
use super::search::StageSearch;
use super::signed;
use super::terms::{Effect, Term};
use super::time_rival::TIME_RIVALS;
use super::unexplained::{time_splines, MIN_TIME_INTERVALS, TIME_KNOT_S};

/// Copies of the bootstrap: at least 20, as the issue asks.
pub const COPIES: usize = 20;
/// Copies in all when the first [`COPIES`] leave the decision within a standard deviation of
/// the bound.
pub const MORE_COPIES: usize = 60;
/// The stated false-name rate of one calibrated name (one-sided).
pub const FALSE_NAME_RATE: f64 = 0.01;
/// The fast first screen (nats): a candidate below it is not calibrated, and not named. The
/// fixed threshold of the uncalibrated rule ([`super::THRESHOLD_NATS`]).
pub const SCREEN_NATS: f64 = super::THRESHOLD_NATS;
/// The screen of a rival test (nats): evidence added after the rival under one nat (a
/// likelihood ratio under e, "not worth more than a bare mention" on Kass and Raftery's scale,
/// 1995) is something the rival's world produces without a simulation (its copies' evidence
/// is centred near zero); above it, only the calibrated bound decides. At zero, a name nested
/// in its rival passed on rounding: `gain_drift` after the time spline, which holds every
/// sensitivity linear in time, read 0.0004 nats against copies whose bound was 0.00007, and
/// the report said a change in time could not produce what was seen.
pub const RIVAL_SCREEN_NATS: f64 = 1.0;

/// The bootstrap of one test: the evidence observed on the recording against the evidence on
/// copies simulated without the effect. A test under the screen is not simulated: its copies
/// are empty and its statistics absent.
#[derive(Debug, Clone, Serialize)]
pub struct Calibration {
    /// The evidence on the recording (nats).
    pub observed: f64,
    /// The test on each copy (nats).
    pub null: Vec<f64>,
    /// Mean of the copies.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub null_mean: Option<f64>,
    /// Standard deviation of the copies.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub null_sd: Option<f64>,
    /// The largest copy.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub null_max: Option<f64>,
    /// The evidence the observation must exceed: the larger of the copies' largest and their
    /// one-sided prediction bound at [`Calibration::rate`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bound: Option<f64>,
    /// The stated false-name rate.
    pub rate: f64,
    /// `(1 + copies at or above the observation)/(1 + copies)`.
    pub p_value: f64,
    /// The screen the observation had to clear before it was simulated (nats).
    pub screen: f64,
    /// Whether the observation clears the screen and the bound with enough copies.
    pub passed: bool,
}

impl Calibration {
    /// The rule applied to `observed` against the copies `null` (non-finite copies dropped),
    /// after the screen `screen`.
    pub fn of(observed: f64, null: Vec<f64>, screen: f64) -> Self {
        let null: Vec<f64> = null.into_iter().filter(|v| v.is_finite()).collect();
        let b = null.len();
        let at_or_above = null.iter().filter(|v| **v >= observed).count();
        let stats = (b > 1).then(|| {
            let mean = null.iter().sum::<f64>() / b as f64;
            let sd = (null.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (b - 1) as f64).sqrt();
            let max = null.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let t = t_quantile(1.0 - FALSE_NAME_RATE, (b - 1) as f64);
            (
                mean,
                sd,
                max,
                (mean + t * sd * (1.0 + 1.0 / b as f64).sqrt()).max(max),
            )
        });
        let passed = b >= COPIES
            && observed.is_finite()
            && observed >= screen
            && stats.is_some_and(|(.., bound)| observed > bound);
        Self {
            observed,
            null_mean: stats.map(|s| s.0),
            null_sd: stats.map(|s| s.1),
            null_max: stats.map(|s| s.2),
            bound: stats.map(|s| s.3),
            rate: FALSE_NAME_RATE,
            p_value: (1 + at_or_above) as f64 / (1 + b) as f64,
            screen,
            passed,
            null,
        }
    }

    /// The bound, or infinity when the test was not simulated.
    pub fn bound_or_inf(&self) -> f64 {
        self.bound.unwrap_or(f64::INFINITY)
    }

    /// The calibration in one sentence, from its numbers.
    pub fn sentence(&self) -> String {
        let (Some(mean), Some(sd), Some(max), Some(bound)) =
            (self.null_mean, self.null_sd, self.null_max, self.bound)
        else {
            return format!(
                "evidence {:.1} nats, under the {}-nat screen: not simulated",
                self.observed, self.screen
            );
        };
        format!(
            "evidence {:.1} nats against {} copies simulated without it (mean {mean:.1}, sd \
             {sd:.1}, largest {max:.1}): bound {bound:.1} at a {} % false-name rate, {}",
            self.observed,
            self.null.len(),
            100.0 * self.rate,
            if self.passed { "beaten" } else { "not beaten" }
        )
    }

    /// Whether the observation is close enough to the bound (within a standard deviation of
    /// the copies) that more copies should decide.
    fn close(&self) -> bool {
        let (Some(bound), Some(sd)) = (self.bound, self.null_sd) else {
            return false;
        };
        self.null.len() < MORE_COPIES
            && self.observed >= self.screen
            && (self.observed - bound).abs() < sd
    }
}

/// The standard normal quantile (Acklam's rational approximation, relative error < 1.2e-9).
pub fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    let low = 0.02425;
    if p <= 0.0 {
        return f64::NEG_INFINITY;
    }
    if p >= 1.0 {
        return f64::INFINITY;
    }
    if p < low {
        let q = (-2.0 * p.ln()).sqrt();
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    } else if p <= 1.0 - low {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    } else {
        -normal_quantile(1.0 - p)
    }
}

/// Student's t quantile with `df` degrees of freedom: the Cornish-Fisher expansion of the
/// normal quantile in `1/df` to the fourth order (Abramowitz & Stegun 26.7.5); within 0.1 % of
/// the exact value from `df` = 10 at the 99th percentile.
pub fn t_quantile(p: f64, df: f64) -> f64 {
    let z = normal_quantile(p);
    let (z3, z5, z7, z9) = (z.powi(3), z.powi(5), z.powi(7), z.powi(9));
    z + (z3 + z) / (4.0 * df)
        + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * df.powi(2))
        + (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * df.powi(3))
        + (79.0 * z9 + 776.0 * z7 + 1482.0 * z5 - 1920.0 * z3 - 945.0 * z) / (92_160.0 * df.powi(4))
}

/// The noise of the copies: an AR(p) process of the fuller model's residual during motion.
#[derive(Debug, Clone, PartialEq)]
pub struct CopyNoise {
    /// `φ₁ … φ_p`.
    pub phi: Vec<f64>,
    /// Innovation standard deviation.
    pub innovation: f64,
}

impl CopyNoise {
    /// Yule-Walker (Levinson-Durbin) fit of `residual` over the samples where `mask` holds,
    /// its order chosen by Akaike's criterion up to `max_order`.
    pub fn fit(residual: &[f64], mask: &[bool], max_order: usize) -> Self {
        let idx: Vec<usize> = (0..residual.len()).filter(|&i| mask[i]).collect();
        let n = idx.len();
        if n < 2 * max_order + 8 {
            return Self {
                phi: Vec::new(),
                innovation: 0.0,
            };
        }
        let mean = idx.iter().map(|&i| residual[i]).sum::<f64>() / n as f64;
        let acov: Vec<f64> = (0..=max_order)
            .map(|k| {
                let mut s = 0.0;
                for &i in &idx {
                    if i + k < residual.len() && mask[i + k] {
                        s += (residual[i] - mean) * (residual[i + k] - mean);
                    }
                }
                s / n as f64
            })
            .collect();
        if !(acov[0].is_finite() && acov[0] > 0.0) {
            return Self {
                phi: Vec::new(),
                innovation: 0.0,
            };
        }
        let mut phi: Vec<f64> = Vec::new();
        let mut err = acov[0];
        let mut best = (n as f64 * err.ln(), Vec::new(), err);
        for k in 1..=max_order {
            let acc: f64 = (1..k).map(|j| phi[j - 1] * acov[k - j]).sum();
            let reflection = (acov[k] - acc) / err;
            if !reflection.is_finite() || reflection.abs() >= 1.0 {
                break;
            }
            let previous = phi.clone();
            for j in 1..k {
                phi[j - 1] = previous[j - 1] - reflection * previous[k - j - 1];
            }
            phi.push(reflection);
            err *= 1.0 - reflection * reflection;
            let aic = n as f64 * err.ln() + 2.0 * k as f64;
            if aic < best.0 {
                best = (aic, phi.clone(), err);
            }
        }
        Self {
            phi: best.1,
            innovation: best.2.max(0.0).sqrt(),
        }
    }

    /// `n` samples of the process, started from its stationary state (a burn-in of
    /// [`BURN_IN`] samples).
    pub fn simulate(&self, n: usize, rng: &mut ChaCha8Rng) -> Vec<f64> {
        let p = self.phi.len();
        let mut x = vec![0.0; n + BURN_IN];
        for t in 0..x.len() {
            let e: f64 = StandardNormal.sample(rng);
            let past: f64 = (0..p.min(t)).map(|k| self.phi[k] * x[t - k - 1]).sum();
            x[t] = past + self.innovation * e;
        }
        x.split_off(BURN_IN)
    }
}

/// Samples drawn and dropped before a copy's noise starts.
pub const BURN_IN: usize = 2000;

/// The slow wander of the copies (issue 31): a surrogate of the recording's own slow residual,
/// with its amplitude spectrum and random phases (Theiler et al. 1992, "Testing for
/// nonlinearity in time series: the method of surrogate data"). The AR model of [`CopyNoise`]
/// has a window of seconds ([`super::CORRELATION_WINDOW_S`]) and cannot carry wander over
/// minutes; without it the copies of a recording whose baseline wanders (the third generator's
/// random-walk drift, its near-1/f noise) never show what a wander does to the candidates (a
/// wander is fitted, by chance, by a line in time or a sensitivity changing in time: Granger &
/// Newbold's spurious regression), and a name was given for the wander (`gain_drift` for a
/// random-walk drift, `creep` for a gain cycling in time).
#[derive(Debug, Clone, PartialEq)]
pub struct Wander {
    /// The time of the first moving sample (s).
    start_s: f64,
    /// The length the spectrum was taken over (s).
    period_s: f64,
    /// The amplitude of the `k`-th harmonic of `period_s`, `k` from 1.
    amplitudes: Vec<f64>,
}

/// Spacing (s) of the grid the slow residual's spectrum is taken on.
const WANDER_GRID_S: f64 = 1.0;

impl Wander {
    /// The spectrum of `slow` (the smooth baseline in time of the fuller model's residual,
    /// [`without_slow_baseline`]'s fit) over the `moving` samples, on a grid of
    /// [`WANDER_GRID_S`], less the line joining its ends (a line in time is a drift the library
    /// names, and the surrogate wraps around), at periods down to half [`TIME_KNOT_S`] (the
    /// spline has nothing faster).
    pub fn fit(slow: &[f64], data: &Data, moving: &[bool]) -> Self {
        let rows: Vec<usize> = (0..slow.len()).filter(|&i| moving[i]).collect();
        let (Some(&first), Some(&last)) = (rows.first(), rows.last()) else {
            return Self::none();
        };
        let (lo, hi) = (data.time_s[first], data.time_s[last]);
        let n = ((hi - lo) / WANDER_GRID_S).floor() as usize;
        if n < 8 {
            return Self::none();
        }
        let at = |t: f64| -> f64 {
            let k = rows
                .partition_point(|&i| data.time_s[i] < t)
                .min(rows.len() - 1);
            slow[rows[k]]
        };
        let grid: Vec<f64> = (0..n).map(|j| at(lo + j as f64 * WANDER_GRID_S)).collect();
        let (y0, y1) = (grid[0], grid[n - 1]);
        let y: Vec<f64> = grid
            .iter()
            .enumerate()
            .map(|(j, v)| v - (y0 + (y1 - y0) * j as f64 / (n - 1) as f64))
            .collect();
        let period_s = n as f64 * WANDER_GRID_S;
        let harmonics = ((period_s / (0.5 * TIME_KNOT_S)).floor() as usize).clamp(1, n / 2);
        let amplitudes = (1..=harmonics)
            .map(|k| {
                let (mut re, mut im) = (0.0, 0.0);
                for (j, v) in y.iter().enumerate() {
                    let phase = std::f64::consts::TAU * (k * j) as f64 / n as f64;
                    re += v * phase.cos();
                    im -= v * phase.sin();
                }
                let a = 2.0 * (re * re + im * im).sqrt() / n as f64;
                if a.is_finite() {
                    a
                } else {
                    0.0
                }
            })
            .collect();
        Self {
            start_s: lo,
            period_s,
            amplitudes,
        }
    }

    /// No wander.
    fn none() -> Self {
        Self {
            start_s: 0.0,
            period_s: 1.0,
            amplitudes: Vec::new(),
        }
    }

    /// A surrogate over `data`'s samples: the harmonics with random phases.
    pub fn simulate(&self, data: &Data, rng: &mut ChaCha8Rng) -> Vec<f64> {
        // Each harmonic as a complex coefficient `a·e^(iφ)`, φ uniform on [0, 2π) (the top 53
        // bits of a draw).
        let coefficients: Vec<(f64, f64)> = self
            .amplitudes
            .iter()
            .map(|a| {
                let phase = std::f64::consts::TAU
                    * (rand_core::RngCore::next_u64(rng) >> 11) as f64
                    / (1u64 << 53) as f64;
                (a * phase.cos(), a * phase.sin())
            })
            .collect();
        data.time_s
            .iter()
            .map(|t| {
                // Σ_k c_k·z^k with z = e^(iu), by Horner's rule: one sine and cosine per sample.
                let u = std::f64::consts::TAU * (t - self.start_s) / self.period_s;
                let (zr, zi) = (u.cos(), u.sin());
                let (mut re, mut im) = (0.0, 0.0);
                for (cr, ci) in coefficients.iter().rev() {
                    let (r, i) = (re + cr, im + ci);
                    re = r * zr - i * zi;
                    im = r * zi + i * zr;
                }
                re
            })
            .collect()
    }
}

/// A target of the channel's regressions, whitened by the channel's frozen noise model: over
/// the training recording and, with a holdout, over the holdout.
#[derive(Debug, Clone)]
pub(super) struct Target {
    white: Vec<f64>,
    white_test: Option<Vec<f64>>,
}

/// A model's design over the recording(s), whitened, with the pseudo-inverse of its training
/// rows: fitting it to a target is a product.
pub(super) struct Prepared {
    cols: Vec<Vec<f64>>,
    test_cols: Option<Vec<Vec<f64>>>,
    /// `p × n_train`: coefficients of the whitened columns from the whitened training target.
    pinv: DMatrix<f64>,
    /// A design with a relaxation's spread: its scaled training rows, the scales and the
    /// labels, to refit under the spread's signs when the free fit breaks them (as
    /// [`super::model::fit`] does).
    signed: Option<SignedRows>,
}

/// What refitting a design under a relaxation's signs needs.
pub(super) struct SignedRows {
    x: DMatrix<f64>,
    scales: Vec<f64>,
    labels: Vec<&'static str>,
}

/// A model fitted to one target: its training and held-out whitened sums of squares and the
/// correlation time of its training residual.
#[derive(Debug, Clone, Copy)]
pub(super) struct Scored {
    test_ss: f64,
    tau: f64,
}

impl StageSearch<'_, '_> {
    /// The training rows.
    fn rows(&self) -> &[usize] {
        &self.search.train_rows
    }

    /// `m`'s design, whitened, with the pseudo-inverse of its training rows (as
    /// [`super::model::fit`] solves it).
    pub(super) fn prepare(&self, m: &StageModel) -> Option<Prepared> {
        let s = self.search;
        let noise = &s.noises[&self.channel];
        let design = m.design(&s.data, &s.inputs.0);
        let cols: Vec<Vec<f64>> = design.columns.iter().map(|c| noise.whiten(c)).collect();
        let test_cols = s.holdout().then(|| {
            m.design(&s.test_data, &s.inputs.1)
                .columns
                .iter()
                .map(|c| noise.whiten(c))
                .collect()
        });
        let rows = self.rows();
        let p = cols.len();
        if rows.len() <= p {
            return None;
        }
        let scales: Vec<f64> = cols
            .iter()
            .map(|c| {
                let v = (rows.iter().map(|&i| c[i] * c[i]).sum::<f64>() / rows.len() as f64).sqrt();
                if v > 0.0 && v.is_finite() {
                    v
                } else {
                    1.0
                }
            })
            .collect();
        let x = DMatrix::from_fn(rows.len(), p, |r, c| cols[c][rows[r]] / scales[c]);
        let signed = design
            .labels
            .contains(&"relaxation_term")
            .then(|| SignedRows {
                x: x.clone(),
                scales: scales.clone(),
                labels: design.labels.clone(),
            });
        let mut pinv = x.svd(true, true).pseudo_inverse(1e-10).ok()?;
        for (c, scale) in scales.iter().enumerate() {
            pinv.row_mut(c).scale_mut(1.0 / scale);
        }
        if !pinv.iter().all(|v| v.is_finite()) {
            return None;
        }
        Some(Prepared {
            cols,
            test_cols,
            pinv,
            signed,
        })
    }

    /// The whitened residual of `prepared` fitted to `target`, over the training recording, and
    /// over the holdout when there is one.
    fn residuals(&self, prepared: &Prepared, target: &Target) -> (Vec<f64>, Option<Vec<f64>>) {
        let rows = self.rows();
        let y = DVector::from_iterator(rows.len(), rows.iter().map(|&i| target.white[i]));
        let mut beta = &prepared.pinv * &y;
        if let Some(sr) = &prepared.signed {
            let held = relaxation_signs(&sr.labels, &beta)
                .and_then(|signs| signed::least_squares(&sr.x, &y, &signs));
            if let Some(b) = held {
                beta = DVector::from_iterator(
                    b.len(),
                    b.iter().zip(&sr.scales).map(|(b, scale)| b / scale),
                );
            }
        }
        let residual = |cols: &[Vec<f64>], white: &[f64]| -> Vec<f64> {
            let mut r = white.to_vec();
            for (c, b) in cols.iter().zip(beta.iter()) {
                for (ri, ci) in r.iter_mut().zip(c) {
                    *ri -= b * ci;
                }
            }
            r
        };
        let train = residual(&prepared.cols, &target.white);
        let test = match (&prepared.test_cols, &target.white_test) {
            (Some(cols), Some(white)) => Some(residual(cols, white)),
            _ => None,
        };
        (train, test)
    }

    /// The training sum of squares of `prepared` fitted to `target`.
    fn train_ss(&self, prepared: &Prepared, target: &Target) -> f64 {
        let (r, _) = self.residuals(prepared, target);
        let train = &self.search.train;
        r.iter()
            .zip(train)
            .filter(|(_, t)| **t)
            .map(|(v, _)| v * v)
            .sum()
    }

    /// `prepared` fitted to `target` and scored as a candidate is.
    fn scored(&self, prepared: &Prepared, target: &Target) -> Scored {
        let s = self.search;
        let (r, r_test) = self.residuals(prepared, target);
        let ss = |v: &[f64], mask: &[bool]| -> f64 {
            v.iter()
                .zip(mask)
                .filter(|(_, m)| **m)
                .map(|(x, _)| x * x)
                .sum()
        };
        Scored {
            test_ss: ss(r_test.as_deref().unwrap_or(&r), &s.test),
            tau: correlation_time_white(&r, &s.train, s.lags),
        }
    }

    /// The held-out samples.
    fn held_out(&self) -> usize {
        self.search.test.iter().filter(|t| **t).count()
    }

    /// For each target, the evidence of each group of shapes over `from` (the best shape of
    /// the group on the training samples, scored on the held-out ones; a spread form in the
    /// group, [`Term::spread`], scored beside it and kept when it has more, as
    /// `Search::best_shape` chooses): `[target][group]`.
    pub(super) fn evidences(
        &self,
        from: &StageModel,
        groups: &[Vec<Term>],
        targets: &[Target],
    ) -> Option<Vec<Vec<f64>>> {
        let base = self.prepare(from)?;
        let n = self.held_out();
        let from_ss: Vec<f64> = targets
            .par_iter()
            .map(|t| self.scored(&base, t).test_ss)
            .collect();
        drop(base);
        let mut out = vec![vec![f64::NAN; groups.len()]; targets.len()];
        for (g, shapes) in groups.iter().enumerate() {
            let prepared: Vec<(bool, Prepared)> = shapes
                .par_iter()
                .filter_map(|t| Some((t.is_spread(), self.prepare(&from.with(t.clone()))?)))
                .collect();
            if prepared.is_empty() {
                continue;
            }
            let column: Vec<f64> = targets
                .par_iter()
                .zip(&from_ss)
                .map(|(target, &from_ss)| {
                    let evidence = |p: &Prepared| {
                        let sc = self.scored(p, target);
                        super::evidence(n, from_ss, sc.test_ss, sc.tau)
                    };
                    let best = prepared
                        .iter()
                        .filter(|(spread, _)| !spread)
                        .map(|(_, p)| (p, self.train_ss(p, target)))
                        .min_by(|a, b| a.1.total_cmp(&b.1))
                        .map(|(p, _)| evidence(p));
                    prepared
                        .iter()
                        .filter(|(spread, _)| *spread)
                        .map(|(_, p)| evidence(p))
                        .chain(best)
                        .filter(|e| !e.is_nan())
                        .fold(f64::NAN, f64::max)
                })
                .collect();
            for (row, e) in out.iter_mut().zip(column) {
                row[g] = e;
            }
        }
        Some(out)
    }

    /// The recording's own target.
    pub(super) fn observed_target(&self) -> Target {
        let s = self.search;
        let noise = &s.noises[&self.channel];
        let target = self.model.design(&s.data, &s.inputs.0).target;
        Target {
            white: noise.whiten(&target),
            white_test: s
                .holdout()
                .then(|| noise.whiten(&self.model.design(&s.test_data, &s.inputs.1).target)),
        }
    }

    /// `count` copies (from number `first` on) of the channel simulated from `world` fitted to
    /// the recording, with noise fitted to the residual of `fuller` ([`CopyNoise`]); `seed`
    /// names the test, so that every run draws the same copies.
    pub(super) fn copies(
        &self,
        world: &StageModel,
        fuller: &StageModel,
        seed: u64,
        first: usize,
        count: usize,
    ) -> Option<Vec<Target>> {
        let s = self.search;
        let noise = &s.noises[&self.channel];
        let design = world.design(&s.data, &s.inputs.0);
        let fitted = fit(&design, noise, &s.train)?;
        let predicted = fitted.predict(&design);
        let predicted_test = s
            .holdout()
            .then(|| fitted.predict(&world.design(&s.test_data, &s.inputs.1)));
        let full_design = fuller.design(&s.data, &s.inputs.0);
        let full = fit(&full_design, noise, &s.train)?;
        let moving = s.data.moving();
        let raw = full.residual(&full_design);
        let residual = without_slow_baseline(&raw, &s.data, &moving);
        let copy_noise = CopyNoise::fit(&residual, &moving, s.lags);
        // The slow wander the fuller model leaves: taken out of the AR fit (whose window is
        // seconds), and put back into every copy as a surrogate, when the effect tested is
        // one a wander imitates (a name outside that family gains nothing from a wander, but
        // the copies' largest evidence, over every candidate, would: the wander's, by
        // `drift` or `gain_drift`, and the name would be held to it).
        let tested_wanders = fuller
            .terms
            .iter()
            .filter(|t| !world.terms.contains(t))
            .any(|t| TIME_RIVALS.contains(&t.effect()));
        let wander = if tested_wanders {
            let slow: Vec<f64> = raw.iter().zip(&residual).map(|(r, f)| r - f).collect();
            Wander::fit(&slow, &s.data, &moving)
        } else {
            Wander::none()
        };
        let seed = seed ^ channel_seed(self.channel);
        Some(
            (first..first + count)
                .into_par_iter()
                .map(|k| {
                    let mut rng = ChaCha8Rng::seed_from_u64(seed);
                    rng.set_stream(k as u64);
                    let mut draw = |mean: &[f64], data: &Data| -> Vec<f64> {
                        let e = copy_noise.simulate(mean.len(), &mut rng);
                        let w = wander.simulate(data, &mut rng);
                        noise.whiten(
                            &mean
                                .iter()
                                .zip(&e)
                                .zip(&w)
                                .map(|((m, e), w)| m + e + w)
                                .collect::<Vec<_>>(),
                        )
                    };
                    let white = draw(&predicted, &s.data);
                    let white_test = predicted_test.as_deref().map(|p| draw(p, &s.test_data));
                    Target { white, white_test }
                })
                .collect(),
        )
    }

    /// The bootstrap of "the largest evidence among `groups` over `world`": copies of `world`
    /// (noise from `fuller`'s residual), the test on each, and the rule applied to `observed`;
    /// more copies when the first leave it close.
    pub(super) fn bootstrap(
        &self,
        world: &StageModel,
        fuller: &StageModel,
        groups: &[Vec<Term>],
        observed: f64,
        screen: f64,
        seed: u64,
    ) -> Calibration {
        let mut null: Vec<f64> = Vec::new();
        let mut wanted = COPIES;
        loop {
            let have = null.len();
            let more = self
                .copies(world, fuller, seed, have, wanted - have)
                .and_then(|targets| self.evidences(world, groups, &targets));
            let Some(more) = more else { break };
            null.extend(more.iter().map(|row| {
                row.iter()
                    .copied()
                    .filter(|v| v.is_finite())
                    .fold(f64::NAN, f64::max)
            }));
            let calibration = Calibration::of(observed, null.clone(), screen);
            if wanted < MORE_COPIES && calibration.close() {
                wanted = MORE_COPIES;
                continue;
            }
            return calibration;
        }
        Calibration::of(observed, null, screen)
    }

    /// The grids of the channel's candidates not yet in its model.
    pub(super) fn candidate_groups(&self) -> Vec<(Effect, Vec<Term>)> {
        let s = self.search;
        super::search::Search::effects(self.channel)
            .iter()
            .filter(|e| !self.model.terms.iter().any(|t| t.effect() == **e))
            .map(|&e| (e, Term::shapes(e, s.span_of(self.channel))))
            .collect()
    }
}

/// `residual` less its least-squares fit by a smooth baseline in time over the `moving`
/// samples (the cubic B-splines of the `unexplained` test's time kind, knots every
/// [`TIME_KNOT_S`]): a baseline that wanders over a minute or more is a drift, structure the
/// library's `drift` or the `time` kind is there to find, not noise for the copies to carry.
/// Left in, a random-walk drift the linear or settling form misses filled the copies with
/// random walks, which named "drift" in them more strongly than on the recording.
pub fn without_slow_baseline(residual: &[f64], data: &Data, moving: &[bool]) -> Vec<f64> {
    let rows: Vec<usize> = (0..residual.len()).filter(|&i| moving[i]).collect();
    let (Some(&first), Some(&last)) = (rows.first(), rows.last()) else {
        return residual.to_vec();
    };
    let (lo, hi) = (data.time_s[first], data.time_s[last]);
    let intervals = (((hi - lo) / TIME_KNOT_S).round() as usize).max(MIN_TIME_INTERVALS);
    let basis = time_splines(&data.time_s, lo, hi, intervals);
    let p = basis.len();
    let x = DMatrix::from_fn(rows.len(), p, |r, c| basis[c][rows[r]]);
    let y = DVector::from_iterator(rows.len(), rows.iter().map(|&i| residual[i]));
    let gram = x.tr_mul(&x);
    let ridge = DMatrix::identity(p, p) * (1e-9 * gram.trace() / p as f64);
    let Some(chol) = (gram + ridge).cholesky() else {
        return residual.to_vec();
    };
    let coef = chol.solve(&x.tr_mul(&y));
    residual
        .iter()
        .enumerate()
        .map(|(i, r)| {
            r - basis
                .iter()
                .zip(coef.iter())
                .map(|(b, c)| b[i] * c)
                .sum::<f64>()
        })
        .collect()
}

/// Seeds of the channels' copies, so that no two channels draw alike.
fn channel_seed(ch: Stage) -> u64 {
    match ch {
        Stage::Plant => 0x9E37_79B9_7F4A_7C15,
        Stage::Sensor(s) => 0xC2B2_AE3D_27D4_EB4F ^ (s.index() as u64 + 1),
    }
}

/// How two names' rivalry came out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// The rival's world cannot produce what was seen; the named one's can.
    Named,
    /// The named one's world cannot produce what was seen; the rival's can.
    Rival,
    /// Each world can produce what was seen: the data cannot tell them apart.
    Neither,
}

/// One candidate `A` against a rival `B`, each simulated as the other's alternative.
#[derive(Debug, Clone, Serialize)]
pub struct Rivalry {
    /// The candidate.
    pub effect: Effect,
    /// Its rival.
    pub rival: Effect,
    /// The candidate's evidence over the current model (nats).
    pub evidence: f64,
    /// The rival's (nats).
    pub rival_evidence: f64,
    /// The candidate's evidence added after the rival, on the recording and on copies of the
    /// model with the rival (fitted): the rival's world.
    pub beyond_rival: Calibration,
    /// The rival's evidence added after the candidate, and on copies of the model with the
    /// candidate, when it was needed (the rival was not excluded).
    pub beyond_effect: Option<Calibration>,
    /// The outcome.
    pub verdict: Verdict,
}

impl Rivalry {
    /// The rivalry in one sentence, from its numbers.
    pub fn sentence(&self) -> String {
        let (a, b) = (self.effect.name(), self.rival.name());
        let first = format!(
            "{a} after {b} {:.1} nats, {b}'s world {}",
            self.beyond_rival.observed,
            reach(&self.beyond_rival)
        );
        let second = self.beyond_effect.as_ref().map_or(String::new(), |c| {
            format!(
                "; {b} after {a} {:.1} nats, {a}'s world {}",
                c.observed,
                reach(c)
            )
        });
        let verdict = match self.verdict {
            Verdict::Named => format!("{b} cannot produce what was seen"),
            Verdict::Rival => format!("{a} cannot produce what was seen, {b} can"),
            Verdict::Neither => "either can produce what was seen".to_owned(),
        };
        format!("{first}{second}: {verdict}")
    }
}

/// What a world's copies reach, in words.
fn reach(c: &Calibration) -> String {
    match (c.null_max, c.bound) {
        (Some(max), Some(bound)) => format!("reaches {max:.1} (bound {bound:.1})"),
        _ => format!("not simulated (under the {}-nat screen)", c.screen),
    }
}

/// What data would tell two rival names apart, in words.
pub fn separating_data(a: Effect, b: Effect, creep_tau_s: Option<f64>) -> String {
    use Effect::*;
    let pair = |x: Effect, y: Effect| (a == x && b == y) || (a == y && b == x);
    if pair(Creep, Drift) {
        format!(
            "holds at zero strain longer than the creep's time constant ({}): a creep relaxes \
             back toward the baseline there, a drift does not",
            creep_tau_s.map_or("its τ".to_owned(), |t| format!("τ = {t:.0} s"))
        )
    } else if pair(Rate, Creep) {
        "the same cycle at several speeds, with holds: a rate effect scales with the speed and \
         is gone within seconds of a hold, a creep grows through the hold"
            .to_owned()
    } else if pair(Hysteresis, Saturation) {
        "full loading and unloading cycles at several amplitudes: a hysteresis loop separates \
         loading from unloading, a saturation follows one curve both ways"
            .to_owned()
    } else if pair(Drift, GainDrift) {
        "a hold at zero strain late in the run: a drift moves the baseline there, a changing \
         sensitivity does not"
            .to_owned()
    } else if pair(Hysteresis, Creep) || pair(Hysteresis, Rate) {
        "holds after reversals and cycles at several speeds: a creep or a rate effect changes \
         during a hold and with speed, a hysteresis loop does not"
            .to_owned()
    } else if pair(Backlash, Relaxation) {
        "holds after reversals: a relaxation continues through a hold, a backlash does not"
            .to_owned()
    } else {
        format!(
            "a longer recording, or one whose protocol excites {} and {} differently",
            a.name(),
            b.name()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A name nested in its rival (`gain_drift` in the time spline, which holds every
    /// sensitivity linear in time) adds nothing after it but rounding: the recording's 0.0004
    /// nats against copies of about 0.00001 must not pass a rival test. It did at a screen of 0.
    #[test]
    fn rounding_never_passes_a_rival_test() {
        let null: Vec<f64> = (0..COPIES)
            .map(|i| 1e-5 * (f64::from(i as u32) - 9.5))
            .collect();
        let nested = Calibration::of(3.6e-4, null.clone(), RIVAL_SCREEN_NATS);
        assert!(!nested.passed, "{nested:?}");
        // A nat and more against the same copies does.
        assert!(Calibration::of(1.5, null, RIVAL_SCREEN_NATS).passed);
    }

    #[test]
    fn quantiles_match_the_tables() {
        // Normal: 0.99 → 2.326348; Student's t (df 19, 0.99) = 2.539483, (df 59) = 2.391229.
        assert!((normal_quantile(0.99) - 2.326_348).abs() < 1e-6);
        assert!((normal_quantile(0.01) + 2.326_348).abs() < 1e-6);
        assert!((t_quantile(0.99, 19.0) - 2.539_483).abs() < 2e-3);
        assert!((t_quantile(0.99, 59.0) - 2.391_229).abs() < 1e-4);
    }

    /// Copies from a normal null: the rule's bound sits near the prediction bound, an
    /// observation beyond it passes, one at the largest copy does not; too few copies never
    /// pass.
    #[test]
    fn the_rule_needs_every_copy_and_the_bound_beaten() {
        let null: Vec<f64> = (0..COPIES).map(|k| (k as f64 - 9.5) * 0.5).collect();
        let at_max = Calibration::of(4.75 + SCREEN_NATS, null.clone(), SCREEN_NATS);
        assert!(at_max.bound >= at_max.null_max);
        assert!(!Calibration::of(4.75, null.clone(), SCREEN_NATS).passed);
        let far = Calibration::of(100.0, null.clone(), SCREEN_NATS);
        assert!(far.passed, "{far:?}");
        assert!((far.p_value - 1.0 / 21.0).abs() < 1e-12);
        let inside = Calibration::of(2.0, null.clone(), SCREEN_NATS);
        assert!(!inside.passed);
        let few = Calibration::of(100.0, null[..COPIES - 1].to_vec(), SCREEN_NATS);
        assert!(!few.passed, "{few:?}");
        // Below the screen: never named, however far beyond the copies.
        let tiny: Vec<f64> = vec![0.0; COPIES];
        assert!(!Calibration::of(SCREEN_NATS - 1.0, tiny, SCREEN_NATS).passed);
    }

    /// A 300 s recording's time base at 25 Hz, moving after a 10 s rest.
    fn wander_data(n: usize) -> (Data, Vec<bool>) {
        let dt = 0.04;
        let data = Data {
            time_s: (0..n).map(|i| i as f64 * dt).collect(),
            stroke_mm: vec![0.0; n],
            angle_deg: vec![0.0; n],
            strain: vec![0.0; n],
            ohm: vec![],
            rest: 250,
            measured: vec![true; n],
            dt_s: dt,
        };
        let moving = data.moving();
        (data, moving)
    }

    /// The copies' wander: a line in time (a drift the library names) gives none; a slow
    /// sinusoid gives surrogates of the same amplitude at random phases.
    #[test]
    fn wander_keeps_the_slow_residuals_spectrum_and_leaves_lines_alone() {
        let (data, moving) = wander_data(7500);
        let line: Vec<f64> = data.time_s.iter().map(|t| 3.0 + 0.2 * t).collect();
        let w = Wander::fit(&line, &data, &moving);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let sim = w.simulate(&data, &mut rng);
        assert!(sim.iter().all(|v| v.abs() < 1e-6), "a line wanders: {w:?}");
        let lo = data.time_s[data.rest];
        let hi = data.time_s[data.len() - 1];
        // Two whole periods over the motion: the ends meet, so the line between them is flat.
        let cycle: Vec<f64> = data
            .time_s
            .iter()
            .map(|t| 5.0 * (std::f64::consts::TAU * 2.0 * (t - lo) / (hi - lo)).sin())
            .collect();
        let w = Wander::fit(&cycle, &data, &moving);
        let rms = |v: &[f64]| {
            let m: Vec<f64> = (data.rest..v.len()).map(|i| v[i]).collect();
            (m.iter().map(|x| x * x).sum::<f64>() / m.len() as f64).sqrt()
        };
        let a = rng_copy(&w, &data, 2);
        let b = rng_copy(&w, &data, 3);
        let want = 5.0 / 2f64.sqrt();
        for copy in [&a, &b] {
            assert!(
                (rms(copy) / want - 1.0).abs() < 0.1,
                "rms {} against {want}",
                rms(copy)
            );
        }
        assert!(
            a.iter().zip(&b).any(|(x, y)| (x - y).abs() > 1.0),
            "the phases are random"
        );
    }

    fn rng_copy(w: &Wander, data: &Data, seed: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        w.simulate(data, &mut rng)
    }

    /// An AR(1) residual is recovered by the copies' noise model, and its simulation has the
    /// same lag-one correlation and spread.
    #[test]
    fn copy_noise_reproduces_an_ar1() {
        let x = crate::discover::noise::tests::ar1(0.95, 40_000);
        let mask = vec![true; x.len()];
        let noise = CopyNoise::fit(&x, &mask, 50);
        assert!((noise.phi[0] - 0.95).abs() < 0.02, "{noise:?}");
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let y = noise.simulate(40_000, &mut rng);
        let var = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>() / v.len() as f64;
        let ratio = var(&y) / var(&x);
        assert!((0.8..1.25).contains(&ratio), "variance ratio {ratio}");
        let lag1 = y.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / y.len() as f64 / var(&y);
        assert!((lag1 - 0.95).abs() < 0.02, "lag one {lag1}");
    }
}
