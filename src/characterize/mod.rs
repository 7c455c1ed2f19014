//! The paper's characterization analyses (Section IV-A, IV-B) over a recording, as a library;
//! `dlw characterize` is a thin command over it and `dlw reproduce` composes them.
//!
//! | kind | paper | what it computes |
//! |---|---|---|
//! | [`loops`] | IV-A1, Fig. 4, Table III | cycles of R against strain, stroke/strain/ΔR against time, the linear and PI fits (`crate::fit`) |
//! | [`rate`] | IV-A2, Fig. 5 | GF and R₀ of every equal-amplitude cycle, GF's correlation with the rise time, R₀'s standard deviation |
//! | [`relaxation`] | IV-A3, Fig. 6 | the holds of the stroke, each hold's strain decay (amount, time constant), the correlation of ΔR with Δε over the holds |
//! | [`estimation`] | IV-B, Tables IV-V, Figs. 7-8 | the angle RMSE of each estimator config as `dlw estimate` computes it; for a two-sensor config tension alone, compression alone and both |
//!
//! Each kind has a function returning a result struct (serializable, for `--json`) and an
//! `add_to_page` method that puts its tables and figures on a [`crate::report::Page`], with a
//! prefix on every figure name so that several analyses share one page.
//!
//! # Errors
//! [`CharacterizeError`] names what the recording lacks for the analysis asked for (no holds,
//! no cycles of different speeds, no config) or passes on a fit's or a replay's error.

pub mod estimation;
pub mod loops;
pub mod rate;
pub mod relaxation;
mod request;

use dlw_estimator::SensorPlane;
use dlw_geometry::{Joint, NotchStyle};
use serde::Serialize;

use crate::fit::{FitError, PlayOrder};
use crate::recording::ProtocolKind;
use crate::recording::Recording;
use crate::replay::ReplayError;
use crate::signal::Prefilter;

/// Pearson correlation, standard deviation, least-squares slope.
/// The statistics the analyses report, from the one `stats` module.
pub use crate::stats::{pearson, slope, std_dev};
/// Estimates of each config against the tracker angle (Table IV, Table V, Figs. 7-8).
pub use estimation::{estimate, EstimationResult, EstimationRun, NamedConfig};
/// Loading/unloading loops and the fits (Fig. 4, Table III).
pub use loops::{loops, LoopsResult, LoopsSensor, LoopsSummary};
/// Gauge factor and R₀ per cycle against the rise time (Fig. 5).
pub use rate::{rate, RateCycle, RateResult, RateSensor};
/// Holds, strain decay and ΔR against Δε (Fig. 6).
pub use relaxation::{relaxation, Hold, RelaxationResult, RelaxationSensor};
/// `dlw characterize` as a library call.
pub use request::{characterize, Characterization, CharacterizeRequest, KindResult};

/// The default shortest hold (s) the relaxation analysis accepts.
pub const DEFAULT_MIN_HOLD_S: f64 = 5.0;

/// Which analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum AnalysisKind {
    /// Resistance-strain loops and fits (Section IV-A1, Fig. 4).
    Loops,
    /// Rate dependence: GF per cycle against rise time, R₀ per cycle (Section IV-A2, Fig. 5).
    Rate,
    /// Relaxation during holds (Section IV-A3, Fig. 6).
    Relaxation,
    /// Angle estimation with each --config (Section IV-B, Tables IV-V, Figs. 7-8).
    Estimation,
}

impl AnalysisKind {
    /// The kind's name as the command line writes it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Loops => "loops",
            Self::Rate => "rate",
            Self::Relaxation => "relaxation",
            Self::Estimation => "estimation",
        }
    }

    /// The kind named `name` (`loops`, `rate`, `relaxation`, `estimation`).
    pub fn from_name(name: &str) -> Option<Self> {
        [Self::Loops, Self::Rate, Self::Relaxation, Self::Estimation]
            .into_iter()
            .find(|k| k.name() == name)
    }

    /// The analysis for the protocol a recording's `rig.toml` states: its top-level `protocol`
    /// (which an imported recording may state), else a simulated recording's scenario's.
    ///
    /// # Errors
    /// [`CharacterizeError::NoKind`] when the rig states no protocol, an unknown one, or `custom`.
    pub fn of_recording(recording: &Recording) -> Result<Self, CharacterizeError> {
        let protocol = recording
            .rig
            .protocol_kind()
            .map_err(|name| CharacterizeError::NoKind {
                protocol: name.to_string(),
            })?;
        match protocol {
            Some(ProtocolKind::Characterization) => Ok(Self::Loops),
            Some(ProtocolKind::RateDependence) => Ok(Self::Rate),
            Some(ProtocolKind::Relaxation) => Ok(Self::Relaxation),
            Some(ProtocolKind::Random) => Ok(Self::Estimation),
            Some(ProtocolKind::Custom) => Err(CharacterizeError::NoKind {
                protocol: "custom".into(),
            }),
            None => Err(CharacterizeError::NoKind {
                protocol: "none".into(),
            }),
        }
    }
}

/// Why an analysis could not be made.
#[derive(Debug, thiserror::Error)]
pub enum CharacterizeError {
    /// No `--kind` and no protocol in `rig.toml` to take it from.
    #[error("rig.toml records protocol {protocol}, which names no analysis; pass --kind loops|rate|relaxation|estimation")]
    NoKind {
        /// The protocol recorded (`none` when there is none).
        protocol: String,
    },
    /// The recording shows the sensor nothing to analyse, or a line could not be fitted.
    #[error(transparent)]
    Signal(#[from] crate::signal::SignalError),
    /// A fit failed.
    #[error(transparent)]
    Fit(#[from] FitError),
    /// An estimator config file could not be read.
    #[error(transparent)]
    Config(#[from] crate::replay::ConfigFileError),
    /// The estimator could not run over the recording.
    #[error(transparent)]
    Replay(#[from] ReplayError),
    /// The recording has no holds.
    #[error("no holds longer than {min_hold_s} s found (the longest constant, non-zero stroke lasts {longest_s:.2} s); relaxation needs holds")]
    NoHolds {
        /// The shortest hold accepted (s).
        min_hold_s: f64,
        /// The longest constant-stroke run away from zero stroke (s).
        longest_s: f64,
    },
    /// Fewer holds than a correlation needs.
    #[error("{found} hold(s) of at least {min_hold_s} s found; the correlation of ΔR with Δε needs at least {min}")]
    TooFewHolds {
        /// Holds found.
        found: usize,
        /// Holds needed.
        min: usize,
        /// The shortest hold accepted (s).
        min_hold_s: f64,
    },
    /// Too few equal-amplitude cycles for the rate analysis.
    #[error("{found} loading/unloading cycle(s) of equal amplitude found (within {share:.0} % of the largest); the rate analysis needs at least {min}")]
    TooFewCycles {
        /// Cycles found.
        found: usize,
        /// Cycles needed.
        min: usize,
        /// Share of the largest amplitude a cycle must reach (%).
        share: f64,
    },
    /// Equal-amplitude cycles that all rise at one speed.
    #[error("the {cycles} equal-amplitude cycles all rise in {min_s:.2} to {max_s:.2} s; the rate analysis needs cycles of different speeds (the longest rise at least {ratio} times the shortest), as in the rate-dependence protocol")]
    OneSpeed {
        /// Cycles compared.
        cycles: usize,
        /// Shortest rise (s).
        min_s: f64,
        /// Longest rise (s).
        max_s: f64,
        /// Ratio needed.
        ratio: f64,
    },
    /// Estimation without a config.
    #[error("estimation needs at least one estimator config (--config C, from dlw fit or dlw estimator-config)")]
    NoConfig,
    /// A shortest hold that is no duration.
    #[error("--min-hold-s {min_hold_s} must be finite and greater than 0")]
    MinHold {
        /// The value asked for (s).
        min_hold_s: f64,
    },
    /// Estimator configs given to a kind that takes none.
    #[error("--config is for --kind estimation; the {kind} analysis takes none")]
    ConfigsForOtherKind {
        /// The kind asked for.
        kind: &'static str,
    },
    /// The kind could not be chosen from the recording's protocol.
    #[error("choosing the analysis for {recording}")]
    Choose {
        /// The recording's name.
        recording: String,
        /// Why.
        source: Box<CharacterizeError>,
    },
    /// The kind's analysis failed.
    #[error("{kind} analysis of {recording}")]
    Analysis {
        /// The kind.
        kind: &'static str,
        /// The recording's name.
        recording: String,
        /// Why.
        source: Box<CharacterizeError>,
    },
    /// A sensor plane the design does not carry.
    #[error("the recording has {columns} voltage column(s) but design {design:?} is {style} with {carries} sensor(s)")]
    Columns {
        /// Voltage columns.
        columns: usize,
        /// The design's name.
        design: String,
        /// `UAN` or `BSN`.
        style: &'static str,
        /// Sensors the design carries.
        carries: usize,
    },
}

/// Settings shared by the kinds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Filter on strain and resistance before any analysis (the paper: 500 samples).
    pub prefilter: Prefilter,
    /// Plays of the PI fits (the paper: 10).
    pub order: PlayOrder,
    /// Shortest hold the relaxation analysis accepts (s).
    pub min_hold_s: f64,
    /// The paper's estimation processing: a 1000-sample moving average on the angle (the PI
    /// configs clamp to the characterized resistance range themselves).
    pub paper_processing: bool,
    /// `loops`: keep every `k`-th sample for the fits (`None`: `dlw fit`'s choice, at most
    /// `crate::fit::MAX_FIT_SAMPLES`).
    pub decimation: Option<usize>,
    /// `loops`: the models fitted (the linear model always is); every model by default.
    pub models: &'static [crate::fit::ModelKind],
}

impl Default for Options {
    fn default() -> Self {
        Self {
            prefilter: Prefilter::MovingAverage(100),
            order: PlayOrder::DEFAULT,
            min_hold_s: DEFAULT_MIN_HOLD_S,
            paper_processing: false,
            decimation: None,
            models: &crate::fit::ModelKind::ALL,
        }
    }
}

/// The sensor planes to analyse: both of a BSN joint's sensors when the recording has two
/// voltage columns, otherwise sensor 1.
///
/// # Errors
/// [`CharacterizeError::Columns`] for two columns on a UAN design.
pub fn planes(
    recording: &Recording,
    joint: &Joint,
    design_name: &str,
) -> Result<Vec<SensorPlane>, CharacterizeError> {
    let columns = recording.samples.volts.len();
    match (joint.style(), columns) {
        (NotchStyle::Bsn, c) if c >= 2 => Ok(vec![SensorPlane::PlusYs, SensorPlane::MinusYs]),
        (NotchStyle::Uan, c) if c >= 2 => Err(CharacterizeError::Columns {
            columns,
            design: design_name.to_owned(),
            style: "UAN",
            carries: 1,
        }),
        _ => Ok(vec![SensorPlane::PlusYs]),
    }
}

/// The column name and role of a sensor, e.g. `v2_V (compression)`.
pub fn sensor_label(plane: SensorPlane, two: bool) -> String {
    let column = format!("v{}_V", plane.column());
    if !two {
        return column;
    }
    match plane {
        SensorPlane::PlusYs => format!("{column} (tension)"),
        SensorPlane::MinusYs => format!("{column} (compression)"),
    }
}

/// A figure name on a shared page: `prefix-name`, or `name` without a prefix.
pub(crate) fn figure_name(prefix: &str, name: &str) -> String {
    crate::analysis::Placement {
        label: "",
        figure_prefix: prefix,
    }
    .figure_name(name)
}

/// `title` with `label` in front, e.g. `Joint A: loops`.
pub(crate) fn titled(label: &str, title: &str) -> String {
    crate::analysis::Placement {
        label,
        figure_prefix: "",
    }
    .titled(title)
}

/// Moved to [`crate::stats`] (one NaN policy); re-exported here this round.
pub(crate) use crate::stats::min_max;
