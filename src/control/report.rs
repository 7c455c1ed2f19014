//! The control report: `report.html` with Fig. 10 for both schemes and Table VI, and
//! `control.csv` with every sample.

use crate::analysis::Placement;
use crate::fixed::push_fixed;
use crate::report::{Chart, ChartError, Page, Series, Table, PALETTE};
use crate::sim::Scenario;

use super::{Control, ControlRun, MtSource, Scheme, PAPER_TABLE_VI};

/// The CSV's file name inside the output folder.
pub const CSV_FILE: &str = "control.csv";

/// Length of the detail window plotted per scheme (s).
pub const WINDOW_S: f64 = 120.0;

const DESIRED: (u8, u8, u8) = (40, 40, 40);
const ACTUAL: (u8, u8, u8) = PALETTE[0];
const SENSED: (u8, u8, u8) = PALETTE[1];

/// `control.csv`: `time_s,desired_deg`, then `actual_deg`, `sensed_deg` and `stroke_mm` for the
/// open loop and the closed loop (prefixed `open_` and `closed_`). `actual` is the angle the EM
/// tracker recorded.
pub fn csv_bytes(control: &Control, run: &ControlRun) -> Vec<u8> {
    let desired = &control.desired.angle_deg;
    let hz = control.desired.scenario.sample_hz;
    let mut out = Vec::with_capacity(desired.len() * 72 + 160);
    out.extend_from_slice(
        b"time_s,desired_deg,open_actual_deg,open_sensed_deg,open_stroke_mm,\
closed_actual_deg,closed_sensed_deg,closed_stroke_mm\n",
    );
    let [open, closed] = &run.traces;
    for (i, &d) in desired.iter().enumerate() {
        push_fixed(&mut out, i as f64 / hz, 6);
        out.push(b',');
        push_fixed(&mut out, d, 4);
        for t in [open, closed] {
            out.push(b',');
            push_fixed(&mut out, t.actual_deg[i], 4);
            out.push(b',');
            push_fixed(&mut out, t.sensed_deg[i], 4);
            out.push(b',');
            push_fixed(&mut out, t.stroke_mm[i], 6);
        }
        out.push(b'\n');
    }
    out
}

/// The report on a page of its own.
pub fn page(control: &Control, run: &ControlRun) -> Page {
    let mut page = Page::new(format!(
        "Closed-loop control of {} (Section IV-C)",
        control.design.file.name
    ));
    add_section(&mut page, control, run, Placement::ALONE);
    page
}

/// The whole section: what ran, the warnings, Table VI against the paper, then
/// [`add_details`].
pub fn add_section(page: &mut Page, control: &Control, run: &ControlRun, at: Placement<'_>) {
    let sc = &control.desired.scenario;
    let n = control.desired.angle_deg.len();
    let duration_s = n as f64 / sc.sample_hz;
    page.text(format!(
        "The desired angle is {}. Open loop commands the stroke θ_d/m_t; closed loop adds the \
         runtime PID's correction on θ_d − θ_sensed, where θ_sensed is the runtime estimator \
         reading the simulated sensor voltage. Both schemes run on the same simulated bench \
         with the same seed, so they see the same noise. {} samples, {} s at {} Hz, seed {}.",
        control.desired.description, n, duration_s, sc.sample_hz, sc.seed
    ));
    for w in control.warnings.iter().chain(&run.warnings) {
        page.text(format!("Warning: {w}."));
    }
    page.heading(at.titled("Table VI: RMSE of each scheme"));
    let mut t = Table::new([
        "RMSE (°)",
        "open loop",
        "closed loop",
        "paper: open loop",
        "paper: closed loop",
    ]);
    let [mo, mc] = &run.metrics;
    let [po, pc] = PAPER_TABLE_VI;
    let rows = [
        (
            "sensed vs actual",
            mo.sensed_vs_actual_rmse_deg,
            mc.sensed_vs_actual_rmse_deg,
            po.0,
            pc.0,
        ),
        (
            "actual vs desired",
            mo.actual_vs_desired_rmse_deg,
            mc.actual_vs_desired_rmse_deg,
            po.1,
            pc.1,
        ),
        (
            "sensed vs desired",
            mo.sensed_vs_desired_rmse_deg,
            mc.sensed_vs_desired_rmse_deg,
            po.2,
            pc.2,
        ),
    ];
    for (name, o, c, p_o, p_c) in rows {
        t.row([
            name.to_string(),
            format!("{o:.2}"),
            format!("{c:.2}"),
            format!("{p_o:.2}"),
            format!("{p_c:.2}"),
        ]);
    }
    t.row([
        "max |actual − desired|".to_string(),
        format!("{:.2}", mo.max_abs_actual_error_deg),
        format!("{:.2}", mc.max_abs_actual_error_deg),
        "—".into(),
        "—".into(),
    ]);
    page.table(t);
    page.text(
        "Actual is the angle the simulated EM tracker records (the paper's ground truth); \
         sensed is the estimator's output. The paper's numbers are for its Joint D on the real \
         bench; the simulator's effect sizes (relaxation, backlash, noise) are illustrative \
         unless the scenario sets measured ones, so only the pattern is comparable: closed loop \
         moves the actual angle towards the sensed one and the sensed one towards the desired.",
    );
    add_details(page, control, run, at);
}

/// The setup, Fig. 10 for both schemes, the tracking error and the stroke: the part of the
/// section that a page with its own Table VI (the reproduction's) shows too.
pub fn add_details(page: &mut Page, control: &Control, run: &ControlRun, at: Placement<'_>) {
    let hz = control.desired.scenario.sample_hz;
    let n = control.desired.angle_deg.len();
    let duration_s = n as f64 / hz;
    page.heading(at.titled("Setup"));
    for line in setup_lines(control, run) {
        page.text(line);
    }
    page.heading(at.titled("Fig. 10: desired, actual and sensed angle"));
    let window_s = duration_s.min(WINDOW_S);
    let window = ((window_s * hz).round() as usize).clamp(1, n.max(1));
    let detail = if window < n {
        format!("the first {window_s} s of {duration_s} s")
    } else {
        format!("the whole {duration_s} s")
    };
    for (letter, trace) in ["a", "b"].iter().zip(&run.traces) {
        let chart = angle_chart(control, trace, window);
        page.figure(
            at.figure_name(&format!(
                "fig10{letter}-{}",
                trace.scheme.key().replace('_', "-")
            )),
            chart,
            format!(
                "({letter}) {}: desired, actual (EM tracker) and sensed (estimator) angle, {detail}.",
                trace.scheme.title()
            ),
        );
    }
    page.heading(at.titled("Tracking error and stroke over the whole run"));
    page.figure(
        at.figure_name("tracking-error"),
        error_chart(control, run),
        "True angle − desired angle of both schemes over the whole run (the simulator's true \
         angle, without the tracker's noise, so that the drift is visible): open loop drifts with \
         the plant's relaxation and backlash, which the closed loop's integral removes.",
    );
    page.figure(
        at.figure_name("stroke"),
        stroke_chart(control, run, window),
        format!("Commanded tendon stroke of both schemes, {detail}."),
    );
}

/// The page's files plus `control.csv`, names relative to the output folder.
///
/// # Errors
/// [`ChartError`] when a figure cannot be drawn.
pub fn files(control: &Control, run: &ControlRun) -> Result<Vec<(String, Vec<u8>)>, ChartError> {
    let mut files = page(control, run).files()?;
    files.push((CSV_FILE.to_string(), csv_bytes(control, run)));
    Ok(files)
}

fn times(hz: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| i as f64 / hz).collect()
}

fn angle_chart(control: &Control, trace: &super::Trace, window: usize) -> Chart {
    let hz = control.desired.scenario.sample_hz;
    let t = times(hz, window);
    let d = &control.desired.angle_deg[..window];
    Chart::new(trace.scheme.title(), "time (s)", "angle (°)")
        .with(Series::line(
            "actual",
            Series::zip(&t, &trace.actual_deg[..window]),
            ACTUAL,
        ))
        .with(Series::line(
            "sensed",
            Series::zip(&t, &trace.sensed_deg[..window]),
            SENSED,
        ))
        .with(Series::line("desired", Series::zip(&t, d), DESIRED))
}

fn error_chart(control: &Control, run: &ControlRun) -> Chart {
    let hz = control.desired.scenario.sample_hz;
    let d = &control.desired.angle_deg;
    let mut chart = Chart::new("Tracking error", "time (s)", "true angle − desired (°)");
    for (trace, color) in run.traces.iter().zip([PALETTE[3], PALETTE[2]]) {
        let points = trace
            .true_deg
            .iter()
            .zip(d)
            .enumerate()
            .map(|(i, (a, d))| (i as f64 / hz, a - d))
            .collect();
        chart.push(Series::line(trace.scheme.title(), points, color));
    }
    chart
}

fn stroke_chart(control: &Control, run: &ControlRun, window: usize) -> Chart {
    let t = times(control.desired.scenario.sample_hz, window);
    let mut chart = Chart::new("Tendon stroke", "time (s)", "stroke (mm)");
    for (trace, color) in run.traces.iter().zip([PALETTE[3], PALETTE[2]]) {
        chart.push(Series::line(
            trace.scheme.title(),
            Series::zip(&t, &trace.stroke_mm[..window]),
            color,
        ));
    }
    chart
}

/// The setup as "setting: value" paragraphs (long values read badly in a right-aligned table).
fn setup_lines(control: &Control, run: &ControlRun) -> Vec<String> {
    let sc = &control.desired.scenario;
    let g = &control.gains;
    let mut lines = Vec::new();
    let mut row = |k: &str, v: String| lines.push(format!("{k}: {v}."));
    row("Design", control.design.file.name.clone());
    row("Bench effects", effects(sc));
    row(
        "Feed-forward m_t",
        format!(
            "{} °/mm ({})",
            control.mt_deg_per_mm,
            match control.mt_source {
                MtSource::PlantGain => "the scenario's nominal plant gain",
                MtSource::Given => "given",
            }
        ),
    );
    row(
        "PID gains",
        format!(
            "K_p = {} mm/°, K_i = {} mm/(°·s), K_d = {} mm·s/° (derivative on the sensed angle)",
            g.kp_mm_per_deg, g.ki_mm_per_deg_s, g.kd_mm_s_per_deg
        ),
    );
    row(
        "PID correction limits",
        format!(
            "±{:.3} mm, clamping anti-windup, Δt = {} s",
            control.pid.output_max, control.pid.dt_s
        ),
    );
    row("Estimator", estimator_summary(control));
    for trace in &run.traces {
        let m = if trace.scheme == Scheme::OpenLoop {
            &run.metrics[0]
        } else {
            &run.metrics[1]
        };
        row(
            &format!("{}, held / saturated samples", trace.scheme.title()),
            format!("{} / {}", m.held_samples, m.saturated_samples),
        );
    }
    lines
}

fn estimator_summary(control: &Control) -> String {
    use dlw_estimator::{FilterConfig, ModelConfig};
    let c = &control.config;
    let model = |m: &ModelConfig| match m {
        ModelConfig::Linear(l) => {
            format!("linear, GF {}, R₀ {} kΩ", l.gauge_factor, l.r0_ohm / 1e3)
        }
        ModelConfig::Pi(p) => format!("PI, N = {}", p.weights.len()),
        ModelConfig::ContinuousPi(p) => format!("continuous PI, N = {}", p.weights.len()),
    };
    let filter = |f: &FilterConfig| match f {
        FilterConfig::None => "none".to_string(),
        FilterConfig::MovingAverage { samples } => format!("moving average of {samples} samples"),
        FilterConfig::LowPass {
            time_constant_samples,
        } => format!("low-pass, τ = {time_constant_samples} samples"),
    };
    let mut s = format!("sensor 1: {}", model(&c.sensor.model));
    if let Some(second) = &c.second_sensor {
        s.push_str(&format!("; sensor 2: {} (Eq. 7)", model(&second.model)));
    }
    s.push_str(&format!(
        "; input filter {}, output filter {}",
        filter(&c.input_filter),
        filter(&c.output_filter)
    ));
    s
}

/// The scenario's switched-on effects, in words.
fn effects(sc: &Scenario) -> String {
    let p = &sc.plant;
    let mut on = vec![format!("plant gain {} °/mm", p.gain_deg_per_mm)];
    if p.relaxation.enabled {
        on.push(format!(
            "relaxation {} % (τ {} s)",
            p.relaxation.fraction * 100.0,
            p.relaxation.tau_s
        ));
    }
    if p.backlash.enabled {
        on.push(format!("backlash {} mm", p.backlash.width_mm));
    }
    if p.notch_limit.enabled {
        on.push("notch limit".into());
    }
    for (i, s) in sc.sensors().enumerate() {
        let mut fx = vec![format!("{:?}", s.model).to_lowercase()];
        for (name, enabled) in [
            ("saturation", s.saturation.enabled),
            ("drift", s.drift.enabled),
            ("rate dependence", s.rate.enabled),
            ("creep", s.creep.enabled),
        ] {
            if enabled {
                fx.push(name.into());
            }
        }
        on.push(format!("sensor {}: {}", i + 1, fx.join(", ")));
    }
    if sc.adc.enabled {
        on.push(format!(
            "ADC {} bits, {} mV noise",
            sc.adc.bits,
            sc.adc.noise_v * 1e3
        ));
    }
    if sc.tracker.enabled {
        on.push(format!("tracker noise {}°", sc.tracker.noise_deg));
    }
    on.join("; ")
}
