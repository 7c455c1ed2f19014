//! A bench generator for discovery tests whose effects have other functional forms than the
//! simulator's (issue 9, section 3: "a real joint does not follow our simulator's equations").
//!
//! It is independent of `dlw simulate`: its own stroke pattern, plant, sensor, noise and random
//! numbers. It writes a recording folder in the documented format (`docs/recording-format.md`),
//! and `rig.toml` holds only the rig (no `[scenario]` table), so nothing downstream can read the
//! answer from the file.
//!
//! - **Stroke**: `REST_S` at rest, then ramps of 1.5-8 s to levels drawn uniformly over the
//!   range (UAN: `[0, 1]`; BSN: `[−1, 1]` × the peak stroke), each followed by a hold of 1-12 s.
//! - **Plant**: `θ = GAIN_DEG_PER_MM · s_eff` with, when on,
//!   - [`Effect::Relaxation`]: a two-term Prony series (time constants 3 s and 35 s, fractions
//!     0.04 and 0.05) instead of the simulator's one standard linear solid;
//!   - [`Effect::Backlash`]: a *soft* dead band. While the stroke moves away from the joint's
//!     side of the gap, the joint follows with the weight `smoothstep(|gap|/h)`: it does not
//!     move at a reversal, engages gradually and follows fully once the gap reaches `h`
//!     (`h` = `BACKLASH_MM`, wider on the unloading side with [`Forms::backlash_asymmetry`]).
//!     The simulator's play operator engages at once.
//! - **Sensor** (Eq. 3 strain from the geometry crate; sensor 2 of a BSN joint feels `−ε`):
//!   `R = R₀·(1 + G·f(ε)) + extras` with, when on,
//!   - [`Effect::Hysteresis`]: a Bouc-Wen state added to the strain (no play operators);
//!   - [`Effect::Saturation`]: a rational curve `f(ε) = ε/(1 + |ε|/ε_s)` instead of tanh, or
//!     another memoryless shape ([`Saturation`]: algebraic, power law, piecewise linear);
//!   - [`Effect::Rate`]: a signed square-root response `c·sign(ṙ)·√(|ṙ|/ṙ₀)` to the low-passed
//!     strain rate (not proportional, not logarithmic);
//!   - [`Effect::Creep`]: two first-order creeps (3 s and 40 s) of the resistance change;
//!   - [`Effect::Drift`]: an exponential warm-up of the baseline, `D·(1 − e^(−t/T))`, or a
//!     square root of time ([`Forms::drift_sqrt`]); neither linear in time nor a random walk.
//! - **Outside the library** ([`Outside`], on [`Forms::outside_sensor`]): a sensitivity that
//!   fades (settling, in a step, by cycles), follows a slow sinusoid, or a sensor that stiffens,
//!   has a dead zone, a quadratic term, or an offset above a strain.
//! - **Noise**, on the divider voltage and on the tracker angle: white plus AR(1) with other
//!   correlation times than the simulator's (0.7 s on the voltage, 2.5 s on the angle).
//!
//! Effect sizes are stated relative to the sensor's span over the recording (`SIZE_*`), so the
//! same generator serves a sensitive UAN sensor and Joint C's insensitive BSN sensors.
#![allow(dead_code)]

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

use dlw::design::Design;
use dlw_geometry::{Divider, NotchStyle};

use super::rng::{Noise, Rng};

/// Sample rate (Hz).
pub const SAMPLE_HZ: f64 = 500.0;
/// Divider supply (V).
pub const SUPPLY_V: f64 = 5.0;
/// Rest at the start (s): a bench recording starts with the joint at rest.
pub const REST_S: f64 = 10.0;
/// The plant's gain (°/mm): not the simulator's 35.49, so calibration has work to do.
pub const GAIN_DEG_PER_MM: f64 = 31.0;
/// Peak strain of the stroke pattern.
pub const PEAK_STRAIN: f64 = 0.014;
/// Soft backlash: the gap at which the joint follows fully (mm), 1.9° of angle at the gain.
pub const BACKLASH_MM: f64 = 0.06;
/// Relaxation: `(fraction, time constant in s)` of each Prony term.
pub const RELAXATION: [(f64, f64); 2] = [(0.04, 3.0), (0.05, 35.0)];
/// Hysteresis: Bouc-Wen constants `(β, γ)` (`A = 1`, `n = 1`) and its weight in strain.
pub const BOUC_WEN: (f64, f64, f64) = (350.0, 150.0, 1.2);
/// Saturation strain of the rational curve.
pub const SATURATION_STRAIN: f64 = 0.04;
/// Rate: reference rate (1/s), low-pass time constant (s), size as a fraction of the span.
pub const RATE: (f64, f64, f64) = (0.002, 0.4, 0.08);
/// Creep: `(fraction of ΔR, time constant in s)` of each term.
pub const CREEP: [(f64, f64); 2] = [(0.05, 3.0), (0.06, 40.0)];
/// Drift: size as a fraction of the span, and the warm-up time constant (s).
pub const DRIFT: (f64, f64) = (0.25, 120.0);

/// White and AR(1) noise on the voltage (V), and the AR correlation time (s).
pub const NOISE_V: (f64, f64, f64) = (0.002, 0.0015, 0.7);
/// White and AR(1) noise on the tracker angle (°), and the AR correlation time (s).
pub const NOISE_DEG: (f64, f64, f64) = (0.15, 0.12, 2.5);

/// An effect of the generator, named as `dlw discover` names the simulator's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Effect {
    /// Soft dead band in the tendon (plant).
    Backlash,
    /// Prony-series relaxation (plant).
    Relaxation,
    /// Bouc-Wen hysteresis (sensor).
    Hysteresis,
    /// Rational saturation (sensor).
    Saturation,
    /// Signed square-root rate response (sensor).
    Rate,
    /// Two-term creep (sensor).
    Creep,
    /// Exponential warm-up drift (sensor).
    Drift,
}

impl Effect {
    /// All seven.
    pub const ALL: [Effect; 7] = [
        Effect::Backlash,
        Effect::Relaxation,
        Effect::Hysteresis,
        Effect::Saturation,
        Effect::Rate,
        Effect::Creep,
        Effect::Drift,
    ];

    /// The name `dlw discover` reports.
    pub fn name(self) -> &'static str {
        match self {
            Effect::Backlash => "backlash",
            Effect::Relaxation => "relaxation",
            Effect::Hysteresis => "hysteresis",
            Effect::Saturation => "saturation",
            Effect::Rate => "rate",
            Effect::Creep => "creep",
            Effect::Drift => "drift",
        }
    }

    /// Whether it acts on the plant (else on a sensor).
    pub fn is_plant(self) -> bool {
        matches!(self, Effect::Backlash | Effect::Relaxation)
    }
}

/// The memoryless curve of [`Effect::Saturation`]: four shapes, none of them the simulator's
/// `ε_s·tanh(ε/ε_s)`, all with a sensitivity that falls with strain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Saturation {
    /// Rational: `ε/(1 + |ε|/ε_s)`.
    #[default]
    Rational,
    /// Algebraic: `ε/√(1 + (ε/ε_s)²)`.
    Algebraic,
    /// Power law: `sign(ε)·ε_p·(|ε|/ε_p)^0.8`, with `ε_p` the peak strain: a sublinear curve
    /// with no knee.
    Power,
    /// Piecewise linear: slope 1 up to half the peak strain, slope 0.55 beyond (a knee).
    Piecewise,
}

/// Extra forms of the plant and the drift (all off by default, as the generator always was).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Forms {
    /// The saturation's shape.
    pub saturation: Saturation,
    /// Backlash asymmetry: the gap on the unloading side is this many times the loading side's
    /// (1: symmetric, the default).
    pub backlash_asymmetry: Option<f64>,
    /// Drift as a square root of time, `D·√(t/T_end)`, instead of the exponential warm-up.
    pub drift_sqrt: bool,
    /// The plant effects' size, times the constants above (1 when `None`).
    pub plant_scale: Option<f64>,
    /// An effect outside the library, on [`Forms::outside_sensor`]'s sensor.
    pub outside: Option<Outside>,
    /// The sensor (1 or 2) the out-of-library effect acts on (1 when 0).
    pub outside_sensor: usize,
}

/// Effects a real sensor has that the library lacks: a sensitivity that changes over the run
/// in other forms than the library's `gain_drift` (linear in time), and curves or offsets no
/// library effect draws. None of them may be named as one of the seven library effects; each
/// is to be flagged `unexplained`, or a change of sensitivity named `gain_drift`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outside {
    /// The sensitivity fades as `1 − F·(1 − e^(−t/T))` ([`GAIN_FADE`], `T` a fraction of the
    /// run): fatigue that settles.
    GainFade,
    /// The sensitivity drops by [`GAIN_STEP`] at the middle of the run (a crack opening).
    GainStep,
    /// The sensitivity fades in proportion to the strain travelled so far (fatigue by cycles,
    /// not by time), by [`GAIN_CYCLES`] at the end.
    GainCycles,
    /// The sensitivity follows a slow sinusoid, `1 + A·sin(2πt/P)` ([`GAIN_SINE`], `P` a
    /// fraction of the run): a temperature that drifts up and down.
    GainSine,
    /// The sensor stiffens: `f(ε) = ε·(1 + |ε|/ε_k)` ([`STIFFENING_STRAIN`]), its sensitivity
    /// rising with strain.
    Stiffening,
    /// A dead zone: no response below [`DEAD_ZONE`] × the peak strain,
    /// `f(ε) = sign(ε)·max(|ε| − ε_d, 0)`.
    DeadZone,
    /// A quadratic term, `f(ε) = ε + ε²/ε_q` ([`QUADRATIC_STRAIN`]): stiffening on one side,
    /// softening on the other (two-sided strain on a BSN joint).
    Quadratic,
    /// A strain-dependent offset: above half the peak strain the resistance jumps by
    /// [`OFFSET_STEP`] × the span (a crack that opens at a strain).
    OffsetStep,
}

impl Outside {
    /// All of them.
    pub const ALL: [Outside; 8] = [
        Outside::GainFade,
        Outside::GainStep,
        Outside::GainCycles,
        Outside::GainSine,
        Outside::Stiffening,
        Outside::DeadZone,
        Outside::Quadratic,
        Outside::OffsetStep,
    ];
}

/// Out-of-library gain fade: the fraction lost in the end `F` and its time constant `T` as a
/// fraction of the run.
pub const GAIN_FADE: (f64, f64) = (0.25, 0.5);
/// Out-of-library gain step: the fraction lost at the middle of the run.
pub const GAIN_STEP: f64 = 0.15;
/// Out-of-library fade by cycles: the fraction lost by the end of the strain travelled.
pub const GAIN_CYCLES: f64 = 0.25;
/// Out-of-library temperature-like gain: amplitude `A` and period `P` as a fraction of the run.
pub const GAIN_SINE: (f64, f64) = (0.1, 0.5);
/// Out-of-library stiffening: the strain at which the sensitivity has doubled.
pub const STIFFENING_STRAIN: f64 = 0.02;
/// Out-of-library dead zone, as a fraction of the peak strain.
pub const DEAD_ZONE: f64 = 0.15;
/// Out-of-library quadratic term: the strain at which it equals the linear one.
pub const QUADRATIC_STRAIN: f64 = 0.03;
/// Out-of-library strain-dependent offset, as a fraction of the span.
pub const OFFSET_STEP: f64 = 0.05;

/// What to generate.
#[derive(Debug, Clone, Default)]
pub struct Bench {
    /// Effects switched on, with the sensor (1 or 2) a sensor effect acts on.
    pub effects: Vec<(Effect, usize)>,
    /// Length (s), the rest included.
    pub duration_s: f64,
    /// Seed of the pattern and the noise.
    pub seed: u64,
    /// The shapes of the effects.
    pub forms: Forms,
}

fn smoothstep(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    u * u * (3.0 - 2.0 * u)
}

/// The stroke pattern (mm) at every sample: rest, then ramps and holds.
fn stroke_pattern(n: usize, peak_mm: f64, two_sided: bool, rng: &mut Rng) -> Vec<f64> {
    let mut out = Vec::with_capacity(n);
    let rest = (REST_S * SAMPLE_HZ) as usize;
    out.resize(rest.min(n), 0.0);
    let mut level = 0.0;
    while out.len() < n {
        let u = rng.uniform();
        let target = if two_sided { 2.0 * u - 1.0 } else { u } * peak_mm;
        let ramp = ((1.5 + 6.5 * rng.uniform()) * SAMPLE_HZ) as usize;
        let hold = ((1.0 + 11.0 * rng.uniform()) * SAMPLE_HZ) as usize;
        for k in 1..=ramp {
            let w = (1.0 - (PI * k as f64 / ramp as f64).cos()) / 2.0;
            out.push(level + (target - level) * w);
        }
        out.extend(std::iter::repeat(target).take(hold));
        level = target;
    }
    out.truncate(n);
    out
}

/// Writes the recording of `bench` for the design file `design` into `out` (created).
pub fn write_recording(design: &Path, bench: &Bench, out: &Path) {
    let design = Design::load(design).expect("the design loads");
    let joint = design.joint;
    let bsn = joint.style() == NotchStyle::Bsn;
    let sensors = if bsn { 2 } else { 1 };
    // Sensor constants: Joint C's (Table V) for BSN, a sensitive graphene trace for UAN.
    let (r0, gf) = if bsn {
        (74_000.0, 1.28)
    } else {
        (215_000.0, 12.0)
    };
    let dividers = [99_600.0, 102_500.0];
    let has = |e: Effect, sensor: usize| {
        bench
            .effects
            .iter()
            .any(|&(x, s)| x == e && (e.is_plant() || s == sensor))
    };
    let n = (bench.duration_s * SAMPLE_HZ) as usize;
    let dt = 1.0 / SAMPLE_HZ;
    // Another stream than the second generator's for the same seed.
    let mut rng = Rng::new(bench.seed ^ 0xD1B5_4A32_D192_ED03);
    let peak_deg = PEAK_STRAIN / joint.strain_per_deg();
    let strokes = stroke_pattern(n, peak_deg / GAIN_DEG_PER_MM, bsn, &mut rng);

    // Plant.
    let mut s_eff = 0.0_f64;
    let mut last_stroke = 0.0_f64;
    let mut prony = [0.0_f64; 2];
    let mut angles = Vec::with_capacity(n);
    let plant_scale = bench.forms.plant_scale.unwrap_or(1.0);
    let asymmetry = bench.forms.backlash_asymmetry.unwrap_or(1.0);
    for &s in &strokes {
        let s_used = if has(Effect::Backlash, 0) {
            let ds = s - last_stroke;
            // The gap's width on the side the stroke moves toward.
            let h = plant_scale * BACKLASH_MM * if ds >= 0.0 { 1.0 } else { asymmetry };
            let gap = s - s_eff;
            if ds * gap > 0.0 {
                s_eff += ds * smoothstep(gap.abs() / h);
            }
            // A gap never exceeds h: past it the joint follows exactly.
            let gap = s - s_eff;
            if gap.abs() > h {
                s_eff = s - h * gap.signum();
            }
            s_eff
        } else {
            s
        };
        last_stroke = s;
        let elastic = GAIN_DEG_PER_MM * s_used;
        let mut theta = elastic;
        if has(Effect::Relaxation, 0) {
            for (state, (fraction, tau)) in prony.iter_mut().zip(RELAXATION) {
                *state += (plant_scale * fraction * elastic - *state) * (1.0 - (-dt / tau).exp());
                theta -= *state;
            }
        }
        angles.push(theta);
    }

    // Sensors.
    let strain: Vec<f64> = angles
        .iter()
        .map(|a| joint.strain(a.to_radians()))
        .collect();
    let span_strain = strain.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
    let span_ohm = r0 * gf * span_strain;
    let mut volts = vec![Vec::with_capacity(n); sensors];
    for (k, v) in volts.iter_mut().enumerate() {
        let sensor = k + 1;
        let sign = if sensor == 2 { -1.0 } else { 1.0 };
        let divider = Divider {
            fixed_ohm: dividers[k],
            supply_v: SUPPLY_V,
        };
        let (mut z, mut last) = (0.0_f64, 0.0_f64);
        let mut rate = 0.0_f64;
        let mut creep = [0.0_f64; 2];
        let (white, ar, tau) = NOISE_V;
        let mut noise = Noise::new(white, ar, tau, SAMPLE_HZ, &mut rng);
        let outside = bench
            .forms
            .outside
            .filter(|_| sensor == bench.forms.outside_sensor.max(1));
        let travel_total: f64 = strain.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
        let mut travel = 0.0_f64;
        for (i, &e) in strain.iter().enumerate() {
            let t = i as f64 * dt;
            let felt = sign * e;
            let de = felt - last;
            last = felt;
            let mut x = felt;
            if has(Effect::Saturation, sensor) {
                x = match bench.forms.saturation {
                    Saturation::Rational => felt / (1.0 + felt.abs() / SATURATION_STRAIN),
                    Saturation::Algebraic => {
                        felt / (1.0 + (felt / (0.5 * SATURATION_STRAIN)).powi(2)).sqrt()
                    }
                    Saturation::Power => {
                        felt.signum() * PEAK_STRAIN * (felt.abs() / PEAK_STRAIN).powf(0.8)
                    }
                    Saturation::Piecewise => {
                        let knee = 0.5 * PEAK_STRAIN;
                        if felt.abs() <= knee {
                            felt
                        } else {
                            felt.signum() * (knee + 0.55 * (felt.abs() - knee))
                        }
                    }
                };
            }
            match outside {
                Some(Outside::Stiffening) => x *= 1.0 + x.abs() / STIFFENING_STRAIN,
                Some(Outside::DeadZone) => {
                    x = x.signum() * (x.abs() - DEAD_ZONE * PEAK_STRAIN).max(0.0);
                }
                Some(Outside::Quadratic) => x += x * x / QUADRATIC_STRAIN,
                _ => {}
            }
            if has(Effect::Hysteresis, sensor) {
                let (beta, gamma, weight) = BOUC_WEN;
                z += (1.0 - (beta + gamma * (de * z).signum()) * z.abs()) * de;
                x += weight * z;
            }
            let mut change = r0 * gf * x;
            travel += de.abs();
            change *= match outside {
                Some(Outside::GainFade) => {
                    let (fraction, tau) = GAIN_FADE;
                    1.0 - fraction * (1.0 - (-t / (tau * bench.duration_s)).exp())
                }
                Some(Outside::GainStep) if t >= bench.duration_s / 2.0 => 1.0 - GAIN_STEP,
                Some(Outside::GainCycles) => 1.0 - GAIN_CYCLES * travel / travel_total,
                Some(Outside::GainSine) => {
                    let (amplitude, period) = GAIN_SINE;
                    1.0 + amplitude * (2.0 * PI * t / (period * bench.duration_s)).sin()
                }
                _ => 1.0,
            };
            let mut ohm = r0 + change;
            if outside == Some(Outside::OffsetStep) && felt.abs() > 0.5 * span_strain {
                ohm += OFFSET_STEP * span_ohm;
            }
            if has(Effect::Rate, sensor) {
                let (reference, tau, size) = RATE;
                rate += (de / dt - rate) * (1.0 - (-dt / tau).exp());
                ohm += size * span_ohm * rate.signum() * (rate.abs() / reference).sqrt();
            }
            if has(Effect::Creep, sensor) {
                for (state, (fraction, tau)) in creep.iter_mut().zip(CREEP) {
                    *state += (fraction * change - *state) * (1.0 - (-dt / tau).exp());
                    ohm += *state;
                }
            }
            if has(Effect::Drift, sensor) {
                let (size, tau) = DRIFT;
                ohm += size
                    * span_ohm
                    * if bench.forms.drift_sqrt {
                        (t / bench.duration_s).sqrt()
                    } else {
                        1.0 - (-t / tau).exp()
                    };
            }
            let reading = divider.voltage(ohm) + noise.next(&mut rng);
            v.push(reading.clamp(1e-3, SUPPLY_V - 1e-3));
        }
    }

    let (white, ar, tau) = NOISE_DEG;
    let mut tracker = Noise::new(white, ar, tau, SAMPLE_HZ, &mut rng);
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
            "sample_hz = {SAMPLE_HZ:?}\nsupply_v = {SUPPLY_V:?}\ndivider_ohm = [{divider_list}]\nnotes = \"other-forms generator, seed {}\"\n",
            bench.seed
        ),
    )
    .unwrap();
    std::fs::write(out.join("data.csv"), csv).unwrap();
}
