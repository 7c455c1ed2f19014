//! The paper's Section IV on the simulator, in one run (`dlw reproduce`): Joints A-D
//! characterized, fitted, rate- and relaxation-tested, estimated on a random pattern, Joint C
//! with two sensors, and Joint D in closed loop, with the paper's Tables III-VI beside `dlw`'s.
//!
//! ```text
//! joints A-C: characterization ─loops (fit)─▶ Table III, Fig. 4 ─configs─┐
//!             rate-dependence ─rate────────▶ Fig. 5                     │
//!             relaxation ─────relaxation───▶ Fig. 6                     ▼
//!             random ─────────estimation───▶ Table IV, Fig. 7; Joint C: Table V, Fig. 8
//! joint D:    characterization ─fit (PI, N = 3)─▶ config ─control─▶ Table VI, Fig. 10
//! ```
//!
//! The joints run in parallel, one thread each. Every protocol keeps the paper's five
//! repetitions; `duration_scale` shrinks every timing (ramps, holds, rests, the relaxation time
//! constant) by the same factor, so a short run has the same structure in less time.
//!
//! # Errors
//! [`ReproduceError`] names the joint and the experiment that failed.

mod agreement;
mod joints;
pub mod paper;
pub mod patterns;
mod prose;
mod report;
mod result;
mod twin;

use std::path::PathBuf;
use std::sync::Mutex;
use std::time::Instant;

use dlw_estimator::{FilterConfig, ModelConfig};

use crate::characterize::{
    estimate, loops, planes, rate, relaxation, CharacterizeError, EstimationResult, LoopsResult,
    NamedConfig, Options, RateResult, RelaxationResult, DEFAULT_MIN_HOLD_S,
};
use crate::control::{Control, ControlError, ControlResult, DesiredSource, PAPER_GAINS};
use crate::fit::{estimator_config, FitError, ModelKind, PlayOrder};
use crate::signal::Prefilter;
use crate::sim::{plan, ProtocolKind, Recording, SimError};

/// The run's numbers against the paper's, each with its limit, and why one stays outside.
pub use agreement::{
    checks, finding, moved, moved_text, Check, Moved, Unit, HEADLINE_TOLERANCE, TABLE3_ROWS,
};
/// The simulated joints and their scenarios.
pub use joints::{joints, scaled, SimJoint, JOINT_B_PI};
/// The paper's patterns as named checks.
pub use patterns::{max_rate_correlation, patterns, Pattern, RELAXATION_TAU_TOLERANCE};
/// The report page.
pub use report::page;
/// The bench a reproduction runs on: ideal, or the calibrated twin of a bench file.
pub use twin::{
    Bench, BenchFile, Provenance, Range, Tradeoff, TwinError, LETTERS, PAPER_BENCH_PATH,
    PAPER_BENCH_TOML,
};

/// `--short`: every timing a tenth of the paper's.
pub const SHORT_SCALE: f64 = 0.1;

/// The paper's order of Joint D's PI model, "for the purpose of simplifying the control system".
pub const CONTROL_ORDER: PlayOrder = match PlayOrder::checked(3) {
    Some(order) => order,
    None => panic!("3 plays is a PI order the runtime runs"),
};

/// Joint D's desired angle peaks at this share of the strain range its characterization
/// covered. The sensor reads nothing beyond that range (the PI inverse stops at its end), so a
/// desired angle past it cannot be followed in closed loop: Joint D relaxes 15 %, its
/// characterization reached 1.32 % of the 1.5 % it was driven to, and a desired pattern up to
/// the nominal 1.5 % (50°) held the estimate at its 43.5° end while the loop drove the joint to
/// 66-91° (Table VI's closed loop was 8.72° against 4.22° open loop).
pub const CONTROL_RANGE_SHARE: f64 = 0.95;

/// The fits keep at most about this many samples (`dlw fit`: `crate::fit::MAX_FIT_SAMPLES`,
/// 8000). Joint C's PI fits take about 40 s each on 8000 samples; on 4000 they fit in the
/// reproduction's minute, and `docs/performance.md` shows that decimation costs the fit
/// little.
pub const MAX_FIT_SAMPLES: usize = 4000;

/// Why the reproduction stopped.
#[derive(Debug, thiserror::Error)]
pub enum ReproduceError {
    /// A duration scale that is not a positive number.
    #[error("--duration-scale {value} must lie in (0, 1]")]
    Scale {
        /// The value given.
        value: f64,
    },
    /// A simulation failed.
    #[error("simulating Joint {joint}'s {protocol} protocol: {source}")]
    Sim {
        /// The joint.
        joint: char,
        /// The protocol.
        protocol: &'static str,
        /// Why.
        source: SimError,
    },
    /// An analysis failed.
    #[error("Joint {joint}, {analysis}: {source}")]
    Analysis {
        /// The joint.
        joint: char,
        /// The analysis.
        analysis: &'static str,
        /// Why.
        source: CharacterizeError,
    },
    /// A config could not be built from the fits.
    #[error("Joint {joint}, the {model} config: {source}")]
    Config {
        /// The joint.
        joint: char,
        /// The model.
        model: &'static str,
        /// Why.
        source: FitError,
    },
    /// The control simulation failed.
    #[error("Joint D in closed loop: {0}")]
    Control(#[from] ControlError),
    /// Repetitions outside 1 to 5.
    #[error("repeats = {value} must lie in 1 to 5 (the paper's protocols repeat five times)")]
    Repeats {
        /// The value given.
        value: u32,
    },
}

/// How each experiment of one reproduction is sized.
#[derive(Debug, Clone, Copy)]
struct Run {
    scale: f64,
    repeats: u32,
    /// The models the characterization fits.
    models: &'static [ModelKind],
    /// The reproduction's seed ([`Settings::seed`]).
    seed: u64,
}

/// What a reproduction runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Every protocol timing times this, in (0, 1]; 1 is the paper's (1000 s characterization,
    /// 3000 s for the others).
    pub duration_scale: f64,
    /// Repetitions of every protocol, 1 to 5; the paper's 5 unless a calibration asks for a
    /// short-sized run ([`CALIBRATION_REPEATS`]).
    pub repeats: u32,
    /// The simulated bench: the calibrated twin by default, `--ideal` for the clean joints.
    pub bench: Bench,
    /// Which noise the simulations draw (`--seed`): 0, the default, is the seeds every shipped
    /// number was measured with; another value moves every simulation's seed by
    /// [`SEED_STRIDE`] times it, so a second seed is a second bench run of the same scenarios.
    pub seed: u64,
}

impl Settings {
    /// Every experiment at `duration_scale`, five repetitions, on `bench`.
    pub fn new(duration_scale: f64, bench: Bench) -> Self {
        Self {
            duration_scale,
            repeats: PAPER_REPEATS,
            bench,
            seed: 0,
        }
    }
}

/// The simulations of one reproduction use seeds below this (Joints A-C 0-24, Joint D 31-32),
/// so [`Settings::seed`] `s` moves them all to `s × SEED_STRIDE + …` without overlap.
pub const SEED_STRIDE: u64 = 100;

/// The paper's repetitions of every protocol.
pub const PAPER_REPEATS: u32 = 5;

/// A calibration's short-sized evaluation: every protocol once, at the paper's timings (a fifth
/// of a full run; `--short` shrinks the timings instead, which changes what the 2 s average does
/// to the random pattern's ramps).
pub const CALIBRATION_REPEATS: u32 = 1;

/// One of Joints A-C: every analysis.
#[derive(Debug, Clone)]
pub struct JointResult {
    /// `A`, `B`, `C`.
    pub letter: char,
    /// The characterization: loops and fits (Table III); both sensors of Joint C (Table V).
    pub loops: LoopsResult,
    /// Rate dependence.
    pub rate: RateResult,
    /// Relaxation.
    pub relaxation: RelaxationResult,
    /// The random pattern estimated with the fitted linear and PI configs (Table IV) and, for
    /// Joint C, the linear two-sensor config (Table V).
    pub estimation: EstimationResult,
    /// The simulated relaxation time constant (s), scaled with the run's timings.
    pub simulated_tau_s: f64,
}

/// Everything the report shows.
#[derive(Debug, Clone)]
pub struct Reproduction {
    /// The settings.
    pub settings: Settings,
    /// Joints A-C.
    pub joints: Vec<JointResult>,
    /// Joint D.
    pub control: ControlResult,
    /// Seconds the run took: [`reproduce`] sets its own time, a caller may add the report's.
    pub seconds: f64,
    /// `report.html`, once the caller has written it ([`Reproduction::written_to`]).
    pub report: Option<PathBuf>,
}

/// The experiments per joint, for a progress bar.
pub const STEPS: u64 = 3 * 8 + 3;

/// Runs every experiment. `progress` is called once per finished step ([`STEPS`] in all) with
/// its name; it is called from the joints' threads.
///
/// # Errors
/// [`ReproduceError`] naming the joint and experiment.
pub fn reproduce(
    settings: Settings,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Reproduction, ReproduceError> {
    let start = Instant::now();
    let scale = settings.duration_scale;
    if !(scale > 0.0 && scale <= 1.0) {
        return Err(ReproduceError::Scale { value: scale });
    }
    if !(1..=PAPER_REPEATS).contains(&settings.repeats) {
        return Err(ReproduceError::Repeats {
            value: settings.repeats,
        });
    }
    let all = settings.bench.joints();
    let run = Run {
        scale,
        repeats: settings.repeats,
        models: &ModelKind::ALL,
        seed: settings.seed,
    };
    let results: Mutex<Vec<Result<JointResult, ReproduceError>>> = Mutex::new(Vec::new());
    let control: Mutex<Option<Result<ControlResult, ReproduceError>>> = Mutex::new(None);
    std::thread::scope(|s| {
        for joint in &all {
            let (results, control) = (&results, &control);
            s.spawn(move || {
                if joint.letter == 'D' {
                    let r = run_control(joint, run, progress);
                    *control.lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
                } else {
                    let r = run_joint(joint, run, progress);
                    results.lock().unwrap_or_else(|e| e.into_inner()).push(r);
                }
            });
        }
    });
    let mut joints = results
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .collect::<Result<Vec<_>, _>>()?;
    joints.sort_by_key(|j| j.letter);
    let control = control
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .expect("the control thread ran")?;
    Ok(Reproduction {
        settings,
        joints,
        control,
        seconds: start.elapsed().as_secs_f64(),
        report: None,
    })
}

/// One of Joints A-C in a [`TablesRun`]: the characterization and the estimation.
#[derive(Debug, Clone)]
pub struct JointTables {
    /// `A`, `B`, `C`.
    pub letter: char,
    /// The characterization: loops, linear and PI fits (Table III).
    pub loops: LoopsResult,
    /// The random pattern estimated (Tables IV-V).
    pub estimation: EstimationResult,
}

/// What Tables III-VI need and nothing else: each joint's characterization (the linear and PI
/// fits only) and estimation, and Joint D's control. A calibration's evaluation
/// ([`tables`], [`tables_of`]).
#[derive(Debug, Clone)]
pub struct TablesRun {
    /// Joints A-C (those that ran).
    pub joints: Vec<JointTables>,
    /// Joint D, when it ran.
    pub control: Option<ControlResult>,
}

/// Runs only what Tables III-VI need (no rate or relaxation run, no continuous PI fit), the
/// joints in parallel with rayon, with the same seeds and analyses as [`reproduce`]: the
/// numbers are the ones a reproduction of the same settings prints.
///
/// # Errors
/// [`ReproduceError`] naming the joint and experiment.
pub fn tables(settings: &Settings) -> Result<TablesRun, ReproduceError> {
    tables_of(settings, &LETTERS)
}

/// [`tables`] for the joints `letters` only (`D`: the closed loop): the metrics are nearly
/// separable by joint, so a calibration of one joint's parameters runs that joint alone. Each
/// joint's numbers are the ones [`tables`] gives (its own seeds, its own scenario).
///
/// # Errors
/// [`ReproduceError`] naming the joint and experiment.
pub fn tables_of(settings: &Settings, letters: &[char]) -> Result<TablesRun, ReproduceError> {
    use rayon::prelude::*;
    let scale = settings.duration_scale;
    if !(scale > 0.0 && scale <= 1.0) {
        return Err(ReproduceError::Scale { value: scale });
    }
    if !(1..=PAPER_REPEATS).contains(&settings.repeats) {
        return Err(ReproduceError::Repeats {
            value: settings.repeats,
        });
    }
    let run = Run {
        scale,
        repeats: settings.repeats,
        models: &[ModelKind::Linear, ModelKind::Pi],
        seed: settings.seed,
    };
    let quiet = |_: &str| {};
    let all: Vec<SimJoint> = settings
        .bench
        .joints()
        .into_iter()
        .filter(|j| letters.contains(&j.letter))
        .collect();
    let (joints, control) = rayon::join(
        || {
            all.par_iter()
                .filter(|j| j.letter != 'D')
                .map(|joint| {
                    let c = characterize(joint, run, &quiet)?;
                    let estimation = estimation(joint, run, &c, &quiet)?;
                    Ok(JointTables {
                        letter: joint.letter,
                        loops: c.loops,
                        estimation,
                    })
                })
                .collect::<Result<Vec<_>, ReproduceError>>()
        },
        || {
            all.iter()
                .find(|j| j.letter == 'D')
                .map(|d| run_control(d, run, &quiet))
                .transpose()
        },
    );
    Ok(TablesRun {
        joints: joints?,
        control: control?,
    })
}

/// A joint's accuracy on the bench it is simulated on: Table IV's linear and PI RMSE (°) of
/// its random pattern, and Table VI's closed-loop actual-vs-desired RMSE (°) on `control`'s
/// plant (Joint D's), each the reproduction's own procedure.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Accuracy {
    /// Linear model (°).
    pub linear_rmse_deg: f64,
    /// PI model (°).
    pub pi_rmse_deg: f64,
    /// Closed loop, actual vs desired (°).
    pub closed_loop_rmse_deg: f64,
}

/// The accuracy of `joint` (its design and scenario; its letter and `seed`, as
/// [`Settings::seed`], pick the seeds) at `repeats` repetitions of the paper's timings, with the
/// closed loop run on `control_joint` (the same sensor on Joint D's plant).
///
/// # Errors
/// [`ReproduceError`] naming the experiment.
pub fn accuracy(
    joint: &SimJoint,
    control_joint: &SimJoint,
    repeats: u32,
    seed: u64,
) -> Result<Accuracy, ReproduceError> {
    if !(1..=PAPER_REPEATS).contains(&repeats) {
        return Err(ReproduceError::Repeats { value: repeats });
    }
    let run = Run {
        scale: 1.0,
        repeats,
        models: &[ModelKind::Linear, ModelKind::Pi],
        seed,
    };
    let quiet = |_: &str| {};
    let (estimated, control) = rayon::join(
        || -> Result<EstimationResult, ReproduceError> {
            let c = characterize(joint, run, &quiet)?;
            estimation(joint, run, &c, &quiet)
        },
        || run_control(control_joint, run, &quiet),
    );
    let estimated = estimated?;
    let rmse = |config: &str| {
        estimated
            .runs
            .iter()
            .find(|x| x.config == config && !x.split)
            .map_or(f64::NAN, |x| x.metrics.rmse_deg)
    };
    Ok(Accuracy {
        linear_rmse_deg: rmse("linear"),
        pi_rmse_deg: rmse("PI"),
        closed_loop_rmse_deg: control?.run.metrics[1].actual_vs_desired_rmse_deg,
    })
}

impl Reproduction {
    /// The run's Tables III-VI, as a [`tables`] run gives them.
    pub fn tables(&self) -> TablesRun {
        TablesRun {
            joints: self
                .joints
                .iter()
                .map(|j| JointTables {
                    letter: j.letter,
                    loops: j.loops.clone(),
                    estimation: j.estimation.clone(),
                })
                .collect(),
            control: Some(self.control.clone()),
        }
    }
}

fn simulate(
    joint: &SimJoint,
    protocol: ProtocolKind,
    run: Run,
    seed: u64,
) -> Result<Recording, ReproduceError> {
    let sc = repeated(
        scaled(&joint.scenario, protocol, run.scale, seed),
        run.repeats,
    );
    let err = |source| ReproduceError::Sim {
        joint: joint.letter,
        protocol: protocol.name(),
        source,
    };
    let p = plan(&joint.design, without_drift(sc, protocol), None).map_err(err)?;
    let run = p.run().map_err(err)?;
    Ok(Recording {
        rig: p.rig(),
        samples: run.samples,
    })
}

/// `prefilter` with its window times `scale` (at least one sample).
fn scaled_prefilter(prefilter: Prefilter, scale: f64) -> Prefilter {
    match prefilter {
        Prefilter::MovingAverage(n) => {
            Prefilter::MovingAverage(((f64::from(n) * scale).round() as u32).max(1))
        }
        other => other,
    }
}

fn options(run: Run, order: PlayOrder, samples: usize) -> Options {
    Options {
        prefilter: Prefilter::MovingAverage(100),
        order,
        min_hold_s: DEFAULT_MIN_HOLD_S * run.scale,
        paper_processing: true,
        decimation: Some((samples.div_ceil(MAX_FIT_SAMPLES)).max(50)),
        models: run.models,
    }
}

/// `sc` with every protocol repeated `repeats` times (the rest at the start once).
fn repeated(mut sc: crate::sim::Scenario, repeats: u32) -> crate::sim::Scenario {
    let p = &mut sc.protocols;
    p.characterization.repeats = repeats;
    p.rate_dependence.repeats = repeats;
    p.relaxation.repeats = repeats;
    p.random.repeats = repeats;
    sc
}

/// Drift is on only in the rate-dependence run, where the paper measured it (the spread of R₀).
/// Elsewhere it would move the resistance out of the characterized range: on Joint A, with the
/// paper's 1.1 kΩ of drift in every run, the PI estimate of the random pattern had an RMSE of
/// 25.8° against 2.95° for the linear model.
/// The largest strain a fitted model's inverse reads (its characterized range's end).
fn characterized_max_strain(model: &ModelConfig) -> Option<f64> {
    match model {
        ModelConfig::Pi(pi) => pi.max_strain,
        ModelConfig::ContinuousPi(c) => Some(c.max_strain),
        ModelConfig::Linear(_) => None,
    }
    .filter(|e| e.is_finite() && *e > 0.0)
}

fn without_drift(mut sc: crate::sim::Scenario, protocol: ProtocolKind) -> crate::sim::Scenario {
    if protocol != ProtocolKind::RateDependence {
        sc.sensor1.drift.enabled = false;
        if let Some(s) = sc.sensor2.as_mut() {
            s.drift.enabled = false;
        }
    }
    sc
}

/// One joint's characterization: the loops, their fits, and the configs Tables IV-V estimate
/// with (linear and PI; Joint C also the linear two-sensor config).
struct Characterized {
    loops: LoopsResult,
    planes: Vec<dlw_estimator::SensorPlane>,
    configs: Vec<NamedConfig>,
    options: Options,
}

/// The first seed of joint `letter`'s simulations in `run`.
fn seed_of(letter: char, run: Run) -> u64 {
    run.seed.wrapping_mul(SEED_STRIDE) + 10 * u64::from(letter as u8 - b'A')
}

fn analysis_error(
    letter: char,
    analysis: &'static str,
) -> impl Fn(CharacterizeError) -> ReproduceError {
    move |source| ReproduceError::Analysis {
        joint: letter,
        analysis,
        source,
    }
}

fn characterize(
    joint: &SimJoint,
    run: Run,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Characterized, ReproduceError> {
    let letter = joint.letter;
    let j = &joint.design.joint;
    let step = |what: &str| progress(&format!("Joint {letter}: {what}"));
    let rec = simulate(
        joint,
        ProtocolKind::Characterization,
        run,
        seed_of(letter, run) + 1,
    )?;
    step("characterization simulated");
    let opts = options(run, PlayOrder::DEFAULT, rec.samples.len());
    let planes =
        planes(&rec, j, &joint.design.file.name).map_err(analysis_error(letter, "loops"))?;
    let loops = loops(&rec, j, &planes, &opts).map_err(analysis_error(letter, "loops"))?;
    drop(rec);
    step("loops and fits");
    let fits: Vec<_> = loops.sensors.iter().map(|s| s.fit.clone()).collect();
    let config = |fits: &[crate::fit::SensorFit], model, name: &'static str| {
        estimator_config(j, fits, model, opts.prefilter).map_err(|source| ReproduceError::Config {
            joint: letter,
            model: name,
            source,
        })
    };
    let mut configs = vec![
        NamedConfig {
            name: "linear".into(),
            config: config(&fits[..1], ModelKind::Linear, "linear")?,
        },
        NamedConfig {
            name: "PI".into(),
            config: config(&fits[..1], ModelKind::Pi, "PI")?,
        },
    ];
    if fits.len() > 1 {
        configs.push(NamedConfig {
            name: "linear, two-sensor config".into(),
            config: config(&fits, ModelKind::Linear, "two-sensor linear")?,
        });
    }
    Ok(Characterized {
        loops,
        planes,
        configs,
        options: opts,
    })
}

/// The random pattern estimated with the characterization's configs (Tables IV-V).
fn estimation(
    joint: &SimJoint,
    run: Run,
    c: &Characterized,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<EstimationResult, ReproduceError> {
    let letter = joint.letter;
    let rec = simulate(joint, ProtocolKind::Random, run, seed_of(letter, run) + 4)?;
    progress(&format!("Joint {letter}: random pattern simulated"));
    let estimation =
        estimate(&rec, &c.configs, &c.options).map_err(analysis_error(letter, "estimation"))?;
    progress(&format!("Joint {letter}: estimation"));
    Ok(estimation)
}

fn run_joint(
    joint: &SimJoint,
    run: Run,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<JointResult, ReproduceError> {
    let letter = joint.letter;
    let j = &joint.design.joint;
    let seed = seed_of(letter, run);
    let step = |what: &str| progress(&format!("Joint {letter}: {what}"));
    let c = characterize(joint, run, progress)?;

    let rec = simulate(joint, ProtocolKind::RateDependence, run, seed + 2)?;
    step("rate-dependence simulated");
    // The prefilter's window shrinks with the protocol's timings: a fixed 0.2 s average over a
    // rise of 1 s (at --short) bends a curved sensor's loop more for the faster cycles, and GF
    // then follows the rise time with no rate effect.
    let rate_opts = Options {
        prefilter: scaled_prefilter(c.options.prefilter, run.scale),
        ..c.options
    };
    let rate = rate(&rec, j, &c.planes, &rate_opts).map_err(analysis_error(letter, "rate"))?;
    drop(rec);
    step("rate");

    let rec = simulate(joint, ProtocolKind::Relaxation, run, seed + 3)?;
    step("relaxation simulated");
    let relaxation =
        relaxation(&rec, j, &c.planes, &c.options).map_err(analysis_error(letter, "relaxation"))?;
    drop(rec);
    step("relaxation");

    let estimation = estimation(joint, run, &c, progress)?;
    Ok(JointResult {
        letter,
        loops: c.loops,
        rate,
        relaxation,
        estimation,
        simulated_tau_s: joint.scenario.plant.relaxation.tau_s * run.scale,
    })
}

fn run_control(
    joint: &SimJoint,
    run: Run,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<ControlResult, ReproduceError> {
    let j = &joint.design.joint;
    let rec = simulate(
        joint,
        ProtocolKind::Characterization,
        run,
        run.seed.wrapping_mul(SEED_STRIDE) + 31,
    )?;
    progress("Joint D: characterization simulated");
    let opts = options(run, CONTROL_ORDER, rec.samples.len());
    let planes =
        planes(&rec, j, &joint.design.file.name).map_err(|source| ReproduceError::Analysis {
            joint: 'D',
            analysis: "loops",
            source,
        })?;
    let fitted = loops(&rec, j, &planes, &opts).map_err(|source| ReproduceError::Analysis {
        joint: 'D',
        analysis: "loops",
        source,
    })?;
    drop(rec);
    progress("Joint D: PI fit (N = 3)");
    let fits: Vec<_> = fitted.sensors.iter().map(|s| s.fit.clone()).collect();
    let mut config =
        estimator_config(j, &fits, ModelKind::Pi, opts.prefilter).map_err(|source| {
            ReproduceError::Config {
                joint: 'D',
                model: "PI",
                source,
            }
        })?;
    // The fit's config as it is: its input filter (the prefilter, a 100-sample moving average)
    // keeps the loop stable at the paper's gains; no output filter.
    config.output_filter = FilterConfig::None;
    let mut sc = without_drift(
        repeated(
            scaled(
                &joint.scenario,
                ProtocolKind::Random,
                run.scale,
                run.seed.wrapping_mul(SEED_STRIDE) + 32,
            ),
            run.repeats,
        ),
        ProtocolKind::Random,
    );
    if let Some(max_strain) = characterized_max_strain(&config.sensor.model) {
        sc.protocols.peak_strain = sc
            .protocols
            .peak_strain
            .min(CONTROL_RANGE_SHARE * max_strain);
        sc.protocols.amplitude_mm = None;
    }
    let control = Control::new(
        &joint.design,
        sc,
        &DesiredSource::Protocol,
        config,
        PAPER_GAINS,
        None,
    )?;
    let run = control.run()?;
    progress("Joint D: open and closed loop");
    Ok(ControlResult::new(control, run))
}
