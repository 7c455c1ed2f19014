//! Stroke profiles: the tendon stroke over time for each of the paper's bench protocols, or from
//! a CSV file.
//!
//! A profile is a list of knots `(time_s, stroke_mm)` joined by straight lines (the lead screw
//! runs at constant speed between knots), held constant before the first and after the last.
//! A built-in protocol starts with the joint at rest, zero stroke for `rest_start_s` (10 s by
//! default), as a bench recording does: the still segment is where a noise model can be frozen.
//! Then it generates one repetition and repeats it until the duration is covered; its natural
//! duration is the rest plus `repeats` repetitions.
//!
//! | protocol | one repetition (defaults) | natural duration |
//! |---|---|---|
//! | `characterization` | 5 triangle cycles of amplitude A/5, 2A/5 … A at constant stroke speed (the largest rises in 30 s), 4 s rest after each: 200 s | 10 s + 5 × 200 s = 1010 s |
//! | `rate-dependence` | 5 triangle cycles of amplitude A rising (and falling) in 10, 20, 30, 40, 50 s, equal rests filling 600 s | 10 s + 5 × 600 s = 3010 s |
//! | `relaxation` | a staircase up to A in 4 steps and back down, each step a 2 s ramp then a hold: 8 × 75 s = 600 s | 3010 s |
//! | `random` | seeded ramps of 1-10 s to uniform random strokes in [0, A], each held 0-5 s, back to 0 at 600 s | 3010 s |
//! | `custom` | the CSV's knots, not repeated (no rest is added: the file says how it starts) | the CSV's last time |
//!
//! The amplitude `A` defaults to the stroke that gives the paper's ~1.5 % peak strain for the
//! design at the plant's nominal gain: `A = θ(ε = 1.5 %)/gain`, with `θ(ε)` from the design's
//! geometry.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::rng::Stream;

/// Why a stroke profile could not be built.
#[derive(Debug, thiserror::Error)]
pub enum ProtocolError {
    /// The custom profile could not be read.
    #[error("cannot read stroke profile {path}")]
    Read {
        /// The CSV file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The custom profile's content is wrong at one line.
    #[error("stroke profile {path} line {line}: {reason}")]
    Line {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong, naming the value.
        reason: String,
    },
    /// The custom profile has a header but no knots.
    #[error("stroke profile {path} has no data rows (expected lines of time_s,stroke_mm)")]
    Empty {
        /// The CSV file.
        path: PathBuf,
    },
    /// `custom` was chosen without a profile file.
    #[error("protocol custom needs a stroke profile: pass --profile FILE.csv or set protocols.custom.profile")]
    NoProfile,
}

/// The bench protocols: the recording's own type, which the simulator runs.
pub use crate::recording::ProtocolKind;

/// Protocol timing and amplitude (`[protocols]` and its sub-tables).
///
/// | key | default |
/// |---|---|
/// | `peak_strain` | 0.015 (the paper's ~1.5 %) |
/// | `amplitude_mm` | from `peak_strain`, the geometry and the plant gain |
/// | `rest_start_s` | 10: zero stroke before the first repetition of a built-in protocol |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProtocolParams {
    /// Sensor strain the largest stroke reaches at the nominal gain (fraction).
    pub peak_strain: f64,
    /// Largest stroke (mm); `None` means derived from `peak_strain`.
    pub amplitude_mm: Option<f64>,
    /// Time at rest (zero stroke) before a built-in protocol's first repetition (s); 0 starts
    /// moving at once, as the protocols did before this key existed. Not applied to `custom`
    /// profiles.
    pub rest_start_s: f64,
    /// `characterization`.
    pub characterization: Characterization,
    /// `rate-dependence`.
    #[serde(rename = "rate-dependence")]
    pub rate_dependence: RateDependenceProtocol,
    /// `relaxation`.
    pub relaxation: RelaxationProtocol,
    /// `random`.
    pub random: RandomProtocol,
    /// `custom`.
    pub custom: CustomProtocol,
}

impl Default for ProtocolParams {
    fn default() -> Self {
        Self {
            peak_strain: 0.015,
            amplitude_mm: None,
            rest_start_s: DEFAULT_REST_START_S,
            characterization: Characterization::default(),
            rate_dependence: RateDependenceProtocol::default(),
            relaxation: RelaxationProtocol::default(),
            random: RandomProtocol::default(),
            custom: CustomProtocol::default(),
        }
    }
}

/// The default `protocols.rest_start_s` (s): long enough to hold several correlation times of
/// the slowest default noise (`[adc.correlated] tau_s = 2`), short next to the protocols'
/// 200-600 s repetitions, and about what a person does between starting the logger and the motor.
pub const DEFAULT_REST_START_S: f64 = 10.0;

/// The most cycles (or levels) in one repetition of a protocol: the paper's protocols have 5,
/// and each costs a few knots; 2e7 cycles took 1.9 GB for a 60 s run before this limit.
pub const MAX_CYCLES: f64 = 1000.0;
const MAX_CYCLES_WORDS: &str = "must be at most 1000 per repetition";
/// The most repetitions of a protocol.
pub const MAX_REPEATS: f64 = 10_000.0;
const MAX_REPEATS_WORDS: &str = "must be at most 10000";
/// The most ramps in one repetition of the random protocol.
pub const MAX_RANDOM_RAMPS: f64 = 100_000.0;

/// `[protocols.characterization]`: `cycles` triangle cycles of amplitude `A·k/cycles`,
/// `k = 1..cycles`, all at the stroke speed that lifts the largest in `full_rise_s`, each
/// followed by `rest_s` at zero stroke.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Characterization {
    /// Cycles per repetition (5).
    pub cycles: u32,
    /// Rise time of the largest cycle (30 s).
    pub full_rise_s: f64,
    /// Rest after each cycle (4 s).
    pub rest_s: f64,
    /// Repetitions in the natural duration (5).
    pub repeats: u32,
}

impl Default for Characterization {
    fn default() -> Self {
        Self {
            cycles: 5,
            full_rise_s: 30.0,
            rest_s: 4.0,
            repeats: 5,
        }
    }
}

/// `[protocols.rate-dependence]`: one triangle cycle of amplitude `A` per entry of `rise_s`,
/// rising and falling in that time; equal rests after each fill `repeat_s`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RateDependenceProtocol {
    /// Rise (= fall) time of each cycle (10, 20, 30, 40, 50 s).
    pub rise_s: Vec<f64>,
    /// Length of one repetition (600 s).
    pub repeat_s: f64,
    /// Repetitions in the natural duration (5).
    pub repeats: u32,
}

impl Default for RateDependenceProtocol {
    fn default() -> Self {
        Self {
            rise_s: vec![10.0, 20.0, 30.0, 40.0, 50.0],
            repeat_s: 600.0,
            repeats: 5,
        }
    }
}

/// `[protocols.relaxation]`: a staircase up to `A` in `levels` steps and back down to 0; each
/// step ramps in `ramp_s` and holds for the rest of its `repeat_s/(2·levels)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RelaxationProtocol {
    /// Steps up (4); as many come back down.
    pub levels: u32,
    /// Ramp time between levels (2 s).
    pub ramp_s: f64,
    /// Length of one repetition (600 s).
    pub repeat_s: f64,
    /// Repetitions in the natural duration (5).
    pub repeats: u32,
}

impl Default for RelaxationProtocol {
    fn default() -> Self {
        Self {
            levels: 4,
            ramp_s: 2.0,
            repeat_s: 600.0,
            repeats: 5,
        }
    }
}

/// `[protocols.random]`: from zero stroke, ramps lasting `U[min_ramp_s, max_ramp_s]` to strokes
/// drawn from `U[0, A]`, each held for `U[0, max_hold_s]`, then back to 0 at `repeat_s`. The
/// draws come from the scenario's seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RandomProtocol {
    /// Shortest ramp (1 s).
    pub min_ramp_s: f64,
    /// Longest ramp (10 s).
    pub max_ramp_s: f64,
    /// Longest hold (5 s).
    pub max_hold_s: f64,
    /// Length of the pattern (600 s); it is repeated like the paper's.
    pub repeat_s: f64,
    /// Repetitions in the natural duration (5).
    pub repeats: u32,
}

impl Default for RandomProtocol {
    fn default() -> Self {
        Self {
            min_ramp_s: 1.0,
            max_ramp_s: 10.0,
            max_hold_s: 5.0,
            repeat_s: 600.0,
            repeats: 5,
        }
    }
}

/// `[protocols.custom]`: a CSV file with the header `time_s,stroke_mm` and strictly increasing
/// finite times; the stroke is interpolated linearly between rows.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CustomProtocol {
    /// The CSV file; the CLI's `--profile` overrides it.
    pub profile: Option<PathBuf>,
}

impl ProtocolParams {
    /// Reports every out-of-range value to `fail(key, value, limit)`.
    pub(crate) fn check(&self, fail: &mut dyn FnMut(String, f64, &'static str)) {
        self.check_counts(fail);
        self.check_positive(fail);
        self.check_timing(fail);
    }

    /// Counts of cycles, levels and repeats within their limits, and not too many ramps.
    fn check_counts(&self, fail: &mut dyn FnMut(String, f64, &'static str)) {
        let c = &self.characterization;
        let (r, l, m) = (&self.rate_dependence, &self.relaxation, &self.random);
        let counts = [
            (
                "characterization.cycles",
                f64::from(c.cycles),
                MAX_CYCLES,
                MAX_CYCLES_WORDS,
            ),
            (
                "rate-dependence.rise_s (count)",
                r.rise_s.len() as f64,
                MAX_CYCLES,
                MAX_CYCLES_WORDS,
            ),
            (
                "relaxation.levels",
                f64::from(l.levels),
                MAX_CYCLES,
                MAX_CYCLES_WORDS,
            ),
            (
                "characterization.repeats",
                f64::from(c.repeats),
                MAX_REPEATS,
                MAX_REPEATS_WORDS,
            ),
            (
                "rate-dependence.repeats",
                f64::from(r.repeats),
                MAX_REPEATS,
                MAX_REPEATS_WORDS,
            ),
            (
                "relaxation.repeats",
                f64::from(l.repeats),
                MAX_REPEATS,
                MAX_REPEATS_WORDS,
            ),
            (
                "random.repeats",
                f64::from(m.repeats),
                MAX_REPEATS,
                MAX_REPEATS_WORDS,
            ),
        ];
        for (key, value, limit, words) in counts {
            if value > limit {
                fail(key.to_string(), value, words);
            }
        }
        if m.min_ramp_s * MAX_RANDOM_RAMPS < m.repeat_s {
            fail(
                "random.min_ramp_s".into(),
                m.min_ramp_s,
                "must be at least random.repeat_s / 100000 (at most 100000 ramps per repetition)",
            );
        }
    }

    /// Durations, strains and counts that must be greater than 0.
    fn check_positive(&self, fail: &mut dyn FnMut(String, f64, &'static str)) {
        let c = &self.characterization;
        let (r, l, m) = (&self.rate_dependence, &self.relaxation, &self.random);
        let mut positive = |key: &str, v: f64| {
            if !(v.is_finite() && v > 0.0) {
                fail(key.to_string(), v, "must be finite and greater than 0");
            }
        };
        positive("peak_strain", self.peak_strain);
        if let Some(a) = self.amplitude_mm {
            positive("amplitude_mm", a);
        }
        positive("characterization.full_rise_s", c.full_rise_s);
        positive("characterization.cycles", f64::from(c.cycles));
        positive("characterization.repeats", f64::from(c.repeats));
        if r.rise_s.is_empty() {
            positive("rate-dependence.rise_s (count)", 0.0);
        }
        for &t in &r.rise_s {
            positive("rate-dependence.rise_s", t);
        }
        positive("rate-dependence.repeat_s", r.repeat_s);
        positive("rate-dependence.repeats", f64::from(r.repeats));
        positive("relaxation.levels", f64::from(l.levels));
        positive("relaxation.ramp_s", l.ramp_s);
        positive("relaxation.repeat_s", l.repeat_s);
        positive("relaxation.repeats", f64::from(l.repeats));
        positive("random.min_ramp_s", m.min_ramp_s);
        positive("random.repeat_s", m.repeat_s);
        positive("random.repeats", f64::from(m.repeats));
    }

    /// Rests at least 0, and each protocol's parts fitting in its repetition.
    fn check_timing(&self, fail: &mut dyn FnMut(String, f64, &'static str)) {
        let c = &self.characterization;
        let (r, l, m) = (&self.rate_dependence, &self.relaxation, &self.random);
        if !(self.rest_start_s.is_finite() && self.rest_start_s >= 0.0) {
            fail(
                "rest_start_s".into(),
                self.rest_start_s,
                "must be finite and at least 0",
            );
        }
        if !(c.rest_s.is_finite() && c.rest_s >= 0.0) {
            fail(
                "characterization.rest_s".into(),
                c.rest_s,
                "must be finite and at least 0",
            );
        }
        if !(m.max_hold_s.is_finite() && m.max_hold_s >= 0.0) {
            fail(
                "random.max_hold_s".into(),
                m.max_hold_s,
                "must be finite and at least 0",
            );
        }
        if !(m.max_ramp_s.is_finite() && m.max_ramp_s >= m.min_ramp_s) {
            fail(
                "random.max_ramp_s".into(),
                m.max_ramp_s,
                "must be finite and at least random.min_ramp_s",
            );
        }
        if m.repeat_s < 2.0 * m.max_ramp_s {
            fail(
                "random.repeat_s".into(),
                m.repeat_s,
                "must be at least twice random.max_ramp_s",
            );
        }
        let cycles_s: f64 = r.rise_s.iter().map(|t| 2.0 * t).sum();
        if r.repeat_s < cycles_s {
            fail(
                "rate-dependence.repeat_s".into(),
                r.repeat_s,
                "must be at least the cycles' total, 2·Σ rise_s",
            );
        }
        if l.ramp_s * 2.0 * f64::from(l.levels) > l.repeat_s {
            fail(
                "relaxation.ramp_s".into(),
                l.ramp_s,
                "must leave time to hold: 2·levels·ramp_s ≤ repeat_s",
            );
        }
    }
}

/// One point of a stroke profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Knot {
    /// Time (s).
    pub time_s: f64,
    /// Tendon stroke (mm).
    pub stroke_mm: f64,
}

/// A piecewise-linear stroke profile covering a whole recording.
#[derive(Debug, Clone, PartialEq)]
pub struct StrokeProfile {
    knots: Vec<Knot>,
    natural_duration_s: f64,
}

impl StrokeProfile {
    /// Builds the profile of a built-in protocol with amplitude `amplitude_mm`, covering at
    /// least `duration_s` (or its natural duration when `None`). `rng` feeds the random pattern.
    ///
    /// # Errors
    /// [`ProtocolError::NoProfile`] for [`ProtocolKind::Custom`], which has no built-in
    /// pattern: use [`StrokeProfile::from_csv`].
    pub fn built_in(
        kind: ProtocolKind,
        params: &ProtocolParams,
        amplitude_mm: f64,
        duration_s: Option<f64>,
        rng: &mut Stream,
    ) -> Result<Self, ProtocolError> {
        let a = amplitude_mm;
        let (one, repeats) = match kind {
            ProtocolKind::Characterization => (
                characterization(&params.characterization, a),
                params.characterization.repeats,
            ),
            ProtocolKind::RateDependence => (
                rate_dependence(&params.rate_dependence, a),
                params.rate_dependence.repeats,
            ),
            ProtocolKind::Relaxation => {
                (relaxation(&params.relaxation, a), params.relaxation.repeats)
            }
            ProtocolKind::Random => (random(&params.random, a, rng), params.random.repeats),
            ProtocolKind::Custom => return Err(ProtocolError::NoProfile),
        };
        let period_s = one.last().map_or(0.0, |k| k.time_s);
        let rest_s = params.rest_start_s;
        let natural_duration_s = rest_s + period_s * f64::from(repeats);
        let cover_s = duration_s.unwrap_or(natural_duration_s);
        let count = ((cover_s - rest_s) / period_s).ceil().max(1.0) as usize;
        let mut knots = Vec::with_capacity(one.len() * count + 1);
        if rest_s > 0.0 {
            knots.push(Knot {
                time_s: 0.0,
                stroke_mm: 0.0,
            });
        }
        for rep in 0..count {
            let offset = rest_s + period_s * rep as f64;
            // Each repetition starts at zero stroke, where the previous one ended, so its first
            // knot is the previous one's last.
            let skip = usize::from(rep > 0);
            knots.extend(one.iter().skip(skip).map(|k| Knot {
                time_s: k.time_s + offset,
                stroke_mm: k.stroke_mm,
            }));
        }
        Ok(Self {
            knots,
            natural_duration_s,
        })
    }

    /// Reads a custom profile: header `time_s,stroke_mm`, then rows of finite numbers with
    /// strictly increasing time.
    ///
    /// # Errors
    /// [`ProtocolError`] naming the file, the line and the value.
    pub fn from_csv(path: &Path) -> Result<Self, ProtocolError> {
        let text = crate::output::read_limited(path, crate::limits::MAX_RECORDING_BYTES).map_err(
            |source| ProtocolError::Read {
                path: path.to_path_buf(),
                source,
            },
        )?;
        Self::parse_csv(&text).map_err(|e| match e {
            ProtocolError::Line { line, reason, .. } => ProtocolError::Line {
                path: path.to_path_buf(),
                line,
                reason,
            },
            ProtocolError::Empty { .. } => ProtocolError::Empty {
                path: path.to_path_buf(),
            },
            other => other,
        })
    }

    fn parse_csv(text: &str) -> Result<Self, ProtocolError> {
        let knots: Vec<Knot> = parse_series(text, "stroke_mm")?
            .into_iter()
            .map(|(time_s, stroke_mm)| Knot { time_s, stroke_mm })
            .collect();
        let natural_duration_s = knots.last().map_or(0.0, |k| k.time_s);
        Ok(Self {
            knots,
            natural_duration_s,
        })
    }

    /// The protocol's own length (s): its repetitions, or a CSV's last time.
    pub fn natural_duration_s(&self) -> f64 {
        self.natural_duration_s
    }

    /// The knots.
    pub fn knots(&self) -> &[Knot] {
        &self.knots
    }

    /// The largest stroke magnitude (mm).
    pub fn peak_mm(&self) -> f64 {
        self.knots
            .iter()
            .fold(0.0, |m, k| f64::max(m, k.stroke_mm.abs()))
    }

    /// A cursor that evaluates the profile at non-decreasing times in O(1) amortized.
    pub fn sampler(&self) -> Sampler<'_> {
        Sampler {
            knots: &self.knots,
            next: 0,
        }
    }
}

/// Parses a two-column time series: the header `time_s,<value_column>`, then rows of finite
/// numbers with non-negative, strictly increasing times, ending after time 0. Blank lines are
/// skipped. Used for stroke profiles (`stroke_mm`) and desired-angle profiles (`angle_deg`).
///
/// # Errors
/// [`ProtocolError::Line`] (with an empty path, for the caller to fill in) naming the line and
/// the value, or [`ProtocolError::Empty`] when there is no data row.
pub fn parse_series(text: &str, value_column: &str) -> Result<Vec<(f64, f64)>, ProtocolError> {
    let bad = |line: usize, reason: String| ProtocolError::Line {
        path: PathBuf::new(),
        line,
        reason,
    };
    let header = format!("time_s,{value_column}");
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim_end_matches('\r') == header => {}
        Some((_, h)) => {
            let h = crate::limits::quote(h);
            return Err(bad(1, format!("header is {h:?}, expected {header:?}")));
        }
        None => {
            return Err(ProtocolError::Empty {
                path: PathBuf::new(),
            })
        }
    }
    let mut rows: Vec<(f64, f64)> = Vec::new();
    for (i, raw) in lines {
        let line = i + 1;
        let row = raw.trim_end_matches('\r');
        if row.is_empty() {
            continue;
        }
        let fields: Vec<&str> = row.split(',').collect();
        if fields.len() != 2 {
            return Err(bad(
                line,
                format!("has {} fields, expected 2 ({header})", fields.len()),
            ));
        }
        let num = |name: &str, s: &str| -> Result<f64, ProtocolError> {
            let v: f64 = s.trim().parse().map_err(|_| {
                bad(
                    line,
                    format!("{name} = {:?} is not a number", crate::limits::quote(s)),
                )
            })?;
            if !v.is_finite() {
                return Err(bad(line, format!("{name} = {v} is not finite")));
            }
            Ok(v)
        };
        let time_s = num("time_s", fields[0])?;
        let value = num(value_column, fields[1])?;
        if time_s < 0.0 {
            return Err(bad(line, format!("time_s = {time_s} is negative")));
        }
        if let Some(&(prev, _)) = rows.last() {
            if time_s <= prev {
                return Err(bad(
                    line,
                    format!("time_s = {time_s} does not increase (previous row: {prev})"),
                ));
            }
        }
        rows.push((time_s, value));
    }
    match rows.last() {
        Some(&(t, _)) if t > 0.0 => Ok(rows),
        Some(_) => Err(bad(
            2,
            "the profile ends at time 0, so it has no duration".into(),
        )),
        None => Err(ProtocolError::Empty {
            path: PathBuf::new(),
        }),
    }
}

/// Evaluates a [`StrokeProfile`] at non-decreasing times.
#[derive(Debug, Clone)]
pub struct Sampler<'a> {
    knots: &'a [Knot],
    /// Index of the first knot later than the last time asked for.
    next: usize,
}

impl Sampler<'_> {
    /// Stroke (mm) at `time_s`; times must not decrease between calls.
    #[inline]
    pub fn at(&mut self, time_s: f64) -> f64 {
        while self.next < self.knots.len() && self.knots[self.next].time_s <= time_s {
            self.next += 1;
        }
        match (self.next.checked_sub(1), self.knots.get(self.next)) {
            (Some(i), Some(b)) => {
                let a = self.knots[i];
                let u = (time_s - a.time_s) / (b.time_s - a.time_s);
                a.stroke_mm + u * (b.stroke_mm - a.stroke_mm)
            }
            (None, Some(b)) => b.stroke_mm,
            (Some(i), None) => self.knots[i].stroke_mm,
            (None, None) => 0.0,
        }
    }
}

fn characterization(p: &Characterization, a: f64) -> Vec<Knot> {
    let mut k = Knots::default();
    let n = f64::from(p.cycles);
    for c in 1..=p.cycles {
        let share = f64::from(c) / n;
        let rise = p.full_rise_s * share;
        k.ramp(rise, a * share);
        k.ramp(rise, 0.0);
        k.hold(p.rest_s);
    }
    k.0
}

fn rate_dependence(p: &RateDependenceProtocol, a: f64) -> Vec<Knot> {
    let mut k = Knots::default();
    let cycles_s: f64 = p.rise_s.iter().map(|t| 2.0 * t).sum();
    let rest = (p.repeat_s - cycles_s) / p.rise_s.len() as f64;
    for &rise in &p.rise_s {
        k.ramp(rise, a);
        k.ramp(rise, 0.0);
        k.hold(rest);
    }
    k.0
}

fn relaxation(p: &RelaxationProtocol, a: f64) -> Vec<Knot> {
    let mut k = Knots::default();
    let n = p.levels;
    let step_s = p.repeat_s / f64::from(2 * n);
    let levels = (1..=n).chain((0..n).rev());
    for level in levels {
        k.ramp(p.ramp_s, a * f64::from(level) / f64::from(n));
        k.hold(step_s - p.ramp_s);
    }
    k.0
}

fn random(p: &RandomProtocol, a: f64, rng: &mut Stream) -> Vec<Knot> {
    let mut k = Knots::default();
    loop {
        let ramp = p.min_ramp_s + (p.max_ramp_s - p.min_ramp_s) * rng.uniform();
        let target = a * rng.uniform();
        let hold = p.max_hold_s * rng.uniform();
        // Leave room for the final ramp back to zero, no shorter than the longest ramp.
        if k.end_s() + ramp + hold > p.repeat_s - p.max_ramp_s {
            break;
        }
        k.ramp(ramp, target);
        k.hold(hold);
    }
    let back = p.repeat_s - k.end_s();
    k.ramp(back, 0.0);
    k.0
}

/// Knots under construction, starting at (0 s, 0 mm).
struct Knots(Vec<Knot>);

impl Default for Knots {
    fn default() -> Self {
        Self(vec![Knot {
            time_s: 0.0,
            stroke_mm: 0.0,
        }])
    }
}

impl Knots {
    fn end_s(&self) -> f64 {
        self.0.last().map_or(0.0, |k| k.time_s)
    }

    fn ramp(&mut self, duration_s: f64, to_mm: f64) {
        if duration_s > 0.0 {
            let time_s = self.end_s() + duration_s;
            self.0.push(Knot {
                time_s,
                stroke_mm: to_mm,
            });
        }
    }

    fn hold(&mut self, duration_s: f64) {
        let now = self.0.last().map_or(0.0, |k| k.stroke_mm);
        self.ramp(duration_s, now);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn build(kind: ProtocolKind, duration: Option<f64>) -> StrokeProfile {
        let mut rng = Stream::new(1, 0);
        StrokeProfile::built_in(kind, &ProtocolParams::default(), 2.0, duration, &mut rng).unwrap()
    }

    #[test]
    fn natural_durations_match_the_paper() {
        use ProtocolKind::*;
        // The paper's 5 repetitions (1000 s, 3000 s) after 10 s at rest.
        let table = [
            (Characterization, 1010.0),
            (RateDependence, 3010.0),
            (Relaxation, 3010.0),
            (Random, 3010.0),
        ];
        for (kind, dur) in table {
            let p = build(kind, None);
            assert_relative_eq!(p.natural_duration_s(), dur, epsilon = 1e-9);
            assert!(p.knots().last().unwrap().time_s >= dur - 1e-9, "{kind:?}");
            assert_relative_eq!(p.peak_mm(), 2.0, max_relative = 0.05);
            for w in p.knots().windows(2) {
                assert!(w[1].time_s > w[0].time_s, "{kind:?} {w:?}");
            }
        }
    }

    #[test]
    fn characterization_cycles_grow_and_share_one_speed() {
        let p = build(ProtocolKind::Characterization, None);
        let peaks: Vec<f64> = p.knots()[..17]
            .iter()
            .map(|k| k.stroke_mm)
            .filter(|&s| s > 0.0)
            .collect();
        assert_eq!(peaks, vec![0.4, 0.8, 1.2, 1.6, 2.0]);
        // After the 10 s rest, the first cycle rises 0.4 mm in 6 s, the last 2 mm in 30 s.
        assert_relative_eq!(p.knots()[1].time_s, 10.0);
        assert_relative_eq!(p.knots()[2].time_s, 16.0);
    }

    #[test]
    fn rate_dependence_rises_in_ten_to_fifty_seconds() {
        let p = build(ProtocolKind::RateDependence, None);
        let k = p.knots();
        let rises: Vec<f64> = k
            .windows(2)
            .filter(|w| w[1].stroke_mm > w[0].stroke_mm)
            .take(5)
            .map(|w| w[1].time_s - w[0].time_s)
            .collect();
        assert_eq!(rises, vec![10.0, 20.0, 30.0, 40.0, 50.0]);
    }

    #[test]
    fn sampler_interpolates_and_holds() {
        let p = build(ProtocolKind::Characterization, None);
        let mut s = p.sampler();
        assert_eq!(s.at(0.0), 0.0);
        assert_eq!(s.at(10.0), 0.0);
        assert_relative_eq!(s.at(13.0), 0.2, epsilon = 1e-12);
        assert_relative_eq!(s.at(16.0), 0.4, epsilon = 1e-12);
        assert_relative_eq!(s.at(19.0), 0.2, epsilon = 1e-12);
        assert_eq!(s.at(1e9), 0.0);
    }

    #[test]
    fn random_pattern_follows_the_seed() {
        let params = ProtocolParams::default();
        let make = |seed| {
            let mut rng = Stream::new(seed, 0);
            StrokeProfile::built_in(ProtocolKind::Random, &params, 1.0, None, &mut rng).unwrap()
        };
        assert_eq!(make(3), make(3));
        assert_ne!(make(3), make(4));
        let p = make(3);
        assert!(p.knots().iter().all(|k| (0.0..=1.0).contains(&k.stroke_mm)));
        // The pattern repeats every 600 s.
        let mut s = p.sampler();
        let first = s.at(123.4);
        assert_relative_eq!(s.at(723.4), first, epsilon = 1e-9);
    }

    /// Every built-in protocol holds zero stroke for `rest_start_s` and moves right after; the
    /// rest only delays the pattern (the knots with a rest are those without, shifted), and the
    /// random pattern's draws do not change.
    #[test]
    fn every_built_in_protocol_starts_at_rest() {
        use ProtocolKind::*;
        for kind in [Characterization, RateDependence, Relaxation, Random] {
            let with = |rest: f64| {
                let params = ProtocolParams {
                    rest_start_s: rest,
                    ..ProtocolParams::default()
                };
                let mut rng = Stream::new(1, 0);
                StrokeProfile::built_in(kind, &params, 2.0, None, &mut rng).unwrap()
            };
            let p = with(DEFAULT_REST_START_S);
            let mut s = p.sampler();
            for i in 0..=1000 {
                assert_eq!(
                    s.at(i as f64 * 0.01),
                    0.0,
                    "{kind:?} at {}",
                    i as f64 * 0.01
                );
            }
            assert!(s.at(10.5) > 0.0, "{kind:?} does not move after the rest");
            let none = with(0.0);
            assert!(none.sampler().at(0.5) > 0.0, "{kind:?}");
            assert_relative_eq!(
                p.natural_duration_s(),
                none.natural_duration_s() + 10.0,
                epsilon = 1e-9
            );
            assert_eq!(
                p.knots()[0],
                Knot {
                    time_s: 0.0,
                    stroke_mm: 0.0
                }
            );
            for (a, b) in p.knots()[1..].iter().zip(none.knots()) {
                assert_relative_eq!(a.time_s, b.time_s + 10.0, epsilon = 1e-9);
                assert_eq!(a.stroke_mm, b.stroke_mm, "{kind:?}");
            }
        }
    }

    #[test]
    fn duration_beyond_natural_repeats_the_pattern() {
        let p = build(ProtocolKind::Characterization, Some(1100.0));
        assert!(p.knots().last().unwrap().time_s >= 1100.0);
        let mut s = p.sampler();
        let a = s.at(50.0);
        assert_relative_eq!(s.at(1050.0), a, epsilon = 1e-9);
    }

    #[test]
    fn csv_profile_parses_and_reports_lines() {
        let p = StrokeProfile::parse_csv("time_s,stroke_mm\n0,0\n1.5,0.3\r\n3,0\n").unwrap();
        assert_eq!(p.knots().len(), 3);
        assert_eq!(p.natural_duration_s(), 3.0);
        let table = [
            ("time,stroke\n0,0\n", "line 1"),
            ("time_s,stroke_mm\n0,0\n1,nan\n", "line 3"),
            ("time_s,stroke_mm\n0,0\n1,x\n", "\"x\""),
            ("time_s,stroke_mm\n0,0\n2,1\n2,0\n", "does not increase"),
            ("time_s,stroke_mm\n0,0,1\n", "3 fields"),
            ("time_s,stroke_mm\n", "no data rows"),
            ("time_s,stroke_mm\n-1,0\n", "negative"),
        ];
        for (text, needle) in table {
            let err = StrokeProfile::parse_csv(text).unwrap_err().to_string();
            assert!(err.contains(needle), "{text:?}: {err}");
        }
    }
}
