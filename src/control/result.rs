//! A control simulation's result as one [`Analysis`]: what `dlw control --json` prints, the
//! terminal summary, and the report section.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::{report, Control, ControlRun, Gains, MtSource, Scheme, SchemeMetrics, PAPER_TABLE_VI};
use crate::analysis::{Analysis, Placement};
use crate::report::{ChartError, Page, PAGE_FILE};

/// Both schemes of a control simulation with its setup. Serializes to exactly what
/// `dlw control --json` prints; the keys are part of the interface.
#[derive(Debug, Clone, Serialize)]
pub struct ControlResult {
    /// The design's name.
    pub design: String,
    /// Samples per scheme.
    pub samples: usize,
    /// `samples / sample_hz` (s).
    pub duration_s: f64,
    /// The bench's sample rate (Hz).
    pub sample_hz: f64,
    /// The bench's seed (both schemes run from it).
    pub seed: u64,
    /// Where the desired angle came from, in words.
    pub desired: String,
    /// Feed-forward slope (°/mm).
    pub mt_deg_per_mm: f64,
    /// Where `m_t` came from.
    pub mt_source: MtSource,
    /// The PID gains.
    pub gains: Gains,
    /// The PID correction's limit (± mm).
    pub correction_limit_mm: f64,
    /// Table VI's open-loop row, and a few more numbers.
    pub open_loop: SchemeMetrics,
    /// Table VI's closed-loop row, and a few more numbers.
    pub closed_loop: SchemeMetrics,
    /// The paper's Table VI.
    pub paper: PaperTableVi,
    /// `report.html`, once the caller has written it ([`ControlResult::written_to`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub report: Option<PathBuf>,
    /// `control.csv`, once the caller has written it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub csv: Option<PathBuf>,
    /// Things the user should know: the setup's warnings, then the run's.
    pub warnings: Vec<String>,
    /// The validated simulation (desired angle, scenario, estimator config, PID).
    #[serde(skip)]
    pub control: Control,
    /// Both schemes' traces.
    #[serde(skip)]
    pub run: ControlRun,
}

/// The paper's Table VI ("Joint Control Results", Joint D).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PaperTableVi {
    /// Open loop.
    pub open_loop: PaperRow,
    /// Closed loop.
    pub closed_loop: PaperRow,
}

/// One row of the paper's Table VI (°).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PaperRow {
    /// RMSE of sensed − actual (°).
    pub sensed_vs_actual_rmse_deg: f64,
    /// RMSE of actual − desired (°).
    pub actual_vs_desired_rmse_deg: f64,
    /// RMSE of sensed − desired (°).
    pub sensed_vs_desired_rmse_deg: f64,
}

impl PaperTableVi {
    /// [`PAPER_TABLE_VI`] with named columns.
    pub fn paper() -> Self {
        let row = |(a, b, c): (f64, f64, f64)| PaperRow {
            sensed_vs_actual_rmse_deg: a,
            actual_vs_desired_rmse_deg: b,
            sensed_vs_desired_rmse_deg: c,
        };
        Self {
            open_loop: row(PAPER_TABLE_VI[0]),
            closed_loop: row(PAPER_TABLE_VI[1]),
        }
    }
}

impl ControlResult {
    /// Gathers the simulation `control` and its `run`; no output paths yet.
    pub fn new(control: Control, run: ControlRun) -> Self {
        let sc = &control.desired.scenario;
        let samples = control.desired.angle_deg.len();
        Self {
            design: control.design.file.name.clone(),
            samples,
            duration_s: samples as f64 / sc.sample_hz,
            sample_hz: sc.sample_hz,
            seed: sc.seed,
            desired: control.desired.description.clone(),
            mt_deg_per_mm: control.mt_deg_per_mm,
            mt_source: control.mt_source,
            gains: control.gains,
            correction_limit_mm: control.pid.output_max,
            open_loop: run.metrics[0],
            closed_loop: run.metrics[1],
            paper: PaperTableVi::paper(),
            report: None,
            csv: None,
            warnings: control
                .warnings
                .iter()
                .chain(&run.warnings)
                .cloned()
                .collect(),
            control,
            run,
        }
    }

    /// The report on a page of its own, its figures and `control.csv`, names relative to the
    /// output folder.
    ///
    /// # Errors
    /// [`ChartError`] when a figure cannot be drawn.
    pub fn files(&self) -> Result<Vec<(String, Vec<u8>)>, ChartError> {
        report::files(&self.control, &self.run)
    }

    /// Records that [`ControlResult::files`] were written into `dir`.
    pub fn written_to(&mut self, dir: &Path) {
        self.report = Some(dir.join(PAGE_FILE));
        self.csv = Some(dir.join(report::CSV_FILE));
    }
}

impl Analysis for ControlResult {
    /// The setup, Table VI against the paper, held samples and the files written. The warnings
    /// are not in it: the command prints them to standard error.
    fn summary(&self) -> String {
        let mut out = String::new();
        let g = &self.gains;
        let _ = writeln!(
            out,
            "{}: {} samples ({} s at {} Hz), seed {}, m_t {} °/mm, gains kp {} mm/°, ki {} mm/(°·s), kd {} mm·s/°",
            self.design,
            self.samples,
            self.duration_s,
            self.sample_hz,
            self.seed,
            self.mt_deg_per_mm,
            g.kp_mm_per_deg,
            g.ki_mm_per_deg_s,
            g.kd_mm_s_per_deg
        );
        let _ = writeln!(
            out,
            "  RMSE (°)             open loop   closed loop   (paper: open, closed)"
        );
        let names = [
            "sensed vs actual ",
            "actual vs desired",
            "sensed vs desired",
        ];
        let (open, closed) = (self.open_loop.table_vi(), self.closed_loop.table_vi());
        let paper = PAPER_TABLE_VI.map(|(a, b, c)| [a, b, c]);
        for (k, name) in names.iter().enumerate() {
            let _ = writeln!(
                out,
                "  {name}    {:>9.2}   {:>11.2}   ({:.2}, {:.2})",
                open[k], closed[k], paper[0][k], paper[1][k]
            );
        }
        for (scheme, m) in Scheme::BOTH
            .iter()
            .zip([&self.open_loop, &self.closed_loop])
        {
            if m.held_samples > 0 {
                let _ = writeln!(out, "  {}: {} held samples", scheme.title(), m.held_samples);
            }
        }
        if let Some(report) = &self.report {
            let _ = writeln!(out, "  report               {}", report.display());
        }
        if let Some(csv) = &self.csv {
            let _ = writeln!(out, "  samples              {}", csv.display());
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: Placement<'_>) {
        report::add_section(page, &self.control, &self.run, at);
    }
}
