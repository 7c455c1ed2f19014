//! A robot control simulation's result: what `dlw control --design ROBOT --json` prints, the
//! terminal summary, `control.csv` with every joint's columns, and `report.html` with each
//! joint's desired, actual and sensed angle.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::report::{CSV_FILE, WINDOW_S};
use super::robot::{RobotControl, RobotControlRun};
use super::{Gains, MtSource, Scheme, SchemeMetrics};
use crate::fixed::push_fixed;
use crate::report::{Chart, ChartError, Page, Series, Table, PAGE_FILE, PALETTE};

const DESIRED: (u8, u8, u8) = (40, 40, 40);
const ACTUAL: (u8, u8, u8) = PALETTE[0];
const SENSED: (u8, u8, u8) = PALETTE[1];
const OPEN: (u8, u8, u8) = PALETTE[2];

/// One joint's result. The JSON keys are part of the interface.
#[derive(Debug, Clone, Serialize)]
pub struct JointControl {
    /// 1-based joint.
    pub joint: usize,
    /// Its design's name.
    pub design: String,
    /// Its bench's seed.
    pub seed: u64,
    /// Where its desired angle came from, in words.
    pub desired: String,
    /// Its feed-forward slope (°/mm).
    pub mt_deg_per_mm: f64,
    /// Its PID correction's limit (± mm).
    pub correction_limit_mm: f64,
    /// Open loop: `actual_vs_desired_rmse_deg` and `max_abs_actual_error_deg` are its tracking
    /// RMSE and largest error.
    pub open_loop: SchemeMetrics,
    /// Closed loop, the same keys.
    pub closed_loop: SchemeMetrics,
}

/// A robot's control simulation. Serializes to exactly what `dlw control --json` prints for a
/// robot; the keys are part of the interface.
#[derive(Debug, Clone, Serialize)]
pub struct RobotControlResult {
    /// The robot's name.
    pub robot: String,
    /// Samples per scheme.
    pub samples: usize,
    /// `samples / sample_hz` (s).
    pub duration_s: f64,
    /// The bench's sample rate (Hz).
    pub sample_hz: f64,
    /// The tendon coupling (`none`, `york-swaney`).
    pub coupling: &'static str,
    /// The PID gains, every joint's.
    pub gains: Gains,
    /// Where each joint's `m_t` came from.
    pub mt_source: MtSource,
    /// Each joint's result, joint 1 (distal) first.
    pub joints: Vec<JointControl>,
    /// `report.html`, once written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub report: Option<PathBuf>,
    /// `control.csv`, once written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub csv: Option<PathBuf>,
    /// Things the user should know: the setup's warnings, then the run's.
    pub warnings: Vec<String>,
    /// The validated simulation.
    #[serde(skip)]
    pub control: RobotControl,
    /// Both schemes' traces.
    #[serde(skip)]
    pub run: RobotControlRun,
}

impl RobotControlResult {
    /// Gathers `control` and its `run`.
    pub fn new(control: RobotControl, run: RobotControlRun) -> Self {
        let joints = control
            .joints
            .iter()
            .zip(&run.metrics)
            .enumerate()
            .map(|(j, (c, m))| JointControl {
                joint: j + 1,
                design: c.design.file.name.clone(),
                seed: c.desired.scenario.seed,
                desired: c.desired.description.clone(),
                mt_deg_per_mm: c.mt_deg_per_mm,
                correction_limit_mm: c.pid.output_max,
                open_loop: m[0],
                closed_loop: m[1],
            })
            .collect();
        let mut warnings = control.warnings.clone();
        warnings.extend(run.warnings.iter().cloned());
        Self {
            robot: control.robot.clone(),
            samples: control.samples(),
            duration_s: control.samples() as f64 / control.sample_hz(),
            sample_hz: control.sample_hz(),
            coupling: control.coupling.name(),
            gains: control.gains,
            mt_source: control.mt_source,
            joints,
            report: None,
            csv: None,
            warnings,
            control,
            run,
        }
    }

    /// Records where `report.html` and `control.csv` were written.
    pub fn written_to(&mut self, dir: &Path) {
        self.report = Some(dir.join(PAGE_FILE));
        self.csv = Some(dir.join(CSV_FILE));
    }

    /// The terminal summary: one line per joint and scheme.
    pub fn summary(&self) -> String {
        let mut out = format!(
            "{}: {} samples ({:.1} s at {} Hz), {} joints, tendon coupling {}\n",
            self.robot,
            self.samples,
            self.duration_s,
            self.sample_hz,
            self.joints.len(),
            self.coupling
        );
        for j in &self.joints {
            for (name, m) in [("open loop", &j.open_loop), ("closed loop", &j.closed_loop)] {
                let _ = writeln!(
                    out,
                    "  joint {} {name:<12} tracking RMSE {:.3}°, max |error| {:.3}°, sensed vs actual RMSE {:.3}°",
                    j.joint,
                    m.actual_vs_desired_rmse_deg,
                    m.max_abs_actual_error_deg,
                    m.sensed_vs_actual_rmse_deg
                );
            }
        }
        if let Some(r) = &self.report {
            let _ = writeln!(out, "  report              {}", r.display());
        }
        if let Some(c) = &self.csv {
            let _ = writeln!(out, "  csv                 {}", c.display());
        }
        out
    }

    /// `control.csv`: `time_s`, `desiredK_deg` per joint, then per scheme (prefix `open_`,
    /// `closed_`) and joint `angleK_deg` (the tracker's), `sensedK_deg` and `strokeK_mm`.
    pub fn csv_bytes(&self) -> Vec<u8> {
        let n = self.joints.len();
        let hz = self.sample_hz;
        let mut out = Vec::with_capacity(self.samples * (16 + n * 64) + 256);
        let mut header = "time_s".to_string();
        for k in 1..=n {
            let _ = write!(header, ",desired{k}_deg");
        }
        for prefix in ["open", "closed"] {
            for k in 1..=n {
                let _ = write!(
                    header,
                    ",{prefix}_angle{k}_deg,{prefix}_sensed{k}_deg,{prefix}_stroke{k}_mm"
                );
            }
        }
        header.push('\n');
        out.extend_from_slice(header.as_bytes());
        for i in 0..self.samples {
            push_fixed(&mut out, i as f64 / hz, 6);
            for c in &self.control.joints {
                out.push(b',');
                push_fixed(&mut out, c.desired.angle_deg[i], 4);
            }
            for trace in &self.run.traces {
                for t in &trace.joints {
                    out.push(b',');
                    push_fixed(&mut out, t.actual_deg[i], 4);
                    out.push(b',');
                    push_fixed(&mut out, t.sensed_deg[i], 4);
                    out.push(b',');
                    push_fixed(&mut out, t.stroke_mm[i], 6);
                }
            }
            out.push(b'\n');
        }
        out
    }

    /// The report: each joint's metrics, then per joint its closed and open loop over the
    /// first [`WINDOW_S`] seconds.
    pub fn page(&self) -> Page {
        let mut page = Page::new(format!("Closed-loop control of {}", self.robot));
        page.text(format!(
            "{} joints, each on its estimated angle (the robot estimator undoes the config's crosstalk); tendon coupling {}; PID K_p {} mm/°, K_i {} mm/(°·s), K_d {} mm·s/° on every joint; {} samples ({:.1} s at {} Hz).",
            self.joints.len(),
            self.coupling,
            self.gains.kp_mm_per_deg,
            self.gains.ki_mm_per_deg_s,
            self.gains.kd_mm_s_per_deg,
            self.samples,
            self.duration_s,
            self.sample_hz
        ));
        for w in &self.warnings {
            page.text(format!("Warning: {w}"));
        }
        let mut table = Table::new([
            "joint",
            "scheme",
            "actual vs desired RMSE (°)",
            "max |actual − desired| (°)",
            "sensed vs actual RMSE (°)",
            "true vs desired RMSE (°)",
        ]);
        for j in &self.joints {
            for (scheme, m) in [
                (Scheme::OpenLoop, &j.open_loop),
                (Scheme::ClosedLoop, &j.closed_loop),
            ] {
                table.row([
                    format!("{} ({})", j.joint, j.design),
                    scheme.title().to_string(),
                    format!("{:.3}", m.actual_vs_desired_rmse_deg),
                    format!("{:.3}", m.max_abs_actual_error_deg),
                    format!("{:.3}", m.sensed_vs_actual_rmse_deg),
                    format!("{:.3}", m.true_vs_desired_rmse_deg),
                ]);
            }
        }
        page.table(table);
        let window = ((WINDOW_S * self.sample_hz) as usize).clamp(1, self.samples.max(1));
        let time_s: Vec<f64> = (0..window).map(|i| i as f64 / self.sample_hz).collect();
        let [open, closed] = &self.run.traces;
        for (j, c) in self.control.joints.iter().enumerate() {
            let mut chart = Chart::new(
                format!("Joint {} ({})", j + 1, c.design.file.name),
                "time (s)",
                "angle (°)",
            );
            let w = |v: &[f64]| Series::zip(&time_s, &v[..window]);
            chart.push(Series::line("desired", w(&c.desired.angle_deg), DESIRED));
            chart.push(Series::line(
                "open loop actual",
                w(&open.joints[j].actual_deg),
                OPEN,
            ));
            chart.push(Series::line(
                "closed loop actual",
                w(&closed.joints[j].actual_deg),
                ACTUAL,
            ));
            chart.push(Series::line(
                "closed loop sensed",
                w(&closed.joints[j].sensed_deg),
                SENSED,
            ));
            let m = &self.joints[j];
            page.figure(
                format!("joint-{}", j + 1),
                chart,
                format!(
                    "joint {}: closed loop tracks with RMSE {:.3}° (max {:.3}°), open loop {:.3}° (max {:.3}°); the first {:.1} s",
                    j + 1,
                    m.closed_loop.actual_vs_desired_rmse_deg,
                    m.closed_loop.max_abs_actual_error_deg,
                    m.open_loop.actual_vs_desired_rmse_deg,
                    m.open_loop.max_abs_actual_error_deg,
                    window as f64 / self.sample_hz
                ),
            );
        }
        page
    }

    /// The page's files plus `control.csv`, names relative to the output folder.
    ///
    /// # Errors
    /// [`ChartError`] when a figure cannot be drawn.
    pub fn files(&self) -> Result<Vec<(String, Vec<u8>)>, ChartError> {
        let mut files = self.page().files()?;
        files.push((CSV_FILE.to_string(), self.csv_bytes()));
        Ok(files)
    }
}
