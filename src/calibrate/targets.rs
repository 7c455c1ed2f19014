//! What a calibration aims at: the paper's summary numbers, each a number a reproduction
//! computes, with the paper's value and a tolerance; and the side conditions (Table III's
//! fitted parameters no further from the paper than on the ideal bench, the paper's patterns).

use serde::Serialize;

use crate::reproduce::paper::{TABLE_IV, TWO_SENSOR_RMSE};
use crate::reproduce::TablesRun;
use crate::sensor::{Sensor, Sensors};

/// The tolerance on every target: within 25 % of the paper's value (the reproduction's
/// own agreement for these numbers).
pub const TARGET_TOLERANCE: f64 = crate::reproduce::HEADLINE_TOLERANCE;

/// Table VI's actual-vs-desired RMSE (°), open loop then closed loop.
pub const TABLE_VI_ACTUAL_VS_DESIRED: [f64; 2] = [8.14, 2.92];

/// A number a reproduction computes, read from its Tables III-VI.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Metric {
    /// Table IV: a joint's one-sensor RMSE (°) with the linear or the PI config.
    Table4 {
        /// `A`, `B`, `C`.
        joint: char,
        /// `true` for PI.
        pi: bool,
    },
    /// Table V: Joint C's two-sensor config read by `sensors` (°).
    Table5 {
        /// Tension, compression or both.
        sensors: Sensors,
    },
    /// Table VI: Joint D's actual-vs-desired RMSE (°), open or closed loop.
    Table6 {
        /// `true` for closed loop.
        closed: bool,
    },
    /// A Table III number of a joint's sensor 1.
    Table3 {
        /// `A`, `B`, `C`.
        joint: char,
        /// Which one.
        field: Table3Field,
    },
    /// The linear fit's resistance RMSE over the PI fit's on a joint's characterization (the
    /// evidence `reproduce::patterns` reads for "a line cannot win").
    LineOverPiResidual {
        /// `A`, `B`, `C`.
        joint: char,
    },
}

/// A row of Table III.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Table3Field {
    /// `GF`.
    GaugeFactor,
    /// `R₀`.
    R0,
    /// `R_c`.
    CenterOhm,
    /// `ε_c`.
    CenterStrain,
    /// `m_c`.
    CenterSlope,
    /// `R_peak` (Joint C's read as 75.4 kΩ, the misprint corrected).
    PeakOhm,
    /// `ε_peak`.
    PeakStrain,
}

impl Table3Field {
    /// Every row.
    pub const ALL: [Self; 7] = [
        Self::GaugeFactor,
        Self::R0,
        Self::CenterOhm,
        Self::CenterStrain,
        Self::CenterSlope,
        Self::PeakOhm,
        Self::PeakStrain,
    ];

    /// The row's name in a metric's (`table3.A.m_c`), as the reproduction's checks name it.
    fn name(self) -> &'static str {
        let i = Self::ALL.iter().position(|f| *f == self).unwrap_or(0);
        crate::reproduce::TABLE3_ROWS[i]
    }

    /// The paper's value for joint index `i` (0 = A).
    fn paper(self, i: usize) -> f64 {
        let row = Self::ALL.iter().position(|f| *f == self).unwrap_or(0);
        crate::reproduce::paper::table_iii_as_read(i)[row]
    }
}

const TENSION: Sensors = Sensors::Single(Sensor::One);
const COMPRESSION: Sensors = Sensors::Single(Sensor::Two);

impl Metric {
    /// The joint whose runs give the number: Table V's is Joint C's, Table VI's Joint D's.
    /// `reproduce::tables_of` runs each joint on its own scenario and seeds, so the number
    /// depends on no other joint's parameters.
    pub fn joint(self) -> char {
        match self {
            Self::Table4 { joint, .. }
            | Self::Table3 { joint, .. }
            | Self::LineOverPiResidual { joint } => joint,
            Self::Table5 { .. } => 'C',
            Self::Table6 { .. } => 'D',
        }
    }

    /// A short name, `table4.A.pi`, `table5.both`, `table6.closed`, `table3.C.m_c`.
    pub fn name(self) -> String {
        match self {
            Self::Table4 { joint, pi } => {
                format!("table4.{joint}.{}", if pi { "pi" } else { "linear" })
            }
            Self::Table5 { sensors } => format!(
                "table5.{}",
                match sensors {
                    Sensors::Both => "both",
                    s if s == COMPRESSION => "compression",
                    _ => "tension",
                }
            ),
            Self::Table6 { closed } => {
                format!("table6.{}", if closed { "closed" } else { "open" })
            }
            Self::Table3 { joint, field } => format!("table3.{joint}.{}", field.name()),
            Self::LineOverPiResidual { joint } => format!("residual_ratio.{joint}"),
        }
    }

    /// The paper's value, where it has one.
    pub fn paper(self) -> Option<f64> {
        let index = |j: char| usize::from(j as u8 - b'A');
        match self {
            Self::Table4 { joint, pi } => Some(TABLE_IV[index(joint)][usize::from(pi)]),
            Self::Table5 { sensors } => Some(match sensors {
                Sensors::Both => TWO_SENSOR_RMSE[2],
                s if s == COMPRESSION => TWO_SENSOR_RMSE[1],
                _ => TWO_SENSOR_RMSE[0],
            }),
            Self::Table6 { closed } => Some(TABLE_VI_ACTUAL_VS_DESIRED[usize::from(closed)]),
            Self::Table3 { joint, field } => Some(field.paper(index(joint))),
            Self::LineOverPiResidual { .. } => None,
        }
    }

    /// The run's value; `None` when the run lacks it (a fit that failed).
    pub fn value(self, run: &TablesRun) -> Option<f64> {
        let joint = |letter: char| run.joints.iter().find(|j| j.letter == letter);
        let rmse = |letter: char, config: &str, sensors: Sensors| {
            joint(letter)?
                .estimation
                .runs
                .iter()
                .find(|x| x.config == config && x.sensors == sensors)
                .map(|x| x.metrics.rmse_deg)
        };
        let v = match self {
            Self::Table4 { joint, pi } => rmse(joint, if pi { "PI" } else { "linear" }, TENSION)?,
            Self::Table5 { sensors } => rmse('C', "linear, two-sensor config", sensors)?,
            Self::Table6 { closed } => {
                run.control.as_ref()?.run.metrics[usize::from(closed)].actual_vs_desired_rmse_deg
            }
            Self::Table3 {
                joint: letter,
                field,
            } => {
                let s = &joint(letter)?.loops.sensors.first()?.summary;
                let c = s.characteristic.as_ref();
                match field {
                    Table3Field::GaugeFactor => s.gauge_factor,
                    Table3Field::R0 => s.r0_ohm,
                    Table3Field::CenterOhm => c?.center_ohm,
                    Table3Field::CenterStrain => c?.center_strain,
                    Table3Field::CenterSlope => c?.center_slope_ohm,
                    Table3Field::PeakOhm => c?.peak_ohm,
                    Table3Field::PeakStrain => c?.peak_strain,
                }
            }
            Self::LineOverPiResidual { joint: letter } => {
                let s = &joint(letter)?.loops.sensors.first()?.summary;
                s.linear_rmse_ohm / s.pi_rmse_ohm?
            }
        };
        v.is_finite().then_some(v)
    }

    /// The ten numbers of the table: Table IV (linear and PI, Joints A-C), Table V
    /// (compression and both; tension is Table IV's Joint C linear) and Table VI (actual vs
    /// desired, open and closed loop).
    pub const TARGETS: [Self; 10] = [
        Self::Table4 {
            joint: 'A',
            pi: false,
        },
        Self::Table4 {
            joint: 'A',
            pi: true,
        },
        Self::Table4 {
            joint: 'B',
            pi: false,
        },
        Self::Table4 {
            joint: 'B',
            pi: true,
        },
        Self::Table4 {
            joint: 'C',
            pi: false,
        },
        Self::Table4 {
            joint: 'C',
            pi: true,
        },
        Self::Table5 {
            sensors: COMPRESSION,
        },
        Self::Table5 {
            sensors: Sensors::Both,
        },
        Self::Table6 { closed: false },
        Self::Table6 { closed: true },
    ];

    /// Every Table III number of Joints A-C.
    pub fn table3() -> Vec<Self> {
        ['A', 'B', 'C']
            .into_iter()
            .flat_map(|joint| {
                Table3Field::ALL
                    .into_iter()
                    .map(move |field| Self::Table3 { joint, field })
            })
            .collect()
    }

    /// Everything a calibration reads from a run: the targets, Table III, and the residual
    /// ratio of Joint C.
    pub fn all() -> Vec<Self> {
        let mut all = Self::TARGETS.to_vec();
        all.extend(Self::table3());
        all.push(Self::LineOverPiResidual { joint: 'C' });
        all
    }
}

/// One target: a metric, the paper's value, the tolerance (relative).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Target {
    /// The number.
    pub metric: Metric,
    /// The paper's value.
    pub paper: f64,
    /// Relative tolerance: the target is met within `paper·(1 ± tolerance)`.
    pub tolerance: f64,
}

impl Target {
    /// The ten targets at 25 %.
    pub fn paper_targets() -> Vec<Self> {
        Metric::TARGETS
            .into_iter()
            .filter_map(|metric| {
                Some(Self {
                    metric,
                    paper: metric.paper()?,
                    tolerance: TARGET_TOLERANCE,
                })
            })
            .collect()
    }

    /// `value`'s distance from the paper in tolerances, on a log scale:
    /// `ln(value/paper)/ln(1 + tolerance)`; |score| ≤ 1 (about) is met.
    pub fn score(&self, value: f64) -> f64 {
        (value / self.paper).ln() / (1.0 + self.tolerance).ln()
    }

    /// Whether `value` lies within `paper·(1 ± tolerance)`.
    pub fn met(&self, value: f64) -> bool {
        (value / self.paper - 1.0).abs() <= self.tolerance
    }
}

/// A Table III number may be at most this much further from the paper (relative, in absolute
/// percentage points) than on the ideal bench at full size: its "current agreement", with room
/// for the noise of one run (the full-size fits of two seeds differ by about this much).
pub const TABLE3_SLACK: f64 = 0.05;

/// Table III's side condition: each number's relative distance from the paper may be at most
/// `ideal + TABLE3_SLACK`, where `ideal` is the ideal bench's at full size.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Agreement {
    /// The number.
    pub metric: Metric,
    /// The paper's value.
    pub paper: f64,
    /// The largest relative distance allowed.
    pub max_relative: f64,
}

impl Agreement {
    /// The relative distance of `value` from the paper.
    pub fn relative(&self, value: f64) -> f64 {
        (value / self.paper - 1.0).abs()
    }

    /// Whether `value` keeps the agreement.
    pub fn kept(&self, value: f64) -> bool {
        self.relative(value) <= self.max_relative
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The calibration's metric names are the ones the reproduction's checks carry (its report
    /// reads a bench file's agreements and trade-offs by these names).
    #[test]
    fn metric_names_are_the_reproductions_check_names() {
        let names: Vec<String> = Metric::TARGETS.iter().map(|m| m.name()).collect();
        assert_eq!(
            names,
            [
                "table4.A.linear",
                "table4.A.pi",
                "table4.B.linear",
                "table4.B.pi",
                "table4.C.linear",
                "table4.C.pi",
                "table5.compression",
                "table5.both",
                "table6.open",
                "table6.closed"
            ]
        );
        assert_eq!(
            Metric::Table3 {
                joint: 'A',
                field: Table3Field::CenterSlope
            }
            .name(),
            "table3.A.m_c"
        );
    }
}
