//! The scenario file: which effects the simulated bench has, each switchable with its
//! parameters, and every key's documented default.
//!
//! A scenario is TOML with unknown keys refused at every level, so a misspelt parameter never
//! silently takes its default. Every key may be left out. Sensor parameters whose defaults depend
//! on the design's notch style are `None` in the file and filled in by [`Scenario::resolve`]; the
//! resolved scenario (everything concrete, seed included) is what `rig.toml` records, and it is
//! itself a valid scenario file that reproduces the run.
//!
//! ```toml
//! protocol = "random"          # characterization | rate-dependence | relaxation | random | custom
//! seed = 7
//! [plant.relaxation]          # present, so on
//! fraction = 0.08
//! [sensor1]
//! gauge_factor = 22.0
//! r0_ohm = 77.2e3
//! [sensor1.drift]              # on, with its defaults
//! [sensor1.creep]
//! enabled = false              # present but switched off
//! [adc.correlated]             # slow, correlated ADC noise on top of the white noise
//! ```
//!
//! **An effect table that is present is on** unless it says `enabled = false`:
//! `[plant.relaxation]` with only a `fraction` switches relaxation on. A table that is absent
//! keeps its documented default (off for every effect and for correlated noise; on for `[adc]`
//! and `[tracker]`). In serde terms: each table's `enabled` field defaults to `true`
//! (`#[serde(default = "present")]`) when the table is read, while the enclosing struct's
//! `Default`, used when the table is missing, has it off.
//!
//! The defaults, where they come from, and what each effect does, are in the doc of each table's
//! type and in `docs/simulator.md`.

use std::path::PathBuf;

use dlw_estimator::{ContinuousPiConfig, EstimatorError, PiConfig};
use dlw_geometry::NotchStyle;
use serde::{Deserialize, Serialize};

use super::pi_default::{JOINT_A_PI, JOINT_C_PI};
use super::protocol::{ProtocolKind, ProtocolParams};
use crate::design::Design;

/// Why a scenario was refused.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("cannot read scenario {path}")]
    Read {
        /// The scenario file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// Not valid TOML for a scenario (unknown key, wrong type).
    #[error("scenario {path}: {message}")]
    Parse {
        /// The scenario file.
        path: PathBuf,
        /// The TOML parser's message, which names the key and line.
        message: String,
    },
    /// A number is outside its allowed range.
    #[error("scenario key {key} = {value} is out of range ({limit})")]
    OutOfRange {
        /// Dotted key, as written in the file.
        key: String,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        limit: &'static str,
    },
    /// A second sensor was configured for a one-sensor (UAN) design.
    #[error("scenario sets [sensor2], but design {design:?} is UAN with one sensor")]
    SecondSensorOnUan {
        /// The design's name.
        design: String,
    },
    /// A sensor model's parameters were refused by the estimator crate, whose forward model
    /// the simulator runs.
    #[error("scenario table [{table}]: {reason}")]
    Model {
        /// The table, e.g. `sensor1.pi`.
        table: String,
        /// What the estimator crate refused.
        reason: EstimatorError,
    },
    /// A model was chosen whose parameters have no default and were not given.
    #[error("sensor{sensor} uses model {model:?} but [sensor{sensor}.{model}] is missing ({why})")]
    MissingModel {
        /// 1 or 2.
        sensor: usize,
        /// The model's name.
        model: &'static str,
        /// Why there is no default.
        why: &'static str,
    },
    /// No protocol was chosen on the command line or in the scenario.
    #[error("no protocol chosen: pass --protocol or set protocol in the scenario")]
    NoProtocol,
    /// The seed does not fit the TOML integer that records it.
    #[error("seed {seed} is too large (at most {max})")]
    SeedTooLarge {
        /// The seed given.
        seed: u64,
        /// The largest seed a TOML file can record, 2^63 − 1.
        max: u64,
    },
}

/// The `enabled` of an effect table that is present in the file but does not say: on.
fn present() -> bool {
    true
}

/// A whole scenario (the top level of the file).
///
/// | key | default | meaning |
/// |---|---|---|
/// | `protocol` | none (the CLI's `--protocol`) | which stroke profile to run |
/// | `duration_s` | the protocol's (10 s at rest plus 1000 s characterization, 3000 s others; the CSV's last time) | recording length |
/// | `seed` | 0 | seeds every random stream (noise, drift, the random protocol) |
/// | `sample_hz` | 500 | the paper's DAQ rate |
/// | `supply_v` | 5 | divider supply `V+` |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scenario {
    /// The stroke profile to run; the CLI's `--protocol` overrides it.
    pub protocol: Option<ProtocolKind>,
    /// Recording length (s); `None` means the protocol's natural length.
    pub duration_s: Option<f64>,
    /// Seed of every random stream; the CLI's `--seed` overrides it.
    pub seed: u64,
    /// Sample rate (Hz).
    pub sample_hz: f64,
    /// Divider supply `V+` (V).
    pub supply_v: f64,
    /// Stroke → angle.
    pub plant: PlantParams,
    /// Sensor 1 (the only sensor of a UAN joint; the one in tension for positive angles).
    pub sensor1: SensorParams,
    /// Sensor 2 of a BSN joint (reads `−ε`); must be absent for UAN.
    pub sensor2: Option<SensorParams>,
    /// The DAQ's analog-to-digital converter.
    pub adc: AdcParams,
    /// The EM tracker that records the ground-truth angle.
    pub tracker: TrackerParams,
    /// The bench's slow temperature wander, which moves every sensor's resistance by its
    /// `tcr_per_k`.
    pub temperature: Temperature,
    /// Timing of each protocol.
    pub protocols: ProtocolParams,
}

impl Default for Scenario {
    fn default() -> Self {
        Self {
            protocol: None,
            duration_s: None,
            seed: 0,
            sample_hz: 500.0,
            supply_v: 5.0,
            plant: PlantParams::default(),
            sensor1: SensorParams::default(),
            sensor2: None,
            adc: AdcParams::default(),
            tracker: TrackerParams::default(),
            temperature: Temperature::default(),
            protocols: ProtocolParams::default(),
        }
    }
}

/// Stroke → angle (`[plant]`): a linear gain plus three switchable effects.
///
/// | key | default | source |
/// |---|---|---|
/// | `gain_deg_per_mm` | 35.49 | the paper's Joint D, `m_t` (Section IV-C) |
/// | `backlash` | off, `width_mm = 0.05` | illustrative: ~1.8° of dead band at Joint D's gain |
/// | `relaxation` | off, `fraction = 0.05`, `tau_s = 20` | illustrative: the paper shows the decay (Section IV-A3) but no numbers |
/// | `notch_limit` | off | the angle stops where the notches close (`Joint::closing_angle_rad`) |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlantParams {
    /// Angle per millimetre of tendon stroke (°/mm).
    pub gain_deg_per_mm: f64,
    /// Tendon backlash: a dead band at every reversal.
    pub backlash: Backlash,
    /// Viscoelastic relaxation of tube and tendon under a held stroke.
    pub relaxation: Relaxation,
    /// Notch-closing limit.
    pub notch_limit: NotchLimit,
}

impl Default for PlantParams {
    fn default() -> Self {
        Self {
            gain_deg_per_mm: 35.49,
            backlash: Backlash::default(),
            relaxation: Relaxation::default(),
            notch_limit: NotchLimit::default(),
        }
    }
}

/// Tendon backlash (`[plant.backlash]`): the effective stroke is a play operator of the stroke
/// with total dead band `width_mm`, so the angle lags by `width_mm` at every reversal.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Backlash {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Total dead band (mm), twice the play radius.
    pub width_mm: f64,
}

impl Default for Backlash {
    fn default() -> Self {
        Self {
            enabled: false,
            width_mm: 0.05,
        }
    }
}

/// Viscoelastic relaxation (`[plant.relaxation]`), a standard linear solid: under a held stroke
/// the angle decays by `fraction` of its elastic value with time constant `tau_s`. With
/// `[[plant.relaxation.terms]]`, a generalized Maxwell solid (a Prony series) instead: the sum of
/// such relaxations, one per term, and `fraction` and `tau_s` are not used.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Relaxation {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Share of the elastic angle lost once fully relaxed, in `[0, 1)`.
    pub fraction: f64,
    /// Time constant (s).
    pub tau_s: f64,
    /// A spread of time constants (at most [`MAX_RELAXATION_TERMS`]): when not empty, the
    /// relaxation is their sum. `discover` writes them when it names a relaxation in that form.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub terms: Vec<RelaxationTerm>,
}

impl Default for Relaxation {
    fn default() -> Self {
        Self {
            enabled: false,
            fraction: 0.05,
            tau_s: 20.0,
            terms: Vec::new(),
        }
    }
}

/// Most terms a relaxation's Prony series may have.
pub const MAX_RELAXATION_TERMS: usize = 32;

/// One term of a relaxation's Prony series (`[[plant.relaxation.terms]]`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RelaxationTerm {
    /// Share of the elastic angle this term loses once fully relaxed, in `[0, 1)` (a
    /// generalized Maxwell solid's shares are at least zero); the terms' sum, the whole share
    /// lost, lies in `[0, 1)` too.
    pub fraction: f64,
    /// Time constant (s).
    pub tau_s: f64,
}

impl Relaxation {
    /// The relaxation's terms, `(fraction, tau_s)`: its Prony series, or its one term.
    pub fn series(&self) -> Vec<(f64, f64)> {
        if self.terms.is_empty() {
            vec![(self.fraction, self.tau_s)]
        } else {
            self.terms.iter().map(|t| (t.fraction, t.tau_s)).collect()
        }
    }
}

/// Notch-closing limit (`[plant.notch_limit]`): the angle stops at `Joint::closing_angle_rad`
/// (for UAN only in the closing direction, positive angles; for BSN both ways).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NotchLimit {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
}

/// The resistance model of a sensor.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SensorModelKind {
    /// Eq. 6: `R = R0·(1 + GF·ε)`.
    #[default]
    Linear,
    /// The paper's generalized Prandtl-Ishlinskii model (Eqs. 8-11), `[sensorN.pi]`.
    Pi,
    /// The continuous generalized PI variant (envelopes inside the plays),
    /// `[sensorN.continuous_pi]`; no default.
    ContinuousPi,
}

/// One sensor (`[sensor1]`, `[sensor2]`).
///
/// | key | default UAN | default BSN sensor 1 / sensor 2 | source |
/// |---|---|---|---|
/// | `model` | `linear` | `linear` | |
/// | `gauge_factor` | 15.3 | 1.28 / 0.680 | Table III (Joint A); Table V (Joint C tension / compression) |
/// | `r0_ohm` | 215e3 | 74.0e3 / 88.9e3 | same |
/// | `divider_ohm` | 99.6e3 | 99.6e3 / 102.5e3 | Section II-B, System Assembly |
/// | `pi` | Joint A | Joint C / none | Table III's points, see `pi_default` (no default for sensor 2: the paper fits it only linearly) |
/// | `continuous_pi` | none | none | |
/// | `saturation` | off, `strain = 0.02` | same | the paper's conclusion: saturation below 2 % |
/// | `drift` | off, 0 Ω/s, 20 Ω/√s | 0 Ω/s, 0.7 Ω/√s | the spread of R0 over 3000 s (Section IV-A2): 1.10 kΩ (A), 0.038 kΩ (C) |
/// | `rate` | off, `log`, 0.1 per decade, 1e-3 /s, 1 s; `signed`: 0.05 s·R0·GF | same | illustrative (the paper found no correlation) |
/// | `creep` | off, 0.03, 30 s; second term 0, 3 s | same | illustrative (Section IV-A3: the resistance barely changed during holds) |
/// | `gain_drift` | off, `fade_per_hour = 0.2` | same | illustrative: fatigue, the durability the paper's conclusion leaves open |
/// | `noise` | off, `sigma_ppm = 1000`, `tau_s = 2` | same | illustrative: the trace's own slow resistance noise (1/f noise of a carbon film, its silver-epoxy contacts) |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorParams {
    /// `linear`, `pi` or `continuous_pi`.
    pub model: SensorModelKind,
    /// Gauge factor of the linear model.
    pub gauge_factor: Option<f64>,
    /// Unstrained resistance `R0` of the linear model (Ω).
    pub r0_ohm: Option<f64>,
    /// The divider's fixed resistor `R_k` (Ω).
    pub divider_ohm: Option<f64>,
    /// Generalized PI parameters, used when `model = "pi"`: the estimator crate's `PiConfig`,
    /// the same table as `[sensor.model.pi]` in an estimator config.
    pub pi: Option<PiConfig>,
    /// Continuous PI parameters, used when `model = "continuous_pi"`: the estimator crate's
    /// `ContinuousPiConfig`.
    pub continuous_pi: Option<ContinuousPiConfig>,
    /// Soft saturation of the strain the sensor feels.
    pub saturation: Saturation,
    /// Baseline drift of the resistance.
    pub drift: Drift,
    /// Strain-rate-dependent sensitivity.
    pub rate: RateDependence,
    /// Creep of the resistance under held strain.
    pub creep: Creep,
    /// The sensitivity fading over the run (fatigue).
    pub gain_drift: GainDrift,
    /// The trace's own slow resistance noise.
    pub noise: SensorNoise,
    /// Temperature coefficient of the resistance (1/K): under the bench's `[temperature]`
    /// wander `T(t)` the resistance is `R·(1 + tcr_per_k·T)`.
    pub tcr_per_k: f64,
}

impl Default for SensorParams {
    fn default() -> Self {
        Self {
            model: SensorModelKind::Linear,
            gauge_factor: None,
            r0_ohm: None,
            divider_ohm: None,
            pi: None,
            continuous_pi: None,
            saturation: Saturation::default(),
            drift: Drift::default(),
            rate: RateDependence::default(),
            creep: Creep::default(),
            gain_drift: GainDrift::default(),
            noise: SensorNoise::default(),
            tcr_per_k: DEFAULT_TCR_PER_K,
        }
    }
}

/// The default temperature coefficient of a sensor's resistance (1/K): −0.1 %/K, the order of
/// magnitude reported for laser-induced graphene on polyimide (its resistance falls as it
/// warms). Illustrative: the paper names temperature as an open question and gives no number.
pub const DEFAULT_TCR_PER_K: f64 = -1e-3;

/// The largest `|tcr_per_k|` (1/K): 1 %/K, ten times the default, far beyond any carbon
/// film's.
pub const MAX_TCR_PER_K: f64 = 0.01;

/// The bench's temperature wander (`[temperature]`): a first-order autoregressive (sampled
/// Ornstein-Uhlenbeck) temperature deviation `T(t)` in kelvin, stationary standard deviation
/// `sigma_k` and correlation time `tau_s`, shared by every sensor of the joint (they sit on
/// one tube), each of which reads `R·(1 + tcr_per_k·T)`. A slow wander of `R₀` that the
/// characterization's fit cannot know: the paper names temperature as open (Section V).
/// Common to both sensors of a BSN joint, it moves their resistances the same way while the
/// bending moves them opposite ways, so Eq. 7's difference cancels it.
///
/// | key | default | why |
/// |---|---|---|
/// | `enabled` | false (the table absent); true when present | old recordings keep their draws |
/// | `sigma_k` | 0.5 | a lab's air-conditioning cycle and the motor's warmth: tenths of a kelvin to a kelvin |
/// | `tau_s` | 600 | minutes: slower than every hold and ramp, faster than the 3000 s run |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Temperature {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Stationary RMS of the temperature deviation (K).
    pub sigma_k: f64,
    /// Correlation time (s).
    pub tau_s: f64,
}

impl Default for Temperature {
    fn default() -> Self {
        Self {
            enabled: false,
            sigma_k: 0.5,
            tau_s: 600.0,
        }
    }
}

/// The largest `temperature.sigma_k` (K): a wander of 20 K is no longer a bench at room
/// temperature.
pub const MAX_TEMPERATURE_SIGMA_K: f64 = 20.0;

/// Gain drift (`[sensorN.gain_drift]`): the sensor's resistance change `ΔR` is scaled by
/// `1 − fade_per_hour·t/3600 s`, a sensitivity that fades over the run (fatigue of the
/// graphene trace: one of the paper's open questions, durability). The change is measured from
/// the model's resistance at zero strain, so the baseline stays and the gain goes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GainDrift {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Fraction of the sensitivity lost per hour (negative: it grows).
    pub fade_per_hour: f64,
}

impl Default for GainDrift {
    fn default() -> Self {
        Self {
            enabled: false,
            fade_per_hour: 0.2,
        }
    }
}

/// Soft saturation (`[sensorN.saturation]`): the sensor feels `ε_s·tanh(ε/ε_s)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Saturation {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Saturation strain `ε_s` (fraction).
    pub strain: f64,
}

impl Default for Saturation {
    fn default() -> Self {
        Self {
            enabled: false,
            strain: 0.02,
        }
    }
}

/// A sensor's own resistance noise (`[sensorN.noise]`): the resistance is `R·(1 + n(t))`, `n`
/// a first-order autoregressive (sampled Ornstein-Uhlenbeck) process with stationary RMS
/// `sigma_ppm`·10⁻⁶ and correlation time `tau_s`, from the sensor's own random stream. The
/// noise of the trace itself (a carbon film's 1/f noise, the silver-epoxy contacts), relative to
/// its resistance as such noise is (Hooge's law), so it costs a sensor of small gauge factor more
/// strain: `sigma_ppm·10⁻⁶/GF`. Unlike the ADC's voltage noise it belongs to the sensor, so the
/// two sensors of a BSN joint may differ; unlike `[temperature]` the two sensors' noises are
/// independent, so Eq. 7's difference does not cancel them.
///
/// | key | default | why |
/// |---|---|---|
/// | `enabled` | false (the table absent); true when present | old recordings keep their draws |
/// | `sigma_ppm` | 1000 | 0.1 % of `R`: of the order of the paper's Joint C residual (r² 0.888 on a 1.9 % range) |
/// | `tau_s` | 2 | seconds: it survives the paper's 1-2 s averages, as the paper's errors did |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorNoise {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Stationary RMS of the relative resistance noise (parts per million of `R`).
    pub sigma_ppm: f64,
    /// Correlation time (s).
    pub tau_s: f64,
}

impl Default for SensorNoise {
    fn default() -> Self {
        Self {
            enabled: false,
            sigma_ppm: 1000.0,
            tau_s: 2.0,
        }
    }
}

/// The largest `sensorN.noise.sigma_ppm`: 10 % of the resistance, far beyond a working sensor.
pub const MAX_SENSOR_NOISE_PPM: f64 = 1e5;

/// The largest `|gain_drift.fade_per_hour|`: the sensitivity gone in 6 minutes.
pub const MAX_FADE_PER_HOUR: f64 = 10.0;

/// Baseline drift (`[sensorN.drift]`): `R += rate·t + settle·(1 − e^(−t/τ)) + W(t)`, `W` a
/// random walk with `σ_W(t) = random_walk_ohm_per_sqrt_s·√t`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Drift {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Linear drift (Ω/s).
    pub rate_ohm_per_s: f64,
    /// Random-walk intensity (Ω/√s); `None` means the style's default.
    pub random_walk_ohm_per_sqrt_s: Option<f64>,
    /// A settling (warm-up) drift: `settle_ohm·(1 − e^(−t/settle_tau_s))` is added, a baseline
    /// that moves at first and then levels off, which a rate cannot express (0: off).
    pub settle_ohm: f64,
    /// Time constant of the settling drift (s).
    pub settle_tau_s: f64,
}

impl Default for Drift {
    fn default() -> Self {
        Self {
            enabled: false,
            rate_ohm_per_s: 0.0,
            random_walk_ohm_per_sqrt_s: None,
            settle_ohm: 0.0,
            settle_tau_s: 300.0,
        }
    }
}

/// How the strain rate changes the resistance (`[sensorN.rate] form`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RateForm {
    /// The sensitivity grows with the logarithm of the rate's magnitude, the same for loading and
    /// unloading: `ΔR·(1 + per_decade·log10(1 + |ε̇|/reference_rate_per_s))`.
    #[default]
    Log,
    /// A signed term linear in the strain rate: `ΔR + ohm_per_strain_per_s·ε̇`, so loading reads
    /// high and unloading low (a viscous, Kelvin-Voigt-like lead), a loop whose width grows with
    /// speed.
    Signed,
}

/// Rate dependence (`[sensorN.rate]`), of one of two forms, both driven by the strain rate the
/// sensor feels smoothed by a first-order low-pass of time constant `smoothing_s`:
///
/// - `form = "log"` (the default): the resistance change is scaled by
///   `1 + per_decade·log10(1 + |ε̇|/reference_rate_per_s)`;
/// - `form = "signed"`: `ohm_per_strain_per_s·ε̇` is added, with the sign of the rate.
///
/// The keys of the other form are kept (and recorded) but not used.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RateDependence {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// `log` or `signed`.
    pub form: RateForm,
    /// `log`: relative sensitivity change per decade of strain rate.
    pub per_decade: f64,
    /// `log`: strain rate at which the gain is `1 + per_decade·log10(2)` (1/s).
    pub reference_rate_per_s: f64,
    /// `signed`: resistance added per unit of strain rate (Ω per 1/s, that is Ω·s); `None`
    /// means 0.05 s times the sensor's linear sensitivity `R0·GF`, as if the sensor read the
    /// strain 50 ms ahead.
    pub ohm_per_strain_per_s: Option<f64>,
    /// Smoothing of the strain rate (s), both forms.
    pub smoothing_s: f64,
}

/// The signed rate form's default lead (s): `ohm_per_strain_per_s = SIGNED_RATE_LEAD_S·R0·GF`.
pub const SIGNED_RATE_LEAD_S: f64 = 0.05;

impl Default for RateDependence {
    fn default() -> Self {
        Self {
            enabled: false,
            form: RateForm::Log,
            per_decade: 0.1,
            reference_rate_per_s: 1e-3,
            ohm_per_strain_per_s: None,
            smoothing_s: 1.0,
        }
    }
}

/// Sensor creep (`[sensorN.creep]`): the resistance change grows by `fraction` of itself with
/// time constant `tau_s` while the strain is held, and by `fast_fraction` more with
/// `fast_tau_s` (a second Prony term; 0 by default: one time constant).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Creep {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Relative growth of the resistance change once settled.
    pub fraction: f64,
    /// Time constant (s).
    pub tau_s: f64,
    /// Relative growth of the second, faster term once settled.
    pub fast_fraction: f64,
    /// The second term's time constant (s).
    pub fast_tau_s: f64,
}

impl Default for Creep {
    fn default() -> Self {
        Self {
            enabled: false,
            fraction: 0.03,
            tau_s: 30.0,
            fast_fraction: 0.0,
            fast_tau_s: 3.0,
        }
    }
}

/// The DAQ's ADC (`[adc]`): Gaussian white noise `noise_v` (RMS) and, when switched on, correlated
/// noise on the voltage, then quantization to
/// `bits` over `[min_v, max_v]` (readings beyond the range clip to it).
///
/// | key | default | source |
/// |---|---|---|
/// | `enabled` | true | |
/// | `bits` | 16 | a National Instruments DAQ (the paper's) |
/// | `min_v`, `max_v` | −10, 10 | its ±10 V range: 0.305 mV per code |
/// | `noise_v` | 0.005 | illustrative: the paper calls the noise "high" and filters over 500 samples |
/// | `correlated` | off | [`AdcCorrelated`]: slow noise with a correlation time of seconds |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AdcParams {
    /// Switch: off records the exact divider voltage (and no noise at all).
    #[serde(default = "present")]
    pub enabled: bool,
    /// Resolution (bits), 1 to 32.
    pub bits: u32,
    /// Lower end of the input range (V).
    pub min_v: f64,
    /// Upper end of the input range (V).
    pub max_v: f64,
    /// RMS white voltage noise before quantization (V).
    pub noise_v: f64,
    /// Slow, correlated voltage noise on top of the white noise.
    pub correlated: AdcCorrelated,
}

impl Default for AdcParams {
    fn default() -> Self {
        Self {
            enabled: true,
            bits: 16,
            min_v: -10.0,
            max_v: 10.0,
            noise_v: 0.005,
            correlated: AdcCorrelated::default(),
        }
    }
}

/// Correlated ADC noise (`[adc.correlated]`): a first-order autoregressive (sampled
/// Ornstein-Uhlenbeck) voltage `c` added to each channel before quantization, with stationary
/// standard deviation `sigma_v` and correlation time `tau_s`:
/// `c[k+1] = φ·c[k] + sigma_v·√(1 − φ²)·n[k]`, `φ = e^(−Δt/τ)`, `c[0] ~ N(0, sigma_v²)`; each
/// channel has its own stream. Its lag-`k` autocorrelation is `e^(−k·Δt/τ)`.
///
/// | key | default | why |
/// |---|---|---|
/// | `enabled` | false (the table absent); true when present | old recordings keep their noise |
/// | `sigma_v` | 0.002 | 0.4 × the white 5 mV: the slow wander of a divider on a USB-powered 5 V supply (0.1 % of 5 V at the 2.5 V midpoint is 2.5 mV) and of a carbon-composite sensor's 1/f noise, well above a 16-bit NI DAQ's own offset drift |
/// | `tau_s` | 2 | seconds: slower than any filter the paper uses (1 s), faster than the drift's minutes |
///
/// The values are illustrative, chosen from the sources above rather than measured on the
/// paper's bench; see `docs/simulator.md`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AdcCorrelated {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Stationary RMS of the correlated voltage (V).
    pub sigma_v: f64,
    /// Correlation time (s).
    pub tau_s: f64,
}

impl Default for AdcCorrelated {
    fn default() -> Self {
        Self {
            enabled: false,
            sigma_v: 0.002,
            tau_s: 2.0,
        }
    }
}

/// The EM tracker (`[tracker]`): the recorded angle is the true angle plus Gaussian white noise
/// and, when switched on, a correlated error.
///
/// | key | default | source |
/// |---|---|---|
/// | `enabled` | true | |
/// | `noise_deg` | 0.3 | NDI Aurora's specified orientation accuracy, 0.30° RMS |
/// | `correlated` | off | [`TrackerCorrelated`]: slow error with a correlation time of seconds |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TrackerParams {
    /// Switch: off records the true angle (and no noise at all).
    #[serde(default = "present")]
    pub enabled: bool,
    /// RMS white angle noise (°).
    pub noise_deg: f64,
    /// Slow, correlated angle error on top of the white noise.
    pub correlated: TrackerCorrelated,
}

impl Default for TrackerParams {
    fn default() -> Self {
        Self {
            enabled: true,
            noise_deg: 0.3,
            correlated: TrackerCorrelated::default(),
        }
    }
}

/// Correlated tracker error (`[tracker.correlated]`): the same first-order autoregressive
/// process as [`AdcCorrelated`], in degrees, added to the recorded angle.
///
/// | key | default | why |
/// |---|---|---|
/// | `enabled` | false (the table absent); true when present | old recordings keep their noise |
/// | `sigma_deg` | 0.2 | comparable to the white 0.3°: an NDI Aurora's specified 0.30° RMS is mostly field distortion that changes as the tip sensor moves through the field, and the system's own filtering of its ~40 Hz measurements; at 500 Hz both show as error that wanders rather than jitters (modelled as wandering with time, not position) |
/// | `tau_s` | 1 | a second: the time the joint takes to move the sensor through a different part of the field on the protocols' 1-10 s ramps |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TrackerCorrelated {
    /// Switch: `true` once the table is present, unless it says `enabled = false`.
    #[serde(default = "present")]
    pub enabled: bool,
    /// Stationary RMS of the correlated angle error (°).
    pub sigma_deg: f64,
    /// Correlation time (s).
    pub tau_s: f64,
}

impl Default for TrackerCorrelated {
    fn default() -> Self {
        Self {
            enabled: false,
            sigma_deg: 0.2,
            tau_s: 1.0,
        }
    }
}

/// Defaults that depend on which sensor of which style, from the paper's Tables III-V.
struct SensorDefaults {
    gauge_factor: f64,
    r0_ohm: f64,
    divider_ohm: f64,
    random_walk_ohm_per_sqrt_s: f64,
}

fn sensor_defaults(style: NotchStyle, index: usize) -> SensorDefaults {
    match (style, index) {
        (NotchStyle::Uan, _) => SensorDefaults {
            gauge_factor: 15.3,
            r0_ohm: 215e3,
            divider_ohm: 99.6e3,
            // 1.10 kΩ over 3000 s: 1100/√3000.
            random_walk_ohm_per_sqrt_s: 20.0,
        },
        (NotchStyle::Bsn, 1) => SensorDefaults {
            gauge_factor: 1.28,
            r0_ohm: 74.0e3,
            divider_ohm: 99.6e3,
            // 0.038 kΩ over 3000 s: 38/√3000.
            random_walk_ohm_per_sqrt_s: 0.7,
        },
        (NotchStyle::Bsn, _) => SensorDefaults {
            gauge_factor: 0.680,
            r0_ohm: 88.9e3,
            divider_ohm: 102.5e3,
            random_walk_ohm_per_sqrt_s: 0.7,
        },
    }
}

impl Scenario {
    /// Reads a scenario file (nothing is resolved yet).
    ///
    /// # Errors
    /// [`ScenarioError::Read`] or [`ScenarioError::Parse`] naming the file and key.
    pub fn load(path: &std::path::Path) -> Result<Self, ScenarioError> {
        let text = crate::output::read_limited(path, crate::limits::MAX_TEXT_INPUT_BYTES).map_err(
            |source| ScenarioError::Read {
                path: path.to_path_buf(),
                source,
            },
        )?;
        toml::from_str(&text).map_err(|e| ScenarioError::Parse {
            path: path.to_path_buf(),
            message: crate::limits::parser_message(&e),
        })
    }

    /// Fills every default that depends on the design (the sensors' by notch style, the
    /// protocol amplitude from the geometry) and checks every number.
    ///
    /// # Errors
    /// [`ScenarioError`] naming the key, the value and the limit.
    pub fn resolve(mut self, design: &Design) -> Result<Self, ScenarioError> {
        let style = design.joint.style();
        if self.seed > i64::MAX as u64 {
            return Err(ScenarioError::SeedTooLarge {
                seed: self.seed,
                max: i64::MAX as u64,
            });
        }
        resolve_sensor(&mut self.sensor1, style, 1)?;
        match (style, self.sensor2.as_mut()) {
            (NotchStyle::Uan, Some(_)) => {
                return Err(ScenarioError::SecondSensorOnUan {
                    design: design.file.name.clone(),
                })
            }
            (NotchStyle::Uan, None) => {}
            (NotchStyle::Bsn, Some(s)) => resolve_sensor(s, style, 2)?,
            (NotchStyle::Bsn, None) => {
                let mut s = SensorParams::default();
                resolve_sensor(&mut s, style, 2)?;
                self.sensor2 = Some(s);
            }
        }
        self.validate()?;
        // The stroke that reaches the peak strain at the nominal gain, from the geometry.
        let peak_angle_deg = design
            .joint
            .angle_at_strain(self.protocols.peak_strain)
            .to_degrees();
        self.protocols
            .amplitude_mm
            .get_or_insert(peak_angle_deg / self.plant.gain_deg_per_mm);
        Ok(self)
    }

    /// The scenario with the command line's choices put over the file's: each `Some` replaces
    /// the scenario's value.
    pub fn overridden(mut self, o: &Overrides) -> Self {
        if o.protocol.is_some() {
            self.protocol = o.protocol;
        }
        if let Some(seed) = o.seed {
            self.seed = seed;
        }
        if o.duration_s.is_some() {
            self.duration_s = o.duration_s;
        }
        self
    }

    /// Switches the correlated ADC and tracker noise on or off (`--noise realistic` / `white`),
    /// keeping their parameters.
    pub fn set_correlated_noise(&mut self, on: bool) {
        self.adc.correlated.enabled = on;
        self.tracker.correlated.enabled = on;
    }

    /// The sensors, in order (one for UAN, two for BSN once resolved).
    pub fn sensors(&self) -> impl Iterator<Item = &SensorParams> {
        std::iter::once(&self.sensor1).chain(self.sensor2.as_ref())
    }

    fn validate(&self) -> Result<(), ScenarioError> {
        let mut c = Checker::default();
        if let Some(d) = self.duration_s {
            c.positive("duration_s", d);
            c.at_most("duration_s", d, 1e6, "at most 1e6 s");
        }
        c.positive("sample_hz", self.sample_hz);
        c.at_most("sample_hz", self.sample_hz, 1e6, "at most 1e6 Hz");
        c.positive("supply_v", self.supply_v);
        let p = &self.plant;
        c.positive("plant.gain_deg_per_mm", p.gain_deg_per_mm);
        c.positive("plant.backlash.width_mm", p.backlash.width_mm);
        c.fraction("plant.relaxation.fraction", p.relaxation.fraction);
        c.positive("plant.relaxation.tau_s", p.relaxation.tau_s);
        let terms = &p.relaxation.terms;
        c.at_most(
            "plant.relaxation.terms (count)",
            terms.len() as f64,
            MAX_RELAXATION_TERMS as f64,
            "at most 32 terms",
        );
        for (i, t) in terms.iter().enumerate() {
            let k = |name: &str| format!("plant.relaxation.terms[{i}].{name}");
            c.positive(&k("tau_s"), t.tau_s);
            c.fraction(&k("fraction"), t.fraction);
        }
        if !terms.is_empty() {
            let total: f64 = terms.iter().map(|t| t.fraction).sum();
            c.fraction("plant.relaxation.terms (sum of fractions)", total);
        }
        for (i, s) in self.sensors().enumerate() {
            let k = |name: &str| format!("sensor{}.{name}", i + 1);
            c.finite(&k("gauge_factor"), s.gauge_factor.unwrap_or(f64::NAN));
            c.positive(&k("r0_ohm"), s.r0_ohm.unwrap_or(f64::NAN));
            c.positive(&k("divider_ohm"), s.divider_ohm.unwrap_or(f64::NAN));
            c.positive(&k("saturation.strain"), s.saturation.strain);
            c.finite(&k("drift.rate_ohm_per_s"), s.drift.rate_ohm_per_s);
            c.finite(&k("gain_drift.fade_per_hour"), s.gain_drift.fade_per_hour);
            c.at_most(
                &k("gain_drift.fade_per_hour"),
                s.gain_drift.fade_per_hour.abs(),
                MAX_FADE_PER_HOUR,
                "|fade_per_hour| at most 10 (the sensitivity gone in 6 minutes)",
            );
            c.finite(&k("drift.settle_ohm"), s.drift.settle_ohm);
            c.positive(&k("drift.settle_tau_s"), s.drift.settle_tau_s);
            c.non_negative(
                &k("drift.random_walk_ohm_per_sqrt_s"),
                s.drift.random_walk_ohm_per_sqrt_s.unwrap_or(f64::NAN),
            );
            c.finite(&k("rate.per_decade"), s.rate.per_decade);
            c.positive(&k("rate.reference_rate_per_s"), s.rate.reference_rate_per_s);
            c.positive(&k("rate.smoothing_s"), s.rate.smoothing_s);
            c.finite(
                &k("rate.ohm_per_strain_per_s"),
                s.rate.ohm_per_strain_per_s.unwrap_or(f64::NAN),
            );
            c.finite(&k("creep.fraction"), s.creep.fraction);
            c.positive(&k("creep.tau_s"), s.creep.tau_s);
            c.finite(&k("creep.fast_fraction"), s.creep.fast_fraction);
            c.positive(&k("creep.fast_tau_s"), s.creep.fast_tau_s);
            c.non_negative(&k("noise.sigma_ppm"), s.noise.sigma_ppm);
            c.at_most(
                &k("noise.sigma_ppm"),
                s.noise.sigma_ppm,
                MAX_SENSOR_NOISE_PPM,
                "at most 1e5 ppm (10 % of the resistance)",
            );
            c.positive(&k("noise.tau_s"), s.noise.tau_s);
            c.finite(&k("tcr_per_k"), s.tcr_per_k);
            c.at_most(
                &k("tcr_per_k"),
                s.tcr_per_k.abs(),
                MAX_TCR_PER_K,
                "|tcr_per_k| at most 0.01 (1 %/K)",
            );
        }
        for (i, s) in self.sensors().enumerate() {
            let table = |name: &str| format!("sensor{}.{name}", i + 1);
            if let Some(Err(reason)) = s.pi.as_ref().map(PiConfig::validate) {
                return Err(ScenarioError::Model {
                    table: table("pi"),
                    reason,
                });
            }
            if let Some(Err(reason)) = s.continuous_pi.as_ref().map(ContinuousPiConfig::validate) {
                return Err(ScenarioError::Model {
                    table: table("continuous_pi"),
                    reason,
                });
            }
        }
        let a = &self.adc;
        if !(1..=32).contains(&a.bits) {
            c.fail("adc.bits".into(), f64::from(a.bits), "1 to 32");
        }
        c.finite("adc.min_v", a.min_v);
        if !(a.max_v > a.min_v && a.max_v.is_finite()) {
            c.fail("adc.max_v".into(), a.max_v, "finite and above adc.min_v");
        }
        c.non_negative("adc.noise_v", a.noise_v);
        c.non_negative("adc.correlated.sigma_v", a.correlated.sigma_v);
        c.positive("adc.correlated.tau_s", a.correlated.tau_s);
        let t = &self.tracker;
        c.non_negative("tracker.noise_deg", t.noise_deg);
        c.non_negative("tracker.correlated.sigma_deg", t.correlated.sigma_deg);
        c.positive("tracker.correlated.tau_s", t.correlated.tau_s);
        let w = &self.temperature;
        c.non_negative("temperature.sigma_k", w.sigma_k);
        c.at_most(
            "temperature.sigma_k",
            w.sigma_k,
            MAX_TEMPERATURE_SIGMA_K,
            "at most 20 K",
        );
        c.positive("temperature.tau_s", w.tau_s);
        self.protocols
            .check(&mut |key, value, limit| c.fail(format!("protocols.{key}"), value, limit));
        c.finish()
    }
}

fn resolve_sensor(
    s: &mut SensorParams,
    style: NotchStyle,
    index: usize,
) -> Result<(), ScenarioError> {
    let d = sensor_defaults(style, index);
    s.gauge_factor.get_or_insert(d.gauge_factor);
    s.r0_ohm.get_or_insert(d.r0_ohm);
    s.divider_ohm.get_or_insert(d.divider_ohm);
    s.drift
        .random_walk_ohm_per_sqrt_s
        .get_or_insert(d.random_walk_ohm_per_sqrt_s);
    let sensitivity_ohm = s.r0_ohm.unwrap_or(f64::NAN) * s.gauge_factor.unwrap_or(f64::NAN);
    s.rate
        .ohm_per_strain_per_s
        .get_or_insert(SIGNED_RATE_LEAD_S * sensitivity_ohm);
    match s.model {
        SensorModelKind::Linear => {}
        SensorModelKind::Pi if s.pi.is_some() => {}
        SensorModelKind::Pi => match (style, index) {
            (NotchStyle::Uan, _) => s.pi = Some(JOINT_A_PI.to_config()),
            (NotchStyle::Bsn, 1) => s.pi = Some(JOINT_C_PI.to_config()),
            _ => {
                return Err(ScenarioError::MissingModel {
                    sensor: index,
                    model: "pi",
                    why: "the paper fits the compression sensor only linearly",
                })
            }
        },
        SensorModelKind::ContinuousPi if s.continuous_pi.is_some() => {}
        SensorModelKind::ContinuousPi => {
            return Err(ScenarioError::MissingModel {
                sensor: index,
                model: "continuous_pi",
                why: "the paper has no continuous PI fit to default to",
            })
        }
    }
    Ok(())
}

/// Collects the first out-of-range value.
#[derive(Default)]
struct Checker {
    first: Option<ScenarioError>,
}

impl Checker {
    fn fail(&mut self, key: String, value: f64, limit: &'static str) {
        if self.first.is_none() {
            self.first = Some(ScenarioError::OutOfRange { key, value, limit });
        }
    }
    fn finite(&mut self, key: &str, v: f64) {
        if !v.is_finite() {
            self.fail(key.into(), v, "must be a finite number");
        }
    }
    fn positive(&mut self, key: &str, v: f64) {
        if !(v.is_finite() && v > 0.0) {
            self.fail(key.into(), v, "must be finite and greater than 0");
        }
    }
    fn non_negative(&mut self, key: &str, v: f64) {
        if !(v.is_finite() && v >= 0.0) {
            self.fail(key.into(), v, "must be finite and at least 0");
        }
    }
    fn fraction(&mut self, key: &str, v: f64) {
        if !(0.0..1.0).contains(&v) {
            self.fail(key.into(), v, "must lie in [0, 1)");
        }
    }
    fn at_most(&mut self, key: &str, v: f64, max: f64, limit: &'static str) {
        if v > max {
            self.fail(key.into(), v, limit);
        }
    }
    fn finish(self) -> Result<(), ScenarioError> {
        self.first.map_or(Ok(()), Err)
    }
}

/// What a command line may put over a scenario file's values ([`Scenario::overridden`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Overrides {
    /// The stroke protocol.
    pub protocol: Option<ProtocolKind>,
    /// The seed of every random stream.
    pub seed: Option<u64>,
    /// The recording's length (s).
    pub duration_s: Option<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::test_design;

    #[test]
    fn empty_file_resolves_to_documented_defaults() {
        let s: Scenario = toml::from_str("").unwrap();
        let uan = s.clone().resolve(&test_design(NotchStyle::Uan)).unwrap();
        assert_eq!(uan.sample_hz, 500.0);
        assert_eq!(uan.plant.gain_deg_per_mm, 35.49);
        assert_eq!(uan.sensor1.gauge_factor, Some(15.3));
        assert_eq!(uan.sensor1.r0_ohm, Some(215e3));
        assert_eq!(uan.sensor1.divider_ohm, Some(99.6e3));
        assert!(uan.sensor2.is_none());
        let bsn = s.resolve(&test_design(NotchStyle::Bsn)).unwrap();
        let s2 = bsn.sensor2.as_ref().unwrap();
        assert_eq!(bsn.sensor1.gauge_factor, Some(1.28));
        assert_eq!(s2.gauge_factor, Some(0.680));
        assert_eq!(s2.r0_ohm, Some(88.9e3));
        assert_eq!(s2.divider_ohm, Some(102.5e3));
    }

    #[test]
    fn resolved_scenario_round_trips_through_toml() {
        let s: Scenario = toml::from_str(
            "seed = 9\n[sensor1]\nmodel = \"pi\"\n[sensor1.rate]\nform = \"signed\"\n[adc.correlated]\nsigma_v = 0.003\n[tracker.correlated]\n[protocols]\nrest_start_s = 4.0\n",
        )
        .unwrap();
        let r = s.resolve(&test_design(NotchStyle::Bsn)).unwrap();
        assert_eq!(r.sensor1.rate.form, RateForm::Signed);
        assert!(r.adc.correlated.enabled && r.tracker.correlated.enabled);
        let text = toml::to_string(&r).unwrap();
        let back: Scenario = toml::from_str(&text).unwrap();
        assert_eq!(back, r);
        assert_eq!(
            back.clone().resolve(&test_design(NotchStyle::Bsn)).unwrap(),
            r
        );
        // A relaxation's Prony series too, as `discover` writes it.
        let s: Scenario = toml::from_str(
            "[[plant.relaxation.terms]]\nfraction = 0.2\ntau_s = 2.0\n[[plant.relaxation.terms]]\nfraction = 0.05\ntau_s = 64.0\n",
        )
        .unwrap();
        let r = s.resolve(&test_design(NotchStyle::Uan)).unwrap();
        assert!(r.plant.relaxation.enabled);
        assert_eq!(r.plant.relaxation.series(), vec![(0.2, 2.0), (0.05, 64.0)]);
        let back: Scenario = toml::from_str(&toml::to_string(&r).unwrap()).unwrap();
        assert_eq!(back, r);
    }

    #[test]
    fn refuses_unknown_keys_and_bad_values() {
        let err = toml::from_str::<Scenario>("[plant.relaxation]\ntau = 3\n").unwrap_err();
        assert!(err.to_string().contains("tau"), "{err}");
        let table = [
            ("sample_hz = 0.0", "sample_hz"),
            (
                "[plant.relaxation]\nfraction = 1.5",
                "plant.relaxation.fraction",
            ),
            ("[sensor1]\nr0_ohm = -5.0", "sensor1.r0_ohm"),
            ("[adc]\nbits = 40", "adc.bits"),
            ("[adc]\nmax_v = -20.0", "adc.max_v"),
            ("[tracker]\nnoise_deg = -1.0", "tracker.noise_deg"),
            ("[adc.correlated]\ntau_s = 0.0", "adc.correlated.tau_s"),
            ("[adc.correlated]\nsigma_v = -0.1", "adc.correlated.sigma_v"),
            (
                "[tracker.correlated]\nsigma_deg = -1.0",
                "tracker.correlated.sigma_deg",
            ),
            (
                "[tracker.correlated]\ntau_s = -2.0",
                "tracker.correlated.tau_s",
            ),
            (
                "[sensor1.rate]\nform = \"signed\"\nohm_per_strain_per_s = nan",
                "sensor1.rate.ohm_per_strain_per_s",
            ),
            ("[protocols]\nrest_start_s = -1.0", "protocols.rest_start_s"),
            ("[temperature]\nsigma_k = -1.0", "temperature.sigma_k"),
            ("[temperature]\nsigma_k = 50.0", "temperature.sigma_k"),
            ("[temperature]\ntau_s = 0.0", "temperature.tau_s"),
            ("[sensor1]\ntcr_per_k = 0.5", "sensor1.tcr_per_k"),
            (
                "[sensor1.noise]\nsigma_ppm = -1.0",
                "sensor1.noise.sigma_ppm",
            ),
            (
                "[sensor1.noise]\nsigma_ppm = 2e5",
                "sensor1.noise.sigma_ppm",
            ),
            ("[sensor1.noise]\ntau_s = 0.0", "sensor1.noise.tau_s"),
            ("[sensor1]\ntcr_per_k = nan", "sensor1.tcr_per_k"),
            (
                "[[plant.relaxation.terms]]\nfraction = 0.1\ntau_s = 0.0",
                "plant.relaxation.terms[0].tau_s",
            ),
            (
                "[[plant.relaxation.terms]]\nfraction = 0.1\ntau_s = 1.0\n[[plant.relaxation.terms]]\nfraction = -1.0\ntau_s = 9.0",
                "plant.relaxation.terms[1].fraction",
            ),
            (
                "[[plant.relaxation.terms]]\nfraction = 0.6\ntau_s = 1.0\n[[plant.relaxation.terms]]\nfraction = 0.5\ntau_s = 9.0",
                "plant.relaxation.terms (sum of fractions)",
            ),
        ];
        for (text, key) in table {
            let s: Scenario = toml::from_str(text).unwrap();
            let err = s
                .resolve(&test_design(NotchStyle::Uan))
                .unwrap_err()
                .to_string();
            assert!(err.contains(key), "{text}: {err}");
        }
    }

    /// Every effect table: absent keeps the default (off; on for `[adc]` and `[tracker]`),
    /// present is on, present with `enabled = false` is off.
    #[test]
    fn a_present_effect_table_is_on_unless_it_says_off() {
        type Switch = fn(&Scenario) -> bool;
        let tables: [(&str, bool, Switch); 17] = [
            ("[plant.backlash]", false, |s| s.plant.backlash.enabled),
            ("[plant.relaxation]\nfraction = 0.1", false, |s| {
                s.plant.relaxation.enabled
            }),
            ("[plant.notch_limit]", false, |s| {
                s.plant.notch_limit.enabled
            }),
            ("[sensor1.saturation]\nstrain = 0.01", false, |s| {
                s.sensor1.saturation.enabled
            }),
            ("[sensor1.drift]\nrate_ohm_per_s = 3.0", false, |s| {
                s.sensor1.drift.enabled
            }),
            ("[sensor1.rate]\nform = \"signed\"", false, |s| {
                s.sensor1.rate.enabled
            }),
            ("[sensor1.creep]", false, |s| s.sensor1.creep.enabled),
            ("[sensor2.drift]", false, |s| {
                s.sensor2.as_ref().is_some_and(|p| p.drift.enabled)
            }),
            ("[adc]\nnoise_v = 0.001", true, |s| s.adc.enabled),
            ("[adc.correlated]", false, |s| s.adc.correlated.enabled),
            ("[tracker]\nnoise_deg = 0.1", true, |s| s.tracker.enabled),
            ("[tracker.correlated]\ntau_s = 3.0", false, |s| {
                s.tracker.correlated.enabled
            }),
            ("[sensor2.rate]", false, |s| {
                s.sensor2.as_ref().is_some_and(|p| p.rate.enabled)
            }),
            ("[sensor2.saturation]", false, |s| {
                s.sensor2.as_ref().is_some_and(|p| p.saturation.enabled)
            }),
            ("[temperature]\nsigma_k = 1.0", false, |s| {
                s.temperature.enabled
            }),
            ("[sensor1.noise]\nsigma_ppm = 10.0", false, |s| {
                s.sensor1.noise.enabled
            }),
            ("[sensor2.noise]", false, |s| {
                s.sensor2.as_ref().is_some_and(|p| p.noise.enabled)
            }),
        ];
        let bsn = test_design(NotchStyle::Bsn);
        let parse = |text: &str| -> Scenario {
            toml::from_str::<Scenario>(text)
                .unwrap()
                .resolve(&bsn)
                .unwrap()
        };
        let absent = parse("");
        for (table, default, on) in tables {
            assert_eq!(on(&absent), default, "{table} absent");
            assert!(on(&parse(table)), "{table} present");
            assert!(
                !on(&parse(&format!("{table}\nenabled = false\n"))),
                "{table} with enabled = false"
            );
            assert!(
                on(&parse(&format!("{table}\nenabled = true\n"))),
                "{table} with enabled = true"
            );
        }
        // A table switched on keeps the other keys' defaults and the keys given.
        let r = parse("[plant.relaxation]\nfraction = 0.1\n");
        assert_eq!(
            (r.plant.relaxation.fraction, r.plant.relaxation.tau_s),
            (0.1, 20.0)
        );
        assert!(!r.plant.backlash.enabled && !r.sensor1.drift.enabled);
    }

    #[test]
    fn pi_defaults_and_missing_models() {
        let s: Scenario = toml::from_str("[sensor1]\nmodel = \"pi\"\n").unwrap();
        let r = s.resolve(&test_design(NotchStyle::Uan)).unwrap();
        assert_eq!(r.sensor1.pi, Some(JOINT_A_PI.to_config()));
        let s: Scenario = toml::from_str("[sensor2]\nmodel = \"pi\"\n").unwrap();
        let err = s
            .resolve(&test_design(NotchStyle::Bsn))
            .unwrap_err()
            .to_string();
        assert!(err.contains("[sensor2.pi] is missing"), "{err}");
        let s: Scenario = toml::from_str("[sensor1]\nmodel = \"continuous_pi\"\n").unwrap();
        let err = s
            .resolve(&test_design(NotchStyle::Uan))
            .unwrap_err()
            .to_string();
        assert!(err.contains("[sensor1.continuous_pi] is missing"), "{err}");
        let text = "[sensor1]\nmodel = \"pi\"\n[sensor1.pi]\nweights = [0.0]\nradii = [0.0]\nloading_tanh = [1.0, 1.0, 0.0, 0.0]\nunloading_tanh = [1.0, 1.0, 0.0, 0.0]\ncenter_strain = 0.0\ncenter_ohm = 1e5\nmin_ohm = 9e4\nmax_ohm = 1.1e5\n";
        let s: Scenario = toml::from_str(text).unwrap();
        let err = s
            .resolve(&test_design(NotchStyle::Uan))
            .unwrap_err()
            .to_string();
        assert!(err.contains("[sensor1.pi]"), "{err}");
    }

    #[test]
    fn second_sensor_on_uan_is_refused() {
        let s: Scenario = toml::from_str("[sensor2]\ngauge_factor = 1.0\n").unwrap();
        let err = s
            .resolve(&test_design(NotchStyle::Uan))
            .unwrap_err()
            .to_string();
        assert!(err.contains("sensor2") && err.contains("Joint A"), "{err}");
    }
}
