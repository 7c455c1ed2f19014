//! Resistance-strain loops (Section IV-A1, Fig. 4, Table III): the recording split into
//! loading/unloading cycles, resistance against strain one colour per cycle, stroke, strain and
//! ΔR against time, and the linear and PI fits of `crate::fit` drawn over the loops.

use dlw_estimator::SensorPlane;
use dlw_geometry::Joint;
use serde::Serialize;

use super::{figure_name, sensor_label, titled, CharacterizeError, Options};
use crate::fit::{fit_sensor_models, Characteristic, FitError, FitOptions, ModelKind, SensorFit};
use crate::recording::Recording;
use crate::report::{Chart, Page, Series, Table, PALETTE};

/// One sensor's numbers (`--json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoopsSummary {
    /// `v1_V`, `v2_V (compression)`, ….
    pub sensor: String,
    /// Loading/unloading cycles found.
    pub cycles: usize,
    /// Linear gauge factor (Eq. 5).
    pub gauge_factor: f64,
    /// Linear `R₀` (Ω).
    pub r0_ohm: f64,
    /// r² of the linear fit.
    pub r2: f64,
    /// Linear model's resistance RMSE (Ω).
    pub linear_rmse_ohm: f64,
    /// Table III's characteristic points, with two cycles or more.
    pub characteristic: Option<Characteristic>,
    /// The generalized PI fit's resistance RMSE (Ω), when it was fitted.
    pub pi_rmse_ohm: Option<f64>,
    /// Why the PI was not fitted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pi_error: Option<String>,
}

/// One sensor: its numbers and the fit behind them.
#[derive(Debug, Clone, Serialize)]
pub struct LoopsSensor {
    /// The numbers.
    #[serde(flatten)]
    pub summary: LoopsSummary,
    /// The fit (observations, cycles, every model).
    #[serde(skip)]
    pub fit: SensorFit,
    /// The stroke at the observations' samples (mm).
    #[serde(skip)]
    pub stroke_mm: Vec<f64>,
}

/// The loops analysis of every sensor.
#[derive(Debug, Clone, Serialize)]
pub struct LoopsResult {
    /// One per sensor.
    pub sensors: Vec<LoopsSensor>,
}

/// Fits every model to each sensor on `planes` (the fits `dlw fit` makes) and keeps what
/// Fig. 4 draws.
///
/// # Errors
/// [`CharacterizeError::Fit`] when a sensor's observations or linear fit fail; a PI fit that
/// fails is reported in the summary instead.
pub fn loops(
    recording: &Recording,
    joint: &Joint,
    planes: &[SensorPlane],
    options: &Options,
) -> Result<LoopsResult, CharacterizeError> {
    let fit_options = FitOptions {
        model: ModelKind::Linear,
        order: options.order,
        prefilter: options.prefilter,
        decimation: options.decimation,
    };
    let two = planes.len() > 1;
    // Each sensor's fit on its own thread: a BSN joint's two PI fits are independent.
    let fits: Vec<Result<SensorFit, FitError>> = std::thread::scope(|s| {
        let handles: Vec<_> = planes
            .iter()
            .map(|&plane| {
                let fit_options = &fit_options;
                s.spawn(move || {
                    fit_sensor_models(
                        recording,
                        joint,
                        plane,
                        fit_options,
                        options.models,
                        &|_| {},
                    )
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    let mut sensors = Vec::new();
    for (fit, &plane) in fits.into_iter().zip(planes) {
        let fit = fit?;
        // By row, not by `step_by(decimation)`: rows the tracker did not measure are not
        // observations.
        let stroke_mm: Vec<f64> = fit
            .observations
            .rows
            .iter()
            .map(|&i| recording.samples.stroke_mm[i])
            .collect();
        let (pi_rmse_ohm, pi_error) = match &fit.pi {
            Ok(p) => (Some(p.rmse_ohm), None),
            Err(e) => (None, Some(e.clone())),
        };
        sensors.push(LoopsSensor {
            summary: LoopsSummary {
                sensor: sensor_label(plane, two),
                cycles: fit.cycles.len(),
                gauge_factor: fit.linear.gauge_factor,
                r0_ohm: fit.linear.r0_ohm,
                r2: fit.linear.r2,
                linear_rmse_ohm: fit.linear.rmse_ohm,
                characteristic: fit.characteristic,
                pi_rmse_ohm,
                pi_error,
            },
            fit,
            stroke_mm,
        });
    }
    Ok(LoopsResult { sensors })
}

impl LoopsResult {
    /// Adds Table III's numbers and Fig. 4's plots for each sensor. `label` goes in front of
    /// headings and titles (e.g. `Joint A`), `prefix` in front of figure names.
    fn section(&self, page: &mut Page, label: &str, prefix: &str) {
        let mut t = Table::new([
            "sensor",
            "cycles",
            "GF",
            "R₀ (kΩ)",
            "r²",
            "R_c (kΩ)",
            "ε_c (%)",
            "m_c (kΩ)",
            "R_peak (kΩ)",
            "ε_peak (%)",
            "linear RMSE (Ω)",
            "PI RMSE (Ω)",
        ]);
        for s in &self.sensors {
            let m = &s.summary;
            let c = m.characteristic;
            let ch = |f: &dyn Fn(&Characteristic) -> String| c.as_ref().map_or("–".into(), f);
            t.row([
                m.sensor.clone(),
                m.cycles.to_string(),
                format!("{:.3}", m.gauge_factor),
                format!("{:.2}", m.r0_ohm / 1e3),
                format!("{:.4}", m.r2),
                ch(&|c| format!("{:.2}", c.center_ohm / 1e3)),
                ch(&|c| format!("{:.3}", c.center_strain * 100.0)),
                ch(&|c| format!("{:.0}", c.center_slope_ohm / 1e3)),
                ch(&|c| format!("{:.2}", c.peak_ohm / 1e3)),
                ch(&|c| format!("{:.3}", c.peak_strain * 100.0)),
                format!("{:.1}", m.linear_rmse_ohm),
                m.pi_rmse_ohm
                    .map_or_else(|| "not fitted".into(), |r| format!("{r:.1}")),
            ]);
        }
        page.table(t);
        for s in &self.sensors {
            for e in s.summary.pi_error.iter() {
                page.text(format!(
                    "{}: the PI model was not fitted: {e}.",
                    s.summary.sensor
                ));
            }
        }
        for (k, s) in self.sensors.iter().enumerate() {
            let column = s.fit.plane.column();
            // Stroke, strain and ΔR against time are the same recording for both sensors.
            if k == 0 {
                time_series(page, s, label, prefix);
            } else {
                let obs = &s.fit.observations;
                let mut dr = Chart::new(
                    titled(label, &format!("ΔR against time, {}", s.summary.sensor)),
                    "time (s)",
                    "ΔR = R − R₀ (kΩ)",
                );
                dr.size = (900, 260);
                dr.push(Series::line(
                    "",
                    obs.time_s
                        .iter()
                        .zip(&obs.ohm)
                        .map(|(t, r)| (*t, (r - s.fit.linear.r0_ohm) / 1e3))
                        .collect(),
                    PALETTE[3],
                ));
                page.figure(
                    figure_name(prefix, &format!("delta-r-v{column}")),
                    dr,
                    format!(
                        "Change in resistance of {} (cf. Fig. 4(c)).",
                        s.summary.sensor
                    ),
                );
            }
            page.figure(
                figure_name(prefix, &format!("loops-v{column}")),
                loop_chart(s, label),
                format!(
                    "Resistance against strain of {}, each loading/unloading cycle in its own \
                     colour, with the linear fit (green) and the PI fit over the last cycle (purple) \
                     drawn over the data (cf. Fig. 4(d-f)).",
                    s.summary.sensor
                ),
            );
        }
    }
}

fn time_series(page: &mut Page, s: &LoopsSensor, label: &str, prefix: &str) {
    let obs = &s.fit.observations;
    let mut stroke = Chart::new(titled(label, "Tendon stroke"), "time (s)", "stroke (mm)");
    stroke.size = (900, 240);
    stroke.push(Series::line(
        "",
        Series::zip(&obs.time_s, &s.stroke_mm),
        PALETTE[0],
    ));
    let mut strain = Chart::new(
        titled(label, "Strain from the tracker angle (Eq. 3)"),
        "time (s)",
        "strain (%)",
    );
    strain.size = (900, 240);
    strain.push(Series::line(
        "",
        obs.time_s
            .iter()
            .zip(&obs.strain)
            .map(|(t, e)| (*t, e * 100.0))
            .collect(),
        PALETTE[2],
    ));
    let mut dr = Chart::new(
        titled(
            label,
            &format!("ΔR from the divider voltage (Eq. 4), {}", s.summary.sensor),
        ),
        "time (s)",
        "ΔR = R − R₀ (kΩ)",
    );
    dr.size = (900, 240);
    dr.push(Series::line(
        "",
        obs.time_s
            .iter()
            .zip(&obs.ohm)
            .map(|(t, r)| (*t, (r - s.fit.linear.r0_ohm) / 1e3))
            .collect(),
        PALETTE[3],
    ));
    page.figure(
        figure_name(prefix, "stroke"),
        stroke,
        "(a) The tendon stroke pattern.",
    );
    page.figure(
        figure_name(prefix, "strain"),
        strain,
        "(b) The strain at the sensor, from the tracker's angle, after the prefilter.",
    );
    page.figure(
        figure_name(prefix, "delta-r"),
        dr,
        "(c) The change in resistance from the linear fit's R₀, after the prefilter.",
    );
}

fn loop_chart(s: &LoopsSensor, label: &str) -> Chart {
    s.fit.loop_chart(titled(
        label,
        &format!("Resistance against strain, {}", s.summary.sensor),
    ))
}

impl crate::analysis::Analysis for LoopsResult {
    fn summary(&self) -> String {
        use std::fmt::Write;
        let r = self;
        let mut out = String::new();
        for s in &r.sensors {
            let m = &s.summary;
            let _ = writeln!(out, "sensor {}: {} cycles", m.sensor, m.cycles);
            let _ = writeln!(
                out,
                "  linear  GF = {:.4}, R0 = {:.1} Ω, r² = {:.4}, RMSE {:.1} Ω",
                m.gauge_factor, m.r0_ohm, m.r2, m.linear_rmse_ohm
            );
            if let Some(c) = &m.characteristic {
                let _ = writeln!(out,
                "  Table III  R_c = {:.2} kΩ, ε_c = {:.3} %, m_c = {:.0} kΩ, R_peak = {:.2} kΩ, ε_peak = {:.3} %",
                c.center_ohm / 1e3,
                c.center_strain * 100.0,
                c.center_slope_ohm / 1e3,
                c.peak_ohm / 1e3,
                c.peak_strain * 100.0
            );
            }
            match (&m.pi_rmse_ohm, &m.pi_error) {
                (Some(x), _) => {
                    let _ = writeln!(out, "  PI      RMSE {x:.1} Ω");
                }
                (None, Some(e)) => {
                    let _ = writeln!(out, "  PI      not fitted: {e}");
                }
                _ => {}
            }
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: crate::analysis::Placement<'_>) {
        self.section(page, at.label, at.figure_prefix);
    }
}
