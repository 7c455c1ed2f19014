//! What the library cannot explain: after the last named effect, each channel's model is
//! extended by generic, library-free regressors of four kinds (a memoryless curve of any
//! shape, memory, history, time), and the held-out evidence for the extension is measured
//! the way every candidate's is (whitened likelihood gain over held-out samples, divided by the
//! correlation time of the training residual). The kind that alone adds the most says where
//! it is.
//!
//! This is the residual analysis of MATLAB's `resid` (is what remains white, and is it
//! independent of the input?) made a likelihood test on held-out data: a correlation between
//! the residual and the input, at any lag or through any curve, shows as held-out evidence for
//! these regressors; slow noise the frozen noise model misses is discounted by the correlation
//! time, so a clean recording's residual is not flagged for being coloured.
//!
//! **Time, in any smooth form** (issue 31). The time kind is a penalized spline in time (cubic
//! B-splines with knots every [`TIME_KNOT_S`], a second-difference penalty, Eilers & Marx's
//! P-spline), once alone (a baseline that wanders) and once times the input (a sensitivity
//! that wanders): a fade, a step, a random walk or a cycle of any period down to about two
//! knot spacings. Its smoothing is chosen by cross-validation over the training blocks, each
//! left out in turn, so that the held-out blocks the evidence is measured on play no part in
//! choosing it. Until issue 31 it was a trend and two harmonics of the recording's length, and
//! a gain cycling at another period passed unseen.
//!
//! **A curve of any shape** is drawn on the input without the tracker's noise (a sensor's
//! smoothed angle, never the plant model; the plant's stroke) and penalized like the time
//! spline (second differences of its knots' values, smoothing by the same cross-validation).
//!
//! **Calibrated** like a name ([`super::calibrate`]): a channel whose evidence clears the
//! screen ([`UNEXPLAINED_NATS`]) is simulated from its final model, with noise fitted to the
//! extended model's residual, and flagged only when its evidence beats the copies' by the rule.
//! `--fast` flags on the screen alone.

use nalgebra::{Cholesky, DMatrix, DVector, Dyn};
use rand_chacha::ChaCha8Rng;
use rand_core::SeedableRng;
use rayon::prelude::*;
use serde::Serialize;

use super::calibrate::{Calibration, CopyNoise, COPIES, MORE_COPIES};
use super::data::Data;
use super::model::{correlation_time_white, Design, Stage};
use super::noise::ArNoise;
use super::terms::{hats, low_pass, play, Term};

/// Evidence (nats) the generic regressors need before a channel is tested by its calibration
/// (or, with `--fast`, flagged): the same bar as naming an effect ([`super::THRESHOLD_NATS`]).
pub const UNEXPLAINED_NATS: f64 = super::THRESHOLD_NATS;
/// Time constants of the history regressors (s): a lag of the input, fast and slow.
pub const HISTORY_TAUS_S: [f64; 2] = [3.0, 30.0];
/// Radii of the memory regressors, as fractions of the input's span.
pub const MEMORY_RADII: [f64; 2] = [0.1, 0.3];
/// Knot spacing of the time spline (s): a change in the baseline or the sensitivity over a
/// minute or more is followed; faster is the other kinds' (and the noise's).
pub const TIME_KNOT_S: f64 = 60.0;
/// The time spline has at least this many intervals over the motion (a 300 s recording: 5).
pub const MIN_TIME_INTERVALS: usize = 3;
/// Smoothing weights tried by the cross-validation, as powers of ten times the ratio of the
/// penalized columns' Gram trace to the penalty's.
pub const SMOOTHING_POWERS: [i32; 8] = [-4, -3, -2, -1, 0, 1, 2, 3];
/// Ridge added to every fit's normal equations, relative to their mean diagonal: it keeps a
/// column no sample reaches (a hat beyond the data) from making them singular.
const RIDGE: f64 = 1e-9;
/// Folds of the cross-validation when the training samples are one run (a holdout).
const FOLDS: usize = 5;
/// Most folds of the cross-validation: a long recording's many training blocks
/// ([`super::data::Data::blocks`]) are dealt into this many, each fold every tenth block.
const MAX_FOLDS: usize = 10;

/// A kind of generic regressor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GenericKind {
    /// A memoryless curve of the input of any shape (piecewise linear).
    Curve,
    /// Plays of the input: loops, a difference between loading and unloading.
    Memory,
    /// Lags of the input: what happens during holds and after changes.
    History,
    /// A penalized spline in time, alone and times the input: a baseline or a sensitivity that
    /// changes over the run in any smooth way ([`TIME_KNOT_S`]).
    Time,
    /// The same spline times the input only: a sensitivity that changes over the run in any
    /// smooth way, and no baseline. Not one of the `unexplained` test's kinds ([`Self::ALL`]):
    /// the rival an ambiguity among names a change in time imitates is told from
    /// ([`super::decide`]).
    Sensitivity,
    /// The same spline alone: a baseline that changes over the run in any smooth way. Not one
    /// of the `unexplained` test's kinds either: a wandering baseline's test against a
    /// wandering sensitivity ([`super::wander`]).
    Baseline,
}

impl GenericKind {
    /// Every kind.
    pub const ALL: [GenericKind; 4] = [
        GenericKind::Curve,
        GenericKind::Memory,
        GenericKind::History,
        GenericKind::Time,
    ];

    /// Where the structure shows, for people.
    pub fn place(self) -> &'static str {
        match self {
            GenericKind::Curve => {
                "along the input's range: a curve no named effect draws (high strain or stroke)"
            }
            GenericKind::Memory => "at reversals: loading and unloading differ",
            GenericKind::History => "during holds and after changes: the channel lags its input",
            GenericKind::Time => "over the run: the baseline or the sensitivity changes with time",
            GenericKind::Sensitivity => "over the run: the sensitivity changes with time",
            GenericKind::Baseline => "over the run: the baseline changes with time",
        }
    }
}

/// A channel with structure the library does not explain.
#[derive(Debug, Clone, Serialize)]
pub struct Unexplained {
    /// The channel.
    #[serde(serialize_with = "channel_name")]
    pub channel: Stage,
    /// Held-out evidence of the generic regressors over the final model (nats).
    pub evidence: f64,
    /// The kind that alone adds the most evidence.
    pub kind: GenericKind,
    /// Where it is, in words.
    #[serde(rename = "where")]
    pub place: &'static str,
    /// The evidence each kind alone adds to the final model (nats), in [`GenericKind::ALL`]'s order.
    pub by_kind: Vec<(GenericKind, f64)>,
    /// The bootstrap the flag was given by (absent with `--fast`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub calibration: Option<Calibration>,
}

fn channel_name<S: serde::Serializer>(c: &Stage, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&c.name())
}

/// Cubic B-splines over `t` with `intervals` equal intervals on `[lo, hi]` (`t` clamped to it):
/// `intervals + 3` columns.
pub fn time_splines(t: &[f64], lo: f64, hi: f64, intervals: usize) -> Vec<Vec<f64>> {
    let width = ((hi - lo) / intervals as f64).max(f64::MIN_POSITIVE);
    let mut cols = vec![vec![0.0; t.len()]; intervals + 3];
    for (i, &ti) in t.iter().enumerate() {
        let u = ((ti.clamp(lo, hi) - lo) / width).min(intervals as f64 - 1e-12);
        let k = u.floor() as usize;
        let f = u - k as f64;
        // The four cubic B-splines non-zero on interval k, at fraction f.
        let b = [
            (1.0 - f).powi(3) / 6.0,
            (3.0 * f.powi(3) - 6.0 * f * f + 4.0) / 6.0,
            (-3.0 * f.powi(3) + 3.0 * f * f + 3.0 * f + 1.0) / 6.0,
            f.powi(3) / 6.0,
        ];
        for (j, v) in b.iter().enumerate() {
            cols[k + j][i] = *v;
        }
    }
    cols
}

/// The time kind's B-splines over `data`: knots every [`TIME_KNOT_S`] over the motion, at
/// least [`MIN_TIME_INTERVALS`] intervals.
fn time_splines_of(data: &Data) -> Vec<Vec<f64>> {
    let (lo, hi, intervals) = time_intervals(data, TIME_KNOT_S);
    time_splines(&data.time_s, lo, hi, intervals)
}

/// The motion's first and last time and how many intervals of about `knot_s` cover it (at
/// least [`MIN_TIME_INTERVALS`]).
fn time_intervals(data: &Data, knot_s: f64) -> (f64, f64, usize) {
    let moving = &data.time_s[data.rest.min(data.len())..];
    let lo = moving.first().copied().unwrap_or(0.0);
    let hi = moving.last().copied().unwrap_or(lo);
    let intervals = (((hi - lo) / knot_s).round() as usize).max(MIN_TIME_INTERVALS);
    (lo, hi, intervals)
}

/// The knots' spacing of the time kind over `data` (s): [`TIME_KNOT_S`] rounded so that a
/// whole number of intervals covers the motion.
pub fn time_knot_s(data: &Data) -> f64 {
    let (lo, hi, intervals) = time_intervals(data, TIME_KNOT_S);
    (hi - lo) / intervals as f64
}

/// The columns of a wandering baseline ([`Term::Wander`]): the B-splines of knots every
/// `knot_s` over the motion, the first left out (they add up to one, and the offset holds it).
pub fn wander_splines(data: &Data, knot_s: f64) -> Vec<Vec<f64>> {
    let (lo, hi, intervals) = time_intervals(data, knot_s);
    time_splines(&data.time_s, lo, hi, intervals)
        .into_iter()
        .skip(1)
        .collect()
}

/// Each spline times the input `x`: a sensitivity that changes in time.
fn time_gain(splines: &[Vec<f64>], x: &[f64]) -> Vec<Vec<f64>> {
    splines
        .iter()
        .map(|b| x.iter().zip(b).map(|(x, b)| x * b).collect())
        .collect()
}

/// The second-difference penalty `DᵀD` of `m` spline coefficients.
fn second_difference(m: usize) -> DMatrix<f64> {
    let mut p = DMatrix::zeros(m, m);
    for r in 0..m.saturating_sub(2) {
        let d = [(r, 1.0), (r + 1, -2.0), (r + 2, 1.0)];
        for &(i, a) in &d {
            for &(j, b) in &d {
                p[(i, j)] += a * b;
            }
        }
    }
    p
}

/// The columns of one kind (or of the final model), over the training recording and the
/// evaluation one, and the penalty of those that are penalized (a block per spline).
struct Group {
    cols: Vec<Vec<f64>>,
    test_cols: Option<Vec<Vec<f64>>>,
    /// `(first column, DᵀD)` of each penalized block.
    penalties: Vec<(usize, DMatrix<f64>)>,
}

/// The data a test needs: the final model's designs over the training and the evaluation
/// recordings, which samples are which, the frozen noise, and the lags of the correlation time.
pub struct Residuals<'a> {
    /// The final model over the training recording.
    pub train_design: &'a Design,
    /// Over the evaluation recording.
    pub test_design: &'a Design,
    /// The training recording.
    pub data: &'a Data,
    /// The evaluation recording.
    pub test_data: &'a Data,
    /// Training samples.
    pub train: &'a [bool],
    /// Held-out samples.
    pub test: &'a [bool],
    /// The channel's frozen noise model.
    pub noise: &'a ArNoise,
    /// Lags over which the correlation time is summed.
    pub lags: usize,
    /// The input's span (peak |strain|, or the stroke's range).
    pub span: f64,
    /// Whether the evaluation recording is another one (a holdout).
    pub holdout: bool,
}

/// One fitted set of groups, ready for any target: the normal equations of each fold left out
/// and of all folds, at every smoothing weight (one, unpenalized, for a set without a spline).
pub(super) struct Prepared {
    groups: Vec<usize>,
    /// Per smoothing weight: the factor of all training folds, and of each fold left out.
    factors: Vec<Factors>,
}

/// At one smoothing weight: the factor of all training folds, and of each fold left out.
type Factors = (Cholesky<f64, Dyn>, Vec<Cholesky<f64, Dyn>>);

/// A set's columns, and where each penalized block starts among them with its penalty.
type Columns<'a> = (Vec<&'a Vec<f64>>, Vec<(usize, &'a DMatrix<f64>)>);

/// A group of unpenalized columns beside the kinds: over the training recording and, with a
/// holdout, over the evaluation one.
pub(super) type Extra = (Vec<Vec<f64>>, Option<Vec<Vec<f64>>>);

/// The statistic (the larger of all kinds together and the best kind alone), each kind's
/// evidence alone, and every set's fit.
type Statistic = (f64, Vec<(GenericKind, f64)>, Vec<SetFit>);

/// A channel's generic test over any target: the groups' whitened columns (group 0 the
/// model's, then each kind's, then any extra group's), the sets of groups fitted, the folds.
pub(super) struct Generic<'a> {
    r: &'a Residuals<'a>,
    groups: Vec<Group>,
    sets: Vec<Vec<usize>>,
    folds: Vec<Vec<usize>>,
}

/// A target whitened over the training recording and, with a holdout, the evaluation one.
#[derive(Clone)]
pub(super) struct Target {
    white: Vec<f64>,
    white_test: Option<Vec<f64>>,
}

/// The result of one set on one target: the held-out sum of squares, the correlation time of
/// the training residual, and the whitened training residual.
pub(super) struct SetFit {
    test_ss: f64,
    tau: f64,
    residual: Vec<f64>,
    test_residual: Option<Vec<f64>>,
}

impl Residuals<'_> {
    /// The generic columns of `kind` over `data`, from its input `x` (the curve from `smooth`,
    /// the input without the tracker's noise), and the penalized blocks among them.
    fn columns(
        &self,
        kind: GenericKind,
        x: &[f64],
        smooth: &[f64],
        data: &Data,
    ) -> (Vec<Vec<f64>>, Vec<(usize, usize)>) {
        match kind {
            GenericKind::Curve => {
                let h = hats(smooth, &Term::static_knots(self.span));
                let m = h.len();
                (h, vec![(0, m)])
            }
            GenericKind::Memory => (
                MEMORY_RADII
                    .iter()
                    .map(|f| play(x, f * self.span))
                    .collect(),
                Vec::new(),
            ),
            GenericKind::History => (
                HISTORY_TAUS_S
                    .iter()
                    .map(|&tau_s| low_pass(x, tau_s, data.dt_s))
                    .collect(),
                Vec::new(),
            ),
            GenericKind::Sensitivity => {
                let gain = time_gain(&time_splines_of(data), x);
                let m = gain.len();
                (gain, vec![(0, m)])
            }
            GenericKind::Baseline => {
                let offset = time_splines_of(data);
                let m = offset.len();
                (offset, vec![(0, m)])
            }
            GenericKind::Time => {
                let offset = time_splines_of(data);
                let gain = time_gain(&offset, x);
                let m = offset.len();
                (
                    offset.into_iter().chain(gain).collect(),
                    vec![(0, m), (m, m)],
                )
            }
        }
    }

    /// The input column of a design: its `gain` (the measured strain of a sensor, the stroke of
    /// the plant: never a modelled input).
    fn input(design: &Design) -> Option<Vec<f64>> {
        let at = design.labels.iter().position(|l| *l == "gain")?;
        Some(design.columns[at].clone())
    }

    /// The input without the tracker's noise: a sensor's `gain_proxy` (the smoothed measured
    /// angle's strain, never the plant model), the plant's stroke. A curve of fine knots near
    /// zero strain drawn on the noisy strain fitted the training blocks' tracker noise and
    /// missed the held-out ones by ten times the noise (the third generator's clean Joint A:
    /// held-out sum of squares 14 times the model's).
    fn smooth_input(design: &Design) -> Option<Vec<f64>> {
        let at = design
            .labels
            .iter()
            .position(|l| *l == "gain_proxy")
            .or_else(|| design.labels.iter().position(|l| *l == "gain"))?;
        Some(design.columns[at].clone())
    }

    /// The whitened, scaled columns of the final model and of each kind, with the sets of the
    /// `unexplained` test ([`Generic::kind_sets`]).
    fn generic(&self) -> Option<Generic<'_>> {
        self.generic_of(
            &GenericKind::ALL,
            Vec::new(),
            Generic::kind_sets(GenericKind::ALL.len()),
        )
    }

    /// The whitened, scaled columns of the final model (group 0), of each of `kinds` (groups
    /// 1 to `kinds.len()`) and of each `extra` group after them (unpenalized columns over the
    /// training and, with a holdout, the evaluation recording), fitted in `sets`.
    pub(super) fn generic_of(
        &self,
        kinds: &[GenericKind],
        extra: Vec<Extra>,
        sets: Vec<Vec<usize>>,
    ) -> Option<Generic<'_>> {
        let rows: Vec<usize> = (0..self.train.len()).filter(|&i| self.train[i]).collect();
        if rows.len() < 10 * FOLDS {
            return None;
        }
        let x = Self::input(self.train_design)?;
        let x_test = Self::input(self.test_design)?;
        let smooth = Self::smooth_input(self.train_design)?;
        let smooth_test = Self::smooth_input(self.test_design)?;
        let whiten = |cols: Vec<Vec<f64>>| -> Vec<Vec<f64>> {
            cols.iter().map(|c| self.noise.whiten(c)).collect()
        };
        let mut groups = Vec::new();
        let scale_of = |c: &[f64]| -> f64 {
            let v = (rows.iter().map(|&i| c[i] * c[i]).sum::<f64>() / rows.len() as f64).sqrt();
            if v > 0.0 && v.is_finite() {
                v
            } else {
                1.0
            }
        };
        let make = |cols: Vec<Vec<f64>>,
                    test: Option<Vec<Vec<f64>>>,
                    blocks: Vec<(usize, usize)>|
         -> Group {
            let mut cols = whiten(cols);
            let mut test = test.map(whiten);
            // Columns are scaled to unit RMS over the training rows; a penalized block by one
            // common scale, so that its penalty means the same for every coefficient.
            let mut scales: Vec<f64> = cols.iter().map(|c| scale_of(c)).collect();
            for &(first, m) in &blocks {
                let common = scales[first..first + m].iter().sum::<f64>() / m as f64;
                for s in &mut scales[first..first + m] {
                    *s = common;
                }
            }
            for (j, s) in scales.iter().enumerate() {
                cols[j].iter_mut().for_each(|v| *v /= s);
                if let Some(t) = &mut test {
                    t[j].iter_mut().for_each(|v| *v /= s);
                }
            }
            Group {
                cols,
                test_cols: test,
                penalties: blocks
                    .into_iter()
                    .map(|(first, m)| (first, second_difference(m)))
                    .collect(),
            }
        };
        groups.push(make(
            self.train_design.columns.clone(),
            self.holdout.then(|| self.test_design.columns.clone()),
            Vec::new(),
        ));
        for &kind in kinds {
            let (cols, blocks) = self.columns(kind, &x, &smooth, self.data);
            let test = self
                .holdout
                .then(|| self.columns(kind, &x_test, &smooth_test, self.test_data).0);
            groups.push(make(cols, test, blocks));
        }
        for (cols, test) in extra {
            groups.push(make(cols, test.filter(|_| self.holdout), Vec::new()));
        }
        Some(Generic {
            r: self,
            groups,
            sets,
            folds: folds(&rows),
        })
    }

    /// The channel's unexplained structure, if its evidence reaches [`UNEXPLAINED_NATS`] and,
    /// unless `fast`, beats its calibration; `seed` names the channel's copies.
    pub fn test(&self, channel: Stage, fast: bool, seed: u64) -> Option<Unexplained> {
        let g = self.generic()?;
        let sets = g.prepare_sets()?;
        let observed_target = Target {
            white: self.noise.whiten(&self.train_design.target),
            white_test: self
                .holdout
                .then(|| self.noise.whiten(&self.test_design.target)),
        };
        let (evidence, by_kind, fits) = g.statistic(&sets, &observed_target)?;
        if evidence.is_nan() || evidence < UNEXPLAINED_NATS {
            return None;
        }
        let (kind, _) = by_kind
            .iter()
            .copied()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((GenericKind::Curve, f64::NEG_INFINITY));
        let calibration = if fast {
            None
        } else {
            let c = g.calibrate(&sets, &fits, evidence, seed);
            if !c.passed {
                return None;
            }
            Some(c)
        };
        Some(Unexplained {
            channel,
            evidence,
            kind,
            place: kind.place(),
            by_kind,
            calibration,
        })
    }
}

/// The training rows cut into folds: each run of consecutive training rows (a training block),
/// every [`MAX_FOLDS`]-th run together when there are more, or, when they are one run,
/// [`FOLDS`] equal parts.
fn folds(rows: &[usize]) -> Vec<Vec<usize>> {
    let mut runs: Vec<Vec<usize>> = Vec::new();
    for &i in rows {
        match runs.last_mut() {
            Some(run) if run.last() == Some(&(i - 1)) => run.push(i),
            _ => runs.push(vec![i]),
        }
    }
    if runs.len() > MAX_FOLDS {
        let mut folds = vec![Vec::new(); MAX_FOLDS];
        for (k, run) in runs.into_iter().enumerate() {
            folds[k % MAX_FOLDS].extend(run);
        }
        return folds;
    }
    if runs.len() >= 3 {
        return runs;
    }
    let size = rows.len().div_ceil(FOLDS);
    rows.chunks(size).map(<[usize]>::to_vec).collect()
}

impl Generic<'_> {
    /// The sets of the `unexplained` test of `kinds` kinds: the final model alone, each kind
    /// alone with it, and all kinds.
    fn kind_sets(kinds: usize) -> Vec<Vec<usize>> {
        let mut sets = vec![vec![0]];
        sets.extend((1..=kinds).map(|k| vec![0, k]));
        sets.push((0..=kinds).collect());
        sets
    }

    /// The columns of a set, and where each penalized block starts among them.
    fn columns_of(&self, set: &[usize]) -> Columns<'_> {
        let mut cols = Vec::new();
        let mut penalties = Vec::new();
        for &g in set {
            let group = &self.groups[g];
            for (first, p) in &group.penalties {
                penalties.push((cols.len() + first, p));
            }
            cols.extend(group.cols.iter());
        }
        (cols, penalties)
    }

    /// Each set's normal equations factored for every smoothing weight and fold.
    pub(super) fn prepare_sets(&self) -> Option<Vec<Prepared>> {
        self.sets
            .clone()
            .into_par_iter()
            .map(|set| {
                let (cols, penalties) = self.columns_of(&set);
                let p = cols.len();
                let gram_of = |rows: &[usize]| -> DMatrix<f64> {
                    let x = DMatrix::from_fn(rows.len(), p, |r, c| cols[c][rows[r]]);
                    x.tr_mul(&x)
                };
                let per_fold: Vec<DMatrix<f64>> = self.folds.iter().map(|f| gram_of(f)).collect();
                let total = per_fold.iter().fold(DMatrix::zeros(p, p), |a, g| a + g);
                let mean_diag = total.trace() / p as f64;
                let mut penalty = DMatrix::zeros(p, p);
                for (first, d) in &penalties {
                    let m = d.nrows();
                    penalty.view_mut((*first, *first), (m, m)).copy_from(d);
                }
                let weights: Vec<f64> = if penalties.is_empty() {
                    vec![0.0]
                } else {
                    let spline_trace: f64 = penalties
                        .iter()
                        .map(|(first, d)| {
                            (0..d.nrows())
                                .map(|k| total[(first + k, first + k)])
                                .sum::<f64>()
                        })
                        .sum();
                    let ratio = spline_trace / penalty.trace().max(f64::MIN_POSITIVE);
                    SMOOTHING_POWERS
                        .iter()
                        .map(|&k| ratio * 10f64.powi(k))
                        .collect()
                };
                let ridge = DMatrix::identity(p, p) * (RIDGE * mean_diag);
                let factor = |g: &DMatrix<f64>, w: f64| (g + &penalty * w + &ridge).cholesky();
                let factors = weights
                    .iter()
                    .map(|&w| {
                        let all = factor(&total, w)?;
                        let left_out = per_fold
                            .iter()
                            .map(|gf| factor(&(&total - gf), w))
                            .collect::<Option<Vec<_>>>()?;
                        Some((all, left_out))
                    })
                    .collect::<Option<Vec<_>>>()?;
                Some(Prepared {
                    groups: set,
                    factors,
                })
            })
            .collect()
    }

    /// `set` fitted to `target`: the smoothing weight by cross-validation over the folds, then
    /// all folds at that weight.
    pub(super) fn fit(&self, set: &Prepared, target: &Target) -> SetFit {
        let (cols, _) = self.columns_of(&set.groups);
        let p = cols.len();
        let xty = |rows: &[usize]| -> DVector<f64> {
            DVector::from_iterator(
                p,
                cols.iter()
                    .map(|c| rows.iter().map(|&i| c[i] * target.white[i]).sum::<f64>()),
            )
        };
        let per_fold: Vec<DVector<f64>> = self.folds.iter().map(|f| xty(f)).collect();
        let total = per_fold.iter().fold(DVector::zeros(p), |a, v| a + v);
        // The fitted values at `rows`, column by column (each row's sum in the columns' order,
        // as a sum per row would give it, but reading each column straight through).
        let predict = |beta: &DVector<f64>, rows: &mut dyn Iterator<Item = usize>| -> Vec<f64> {
            let rows: Vec<usize> = rows.collect();
            let mut fitted = vec![0.0; rows.len()];
            for (c, b) in cols.iter().zip(beta.iter()) {
                for (f, &i) in fitted.iter_mut().zip(&rows) {
                    *f += c[i] * b;
                }
            }
            fitted
        };
        let chosen = if set.factors.len() == 1 {
            0
        } else {
            (0..set.factors.len())
                .map(|w| {
                    let cv: f64 = self
                        .folds
                        .iter()
                        .zip(&set.factors[w].1)
                        .zip(&per_fold)
                        .map(|((fold, factor), c)| {
                            let beta = factor.solve(&(&total - c));
                            fold.iter()
                                .zip(predict(&beta, &mut fold.iter().copied()))
                                .map(|(&i, p)| (target.white[i] - p).powi(2))
                                .sum::<f64>()
                        })
                        .sum();
                    (w, cv)
                })
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map_or(0, |(w, _)| w)
        };
        let beta = set.factors[chosen].0.solve(&total);
        let residual: Vec<f64> = target
            .white
            .iter()
            .zip(predict(&beta, &mut (0..target.white.len())))
            .map(|(w, p)| w - p)
            .collect();
        let test_residual: Option<Vec<f64>> = target.white_test.as_ref().map(|white| {
            let mut test_cols: Vec<&Vec<f64>> = Vec::new();
            for &g in &set.groups {
                test_cols.extend(self.groups[g].test_cols.iter().flatten());
            }
            (0..white.len())
                .map(|i| {
                    white[i]
                        - test_cols
                            .iter()
                            .zip(beta.iter())
                            .map(|(c, b)| c[i] * b)
                            .sum::<f64>()
                })
                .collect()
        });
        let test_ss = test_residual
            .as_deref()
            .unwrap_or(&residual)
            .iter()
            .zip(self.r.test)
            .filter(|(_, t)| **t)
            .map(|(v, _)| v * v)
            .sum();
        SetFit {
            test_ss,
            tau: correlation_time_white(&residual, self.r.train, self.r.lags),
            residual,
            test_residual,
        }
    }

    /// The test's evidence on `target` (the larger of all kinds together and the best kind
    /// alone), each kind's alone, and every set's fit.
    fn statistic(&self, sets: &[Prepared], target: &Target) -> Option<Statistic> {
        let fits: Vec<SetFit> = sets.iter().map(|s| self.fit(s, target)).collect();
        let n = self.r.test.iter().filter(|t| **t).count();
        let from = fits[0].test_ss;
        let gain = |f: &SetFit| super::evidence(n, from, f.test_ss, f.tau);
        let by_kind: Vec<(GenericKind, f64)> = GenericKind::ALL
            .iter()
            .zip(&fits[1..=GenericKind::ALL.len()])
            .map(|(k, f)| (*k, gain(f)))
            .filter(|(_, e)| e.is_finite())
            .collect();
        let alone = by_kind
            .iter()
            .map(|(_, e)| *e)
            .fold(f64::NEG_INFINITY, f64::max);
        let together = gain(&fits[fits.len() - 1]);
        // All kinds together can do worse on held-out samples than the best one alone (more
        // columns, fitted to the training blocks' noise): the structure is there if either
        // shows it.
        let evidence = if together.is_finite() {
            together.max(alone)
        } else {
            alone
        };
        Some((evidence, by_kind, fits))
    }

    /// The flag's bootstrap: copies of the final model's fit (noise fitted to the residual of
    /// all kinds together), the statistic on each.
    fn calibrate(
        &self,
        sets: &[Prepared],
        fits: &[SetFit],
        evidence: f64,
        seed: u64,
    ) -> Calibration {
        self.calibrate_by(
            &fits[0],
            &fits[fits.len() - 1],
            evidence,
            UNEXPLAINED_NATS,
            seed,
            &|copy| self.statistic(sets, copy).map_or(f64::NAN, |s| s.0),
        )
    }

    /// A bootstrap of the test `statistic`: copies of the fit `world` (the model the test's
    /// null holds), with noise fitted to the residual of the fit `fuller` (the test's
    /// alternative: Hall & Wilson's guideline), the statistic on each, and the rule applied
    /// to `evidence` after `screen`; [`MORE_COPIES`] when the first leave it close.
    pub(super) fn calibrate_by(
        &self,
        world: &SetFit,
        fuller: &SetFit,
        evidence: f64,
        screen: f64,
        seed: u64,
        statistic: &(dyn Fn(&Target) -> f64 + Sync),
    ) -> Calibration {
        let noise = self.r.noise;
        // Back from whitened residuals to the channel's: the whitening's inverse.
        let colour = |w: &[f64]| -> Vec<f64> {
            let mut e = vec![0.0; w.len()];
            for t in 0..w.len() {
                let past: f64 = noise
                    .phi
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| t > *k)
                    .map(|(k, p)| p * e[t - k - 1])
                    .sum();
                e[t] = w[t] + past;
            }
            e
        };
        let target = &self.r.train_design.target;
        let model: Vec<f64> = target
            .iter()
            .zip(colour(&world.residual))
            .map(|(y, e)| y - e)
            .collect();
        let moving = self.r.data.moving();
        let copy_noise = CopyNoise::fit(&colour(&fuller.residual), &moving, self.r.lags);
        // The world on the holdout: its target less its held-out residual.
        let model_test: Option<Vec<f64>> = world.test_residual.as_ref().map(|w| {
            self.r
                .test_design
                .target
                .iter()
                .zip(colour(w))
                .map(|(y, e)| y - e)
                .collect()
        });
        let draw = |k: usize| -> f64 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            rng.set_stream(k as u64);
            let mut make = |mean: &[f64]| -> Vec<f64> {
                let e = copy_noise.simulate(mean.len(), &mut rng);
                noise.whiten(&mean.iter().zip(&e).map(|(m, e)| m + e).collect::<Vec<_>>())
            };
            let white = make(&model);
            let white_test = model_test.as_deref().map(&mut make);
            statistic(&Target { white, white_test })
        };
        let mut null: Vec<f64> = (0..COPIES).into_par_iter().map(draw).collect();
        let first = Calibration::of(evidence, null.clone(), screen);
        let close = match (first.bound, first.null_sd) {
            (Some(b), Some(sd)) => (evidence - b).abs() < sd,
            _ => false,
        };
        if !close {
            return first;
        }
        null.extend(
            (COPIES..MORE_COPIES)
                .into_par_iter()
                .map(draw)
                .collect::<Vec<_>>(),
        );
        Calibration::of(evidence, null, screen)
    }

    /// The evidence of the best of the sets `alternatives` (indices into the prepared sets;
    /// the best by its training sum of squares, as a candidate's grid shape is chosen) over the
    /// set `from`, on `target`; with the index of that best and the fits of `from` and of it.
    pub(super) fn nested(
        &self,
        sets: &[Prepared],
        from: usize,
        alternatives: &[usize],
        target: &Target,
    ) -> Option<(f64, usize, SetFit, SetFit)> {
        let n = self.r.test.iter().filter(|t| **t).count();
        let base = self.fit(&sets[from], target);
        let train_ss = |f: &SetFit| -> f64 {
            f.residual
                .iter()
                .zip(self.r.train)
                .filter(|(_, t)| **t)
                .map(|(v, _)| v * v)
                .sum()
        };
        let (best, fit) = alternatives
            .iter()
            .map(|&a| (a, self.fit(&sets[a], target)))
            .min_by(|a, b| train_ss(&a.1).total_cmp(&train_ss(&b.1)))?;
        let e = super::evidence(n, base.test_ss, fit.test_ss, fit.tau);
        Some((e, best, base, fit))
    }

    /// The observed target of the test: the final model's, whitened.
    pub(super) fn observed(&self) -> Target {
        Target {
            white: self.r.noise.whiten(&self.r.train_design.target),
            white_test: self
                .r
                .holdout
                .then(|| self.r.noise.whiten(&self.r.test_design.target)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The B-splines add up to one everywhere and the penalty leaves lines alone.
    #[test]
    fn splines_partition_unity_and_lines_are_unpenalized() {
        let t: Vec<f64> = (0..=300).map(f64::from).collect();
        let b = time_splines(&t, 0.0, 300.0, 5);
        assert_eq!(b.len(), 8);
        for i in 0..t.len() {
            let sum: f64 = b.iter().map(|c| c[i]).sum();
            assert!((sum - 1.0).abs() < 1e-12, "at {i}: {sum}");
        }
        let p = second_difference(8);
        let line = DVector::from_iterator(8, (0..8).map(|k| 2.0 + 0.5 * f64::from(k)));
        assert!((line.transpose() * &p * &line)[(0, 0)].abs() < 1e-12);
        let bend = DVector::from_iterator(8, (0..8).map(|k| f64::from(k * k)));
        assert!((bend.transpose() * &p * &bend)[(0, 0)] > 1.0);
    }

    #[test]
    fn folds_are_the_training_blocks_or_equal_parts() {
        let blocks: Vec<usize> = (0..10).chain(20..30).chain(40..50).collect();
        assert_eq!(folds(&blocks).len(), 3);
        let run: Vec<usize> = (0..100).collect();
        let f = folds(&run);
        assert_eq!(f.len(), FOLDS);
        assert_eq!(f.iter().map(Vec::len).sum::<usize>(), 100);
        // A long recording's 51 training blocks are dealt into MAX_FOLDS folds, each every
        // tenth block, every row in one of them.
        let many: Vec<usize> = (0..51).flat_map(|b| 20 * b..20 * b + 10).collect();
        let f = folds(&many);
        assert_eq!(f.len(), MAX_FOLDS);
        assert_eq!(f[0][..11], [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 200]);
        let mut all: Vec<usize> = f.concat();
        all.sort_unstable();
        assert_eq!(all, many);
    }
}

#[cfg(test)]
mod fit_tests {
    use super::*;
    use crate::discover::model::{fit, score};

    /// Without a penalty, a set's fit is the least squares of `model::fit`: the same held-out
    /// sum of squares on a recording-like design.
    #[test]
    fn an_unpenalized_set_is_least_squares() {
        let n = 3000;
        let dt = 0.04;
        let x: Vec<f64> = (0..n)
            .map(|i| 0.006 * (1.0 + (i as f64 * 0.01).sin()))
            .collect();
        let noise = crate::discover::noise::tests::ar1(0.9, n);
        let y: Vec<f64> = x
            .iter()
            .zip(&noise)
            .map(|(x, e)| 180_000.0 + 2.5e6 * x + 4e8 * x * x + 300.0 * e)
            .collect();
        let design = Design {
            columns: vec![vec![1.0; n], x.clone()],
            target: y,
            labels: vec!["offset", "gain"],
        };
        let data = Data {
            time_s: (0..n).map(|i| i as f64 * dt).collect(),
            stroke_mm: vec![0.0; n],
            angle_deg: vec![0.0; n],
            strain: x.clone(),
            ohm: vec![],
            rest: 100,
            measured: vec![true; n],
            dt_s: dt,
        };
        let train: Vec<bool> = (0..n).map(|i| i >= 100 && (i / 290) % 2 == 0).collect();
        let test: Vec<bool> = (0..n).map(|i| i >= 100 && (i / 290) % 2 == 1).collect();
        let ar = ArNoise {
            phi: vec![0.9],
            sigma: 1.0,
        };
        let r = Residuals {
            train_design: &design,
            test_design: &design,
            data: &data,
            test_data: &data,
            train: &train,
            test: &test,
            noise: &ar,
            lags: 50,
            span: 0.012,
            holdout: false,
        };
        let g = r.generic().unwrap();
        let sets = g.prepare_sets().unwrap();
        let target = Target {
            white: ar.whiten(&design.target),
            white_test: None,
        };
        // Set 0 (the model alone) and set 3 (with the history), against model::fit.
        for (set, kinds) in [(0usize, vec![]), (3, vec![GenericKind::History])] {
            let got = g.fit(&sets[set], &target).test_ss;
            let mut d = design.clone();
            for k in kinds {
                let (cols, _) = r.columns(k, &x, &x, &data);
                d.columns.extend(cols);
                d.labels
                    .extend(std::iter::repeat("generic").take(d.columns.len() - d.labels.len()));
            }
            let f = fit(&d, &ar, &train).unwrap();
            let (want, _, _) = score(&f.residual(&d), &ar, &test);
            assert!(
                // The generic fit solves the normal equations (Cholesky), model::fit an SVD: on
                // this design they agree to 2.6e-6 relative (measured), not to 1e-6.
                (got / want - 1.0).abs() < 1e-5,
                "set {set}: {got} against {want}"
            );
        }
    }
}
