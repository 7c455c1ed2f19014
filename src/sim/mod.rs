//! The bench simulator: produces recordings of the paper's bench, in the format a real bench
//! recording uses, from a design, a protocol and a scenario.
//!
//! The chain, one sample at a time (500 Hz by default):
//!
//! ```text
//! tendon stroke ─plant─▶ joint angle θ ─Joint::strain─▶ ε ─sensor─▶ R ─Divider::voltage─▶ V ─ADC─▶ v1_V
//!   (protocol)              │                          (sensor 2: −ε, its own divider)          ─▶ v2_V
//!                           └──────────── EM tracker ─────────────────────────────────────────▶ angle_deg
//! ```
//!
//! Strain and voltage use `dlw_geometry`, the code the planner and the runtime estimator use, so
//! a simulated joint is read with exactly the geometry it was simulated with. Each effect
//! (backlash, relaxation, the notch limit, saturation, drift, rate dependence, creep, ADC and
//! tracker noise, white and correlated) is switched on in the [`Scenario`] with its parameters. Every random draw comes
//! from a ChaCha stream of the scenario's seed, one stream per source, so a seed gives the same
//! recording on every platform.
//!
//! Plan, then run: [`plan`] resolves the scenario against the design and builds the stroke
//! profile; [`Plan::run`] generates the samples in memory, stepping a [`Bench`] (the chain
//! above, one sample at a time, which a controller can also drive); [`Recording::write`]
//! writes them.
//!
//! # Examples
//! ```
//! use dlw::design::Design;
//! use dlw::sim::{plan, ProtocolKind, Scenario};
//!
//! let design = Design::from_toml(include_str!("../../designs/joint-d.toml"))?;
//! let scenario = Scenario {
//!     protocol: Some(ProtocolKind::Characterization),
//!     duration_s: Some(2.0),
//!     ..Scenario::default()
//! };
//! let run = plan(&design, scenario, None)?.run()?;
//! assert_eq!(run.samples.len(), 1000);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Errors
//! [`SimError`]: a scenario value out of range, an unreadable stroke profile, or a scenario that
//! drives a sensor to a non-physical resistance or a divider to a rail.

mod bench;
mod correlated;
mod measure;
mod pi_default;
mod plant;
mod protocol;
mod rng;
pub mod robot;
mod scenario;
mod sensor;

use std::path::PathBuf;

use crate::design::Design;

/// Recording folders: reading, checking and writing.
/// Moved to [`crate::recording`]; these re-exports keep old paths compiling this round.
pub use crate::recording::{
    header, Recording, RecordingError, Rig, Samples, SimulationInfo, DATA_FILE, RIG_FILE,
};
/// The bench stepped one sample at a time (shared by `Plan::run` and closed-loop control).
pub use bench::{Bench, Reading};
/// Correlated (first-order autoregressive) measurement noise.
pub use correlated::Ar1;
/// The divider, ADC and EM tracker models.
pub use measure::{Adc, Tracker};
/// Default PI sensor models from the paper's Table III.
pub use pi_default::{PiCharacteristics, DEFAULT_HYSTERESIS_SHARE, JOINT_A_PI, JOINT_C_PI};
/// Stroke → angle with backlash, relaxation and the notch limit.
pub use plant::Plant;
/// Stroke profiles of the paper's protocols and from CSV.
pub use protocol::{
    parse_series, Characterization, CustomProtocol, Knot, ProtocolError, ProtocolKind,
    ProtocolParams, RandomProtocol, RateDependenceProtocol, RelaxationProtocol, Sampler,
    StrokeProfile, DEFAULT_REST_START_S,
};
/// Seeded random streams.
pub use rng::{streams, Stream};
/// The scenario file: every effect, switchable, with documented defaults.
pub use scenario::{
    AdcCorrelated, AdcParams, Backlash, Creep, Drift, NotchLimit, Overrides, PlantParams,
    RateDependence, RateForm, Relaxation, RelaxationTerm, Saturation, Scenario, ScenarioError,
    SensorModelKind, SensorNoise, SensorParams, Temperature, TrackerCorrelated, TrackerParams,
    DEFAULT_TCR_PER_K, MAX_FADE_PER_HOUR, MAX_RELAXATION_TERMS, MAX_SENSOR_NOISE_PPM,
    MAX_TCR_PER_K, SIGNED_RATE_LEAD_S,
};
/// Strain → resistance with saturation, drift, rate dependence and creep.
pub use sensor::Sensor;

/// Why a simulation failed.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// The scenario was refused.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// The stroke profile could not be built.
    #[error(transparent)]
    Protocol(#[from] ProtocolError),
    /// A sensor model gave a resistance no physical sensor has.
    #[error("sensor {sensor} resistance is {ohm} Ω at t = {time_s} s (strain {strain}), must be finite and greater than 0: the scenario drives the sensor model beyond where it is physical")]
    Resistance {
        /// 1 or 2.
        sensor: usize,
        /// Sample time (s).
        time_s: f64,
        /// The resistance.
        ohm: f64,
        /// The joint strain at that sample.
        strain: f64,
    },
    /// The recording would not fit in memory.
    #[error("duration_s = {duration_s} s at {sample_hz} Hz is {samples} samples, more than the {max} a simulation may hold")]
    TooLong {
        /// Requested duration (s).
        duration_s: f64,
        /// Sample rate (Hz).
        sample_hz: f64,
        /// Samples that would need.
        samples: f64,
        /// The limit, [`MAX_SAMPLES`].
        max: usize,
    },
    /// A recorded voltage reached a rail, which no reader accepts.
    #[error("sensor {sensor} voltage is {volts} V at t = {time_s} s, at or beyond a rail (must lie strictly between 0 and supply_v = {supply_v} V): check the ADC range and the divider")]
    Rail {
        /// 1 or 2.
        sensor: usize,
        /// Sample time (s).
        time_s: f64,
        /// The recorded voltage.
        volts: f64,
        /// The supply.
        supply_v: f64,
    },
}

/// Most samples one simulation holds in memory: 20 million, 11 hours at 500 Hz (about 1 GB of
/// samples and 750 MB of CSV).
pub const MAX_SAMPLES: usize = 20_000_000;

/// A resolved simulation: everything concrete, ready to run.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The design.
    pub design: Design,
    /// The resolved scenario: protocol, duration, seed and every parameter set.
    pub scenario: Scenario,
    /// The stroke profile, covering the duration.
    pub profile: StrokeProfile,
    /// Samples to generate: `round(duration_s·sample_hz)`.
    pub samples: usize,
}

/// The output of a run.
#[derive(Debug, Clone)]
pub struct Run {
    /// The recorded columns, as the bench would write them.
    pub samples: Samples,
    /// The true joint angle (°) before the tracker's noise; not part of a recording.
    pub true_angle_deg: Vec<f64>,
}

/// Resolves `scenario` (with any command-line overrides already applied) against `design` and
/// builds the stroke profile. `profile` overrides the scenario's custom profile path.
///
/// # Errors
/// [`SimError::Scenario`] for a refused value or no protocol; [`SimError::Protocol`] for a bad
/// or missing stroke profile.
pub fn plan(
    design: &Design,
    scenario: Scenario,
    profile: Option<PathBuf>,
) -> Result<Plan, SimError> {
    let mut scenario = scenario.resolve(design)?;
    let kind = scenario.protocol.ok_or(ScenarioError::NoProtocol)?;
    if profile.is_some() {
        scenario.protocols.custom.profile = profile;
    }
    let stroke = match kind {
        ProtocolKind::Custom => {
            let path = scenario
                .protocols
                .custom
                .profile
                .as_ref()
                .ok_or(ProtocolError::NoProfile)?;
            StrokeProfile::from_csv(path)?
        }
        _ => {
            let mut rng = Stream::new(scenario.seed, streams::PROTOCOL);
            let amplitude_mm = scenario.protocols.amplitude_mm.unwrap_or(0.0);
            StrokeProfile::built_in(
                kind,
                &scenario.protocols,
                amplitude_mm,
                scenario.duration_s,
                &mut rng,
            )?
        }
    };
    let duration_s = *scenario
        .duration_s
        .get_or_insert(stroke.natural_duration_s());
    let samples = (duration_s * scenario.sample_hz).round().max(1.0);
    if samples > MAX_SAMPLES as f64 {
        return Err(SimError::TooLong {
            duration_s,
            sample_hz: scenario.sample_hz,
            samples,
            max: MAX_SAMPLES,
        });
    }
    let samples = samples as usize;
    Ok(Plan {
        design: design.clone(),
        scenario,
        profile: stroke,
        samples,
    })
}

impl Plan {
    /// The terminal's line for `run`, written to `output`: samples, duration and rate,
    /// protocol, seed, the correlated noise switched on, and the peak true angle.
    pub fn summary(&self, run: &Run, output: &std::path::Path) -> String {
        let sc = &self.scenario;
        let peak_deg = run
            .true_angle_deg
            .iter()
            .fold(0.0f64, |m, a| m.max(a.abs()));
        let correlated = match (sc.adc.correlated.enabled, sc.tracker.correlated.enabled) {
            (true, true) => ", correlated ADC and tracker noise",
            (true, false) => ", correlated ADC noise",
            (false, true) => ", correlated tracker noise",
            (false, false) => "",
        };
        format!(
            "wrote {}: {} samples ({} s at {} Hz), {} protocol, seed {}{correlated}, peak angle {:.2}°\n",
            output.display(),
            self.samples,
            sc.duration_s.unwrap_or(0.0),
            sc.sample_hz,
            sc.protocol.map_or("?", ProtocolKind::name),
            sc.seed,
            peak_deg
        )
    }

    /// Generates every sample in memory.
    ///
    /// # Errors
    /// [`SimError::Resistance`] or [`SimError::Rail`] at the first sample where the scenario
    /// leaves the physical range.
    pub fn run(&self) -> Result<Run, SimError> {
        let sc = &self.scenario;
        let mut bench = Bench::new(sc, &self.design.joint)?;
        let channels = bench.channels();
        let mut stroke = self.profile.sampler();
        let n = self.samples;
        let mut out = Samples::with_capacity(channels, n);
        let mut true_angle_deg = Vec::with_capacity(n);
        for i in 0..n {
            let time_s = i as f64 / sc.sample_hz;
            let stroke_mm = stroke.at(time_s);
            let reading = bench.step(time_s, stroke_mm)?;
            for (column, volts) in out.volts.iter_mut().zip(reading.volts) {
                column.push(volts);
            }
            true_angle_deg.push(reading.angle_rad.to_degrees());
            out.time_s.push(time_s);
            out.stroke_mm.push(stroke_mm);
            out.angle_deg.push(reading.tracked_deg);
        }
        Ok(Run {
            samples: out,
            true_angle_deg,
        })
    }

    /// The recording's `rig.toml`: the bench's settings plus the design and resolved scenario.
    pub fn rig(&self) -> Rig {
        Rig {
            sample_hz: self.scenario.sample_hz,
            supply_v: self.scenario.supply_v,
            divider_ohm: self
                .scenario
                .sensors()
                .map(|s| s.divider_ohm.unwrap_or(f64::NAN))
                .collect(),
            notes: Some(format!(
                "simulated by dlw {}: {} protocol, seed {}",
                env!("CARGO_PKG_VERSION"),
                self.scenario.protocol.map_or("?", ProtocolKind::name),
                self.scenario.seed
            )),
            simulation: Some(SimulationInfo {
                dlw_version: env!("CARGO_PKG_VERSION").to_string(),
                design_checksum: self.design.checksum.clone(),
            }),
            protocol: None,
            design: toml::Table::try_from(&self.design.file).ok(),
            scenario: toml::Table::try_from(&self.scenario).ok(),
            import: None,
        }
    }
}

/// The scenario a simulated recording's `rig.toml` records, read back as the simulator's type;
/// `None` for a recording that records none (imported, or written by hand).
///
/// # Errors
/// The TOML deserializer's message, naming the key, when the `[scenario]` table is not a
/// scenario this version reads.
pub fn scenario_of(rig: &Rig) -> Result<Option<Scenario>, String> {
    rig.scenario
        .clone()
        .map(|t| {
            t.try_into::<Scenario>()
                .map_err(|e| format!("rig.toml [scenario]: {e}"))
        })
        .transpose()
}

/// Joint A (UAN) or Joint C (BSN) of the paper's Table I, for tests.
#[cfg(test)]
pub(crate) fn test_design(style: dlw_geometry::NotchStyle) -> Design {
    let text = match style {
        dlw_geometry::NotchStyle::Uan => include_str!("../../designs/joint-a.toml"),
        dlw_geometry::NotchStyle::Bsn => include_str!("../../designs/joint-c.toml"),
    };
    Design::from_toml(text).expect("the shipped designs are valid")
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use dlw_geometry::{Divider, NotchStyle};

    fn scenario(kind: ProtocolKind, duration_s: f64) -> Scenario {
        Scenario {
            protocol: Some(kind),
            duration_s: Some(duration_s),
            ..Scenario::default()
        }
    }

    #[test]
    fn amplitude_reaches_the_peak_strain_from_the_geometry() {
        let design = test_design(NotchStyle::Uan);
        let mut sc = scenario(ProtocolKind::Characterization, 1000.0);
        sc.tracker.enabled = false;
        let plan = plan(&design, sc, None).unwrap();
        let run = plan.run().unwrap();
        let peak_deg = run.true_angle_deg.iter().cloned().fold(0.0, f64::max);
        let peak_strain = design.joint.strain(peak_deg.to_radians());
        assert_relative_eq!(peak_strain, 0.015, max_relative = 1e-3);
        // Joint A: ~1.5 % at about 28° (the paper: 1.35 % at 26°).
        assert!((27.0..30.0).contains(&peak_deg), "{peak_deg}");
    }

    #[test]
    fn noise_free_chain_inverts_exactly() {
        let design = test_design(NotchStyle::Bsn);
        let mut sc = scenario(ProtocolKind::Random, 60.0);
        sc.adc.enabled = false;
        sc.tracker.enabled = false;
        let plan = plan(&design, sc, None).unwrap();
        let run = plan.run().unwrap();
        let s = &plan.scenario;
        let s2 = s.sensor2.as_ref().unwrap();
        let d1 = Divider::new(99.6e3, 5.0).unwrap();
        let d2 = Divider::new(102.5e3, 5.0).unwrap();
        for i in (0..run.samples.len()).step_by(97) {
            let r1 = d1.resistance(run.samples.volts[0][i]).unwrap();
            let r2 = d2.resistance(run.samples.volts[1][i]).unwrap();
            let e1 = (r1 / 74.0e3 - 1.0) / 1.28;
            let e2 = (r2 / s2.r0_ohm.unwrap() - 1.0) / 0.680;
            let theta = design.joint.two_sensor_angle(e1, e2).unwrap().to_degrees();
            assert_relative_eq!(theta, run.samples.angle_deg[i], epsilon = 1e-9);
        }
    }

    #[test]
    fn same_seed_same_samples_other_seed_other_samples() {
        let design = test_design(NotchStyle::Uan);
        let run = |seed| {
            let mut sc = scenario(ProtocolKind::Random, 20.0);
            sc.seed = seed;
            plan(&design, sc, None).unwrap().run().unwrap().samples
        };
        assert_eq!(run(1), run(1));
        assert_ne!(run(1), run(2));
    }

    #[test]
    fn nonphysical_resistance_is_an_error_not_a_panic() {
        let design = test_design(NotchStyle::Uan);
        let mut sc = scenario(ProtocolKind::Characterization, 100.0);
        sc.sensor1.gauge_factor = Some(-200.0);
        // Without ADC noise the voltage cannot reach the rail before the resistance reaches 0.
        sc.adc.enabled = false;
        let err = plan(&design, sc, None)
            .unwrap()
            .run()
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("sensor 1 resistance")
                && err.contains("must be finite and greater than 0"),
            "{err}"
        );
    }

    #[test]
    fn refuses_recordings_too_long_to_hold() {
        let design = test_design(NotchStyle::Uan);
        let err = plan(&design, scenario(ProtocolKind::Random, 1e6), None)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("500000000 samples") && err.contains("20000000"),
            "{err}"
        );
    }

    #[test]
    fn rig_records_dividers_design_and_scenario() {
        let design = test_design(NotchStyle::Bsn);
        let plan = plan(&design, scenario(ProtocolKind::Relaxation, 10.0), None).unwrap();
        let rig = plan.rig();
        assert_eq!(rig.divider_ohm, vec![99.6e3, 102.5e3]);
        let file: crate::design::DesignFile = rig.design.clone().unwrap().try_into().unwrap();
        assert_eq!(file, design.file);
        let sc = scenario_of(&rig).unwrap().unwrap();
        assert_eq!(sc.duration_s, Some(10.0));
        assert!(sc.protocols.amplitude_mm.is_some());
        let text = toml::to_string(&rig).unwrap();
        let back: Rig = toml::from_str(&text).unwrap();
        assert_eq!(back, rig);
    }

    /// `[temperature]`: both sensors of a BSN joint at rest read `R₀·(1 + tcr·T)` with one
    /// shared `T` of the configured spread, so Eq. 7's difference of the relative changes
    /// cancels it when the two coefficients are equal; switching it on leaves every other
    /// stream's draws alone.
    #[test]
    fn temperature_wander_moves_both_sensors_together() {
        let design = test_design(NotchStyle::Bsn);
        let mut sc = scenario(ProtocolKind::Characterization, 400.0);
        sc.protocols.rest_start_s = 400.0;
        sc.adc.enabled = false;
        sc.tracker.enabled = false;
        sc.temperature = Temperature {
            enabled: true,
            sigma_k: 2.0,
            tau_s: 5.0,
        };
        let plan = plan(&design, sc, None).unwrap();
        let run = plan.run().unwrap();
        let d1 = Divider::new(99.6e3, 5.0).unwrap();
        let d2 = Divider::new(102.5e3, 5.0).unwrap();
        let relative = |i: usize| {
            let r1 = d1.resistance(run.samples.volts[0][i]).unwrap() / 74.0e3 - 1.0;
            let r2 = d2.resistance(run.samples.volts[1][i]).unwrap() / 88.9e3 - 1.0;
            (r1, r2)
        };
        let kelvin: Vec<f64> = (0..run.samples.len())
            .map(|i| {
                let (r1, r2) = relative(i);
                assert_relative_eq!(r1, r2, epsilon = 1e-12);
                r1 / DEFAULT_TCR_PER_K
            })
            .collect();
        // 400 s of a 5 s process: 80 correlation times, the spread within about 10 %.
        let (sd, r1) = correlated::sd_and_autocorrelation(&kelvin, 1);
        assert_relative_eq!(sd, 2.0, max_relative = 0.2);
        assert!((r1 - (-0.002f64 / 5.0).exp()).abs() < 1e-4, "{r1}");
        // Off, the same seed's ADC and tracker draws are unchanged.
        let mut noisy = scenario(ProtocolKind::Random, 20.0);
        let white = plan_run(&design, noisy.clone());
        noisy.temperature.enabled = true;
        noisy.sensor1.tcr_per_k = 0.0;
        noisy.sensor2 = Some(SensorParams {
            tcr_per_k: 0.0,
            ..SensorParams::default()
        });
        // (`assert!`, not `assert_eq!`: a failure would print every sample.)
        assert!(plan_run(&design, noisy) == white);
    }

    fn plan_run(design: &Design, sc: Scenario) -> Samples {
        plan(design, sc, None).unwrap().run().unwrap().samples
    }
}
