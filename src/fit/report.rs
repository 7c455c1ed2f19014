//! The fit's report page: resistance against strain per cycle with the fitted models drawn
//! over it (the paper's Fig. 4(d-f)), residuals over time, and the fitted parameters.

use crate::analysis::Placement;
use crate::report::{Chart, Legend, Page, Series, Table, PALETTE};

use super::{model_name, SensorFit};

/// A validation result: a model's angle RMSE on another recording.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Validation {
    /// `linear`, `pi`, `continuous-pi`.
    pub model: super::ModelKind,
    /// RMSE of the runtime estimate against the recorded angle (°).
    pub rmse_deg: Option<f64>,
    /// Why there is none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The report of `fits` (one per sensor) of the recording called `name`.
pub fn report_page(name: &str, fits: &[SensorFit], validation: &[Validation]) -> Page {
    let mut page = Page::new(format!("Sensor fit: {name}"));
    add_sections(&mut page, fits, validation, Placement::ALONE);
    page
}

/// Adds the fit's sections for `fits` (one per sensor) to `page`, headings and figure names
/// placed by `at`.
pub fn add_sections(
    page: &mut Page,
    fits: &[SensorFit],
    validation: &[Validation],
    at: Placement<'_>,
) {
    page.text(
        "Resistance from the divider voltage (Eq. 4), strain from the tracker angle (Eq. 3), both \
         through the same prefilter. Each model is fitted to every sensor; the table ranks them \
         by the resistance residual and the Bayesian information criterion (lower is better), \
         and, when a second recording was given, by the runtime estimator's angle RMSE on it.",
    );
    let mut models = Table::new([
        "sensor",
        "model",
        "RMSE (Ω)",
        "parameters",
        "BIC",
        "validation RMSE (°)",
        "note",
    ]);
    for fit in fits {
        for s in &fit.summaries {
            let v = validation
                .iter()
                .find(|v| v.model == s.model)
                .map_or("–".to_owned(), |v| {
                    v.rmse_deg.map_or_else(
                        || v.error.clone().unwrap_or_default(),
                        |r| format!("{r:.3}"),
                    )
                });
            models.row([
                sensor_name(fit),
                model_name(s.model).to_owned(),
                s.skipped
                    .clone()
                    .unwrap_or_else(|| format!("{:.1}", s.rmse_ohm)),
                s.parameters.to_string(),
                if s.bic.is_finite() {
                    format!("{:.1}", s.bic)
                } else {
                    "–".into()
                },
                v,
                s.note.clone().unwrap_or_default(),
            ]);
        }
    }
    page.heading(format!("{}Model choice", label(at)));
    page.table(models);
    for fit in fits {
        sensor_section(page, fit, at);
    }
}

fn label(at: Placement<'_>) -> String {
    if at.label.is_empty() {
        String::new()
    } else {
        format!("{}: ", at.label)
    }
}

fn sensor_name(fit: &SensorFit) -> String {
    format!("v{}_V", fit.plane.column())
}

fn sensor_section(page: &mut Page, fit: &SensorFit, at: Placement<'_>) {
    let name = sensor_name(fit);
    let obs = &fit.observations;
    page.heading(format!("{}Sensor {name}", label(at)));
    let mut loops = loop_chart(fit, format!("Resistance against strain, {name}"));
    loops.size = (900, 560);
    let mut residuals = Chart::new(
        format!("Residual R_model − R over time, {name}"),
        "time (s)",
        "residual (kΩ)",
    );
    let linear_res: Vec<f64> = obs
        .strain
        .iter()
        .zip(&obs.ohm)
        .map(|(e, r)| (fit.linear.resistance(*e) - r) / 1e3)
        .collect();
    residuals.push(Series::line(
        "linear",
        Series::zip(&obs.time_s, &linear_res),
        PALETTE[7],
    ));
    let mut params = Table::new(["parameter", "value"]);
    params.row([
        "linear GF".to_owned(),
        format!("{:.4}", fit.linear.gauge_factor),
    ]);
    params.row([
        "linear R₀ (kΩ)".to_owned(),
        format!("{:.3}", fit.linear.r0_ohm / 1e3),
    ]);
    params.row(["linear r²".to_owned(), format!("{:.4}", fit.linear.r2)]);
    if let Some(c) = &fit.characteristic {
        params.row(["R_c (kΩ)".to_owned(), format!("{:.3}", c.center_ohm / 1e3)]);
        params.row([
            "ε_c (%)".to_owned(),
            format!("{:.4}", c.center_strain * 100.0),
        ]);
        params.row([
            "m_c (kΩ per unit strain)".to_owned(),
            format!("{:.1}", c.center_slope_ohm / 1e3),
        ]);
        params.row(["R_peak (kΩ)".to_owned(), format!("{:.3}", c.peak_ohm / 1e3)]);
        params.row([
            "ε_peak (%)".to_owned(),
            format!("{:.4}", c.peak_strain * 100.0),
        ]);
    }
    for ((label, color), result) in MODEL_COLOURS.iter().zip([&fit.pi, &fit.continuous_pi]) {
        let (label, color) = (*label, *color);
        let Ok(pi) = result else { continue };
        let model = pi.predict_observed(obs);
        let res: Vec<f64> = model
            .iter()
            .zip(&obs.ohm)
            .map(|(m, r)| (m - r) / 1e3)
            .collect();
        residuals.push(Series::line(label, Series::zip(&obs.time_s, &res), color));
        let v = &pi.values;
        params.row([format!("{label} a₁…a₄"), fmt_all(&v.loading)]);
        params.row([format!("{label} a₅…a₈"), fmt_all(&v.unloading)]);
        params.row([format!("{label} weights Pᵢ"), fmt_all(&v.weights)]);
        params.row([format!("{label} radii ρᵢ"), fmt_all(&pi.model.radii)]);
        params.row([
            format!("{label} restarts (start: RMSE Ω)"),
            pi.restarts
                .iter()
                .map(|r| {
                    let note = if r.converged { "" } else { " (not converged)" };
                    format!("{}: {:.1}{note}", r.start, r.rmse_ohm)
                })
                .collect::<Vec<_>>()
                .join(", "),
        ]);
    }
    page.figure(
        format!("{}loops-v{}", at.figure_prefix, fit.plane.column()),
        loops,
        "Each loading/unloading cycle in its own colour; the linear fit, and the hysteretic \
         models over the last cycle (cf. the paper's Fig. 4(d-f)).",
    );
    page.figure(
        format!("{}residuals-v{}", at.figure_prefix, fit.plane.column()),
        residuals,
        "Model minus measured resistance over the recording.",
    );
    page.table(params);
}

/// Colours of the fitted models: linear in green and PI in purple, as in the paper's Fig. 4,
/// darker than the cycles' palette so a fit is not mistaken for a cycle.
const LINEAR_COLOUR: (u8, u8, u8) = (0, 110, 40);
const MODEL_COLOURS: [(&str, (u8, u8, u8)); 2] =
    [("PI", (90, 0, 150)), ("continuous PI", (0, 95, 95))];

/// The resistance-strain loops of one sensor's fit (the paper's Fig. 4(d-f)): each cycle in its
/// own colour (every sample when no cycle was found), the linear fit, and each fitted
/// hysteretic model over the last cycle. The models run over the whole recording (their plays
/// remember the history) and are drawn over the last cycle, so that they show the loop without
/// hiding the data. The one loop chart of `dlw fit`'s and `dlw characterize`'s reports.
pub(super) fn loop_chart(fit: &SensorFit, title: String) -> Chart {
    let obs = &fit.observations;
    let strain_pct: Vec<f64> = obs.strain.iter().map(|e| e * 100.0).collect();
    let kohm: Vec<f64> = obs.ohm.iter().map(|r| r / 1e3).collect();
    let mut chart = Chart::new(title, "strain (%)", "resistance (kΩ)");
    chart.size = (900, 520);
    chart.legend = Legend::LowerRight;
    let count = fit.cycles.len();
    for (i, c) in fit.cycles.iter().enumerate() {
        let r = c.range();
        // Past eight cycles the legend names only the first and the last.
        let name = if count <= 8 || i == 0 || i + 1 == count {
            format!("cycle {}", i + 1)
        } else {
            String::new()
        };
        chart.push(Series::line(
            name,
            Series::zip(&strain_pct[r.clone()], &kohm[r]),
            PALETTE[i % PALETTE.len()],
        ));
    }
    if fit.cycles.is_empty() {
        chart.push(Series::dots(
            "samples",
            Series::zip(&strain_pct, &kohm),
            PALETTE[7],
        ));
    }
    let (lo, hi) = crate::stats::min_max(&obs.strain);
    chart.push(Series::reference(
        "linear fit",
        [lo, hi]
            .iter()
            .map(|&e| (e * 100.0, fit.linear.resistance(e) / 1e3))
            .collect(),
        LINEAR_COLOUR,
    ));
    let shown = fit
        .cycles
        .last()
        .map_or(0..=obs.len().saturating_sub(1), |c| c.range());
    for ((label, colour), result) in MODEL_COLOURS.iter().zip([&fit.pi, &fit.continuous_pi]) {
        let Ok(pi) = result else { continue };
        let model = pi.predict_observed(obs);
        chart.push(Series::reference(
            format!("{label} fit (last cycle)"),
            shown
                .clone()
                .map(|i| (strain_pct[i], model[i] / 1e3))
                .collect(),
            *colour,
        ));
    }
    chart
}

fn fmt_all(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.4e}"))
        .collect::<Vec<_>>()
        .join(", ")
}
