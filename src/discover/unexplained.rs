//! What the library cannot explain: after the last named effect, each channel's model is
//! extended by generic, library-free regressors of four kinds (a memoryless curve of any
//! shape, memory, history, time), and the held-out evidence for the extension is measured
//! the way every candidate's is (whitened likelihood gain over held-out samples, divided by the
//! correlation time of the training residual). Evidence over [`UNEXPLAINED_NATS`] means
//! structure remains that depends on the input or on time and that no named effect explains;
//! the kind that alone adds the most says where it is.
//!
//! This is the residual analysis of MATLAB's `resid` (is what remains white, and is it
//! independent of the input?) made a likelihood test on held-out data: a correlation between
//! the residual and the input, at any lag or through any curve, shows as held-out evidence for
//! these regressors; slow noise the frozen noise model misses is discounted by the correlation
//! time, so a clean recording's residual is not flagged for being coloured.

use serde::Serialize;

use super::data::Data;
use super::model::{correlation_time, fit, score, Channel, Design};
use super::noise::ArNoise;
use super::terms::{hats, low_pass, play, Term};

/// Evidence (nats) the generic regressors need before a channel is flagged: the same bar as
/// naming an effect ([`super::THRESHOLD_NATS`]).
pub const UNEXPLAINED_NATS: f64 = super::THRESHOLD_NATS;
/// Time constants of the history regressors (s): a lag of the input, fast and slow.
pub const HISTORY_TAUS_S: [f64; 2] = [3.0, 30.0];
/// Harmonics of the time regressors: over the run `t/T` ∈ [0, 1], a trend and
/// `cos(2πk·t/T)`, `sin(2πk·t/T)` for `k` = 1, 2, alone and times the input: a baseline and a
/// sensitivity that change in any slow way (a fade, a step, a temperature cycle with up to two
/// periods in the run). Time, squared time and input times time (one linear gain change) missed
/// a gain following a slow sinusoid (tests/discover_unseen.rs, `GainSine`); hats over time
/// extrapolated badly into the held-out last block.
pub const TIME_HARMONICS: usize = 2;
/// Radii of the memory regressors, as fractions of the input's span.
pub const MEMORY_RADII: [f64; 2] = [0.1, 0.3];

/// A kind of generic regressor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// A memoryless curve of the input of any shape (piecewise linear).
    Curve,
    /// Plays of the input: loops, a difference between loading and unloading.
    Memory,
    /// Lags of the input: what happens during holds and after changes.
    History,
    /// Slow functions of time, and the input times them: a baseline or a sensitivity that
    /// changes over the run ([`TIME_HARMONICS`]).
    Time,
}

impl Kind {
    /// Every kind.
    pub const ALL: [Kind; 4] = [Kind::Curve, Kind::Memory, Kind::History, Kind::Time];

    /// Where the structure shows, for people.
    pub fn place(self) -> &'static str {
        match self {
            Kind::Curve => {
                "along the input's range: a curve no named effect draws (high strain or stroke)"
            }
            Kind::Memory => "at reversals: loading and unloading differ",
            Kind::History => "during holds and after changes: the channel lags its input",
            Kind::Time => "growing with time: the baseline or the sensitivity changes over the run",
        }
    }
}

/// A channel with structure the library does not explain.
#[derive(Debug, Clone, Serialize)]
pub struct Unexplained {
    /// The channel.
    #[serde(serialize_with = "channel_name")]
    pub channel: Channel,
    /// Held-out evidence of the generic regressors over the final model (nats).
    pub evidence: f64,
    /// The kind that alone adds the most evidence.
    pub kind: Kind,
    /// Where it is, in words.
    #[serde(rename = "where")]
    pub place: &'static str,
    /// The evidence each kind alone adds to the final model (nats), in [`Kind::ALL`]'s order.
    pub by_kind: Vec<(Kind, f64)>,
}

fn channel_name<S: serde::Serializer>(c: &Channel, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&c.name())
}

/// `design` with the generic regressors of `kinds` appended. The input is the design's
/// `gain` column (the measured strain of a sensor, the stroke of the plant: never the plant
/// model's proxy, so that a plant error cannot show as a sensor's).
fn extended(design: &Design, data: &Data, kinds: &[Kind], span: f64) -> Design {
    let mut d = design.clone();
    let Some(at) = d.labels.iter().position(|l| *l == "gain") else {
        return d;
    };
    let x = d.columns[at].clone();
    let t0 = data.time_s.first().copied().unwrap_or(0.0);
    let length = (data.time_s.last().copied().unwrap_or(t0) - t0).max(f64::MIN_POSITIVE);
    let tau: Vec<f64> = data.time_s.iter().map(|t| (t - t0) / length).collect();
    for kind in kinds {
        let columns: Vec<Vec<f64>> = match kind {
            Kind::Curve => hats(&x, &Term::static_knots(span)),
            Kind::Memory => MEMORY_RADII.iter().map(|f| play(&x, f * span)).collect(),
            Kind::History => HISTORY_TAUS_S
                .iter()
                .map(|&tau_s| low_pass(&x, tau_s, data.dt_s))
                .collect(),
            Kind::Time => {
                let mut slow = vec![tau.clone()];
                for k in 1..=TIME_HARMONICS {
                    let w = 2.0 * std::f64::consts::PI * k as f64;
                    slow.push(tau.iter().map(|v| (w * v).cos()).collect());
                    slow.push(tau.iter().map(|v| (w * v).sin()).collect());
                }
                let gains: Vec<Vec<f64>> = slow
                    .iter()
                    .map(|s| x.iter().zip(s).map(|(x, s)| x * s).collect())
                    .collect();
                slow.into_iter().chain(gains).collect()
            }
        };
        for c in columns {
            d.columns.push(c);
            d.labels.push("generic");
        }
    }
    d
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
}

impl Residuals<'_> {
    /// Held-out whitened sum of squares with the `kinds` added, the samples it is over, and
    /// the correlation time of its training residual.
    fn with(&self, kinds: &[Kind]) -> Option<(f64, usize, f64)> {
        let train = extended(self.train_design, self.data, kinds, self.span);
        let test = extended(self.test_design, self.test_data, kinds, self.span);
        let fitted = fit(&train, self.noise, self.train)?;
        let (ss, _, n) = score(&fitted.residual(&test), self.noise, self.test);
        let tau = correlation_time(&fitted.residual(&train), self.noise, self.train, self.lags);
        Some((ss, n, tau))
    }

    /// The channel's unexplained structure, if its evidence reaches [`UNEXPLAINED_NATS`].
    pub fn test(&self, channel: Channel) -> Option<Unexplained> {
        let (from_ss, n, _) = self.with(&[])?;
        let (all_ss, _, tau) = self.with(&Kind::ALL)?;
        let together = super::evidence(n, from_ss, all_ss, tau);
        let by_kind: Vec<(Kind, f64)> = Kind::ALL
            .iter()
            .filter_map(|&k| {
                let (ss, _, tau) = self.with(&[k])?;
                let e = super::evidence(n, from_ss, ss, tau);
                e.is_finite().then_some((k, e))
            })
            .collect();
        let (kind, alone) = by_kind
            .iter()
            .copied()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((Kind::Curve, f64::NEG_INFINITY));
        // All kinds together can do worse on held-out samples than the best one alone (more
        // columns, fitted to the training blocks' noise): the structure is there if either
        // shows it.
        let evidence = if together.is_finite() {
            together.max(alone)
        } else {
            alone
        };
        if evidence.is_nan() || evidence < UNEXPLAINED_NATS {
            return None;
        }
        Some(Unexplained {
            channel,
            evidence,
            kind,
            place: kind.place(),
            by_kind,
        })
    }
}
