//! A second recording generator, independent of `dlw simulate`, so that the fit is checked on
//! hysteresis it was not built around (issue 7: "the fit must not rely on the data having been
//! made by a PI model").
//!
//! It writes a recording folder in the documented format (`docs/recording-format.md`:
//! `rig.toml` + `data.csv`, one sensor, plane `+y_s`) for a UAN design, with functional forms
//! that differ from the simulator's (no tanh, no play operators):
//!
//! - **Angle path** θ(t) (°), one of
//!   - [`Path::Cycles`]: a rest at 0° of `REST_S`, then loading/unloading cycles of varied
//!     amplitudes (`CYCLE_AMPLITUDES` × the peak angle), each a raised-cosine ramp
//!     `θ = a·(1 − cos(π·u))/2` up over `RAMP_S` and the same back down;
//!   - [`Path::Random`]: a sum of three slow sinusoids (periods 77 s, 32 s, 143 s, phases from the
//!     seed), `θ = θ_peak·(0.5 + 0.25·sin … + 0.15·sin … + 0.1·sin …)`, inside `[0, θ_peak]`;
//!   - [`Path::RateCycles`]: a rate-dependence protocol of its own: `RATE_REPEATS` times, one
//!     raised-cosine cycle to 90 % of the peak at each rise time of `RATE_RISES_S` (up and down
//!     in that time), each followed by `RATE_REST_S` at rest. The joint relaxes: the angle
//!     lags the path by a first-order creep of `RATE_RELAXATION` (fraction, τ), so it
//!     undershoots zero after each unloading and recovers while it rests.
//! - **Strain** `ε = Joint::strain(θ)` (Eq. 3, the geometry crate).
//! - **Hysteresis**: a Bouc-Wen (Duhem-type) internal state `z` (strain units) driven by the
//!   strain, `dz = (A − (β + γ·sign(dε·z))·|z|ⁿ)·dε` with `A = 1`, `n = 1`, `β = 300`,
//!   `γ = 200`, so that `z` saturates at `±A/(β + γ) = ±0.002` while loading and relaxes more
//!   slowly (`β − γ = 100`) on reversal; integrated per sample (explicit Euler on the strain step).
//! - **Saturation**: a power law, `s(ε) = (ε_s/p)·(1 − (1 − ε/ε_s)ᵖ)` with `ε_s = 0.04`, `p = 2`
//!   (`s'(0) = 1`, the slope falling linearly to 0 at `ε_s`; ε is kept below `ε_s`).
//! - **Sensor**: `R = R₀·(1 + G·(s(ε) + κ·z))`, `R₀ = 215 kΩ`, `G = 15`, `κ = 1.5`.
//! - **Divider**: `V = Divider::voltage(R)` (Eq. 4), `R_k = 99.6 kΩ`, `V+ = 5 V`.
//! - **Noise**, seeded (xorshift64* + Box-Muller, no extra crates): on the voltage, white
//!   `σ = 2 mV` plus AR(1) correlated noise `σ = 2 mV`, correlation time 1.5 s; on the tracker
//!   angle, white `σ = 0.1°` plus AR(1) `σ = 0.1°`, correlation time 1.5 s.
#![allow(dead_code)]

use std::fmt::Write as _;
use std::path::Path as FsPath;

use dlw::design::Design;
use dlw_geometry::Divider;

use super::rng::{Noise, Rng};

/// Sample rate (Hz), the paper's bench.
pub const SAMPLE_HZ: f64 = 500.0;
/// Divider supply (V).
pub const SUPPLY_V: f64 = 5.0;
/// Divider fixed resistor (Ω).
pub const DIVIDER_OHM: f64 = 99_600.0;
/// Peak strain of the paths.
pub const PEAK_STRAIN: f64 = 0.015;
/// Rest at the start of the cycles path (s).
pub const REST_S: f64 = 10.0;
/// Duration of each ramp (up or down) of the cycles path (s).
pub const RAMP_S: f64 = 20.0;
/// Amplitudes of the cycles, as fractions of the peak.
pub const CYCLE_AMPLITUDES: [f64; 6] = [1.0, 0.6, 0.85, 0.4, 1.0, 0.7];
/// Rise times of the rate cycles (s): not the simulator's 10-50 s.
pub const RATE_RISES_S: [f64; 5] = [3.0, 5.0, 7.0, 11.0, 16.0];
/// Repetitions of the rate cycles.
pub const RATE_REPEATS: usize = 5;
/// Rest after each rate cycle (s).
pub const RATE_REST_S: f64 = 6.0;
/// The joint's relaxation on the rate path: the fraction of the angle it gives up and its time
/// constant (s).
pub const RATE_RELAXATION: (f64, f64) = (0.05, 3.0);
/// Sensor constants.
pub const R0_OHM: f64 = 215_000.0;
/// Gain on the saturated strain.
pub const GAIN: f64 = 15.0;
/// Weight of the hysteresis state.
pub const KAPPA: f64 = 1.5;
/// Bouc-Wen constants.
pub const BW_A: f64 = 1.0;
/// Bouc-Wen β.
pub const BW_BETA: f64 = 300.0;
/// Bouc-Wen γ.
pub const BW_GAMMA: f64 = 200.0;
/// Bouc-Wen exponent.
pub const BW_N: f64 = 1.0;
/// Saturation strain and power.
pub const SAT_STRAIN: f64 = 0.04;
/// Saturation power.
pub const SAT_POWER: f64 = 2.0;
/// Noise (V, °) and correlation time (s).
pub const WHITE_V: f64 = 0.002;
/// AR(1) voltage noise (V).
pub const AR_V: f64 = 0.002;
/// White angle noise (°).
pub const WHITE_DEG: f64 = 0.1;
/// AR(1) angle noise (°).
pub const AR_DEG: f64 = 0.1;
/// Correlation time of the AR(1) noise (s).
pub const TAU_S: f64 = 1.5;

/// The angle path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Path {
    /// Rest, then loading/unloading cycles of varied amplitudes.
    Cycles,
    /// Slow sinusoids, for validation, lasting this many seconds.
    Random(f64),
    /// Equal-amplitude cycles at several rise times, on a relaxing joint.
    RateCycles,
}

/// The rate path's noise-free angle (°) before relaxation at `t`; `None` past the end.
fn rate_cycle_angle(peak_deg: f64, t: f64) -> Option<f64> {
    if t < REST_S {
        return Some(0.0);
    }
    let mut start = REST_S;
    for _ in 0..RATE_REPEATS {
        for rise in RATE_RISES_S {
            let u = (t - start) / rise;
            if u < 2.0 {
                let a = 0.9 * peak_deg;
                return Some(if u < 1.0 {
                    a * raised_cosine(u)
                } else {
                    a * (1.0 - raised_cosine(u - 1.0))
                });
            }
            start += 2.0 * rise + RATE_REST_S;
            if t < start {
                return Some(0.0);
            }
        }
    }
    None
}

fn raised_cosine(u: f64) -> f64 {
    (1.0 - (std::f64::consts::PI * u.clamp(0.0, 1.0)).cos()) / 2.0
}

/// The noise-free angle (°) of `path` at `t`, with `peak_deg` the peak angle; `None` past the end.
fn angle(path: Path, peak_deg: f64, phases: [f64; 3], t: f64) -> Option<f64> {
    match path {
        Path::Cycles => {
            if t < REST_S {
                return Some(0.0);
            }
            let k = ((t - REST_S) / (2.0 * RAMP_S)) as usize;
            let a = *CYCLE_AMPLITUDES.get(k)? * peak_deg;
            let u = (t - REST_S - k as f64 * 2.0 * RAMP_S) / RAMP_S;
            Some(if u < 1.0 {
                a * raised_cosine(u)
            } else {
                a * (1.0 - raised_cosine(u - 1.0))
            })
        }
        Path::RateCycles => rate_cycle_angle(peak_deg, t),
        Path::Random(duration) => {
            if t > duration {
                return None;
            }
            let w =
                |period: f64, phase: f64| (2.0 * std::f64::consts::PI * t / period + phase).sin();
            let x = 0.5
                + 0.25 * w(77.0, phases[0])
                + 0.15 * w(32.0, phases[1])
                + 0.1 * w(143.0, phases[2]);
            // Start from rest near zero: ramp in over the first 10 s.
            Some(peak_deg * x.clamp(0.0, 1.0) * raised_cosine(t / 10.0))
        }
    }
}

/// The sensor resistance of the saturated strain and the hysteresis state.
fn resistance(strain: f64, z: f64) -> f64 {
    let e = strain.min(0.999 * SAT_STRAIN);
    let s = SAT_STRAIN / SAT_POWER * (1.0 - (1.0 - e / SAT_STRAIN).powf(SAT_POWER));
    R0_OHM * (1.0 + GAIN * (s + KAPPA * z))
}

/// Writes a recording of `path` for the UAN design file `design` into the folder `out`
/// (created), noise seeded by `seed`.
pub fn write_recording(design: &FsPath, path: Path, seed: u64, out: &FsPath) {
    let joint = Design::load(design).expect("the design loads").joint;
    let peak_deg = PEAK_STRAIN / joint.strain_per_deg();
    let divider = Divider {
        fixed_ohm: DIVIDER_OHM,
        supply_v: SUPPLY_V,
    };
    let mut rng = Rng::new(seed);
    let phases = [
        rng.uniform() * std::f64::consts::TAU,
        rng.uniform() * std::f64::consts::TAU,
        rng.uniform() * std::f64::consts::TAU,
    ];
    let mut v_noise = Noise::new(WHITE_V, AR_V, TAU_S, SAMPLE_HZ, &mut rng);
    let mut a_noise = Noise::new(WHITE_DEG, AR_DEG, TAU_S, SAMPLE_HZ, &mut rng);
    let mut csv = String::from("time_s,stroke_mm,angle_deg,v1_V\n");
    let (mut z, mut last_strain) = (0.0_f64, 0.0_f64);
    let mut relaxed = 0.0_f64;
    if path == Path::RateCycles {
        // The sensor was cycled before the recording: one cycle to the rate path's amplitude
        // and back, so that its first recorded cycle does not start from the virgin state.
        let top = joint.strain((0.9 * peak_deg).to_radians());
        let steps = 2000;
        for k in 1..=2 * steps {
            let u = k as f64 / steps as f64;
            let strain = top * if u <= 1.0 { u } else { 2.0 - u };
            let de = strain - last_strain;
            let sign = (de * z).signum();
            z += (BW_A - (BW_BETA + BW_GAMMA * sign) * z.abs().powf(BW_N)) * de;
            last_strain = strain;
        }
    }
    let mut i = 0usize;
    loop {
        let t = i as f64 / SAMPLE_HZ;
        let Some(mut theta) = angle(path, peak_deg, phases, t) else {
            break;
        };
        let commanded = theta;
        if path == Path::RateCycles {
            let (fraction, tau) = RATE_RELAXATION;
            relaxed += (fraction * theta - relaxed) * (1.0 - (-1.0 / (SAMPLE_HZ * tau)).exp());
            theta -= relaxed;
        }
        let strain = joint.strain(theta.to_radians());
        let de = strain - last_strain;
        let sign = (de * z).signum();
        z += (BW_A - (BW_BETA + BW_GAMMA * sign) * z.abs().powf(BW_N)) * de;
        last_strain = strain;
        let volts = (divider.voltage(resistance(strain, z)) + v_noise.next(&mut rng))
            .clamp(1e-3, SUPPLY_V - 1e-3);
        let recorded = theta + a_noise.next(&mut rng);
        writeln!(
            csv,
            "{t:.6},{:.6},{recorded:.4},{volts:.6}",
            commanded * 0.01
        )
        .unwrap();
        i += 1;
    }
    std::fs::create_dir_all(out).unwrap();
    std::fs::write(
        out.join("rig.toml"),
        format!(
            "sample_hz = {SAMPLE_HZ:?}\nsupply_v = {SUPPLY_V:?}\ndivider_ohm = [{DIVIDER_OHM:?}]\nnotes = \"second generator: Bouc-Wen hysteresis, power-law saturation, {path:?}, seed {seed}\"\n"
        ),
    )
    .unwrap();
    std::fs::write(out.join("data.csv"), csv).unwrap();
}
