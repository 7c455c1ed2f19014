//! The exploration spec (`SPEC.toml`): a base design, the parameters to vary, the sensing model,
//! the constraints and the objectives. Read once, validated, then turned into a [`Grid`].

use std::path::{Path, PathBuf};

use dlw_geometry::NotchStyle;
use serde::Deserialize;

use crate::design::MAX_NOTCH_COUNT;

/// Most values one axis may hold.
pub const MAX_AXIS_VALUES: usize = 100_000;
/// Most candidates one spec may describe (10⁹: about 15 minutes at the benchmark's rate).
pub const MAX_CANDIDATES: u64 = 1_000_000_000;
/// Values of a `{ from, to, step }` axis are rounded to 1/this of a mm (1 pm), so that
/// `0.1 + 2·0.1` is written as `0.3` in design files.
const AXIS_ROUNDING_PER_MM: f64 = 1e9;

/// A spec as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpecFile {
    /// The base design, relative to the spec file: every key not varied comes from it.
    pub base: PathBuf,
    /// The tube catalogue, relative to the spec file (default `tubes.toml` beside it).
    #[serde(default)]
    pub tubes: Option<PathBuf>,
    /// Gauge factor `GF` for the sensitivity `R₀·GF·dε/dθ` (Ω/°).
    pub gauge_factor: f64,
    /// Unstrained sensor resistance `R₀` (Ω).
    pub r0_ohm: f64,
    /// The parameters to vary.
    #[serde(default)]
    pub vary: Vary,
    /// The constraints.
    #[serde(default)]
    pub constraints: Constraints,
    /// The objectives.
    pub objectives: Objectives,
}

/// `[vary]`: every key optional; a key left out keeps the base design's value.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Vary {
    /// Tube stock, by catalogue id.
    pub tube: Option<Vec<String>>,
    /// Notch style, which sets the sensor count: `uan` (one sensor) or `bsn` (two).
    pub style: Option<Vec<NotchStyle>>,
    /// Notch arc `s_n` (mm).
    pub notch_arc_mm: Option<Axis>,
    /// Sensor arc `s_s` (mm).
    pub sensor_arc_mm: Option<Axis>,
    /// Notch count `N`.
    pub notch_count: Option<Axis>,
    /// Notch width `h` (mm).
    pub notch_width_mm: Option<Axis>,
    /// Notch spacing `c` (mm).
    pub notch_spacing_mm: Option<Axis>,
}

/// The values of one varied parameter: a list, or a range with a step.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum Axis {
    /// These values.
    List(Vec<f64>),
    /// `from`, `from + step`, … up to `to` (included when it falls on a step).
    Range {
        /// First value.
        from: f64,
        /// Last value (inclusive).
        to: f64,
        /// Step, positive.
        step: f64,
    },
}

/// `[constraints]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Constraints {
    /// The joint must reach this angle with its notches open (°).
    pub min_range_deg: f64,
    /// …and with its backbone within the material's strain limit.
    pub material_within_limit: bool,
    /// …and with its sensor below saturation.
    pub no_saturation: bool,
    /// Largest tendon stroke per degree (mm/°).
    pub max_stroke_per_deg_mm: Option<f64>,
    /// Largest tendon force per degree (N/°).
    pub max_tendon_force_per_deg_n: Option<f64>,
    /// Smallest sensitivity (Ω/°).
    pub min_sensitivity_ohm_per_deg: Option<f64>,
}

impl Default for Constraints {
    fn default() -> Self {
        Self {
            min_range_deg: 0.0,
            material_within_limit: true,
            no_saturation: true,
            max_stroke_per_deg_mm: None,
            max_tendon_force_per_deg_n: None,
            min_sensitivity_ohm_per_deg: None,
        }
    }
}

/// A candidate's metric, as named in specs and in `designs.csv`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// Sensor resistance change per degree at the spec's `GF` and `R₀` (Ω/°).
    SensitivityOhmPerDeg,
    /// Usable range (°): notch closing, and the material and saturation limits the constraints
    /// enable.
    RangeDeg,
    /// Tendon force per degree (N/°).
    TendonForcePerDegN,
    /// Tendon stroke per degree (mm/°).
    StrokePerDegMm,
    /// The angle RMSE (°) the twin of the paper's bench predicts for the joint with the better
    /// of its linear and PI models (Table IV's estimation), by a short simulation of each front
    /// candidate (`explore::predict`).
    PredictedRmseDeg,
    /// The closed-loop actual-vs-desired RMSE (°) the twin predicts with Joint D's plant
    /// (Table VI), by the same short simulation.
    PredictedClosedLoopRmseDeg,
}

impl Metric {
    /// Whether the metric comes from a simulation of the front's candidates (not from the
    /// grid's screen).
    pub fn is_predicted(self) -> bool {
        matches!(
            self,
            Self::PredictedRmseDeg | Self::PredictedClosedLoopRmseDeg
        )
    }

    /// Every metric of the grid's screen, in `designs.csv`'s column order.
    pub const ALL: [Metric; 4] = [
        Metric::SensitivityOhmPerDeg,
        Metric::RangeDeg,
        Metric::TendonForcePerDegN,
        Metric::StrokePerDegMm,
    ];

    /// The name as in specs and CSV headers.
    pub fn key(self) -> &'static str {
        match self {
            Self::SensitivityOhmPerDeg => "sensitivity_ohm_per_deg",
            Self::RangeDeg => "range_deg",
            Self::TendonForcePerDegN => "tendon_force_per_deg_n",
            Self::StrokePerDegMm => "stroke_per_deg_mm",
            Self::PredictedRmseDeg => "predicted_rmse_deg",
            Self::PredictedClosedLoopRmseDeg => "predicted_closed_loop_rmse_deg",
        }
    }

    /// An axis label with the unit.
    pub fn label(self) -> &'static str {
        match self {
            Self::SensitivityOhmPerDeg => "sensitivity (Ω/°)",
            Self::RangeDeg => "usable range (°)",
            Self::TendonForcePerDegN => "tendon force per degree (N/°)",
            Self::StrokePerDegMm => "tendon stroke per degree (mm/°)",
            Self::PredictedRmseDeg => "predicted angle RMSE (°)",
            Self::PredictedClosedLoopRmseDeg => "predicted closed-loop RMSE (°)",
        }
    }
}

/// `[objectives]`: metrics to maximize and to minimize (at least one in all, none twice).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Objectives {
    /// DesignMetrics to make large.
    pub maximize: Vec<Metric>,
    /// DesignMetrics to make small.
    pub minimize: Vec<Metric>,
}

impl Objectives {
    /// `(metric, +1 to maximize or −1 to minimize)`, maximized ones first, in the spec's order.
    pub fn signed(&self) -> Vec<(Metric, f64)> {
        let max = self.maximize.iter().map(|&m| (m, 1.0));
        max.chain(self.minimize.iter().map(|&m| (m, -1.0)))
            .collect()
    }
}

/// Why a spec was refused.
#[derive(Debug, thiserror::Error)]
pub enum SpecError {
    /// The file could not be read.
    #[error("cannot read {path}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// Not valid TOML for a spec or a catalogue.
    #[error("{path}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The parser's message (names the key and line).
        message: String,
    },
    /// A value is out of its range.
    #[error("{name} = {value} {limit}")]
    Value {
        /// The key.
        name: String,
        /// The value given.
        value: String,
        /// What it must be.
        limit: String,
    },
    /// A tube id not in the catalogue.
    #[error("vary.tube: {id:?} is not in the catalogue {path} (it has: {known})")]
    UnknownTube {
        /// The id given.
        id: String,
        /// The catalogue.
        path: PathBuf,
        /// The ids it has.
        known: String,
    },
}

/// Reads a TOML file (through the bounded reader, at most
/// [`crate::limits::MAX_TEXT_INPUT_BYTES`]) into `T`.
pub(crate) fn read_toml<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, SpecError> {
    let text = crate::output::read_limited(path, crate::limits::MAX_TEXT_INPUT_BYTES).map_err(
        |source| SpecError::Read {
            path: path.to_path_buf(),
            source,
        },
    )?;
    toml::from_str(&text).map_err(|e| SpecError::Parse {
        path: path.to_path_buf(),
        message: e.to_string().trim_end().to_string(),
    })
}

fn value_error(name: &str, value: impl ToString, limit: impl Into<String>) -> SpecError {
    SpecError::Value {
        name: name.to_string(),
        value: value.to_string(),
        limit: limit.into(),
    }
}

impl SpecFile {
    /// Reads a spec.
    ///
    /// # Errors
    /// [`SpecError`] naming the file, key or value.
    pub fn read(path: &Path) -> Result<Self, SpecError> {
        let spec: Self = read_toml(path)?;
        spec.validate()?;
        Ok(spec)
    }

    /// Checks the numbers a spec holds directly (axes are checked when expanded).
    ///
    /// # Errors
    /// [`SpecError::Value`] naming the key, its value and its range.
    pub fn validate(&self) -> Result<(), SpecError> {
        for (name, v) in [("gauge_factor", self.gauge_factor), ("r0_ohm", self.r0_ohm)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(value_error(
                    name,
                    v,
                    "must be a finite number greater than 0",
                ));
            }
        }
        let c = &self.constraints;
        if !(c.min_range_deg.is_finite() && (0.0..=3600.0).contains(&c.min_range_deg)) {
            return Err(value_error(
                "constraints.min_range_deg",
                c.min_range_deg,
                "must lie between 0 and 3600",
            ));
        }
        for (name, v) in [
            ("constraints.max_stroke_per_deg_mm", c.max_stroke_per_deg_mm),
            (
                "constraints.max_tendon_force_per_deg_n",
                c.max_tendon_force_per_deg_n,
            ),
            (
                "constraints.min_sensitivity_ohm_per_deg",
                c.min_sensitivity_ohm_per_deg,
            ),
        ] {
            if let Some(v) = v {
                if !(v.is_finite() && v > 0.0) {
                    return Err(value_error(
                        name,
                        v,
                        "must be a finite number greater than 0",
                    ));
                }
            }
        }
        let signed = self.objectives.signed();
        if signed.is_empty() {
            return Err(value_error(
                "objectives",
                "{}",
                "must name at least one metric to maximize or minimize",
            ));
        }
        if signed.iter().all(|(m, _)| m.is_predicted()) {
            // The predicted metrics are simulated for the front of the others only; alone they
            // would simulate every feasible candidate.
            return Err(value_error(
                "objectives",
                signed[0].0.key(),
                "needs a metric of the grid beside it (the prediction runs on their front only)",
            ));
        }
        for (m, sign) in &signed {
            if m.is_predicted() && *sign > 0.0 {
                return Err(value_error(
                    "objectives.maximize",
                    m.key(),
                    "is an error: minimize it",
                ));
            }
        }
        for (i, (m, _)) in signed.iter().enumerate() {
            if signed[..i].iter().any(|(n, _)| n == m) {
                return Err(value_error(
                    "objectives",
                    m.key(),
                    "is named twice (each metric at most once)",
                ));
            }
        }
        Ok(())
    }
}

impl Axis {
    /// The axis's values, checked: finite, positive, at most [`MAX_AXIS_VALUES`].
    ///
    /// # Errors
    /// [`SpecError::Value`] naming `name`.
    pub fn values(&self, name: &str) -> Result<Vec<f64>, SpecError> {
        let values = match *self {
            Axis::List(ref v) => v.clone(),
            Axis::Range { from, to, step } => range_values(name, from, to, step)?,
        };
        if values.is_empty() {
            return Err(value_error(name, "[]", "must hold at least one value"));
        }
        if values.len() > MAX_AXIS_VALUES {
            return Err(value_error(
                name,
                format!("{} values", values.len()),
                format!("must hold at most {MAX_AXIS_VALUES}"),
            ));
        }
        if let Some(bad) = values.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            return Err(value_error(
                name,
                bad,
                "must be a finite number greater than 0",
            ));
        }
        Ok(values)
    }

    /// The axis as notch counts: whole numbers from 1 to the layout's limit.
    ///
    /// # Errors
    /// [`SpecError::Value`] naming the count.
    pub fn counts(&self, name: &str) -> Result<Vec<u32>, SpecError> {
        self.values(name)?
            .into_iter()
            .map(|v| {
                if v.fract() == 0.0 && v >= 1.0 && v <= f64::from(MAX_NOTCH_COUNT) {
                    Ok(v as u32)
                } else {
                    Err(value_error(
                        name,
                        v,
                        format!("must be a whole number from 1 to {MAX_NOTCH_COUNT}"),
                    ))
                }
            })
            .collect()
    }
}

fn range_values(name: &str, from: f64, to: f64, step: f64) -> Result<Vec<f64>, SpecError> {
    if !(step.is_finite() && step > 0.0) {
        return Err(value_error(
            &format!("{name}.step"),
            step,
            "must be a finite number greater than 0",
        ));
    }
    if !(from.is_finite() && to.is_finite() && to >= from) {
        return Err(value_error(
            &format!("{name}.to"),
            to,
            format!("must be finite and at least from = {from}"),
        ));
    }
    let count = ((to - from) / step + 1e-9).floor() + 1.0;
    if count > MAX_AXIS_VALUES as f64 {
        return Err(value_error(
            name,
            format!("{count} values"),
            format!("must hold at most {MAX_AXIS_VALUES}"),
        ));
    }
    Ok((0..count as usize)
        .map(|i| ((from + i as f64 * step) * AXIS_ROUNDING_PER_MM).round() / AXIS_ROUNDING_PER_MM)
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_include_the_end_and_round() {
        let a = Axis::Range {
            from: 0.1,
            to: 0.3,
            step: 0.1,
        };
        assert_eq!(a.values("x").unwrap(), [0.1, 0.2, 0.3]);
        let n = Axis::Range {
            from: 6.0,
            to: 8.0,
            step: 1.0,
        };
        assert_eq!(n.counts("notch_count").unwrap(), [6, 7, 8]);
    }

    #[test]
    fn bad_axes_name_the_key_and_limit() {
        let e = Axis::Range {
            from: 0.1,
            to: 0.3,
            step: 0.0,
        }
        .values("vary.notch_width_mm")
        .unwrap_err()
        .to_string();
        assert_eq!(
            e,
            "vary.notch_width_mm.step = 0 must be a finite number greater than 0"
        );
        let e = Axis::List(vec![2.5])
            .counts("vary.notch_count")
            .unwrap_err();
        assert!(e.to_string().contains("2.5 must be a whole number"), "{e}");
        let e = Axis::List(vec![-1.0])
            .values("vary.notch_arc_mm")
            .unwrap_err();
        assert!(e.to_string().contains("-1 must be a finite number"), "{e}");
        let e = Axis::Range {
            from: 0.0,
            to: 1.0,
            step: 1e-9,
        }
        .values("vary.h")
        .unwrap_err();
        assert!(e.to_string().contains("at most 100000"), "{e}");
    }
}
