//! The accuracy a front candidate will have: the twin of the paper's bench
//! (`designs/scenarios/paper-bench.toml`) simulated on the candidate's geometry, through the
//! reproduction's own characterization, fits and estimation (Table IV) and Joint D's closed
//! loop (Table VI).
//!
//! The graphene sensor's resistance is a function of the strain it feels, so the twin's
//! sensor (its PI model in strain, its noise, drift and thermal wander) moves to a new
//! geometry unchanged: the candidate changes the strain per degree and the range. A UAN
//! candidate borrows the sensor of the twin's UAN joint whose gauge factor is nearest the
//! spec's (Joint A at 15.3, Joint B at 22.0), a BSN candidate Joint C's two sensors; the
//! closed loop runs the same sensor on Joint D's plant (its relaxation and backlash).
//!
//! Each simulation is short-sized (every protocol once at the paper's timings, a fifth of a
//! full run), run on [`PREDICTION_SEEDS`] seeds and averaged, and scaled by the twin's own
//! full/short ratio of the borrowed joint's numbers (the calibration's last full-size check,
//! recorded in the bench file, both sides means over the same seeds), so the prediction is a
//! full run's mean over the seeds. Only the front's candidates are simulated: the grid keeps its speed.

use dlw_geometry::NotchStyle;
use rayon::prelude::*;
use serde::Serialize;

use crate::design::{Design, DesignFile};
use crate::reproduce::{accuracy, Bench, ReproduceError, SimJoint, CALIBRATION_REPEATS};

/// The reproduction seeds (`dlw reproduce --seed`) a prediction averages, as the shipped twin's
/// calibration does (`dlw calibrate --seeds 3`): its full/short corrections are ratios of
/// 3-seed means, and one seed's short run of a slow-noise sensor scatters by about 20 %.
pub const PREDICTION_SEEDS: u64 = 3;

/// A candidate's predicted accuracy (°).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Predicted {
    /// Table IV's linear model.
    pub linear_rmse_deg: f64,
    /// Table IV's PI model.
    pub pi_rmse_deg: f64,
    /// Table VI's closed loop, actual vs desired.
    pub closed_loop_rmse_deg: f64,
    /// The twin joint whose sensor it borrowed.
    pub borrowed: char,
}

/// The twin's joints, and the gauge factor the candidates are scored with.
#[derive(Debug, Clone)]
pub struct Predictor {
    joints: Vec<SimJoint>,
    corrections: [[f64; 3]; 3],
    gauge_factor: f64,
}

/// The full/short correction of metric `key` (`table4.A.linear`) from the bench file's
/// provenance, 1 when it records none.
fn correction(bench: &Bench, key: &str) -> f64 {
    match bench {
        Bench::Twin(file) => file
            .calibration
            .as_ref()
            .and_then(|c| c.corrections.get(key).copied())
            .filter(|c| c.is_finite() && *c > 0.0)
            .unwrap_or(1.0),
        Bench::Ideal => 1.0,
    }
}

impl Predictor {
    /// The shipped twin's predictor for a spec of `gauge_factor`.
    ///
    /// # Errors
    /// [`crate::reproduce::TwinError`] if the shipped bench does not read.
    pub fn paper(gauge_factor: f64) -> Result<Self, crate::reproduce::TwinError> {
        let bench = Bench::paper()?;
        let mut corrections = [[1.0; 3]; 3];
        for (i, letter) in ['A', 'B', 'C'].into_iter().enumerate() {
            corrections[i] = [
                correction(&bench, &format!("table4.{letter}.linear")),
                correction(&bench, &format!("table4.{letter}.pi")),
                correction(&bench, "table6.closed"),
            ];
        }
        Ok(Self {
            joints: bench.joints(),
            corrections,
            gauge_factor,
        })
    }

    /// The twin joint a candidate of `style` borrows its sensor from.
    pub fn borrowed(&self, style: NotchStyle) -> char {
        match style {
            NotchStyle::Bsn => 'C',
            NotchStyle::Uan => {
                if (self.gauge_factor - 15.3).abs() <= (self.gauge_factor - 22.0).abs() {
                    'A'
                } else {
                    'B'
                }
            }
        }
    }

    /// The predicted accuracy of `design`.
    ///
    /// # Errors
    /// [`ReproduceError`] when a simulation or fit of the candidate fails.
    pub fn predict(&self, design: &Design) -> Result<Predicted, ReproduceError> {
        let letter = self.borrowed(design.joint.style());
        let twin = |l: char| self.joints.iter().find(|j| j.letter == l);
        let (Some(source), Some(d)) = (twin(letter), twin('D')) else {
            unreachable!("the twin has Joints A-D")
        };
        let joint = SimJoint {
            letter,
            design: design.clone(),
            scenario: source.scenario.clone(),
        };
        let mut control_scenario = source.scenario.clone();
        control_scenario.plant = d.scenario.plant.clone();
        let control = SimJoint {
            letter: 'D',
            design: design.clone(),
            scenario: control_scenario,
        };
        let mut sum = [0.0; 3];
        for seed in 0..PREDICTION_SEEDS {
            let a = accuracy(&joint, &control, CALIBRATION_REPEATS, seed)?;
            sum[0] += a.linear_rmse_deg;
            sum[1] += a.pi_rmse_deg;
            sum[2] += a.closed_loop_rmse_deg;
        }
        let mean = sum.map(|x| x / PREDICTION_SEEDS as f64);
        let k = self.corrections[usize::from(letter as u8 - b'A')];
        Ok(Predicted {
            linear_rmse_deg: mean[0] * k[0],
            pi_rmse_deg: mean[1] * k[1],
            closed_loop_rmse_deg: mean[2] * k[2],
            borrowed: letter,
        })
    }

    /// Predictions for `files` in parallel; a candidate whose simulation fails gets `None`.
    pub fn predict_all(&self, files: &[DesignFile]) -> Vec<Option<Predicted>> {
        files
            .par_iter()
            .map(|f| {
                let design = Design::from_file(f.clone()).ok()?;
                self.predict(&design).ok()
            })
            .collect()
    }
}
