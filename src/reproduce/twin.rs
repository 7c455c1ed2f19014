//! The bench a reproduction runs on: the ideal simulated joints of [`super::joints`] (`dlw
//! reproduce --ideal`), or the paper's bench as a calibrated twin, one scenario per joint in a
//! bench file (`designs/scenarios/paper-bench.toml`, written by `dlw calibrate`).
//!
//! ```toml
//! [calibration]              # where the scenarios came from (optional)
//! method = "CMA-ES ..."
//! [calibration.parameters]   # the calibrated parameters, by name
//! tracker_noise_deg = 0.3
//! [joint.A]                  # a scenario (docs/simulator.md) for Joint A; B, C and D likewise
//! [joint.A.sensor1]
//! model = "pi"
//! ```
//!
//! Every joint's table is a whole scenario, read and checked as `dlw simulate --scenario` reads
//! one; the protocol, duration and seed are the reproduction's.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::joints::{joints, SimJoint};
use crate::sim::{Scenario, ScenarioError};

/// The twin shipped with dlw, which `dlw reproduce` runs by default.
pub const PAPER_BENCH_TOML: &str = include_str!("../../designs/scenarios/paper-bench.toml");

/// The file's path in the repository, for messages and docs.
pub const PAPER_BENCH_PATH: &str = "designs/scenarios/paper-bench.toml";

/// The joints a bench file must give, in order.
pub const LETTERS: [char; 4] = ['A', 'B', 'C', 'D'];

/// Why a bench file was refused.
#[derive(Debug, thiserror::Error)]
pub enum TwinError {
    /// The file could not be read.
    #[error("cannot read bench file {path}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// Not a bench file (unknown key, wrong type).
    #[error("bench file {path}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The parser's message, naming the key.
        message: String,
    },
    /// A joint is missing or unknown.
    #[error("bench file {path}: {message}")]
    Joints {
        /// The file.
        path: PathBuf,
        /// Which joint.
        message: String,
    },
    /// A joint's scenario was refused.
    #[error("bench file {path}, [joint.{joint}]: {source}")]
    Scenario {
        /// The file.
        path: PathBuf,
        /// The joint.
        joint: char,
        /// Why.
        source: ScenarioError,
    },
}

/// Where a bench file's scenarios came from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    /// The method, in words.
    pub method: String,
    /// Short-sized evaluations the search made.
    pub evaluations: u64,
    /// The objective at the shipped parameters (sum of squared log-ratios over tolerances).
    pub objective: f64,
    /// The calibrated parameters, by name ([`crate::calibrate`]).
    pub parameters: BTreeMap<String, f64>,
    /// Per metric (`table4.A.linear`, …), the full-size value over the short-sized one at the
    /// shipped point: what a short-sized run of this bench is scaled by to predict a full one
    /// (`dlw explore`'s predicted accuracy).
    #[serde(default)]
    pub corrections: BTreeMap<String, f64>,
    /// Per calibrated parameter, the ideal bench's value and the bounds the search kept to:
    /// what the report measures each parameter's move against.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub ranges: BTreeMap<String, Range>,
    /// Per Table III number (`table3.A.m_c`), the largest relative distance from the paper the
    /// calibration allowed: the ideal bench's at full size plus a slack (its "current
    /// agreement"). The report checks the run's Table III against them.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub agreements: BTreeMap<String, f64>,
    /// Trade-offs measured at the shipped point: one parameter moved, every other held, each
    /// value's full-size numbers. The report reads the reason a number stays outside its
    /// agreement from them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tradeoffs: Vec<Tradeoff>,
}

/// A calibrated parameter's ideal value and bounds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Range {
    /// The ideal bench's value.
    pub ideal: f64,
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
    /// Whether the search moved it on a log scale (a correlation time): its move is then a
    /// share of `ln(hi/lo)`.
    #[serde(default)]
    pub log: bool,
}

impl Range {
    /// `value`'s place in the range, 0 at `lo` and 1 at `hi` (on a log scale when `log`).
    pub fn unit(&self, value: f64) -> f64 {
        if self.log && self.lo > 0.0 && value > 0.0 {
            (value / self.lo).ln() / (self.hi / self.lo).ln()
        } else {
            (value - self.lo) / (self.hi - self.lo)
        }
    }
}

/// One parameter of a bench moved through `values` with every other at the shipped point, and
/// what full-size runs measured at each (`metrics`, by name: `table3.A.m_c`, `table4.A.pi`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tradeoff {
    /// The parameter, by its calibration name (`A.sensor1.noise_tau_s`).
    pub parameter: String,
    /// How the numbers were measured (the command, the size, the seed).
    pub measured: String,
    /// The parameter's values.
    pub values: Vec<f64>,
    /// Per metric, its value at each of `values`.
    pub metrics: BTreeMap<String, Vec<f64>>,
}

/// A bench file: one scenario per joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BenchFile {
    /// Where the scenarios came from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub calibration: Option<Provenance>,
    /// `A` … `D`: each joint's scenario.
    pub joint: BTreeMap<String, Scenario>,
}

/// The bench a reproduction runs on.
#[derive(Debug, Clone, PartialEq)]
pub enum Bench {
    /// Today's clean simulated joints ([`super::joints`]): `--ideal`.
    Ideal,
    /// A bench file's scenarios (the calibrated twin).
    Twin(Box<BenchFile>),
}

impl Bench {
    /// The shipped twin, [`PAPER_BENCH_TOML`].
    ///
    /// # Errors
    /// [`TwinError`] if the shipped file does not read (a test checks it does).
    pub fn paper() -> Result<Self, TwinError> {
        BenchFile::parse(PAPER_BENCH_TOML, Path::new(PAPER_BENCH_PATH))
            .map(|f| Self::Twin(f.into()))
    }

    /// The simulated joints: the ideal ones, or each with its scenario from the file.
    pub fn joints(&self) -> Vec<SimJoint> {
        let mut all = joints();
        if let Self::Twin(file) = self {
            for j in &mut all {
                if let Some(sc) = file.joint.get(&j.letter.to_string()) {
                    j.scenario = sc.clone();
                }
            }
        }
        all
    }

    /// `ideal` or `twin`, for reports.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Ideal => "ideal",
            Self::Twin(_) => "twin",
        }
    }
}

impl BenchFile {
    /// Reads and checks a bench file.
    ///
    /// # Errors
    /// [`TwinError`] naming the file, the joint and the key.
    pub fn load(path: &Path) -> Result<Self, TwinError> {
        let text = crate::output::read_limited(path, crate::limits::MAX_TEXT_INPUT_BYTES).map_err(
            |source| TwinError::Read {
                path: path.to_path_buf(),
                source,
            },
        )?;
        Self::parse(&text, path)
    }

    /// Parses and checks `text` (named `path` in messages): every joint `A`-`D` present, no
    /// other, and each scenario resolves against its joint's design.
    ///
    /// # Errors
    /// [`TwinError`].
    pub fn parse(text: &str, path: &Path) -> Result<Self, TwinError> {
        let file: Self = toml::from_str(text).map_err(|e| TwinError::Parse {
            path: path.to_path_buf(),
            message: crate::limits::parser_message(&e),
        })?;
        let joints_err = |message: String| TwinError::Joints {
            path: path.to_path_buf(),
            message,
        };
        for key in file.joint.keys() {
            if !LETTERS.iter().any(|l| l.to_string() == *key) {
                return Err(joints_err(format!(
                    "[joint.{key}] is not one of the paper's joints A, B, C, D"
                )));
            }
        }
        for j in joints() {
            let sc = file
                .joint
                .get(&j.letter.to_string())
                .ok_or_else(|| joints_err(format!("[joint.{}] is missing", j.letter)))?;
            sc.clone()
                .resolve(&j.design)
                .map_err(|source| TwinError::Scenario {
                    path: path.to_path_buf(),
                    joint: j.letter,
                    source,
                })?;
        }
        Ok(file)
    }

    /// The file's text: a header comment, then the TOML.
    ///
    /// # Errors
    /// The serializer's message (a scenario that TOML cannot hold).
    pub fn to_toml(&self, header: &str) -> Result<String, toml::ser::Error> {
        let body = toml::to_string(self)?;
        let comment: String = header.lines().map(|l| format!("# {l}\n")).collect();
        Ok(format!("{comment}\n{body}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_twin_reads_and_gives_every_joint() {
        let Bench::Twin(file) = Bench::paper().unwrap() else {
            panic!("not a twin")
        };
        assert_eq!(file.joint.keys().collect::<Vec<_>>(), ["A", "B", "C", "D"]);
        let joints = Bench::Twin(file).joints();
        assert_eq!(joints.len(), 4);
    }

    #[test]
    fn a_bench_file_round_trips_and_bad_ones_are_refused() {
        let file = BenchFile {
            calibration: None,
            joint: joints()
                .into_iter()
                .map(|j| (j.letter.to_string(), j.scenario))
                .collect(),
        };
        let text = file.to_toml("a test").unwrap();
        assert!(text.starts_with("# a test\n"));
        let p = Path::new("t.toml");
        assert_eq!(BenchFile::parse(&text, p).unwrap(), file);
        let missing = text.replace("[joint.D", "[joint.E");
        let err = BenchFile::parse(&missing, p).unwrap_err().to_string();
        assert!(err.contains("joint.E") || err.contains("joint.D"), "{err}");
        // Joint A's table comes first (the joints are sorted).
        let bad = text.replacen("sample_hz = 500.0", "sample_hz = -1.0", 1);
        let err = BenchFile::parse(&bad, p).unwrap_err().to_string();
        assert!(
            err.contains("[joint.A]") && err.contains("sample_hz"),
            "{err}"
        );
    }
}
