//! A third bench generator for the discovery tests (issue 31), with forms neither the
//! simulator nor the other generators (`other_forms`, `second_generator`) have. It is
//! independent of `dlw simulate`: its own stroke pattern, plant, sensors, noise and random
//! numbers; `rig.toml` holds only the rig, so nothing downstream can read the answer.
//!
//! - **Stroke**: after `REST_S` at rest, segments of two kinds drawn at random: a
//!   minimum-jerk move (1-6 s) to a level drawn over the range (UAN `[0, 1]`, BSN `[−1, 1]` ×
//!   the peak stroke) followed by a hold of 0.5-15 s; or a burst of 2-4 sinusoidal cycles
//!   (period 2-8 s, amplitude 10-40 % of the range) about the current level.
//! - **Plant**: `θ = GAIN_DEG_PER_MM·s`, and with [`Effect::Relaxation`] a relaxation with a
//!   spread of time constants: eight Prony terms log-spaced from 0.3 s to 300 s with equal
//!   fractions (a spectrum flat per decade, the discrete form of a fractional kernel), of total
//!   fraction [`RELAXATION_FRACTION`].
//! - **Sensor** (Eq. 3 strain; sensor 2 of a BSN joint feels `−ε`): `R = R₀·(1 + G·f(ε)·g(t)) +
//!   extras` with, when on,
//!   - [`Effect::Saturation`]: a curve that is not odd: `ε_s⁺·(1 − e^(−ε/ε_s⁺))` in tension,
//!     `ε/(1 + |ε|/ε_s⁻)` in compression with `ε_s⁻ = 2.5·ε_s⁺`;
//!   - [`Effect::Hysteresis`]: a Preisach model, relays on a 24 × 24 grid of switching strains
//!     over the strain range with a Gaussian density about the diagonal;
//!   - [`Effect::Creep`]: six first-order creeps log-spaced from 2 s to 200 s, equal fractions;
//!   - [`Effect::Drift`]: the baseline follows a random walk;
//!   - [`Effect::GainWalk`] (outside the library): the sensitivity follows a random walk;
//!   - [`Effect::GainCycle`] (outside the library): the sensitivity cycles,
//!     `1 + A·sin(2πt/P + φ)`, at a period `P` drawn from 250-700 s.
//! - **Noise**, on the divider voltage and on the tracker angle: white plus a sum of four AR(1)
//!   processes with correlation times 0.2, 0.8, 3.2 and 12.8 s of equal spread (close to 1/f
//!   over two decades), unlike the others' one AR(1). Wander slower than that, a minute or
//!   more, is what discovery calls a drift (a baseline that changes over the run), not noise.
//!
//! Sizes: every effect has a size [`Size`] (×0.5, ×1, ×2 of the constants below, and the
//! larger ×4 and ×8 of [`Size::LARGE`] to find where discovery starts to see an effect),
//! stated relative to the sensor's span. Joint C's sensors are about forty times less sensitive
//! than Joint A's under the same voltage noise, so a BSN sensor's effects are
//! [`BSN_SENSOR_SCALE`] times larger (×2, ×4, ×8 of the constants), as the matrix's Joint C
//! effects are; the plant's (the tracker's noise is the same on both) are not. A size only
//! multiplies the constants: ×0.5, ×1 and ×2 give the same recordings whatever larger sizes
//! exist.
//!
//! Where a size stops being physical ([`Effect::largest_physical`], as a multiple of the
//! constants, before Joint C's ×4): the relaxation at a total fraction of 1 (×10: a hold would
//! relax the angle past zero); the creep at a fraction of 1 (×10: a creep larger than the
//! elastic response it follows); the Preisach loop when its height reaches the span (×8.3: a
//! loop as tall as the whole response); the random-walk gain at ×4 (its excursion's spread is
//! then 0.24, and the sensitivity reaches zero on about 3 seeds in 100 000; at ×8 on about 4 %
//! of them); the cycling gain when its amplitude reaches 1 (×20: the sensitivity changes sign).
//! The saturation (a smaller `ε_s⁺`) and the drift (a wandering baseline, far below `R₀` at
//! ×8) stay physical. So on Joint A every effect is physical up to ×4, and at ×8 all but the
//! random-walk gain. On Joint C (×4 the constants already) the random-walk gain is past
//! physical from ×2 (a size `DLW_DISCOVER_FULL` runs), the creep and the hysteresis from ×4, the
//! cycling gain at ×8; the relaxation, the saturation and the drift stay physical.
#![allow(dead_code)]

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

use dlw::design::Design;
use dlw_geometry::{Divider, NotchStyle};

use super::rng::Rng;

/// Sample rate (Hz).
pub const SAMPLE_HZ: f64 = 500.0;
/// Divider supply (V).
pub const SUPPLY_V: f64 = 5.0;
/// Rest at the start (s).
pub const REST_S: f64 = 10.0;
/// The plant's gain (°/mm): neither the simulator's 35.49 nor the other generator's 31.
pub const GAIN_DEG_PER_MM: f64 = 33.0;
/// Peak strain of the stroke pattern.
pub const PEAK_STRAIN: f64 = 0.013;
/// Relaxation: total fraction of the eight Prony terms at size ×1.
pub const RELAXATION_FRACTION: f64 = 0.10;
/// Relaxation: the terms' time constants, log-spaced over this range (s).
pub const RELAXATION_TAUS_S: (f64, f64) = (0.3, 300.0);
/// Creep: total fraction of the resistance change at size ×1.
pub const CREEP_FRACTION: f64 = 0.10;
/// Creep: the six terms' time constants, log-spaced over this range (s).
pub const CREEP_TAUS_S: (f64, f64) = (2.0, 200.0);
/// Saturation: `ε_s⁺` at size ×1 (the size divides it).
pub const SATURATION_STRAIN: f64 = 0.025;
/// Preisach hysteresis: the loop's half-height at size ×1, as a fraction of the span, and the
/// spread of its relay density off the diagonal, as a fraction of the strain range.
pub const PREISACH: (f64, f64) = (0.06, 0.25);
/// Random-walk drift: its expected excursion at the end at size ×1, as a fraction of the span
/// (Joint A: 1.3 kΩ over 300 s, 75 Ω/√s; the simulator's default random walk is 20 Ω/√s).
pub const DRIFT_WALK: f64 = 0.04;
/// Random-walk gain: its expected excursion at the end at size ×1.
pub const GAIN_WALK: f64 = 0.06;
/// Cycling gain: amplitude at size ×1, and the range its period is drawn from (s).
pub const GAIN_CYCLE: (f64, (f64, f64)) = (0.05, (250.0, 700.0));

/// A BSN joint's sensor effects are this many times the constants (module docs).
pub const BSN_SENSOR_SCALE: f64 = 4.0;

/// Voltage noise (V): white, and the spread of each of the four AR(1) terms.
pub const NOISE_V: (f64, f64) = (0.0018, 0.0008);
/// Tracker noise (°): white, and the spread of each AR(1) term.
pub const NOISE_DEG: (f64, f64) = (0.12, 0.07);
/// Correlation times of the AR(1) terms (s).
pub const NOISE_TAUS_S: [f64; 4] = [0.2, 0.8, 3.2, 12.8];

/// An effect of the third generator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Effect {
    /// Prony relaxation with a spread of time constants (plant).
    Relaxation,
    /// Creep with a spread of time constants (sensor).
    Creep,
    /// Preisach hysteresis (sensor).
    Hysteresis,
    /// A saturation that is not odd (sensor).
    Saturation,
    /// A random-walk baseline (sensor).
    Drift,
    /// A random-walk sensitivity (sensor; outside the library).
    GainWalk,
    /// A sensitivity cycling at a random period (sensor; outside the library).
    GainCycle,
}

impl Effect {
    /// All of them.
    pub const ALL: [Effect; 7] = [
        Effect::Relaxation,
        Effect::Creep,
        Effect::Hysteresis,
        Effect::Saturation,
        Effect::Drift,
        Effect::GainWalk,
        Effect::GainCycle,
    ];

    /// The library name `dlw discover` should give, `None` outside the library.
    pub fn name(self) -> Option<&'static str> {
        match self {
            Effect::Relaxation => Some("relaxation"),
            Effect::Creep => Some("creep"),
            Effect::Hysteresis => Some("hysteresis"),
            Effect::Saturation => Some("saturation"),
            Effect::Drift => Some("drift"),
            Effect::GainWalk | Effect::GainCycle => None,
        }
    }

    /// A short tag for file names.
    pub fn tag(self) -> &'static str {
        match self {
            Effect::Relaxation => "relaxation",
            Effect::Creep => "creep",
            Effect::Hysteresis => "hysteresis",
            Effect::Saturation => "saturation",
            Effect::Drift => "drift",
            Effect::GainWalk => "gain-walk",
            Effect::GainCycle => "gain-cycle",
        }
    }

    /// Whether it acts on the plant.
    pub fn is_plant(self) -> bool {
        self == Effect::Relaxation
    }

    /// The largest size at which the effect is physical on a UAN joint (`bsn = false`) or a
    /// BSN one, whose sensor effects are [`BSN_SENSOR_SCALE`] times larger (module docs).
    pub fn largest_physical(self, bsn: bool) -> f64 {
        let constants = match self {
            // Total fraction 1.
            Effect::Relaxation => 1.0 / RELAXATION_FRACTION,
            Effect::Creep => 1.0 / CREEP_FRACTION,
            // A loop as tall as the span.
            Effect::Hysteresis => 0.5 / PREISACH.0,
            Effect::Saturation | Effect::Drift => f64::INFINITY,
            // The excursion's spread 0.24: the gain reaches zero on about 3e-5 of seeds.
            Effect::GainWalk => 0.24 / GAIN_WALK,
            // An amplitude of 1.
            Effect::GainCycle => 1.0 / GAIN_CYCLE.0,
        };
        if bsn && !self.is_plant() {
            constants / BSN_SENSOR_SCALE
        } else {
            constants
        }
    }
}

/// An effect's size: a multiple of the constants above.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size(pub f64);

impl Size {
    /// The three sizes of the tests.
    pub const ALL: [Size; 3] = [Size(0.5), Size(1.0), Size(2.0)];
    /// Two larger sizes, to measure where an effect is first seen (module docs: not every
    /// effect is physical at ×8).
    pub const LARGE: [Size; 2] = [Size(4.0), Size(8.0)];
}

/// What to generate.
#[derive(Debug, Clone)]
pub struct Bench {
    /// The effect (none: a clean recording), its size, and the sensor (1 or 2) it acts on.
    pub effect: Option<(Effect, Size, usize)>,
    /// Length (s), the rest included.
    pub duration_s: f64,
    /// Seed of the pattern, the noise and the effects' random draws.
    pub seed: u64,
}

/// Coloured noise: white plus four AR(1) terms.
struct Coloured {
    white: f64,
    terms: Vec<(f64, f64, f64)>,
}

impl Coloured {
    fn new(white: f64, spread: f64, rng: &mut Rng) -> Self {
        let terms = NOISE_TAUS_S
            .iter()
            .map(|tau| {
                let phi = (-1.0 / (SAMPLE_HZ * tau)).exp();
                (phi, spread, spread * rng.normal())
            })
            .collect();
        Self { white, terms }
    }

    fn next(&mut self, rng: &mut Rng) -> f64 {
        let mut v = self.white * rng.normal();
        for (phi, spread, state) in &mut self.terms {
            *state = *phi * *state + (1.0 - *phi * *phi).sqrt() * *spread * rng.normal();
            v += *state;
        }
        v
    }
}

/// The stroke pattern (mm).
fn stroke_pattern(n: usize, peak_mm: f64, two_sided: bool, rng: &mut Rng) -> Vec<f64> {
    let mut out = vec![0.0; ((REST_S * SAMPLE_HZ) as usize).min(n)];
    let mut level = 0.0_f64;
    let (lo, hi) = if two_sided {
        (-peak_mm, peak_mm)
    } else {
        (0.0, peak_mm)
    };
    while out.len() < n {
        if rng.uniform() < 0.7 {
            let target = lo + (hi - lo) * rng.uniform();
            let steps = ((1.0 + 5.0 * rng.uniform()) * SAMPLE_HZ) as usize;
            for k in 1..=steps {
                let u = k as f64 / steps as f64;
                let w = u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
                out.push(level + (target - level) * w);
            }
            let hold = ((0.5 + 14.5 * rng.uniform()) * SAMPLE_HZ) as usize;
            out.extend(std::iter::repeat(target).take(hold));
            level = target;
        } else {
            let period = 2.0 + 6.0 * rng.uniform();
            let cycles = 2 + (rng.uniform() * 3.0) as usize;
            let amplitude = (0.1 + 0.3 * rng.uniform()) * (hi - lo);
            // About the current level, kept inside the range.
            let centre = level.clamp(lo + amplitude, hi - amplitude);
            let steps = (period * cycles as f64 * SAMPLE_HZ) as usize;
            // Ease from the level to the centre over the first quarter cycle.
            for k in 1..=steps {
                let t = k as f64 / SAMPLE_HZ;
                let ease = (t / (0.25 * period)).min(1.0);
                let base = level + (centre - level) * ease;
                out.push(base + amplitude * (2.0 * PI * t / period).sin() * ease);
            }
            level = *out.last().unwrap_or(&level);
        }
    }
    out.truncate(n);
    out
}

/// Preisach hysteresis: relays on a grid of switching strains `(α ≥ β)`, each `+1` once the
/// input passes `α`, `−1` once it falls below `β`, weighted by a Gaussian density about the
/// diagonal; the output is the weighted mean state (−1 … 1).
struct Preisach {
    relays: Vec<(f64, f64, f64, f64)>,
    total: f64,
}

impl Preisach {
    fn new(lo: f64, hi: f64, spread: f64) -> Self {
        let k = 24;
        let step = (hi - lo) / (k - 1) as f64;
        let mut relays = Vec::new();
        let mut total = 0.0;
        for i in 0..k {
            for j in 0..=i {
                let (alpha, beta) = (lo + step * i as f64, lo + step * j as f64);
                let width = (alpha - beta) / ((hi - lo) * spread);
                let weight = (-0.5 * width * width).exp();
                relays.push((alpha, beta, weight, -1.0));
                total += weight;
            }
        }
        Self { relays, total }
    }

    fn step(&mut self, x: f64) -> f64 {
        let mut out = 0.0;
        for (alpha, beta, weight, state) in &mut self.relays {
            if x >= *alpha {
                *state = 1.0;
            } else if x <= *beta {
                *state = -1.0;
            }
            out += *weight * *state;
        }
        out / self.total
    }
}

/// Log-spaced time constants.
fn log_spaced(range: (f64, f64), k: usize) -> Vec<f64> {
    (0..k)
        .map(|i| range.0 * (range.1 / range.0).powf(i as f64 / (k - 1) as f64))
        .collect()
}

/// Writes the recording of `bench` for the design file `design` into `out` (created).
pub fn write_recording(design: &Path, bench: &Bench, out: &Path) {
    let design = Design::load(design).expect("the design loads");
    let joint = design.joint;
    let bsn = joint.style() == NotchStyle::Bsn;
    let sensors = if bsn { 2 } else { 1 };
    let constants: [(f64, f64); 2] = if bsn {
        [(74_000.0, 1.28), (88_900.0, 0.68)]
    } else {
        [(180_000.0, 14.0), (180_000.0, 14.0)]
    };
    let dividers = [99_600.0, 102_500.0];
    let n = (bench.duration_s * SAMPLE_HZ) as usize;
    let dt = 1.0 / SAMPLE_HZ;
    let mut rng = Rng::new(bench.seed ^ 0x3C6E_F372_FE94_F82B);
    let peak_deg = PEAK_STRAIN / joint.strain_per_deg();
    let strokes = stroke_pattern(n, peak_deg / GAIN_DEG_PER_MM, bsn, &mut rng);
    let on = |e: Effect| {
        bench
            .effect
            .filter(|(x, ..)| *x == e)
            .map(|(_, s, k)| (s.0, k))
    };

    // Plant.
    let taus = log_spaced(RELAXATION_TAUS_S, 8);
    let mut states = vec![0.0_f64; taus.len()];
    let angles: Vec<f64> = strokes
        .iter()
        .map(|&s| {
            let elastic = GAIN_DEG_PER_MM * s;
            let mut theta = elastic;
            if let Some((size, _)) = on(Effect::Relaxation) {
                let share = size * RELAXATION_FRACTION / taus.len() as f64;
                for (state, tau) in states.iter_mut().zip(&taus) {
                    *state += (share * elastic - *state) * (1.0 - (-dt / tau).exp());
                    theta -= *state;
                }
            }
            theta
        })
        .collect();

    // Sensors.
    let strain: Vec<f64> = angles
        .iter()
        .map(|a| joint.strain(a.to_radians()))
        .collect();
    let peak = strain.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
    // The effects' own random draws come from their own stream, so a clean twin (the same
    // seed without the effect) has the same noise.
    let mut effect_rng = Rng::new(bench.seed ^ 0x9B05_688C_2B3E_6C1F);
    let cycle_period = GAIN_CYCLE.1 .0 + (GAIN_CYCLE.1 .1 - GAIN_CYCLE.1 .0) * effect_rng.uniform();
    let cycle_phase = 2.0 * PI * effect_rng.uniform();
    let mut volts = vec![Vec::with_capacity(n); sensors];
    for (k, v) in volts.iter_mut().enumerate() {
        let sensor = k + 1;
        let (r0, gf) = constants[k];
        let span_ohm = r0 * gf * peak;
        let sign = if sensor == 2 { -1.0 } else { 1.0 };
        let scale = if bsn { BSN_SENSOR_SCALE } else { 1.0 };
        let here = |e: Effect| {
            on(e)
                .filter(|(_, s)| *s == sensor)
                .map(|(size, _)| scale * size)
        };
        let divider = Divider {
            fixed_ohm: dividers[k],
            supply_v: SUPPLY_V,
        };
        let mut noise = Coloured::new(NOISE_V.0, NOISE_V.1, &mut rng);
        let (lo, hi) = if bsn { (-peak, peak) } else { (0.0, peak) };
        let mut preisach = Preisach::new(lo, hi, PREISACH.1);
        let creep_taus = log_spaced(CREEP_TAUS_S, 6);
        let mut creep = vec![0.0_f64; creep_taus.len()];
        let (mut drift, mut gain_walk) = (0.0_f64, 0.0_f64);
        let duration = bench.duration_s;
        for (i, &e) in strain.iter().enumerate() {
            let t = i as f64 * dt;
            let felt = sign * e;
            let mut x = felt;
            if let Some(size) = here(Effect::Saturation) {
                let plus = SATURATION_STRAIN / size;
                x = if felt >= 0.0 {
                    plus * (1.0 - (-felt / plus).exp())
                } else {
                    felt / (1.0 + felt.abs() / (2.5 * plus))
                };
            }
            let mut change = r0 * gf * x;
            if let Some(size) = here(Effect::Hysteresis) {
                change += size * PREISACH.0 * span_ohm * preisach.step(felt);
            }
            let mut gain = 1.0;
            if let Some(size) = here(Effect::GainWalk) {
                gain_walk += GAIN_WALK * size * (dt / duration).sqrt() * effect_rng.normal();
                gain += gain_walk;
            }
            if let Some(size) = here(Effect::GainCycle) {
                gain += GAIN_CYCLE.0 * size * (2.0 * PI * t / cycle_period + cycle_phase).sin();
            }
            change *= gain;
            let mut ohm = r0 + change;
            if let Some(size) = here(Effect::Creep) {
                let share = size * CREEP_FRACTION / creep_taus.len() as f64;
                for (state, tau) in creep.iter_mut().zip(&creep_taus) {
                    *state += (share * change - *state) * (1.0 - (-dt / tau).exp());
                    ohm += *state;
                }
            }
            if let Some(size) = here(Effect::Drift) {
                drift +=
                    DRIFT_WALK * size * span_ohm * (dt / duration).sqrt() * effect_rng.normal();
                ohm += drift;
            }
            let reading = divider.voltage(ohm) + noise.next(&mut rng);
            v.push(reading.clamp(1e-3, SUPPLY_V - 1e-3));
        }
    }
    let mut tracker = Coloured::new(NOISE_DEG.0, NOISE_DEG.1, &mut rng);
    let mut csv = String::from("time_s,stroke_mm,angle_deg,v1_V");
    if bsn {
        csv.push_str(",v2_V");
    }
    csv.push('\n');
    for i in 0..n {
        let t = i as f64 * dt;
        let angle = angles[i] + tracker.next(&mut rng);
        write!(csv, "{t:.6},{:.6},{angle:.4}", strokes[i]).unwrap();
        for v in &volts {
            write!(csv, ",{:.6}", v[i]).unwrap();
        }
        csv.push('\n');
    }
    std::fs::create_dir_all(out).unwrap();
    let divider_list = dividers[..sensors]
        .iter()
        .map(|d| format!("{d:?}"))
        .collect::<Vec<_>>()
        .join(", ");
    std::fs::write(
        out.join("rig.toml"),
        format!(
            "sample_hz = {SAMPLE_HZ:?}\nsupply_v = {SUPPLY_V:?}\ndivider_ohm = [{divider_list}]\nnotes = \"third generator, seed {}\"\n",
            bench.seed
        ),
    )
    .unwrap();
    std::fs::write(out.join("data.csv"), csv).unwrap();
}

/// The realized size of a random-walk effect of `bench` (the drift, the random-walk gain), or
/// its nominal size for the others: the nominal size times the spread of its walk about its
/// mean over the motion, relative to that spread's expectation (a walk from zero whose end has a
/// spread of one: √(1/6)). A random walk's path, not its nominal size, is what a recording
/// shows: one seed's walk at ×8 can wander less than another's at ×1 (the draws are the same as
/// [`write_recording`]'s, in the same order).
pub fn realized_size(bench: &Bench) -> Option<f64> {
    let (effect, size, _) = bench.effect?;
    if !matches!(effect, Effect::Drift | Effect::GainWalk) {
        return Some(size.0);
    }
    let n = (bench.duration_s * SAMPLE_HZ) as usize;
    let dt = 1.0 / SAMPLE_HZ;
    let mut effect_rng = Rng::new(bench.seed ^ 0x9B05_688C_2B3E_6C1F);
    // The cycle's period and phase come first.
    effect_rng.uniform();
    effect_rng.uniform();
    let step = (dt / bench.duration_s).sqrt();
    let rest = (REST_S * SAMPLE_HZ) as usize;
    let mut walk = 0.0;
    let mut path = Vec::with_capacity(n - rest.min(n));
    for i in 0..n {
        walk += step * effect_rng.normal();
        if i >= rest {
            path.push(walk);
        }
    }
    let mean = path.iter().sum::<f64>() / path.len() as f64;
    let spread = (path.iter().map(|w| (w - mean).powi(2)).sum::<f64>() / path.len() as f64).sqrt();
    Some(size.0 * spread / (1.0_f64 / 6.0).sqrt())
}
