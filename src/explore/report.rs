//! What `dlw explore` writes: `designs.csv` (every feasible candidate), `front.csv`, the best
//! `K` as design files, and `report.html` with scatter plots of the objectives, the front
//! highlighted and the paper's Joints A-D marked. Also the `--json` summary.

use std::fmt::Write as _;

use serde::Serialize;

use crate::design::DesignFile;
use crate::report::{Chart, ChartError, Page, Series, Table, PALETTE};

use super::{evaluate, Candidate, Exploration, Metric, Params, Screen};

/// The paper's joints, marked on the plots (B and D share a design).
const PAPER_JOINTS: [(&str, &str); 3] = [
    ("Joint A", include_str!("../../designs/joint-a.toml")),
    ("Joint B/D", include_str!("../../designs/joint-b.toml")),
    ("Joint C", include_str!("../../designs/joint-c.toml")),
];
/// Rows of the front shown in the report's table.
const REPORT_TABLE_ROWS: usize = 25;
/// Grey for all feasible candidates.
const FEASIBLE_GREY: (u8, u8, u8) = (170, 170, 170);

/// An output folder's files: names relative to the folder, and their bytes.
pub type Files = Vec<(String, Vec<u8>)>;

/// One candidate as written in CSV and JSON.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Index in the grid.
    pub index: u64,
    /// Tube id.
    pub tube: String,
    /// `uan` or `bsn`.
    pub style: dlw_geometry::NotchStyle,
    /// Sensors (1 for UAN, 2 for BSN).
    pub sensor_count: u32,
    /// `r_o` (mm).
    pub outer_radius_mm: f64,
    /// `r_i` (mm).
    pub inner_radius_mm: f64,
    /// `s_n` (mm).
    pub notch_arc_mm: f64,
    /// `s_s` (mm).
    pub sensor_arc_mm: f64,
    /// `N`.
    pub notch_count: u32,
    /// `h` (mm).
    pub notch_width_mm: f64,
    /// `c` (mm).
    pub notch_spacing_mm: f64,
    /// `L` (mm).
    pub joint_length_mm: f64,
    /// Ω/°.
    pub sensitivity_ohm_per_deg: f64,
    /// °.
    pub range_deg: f64,
    /// What ends the range.
    pub range_limited_by: dlw_geometry::RangeLimit,
    /// N/°.
    pub tendon_force_per_deg_n: f64,
    /// mm/°.
    pub stroke_per_deg_mm: f64,
    /// °.
    pub closing_deg: f64,
    /// °.
    pub material_limit_deg: f64,
    /// °.
    pub saturation_limit_deg: f64,
    /// The design file written for it, if it is among the best `K`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// The twin's predicted accuracy, when the spec asks for it (front candidates only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub predicted: Option<super::Predicted>,
}

impl Row {
    fn of(c: &Candidate, x: &Exploration, file: Option<String>) -> Self {
        let (p, m) = (&c.params, &c.metrics);
        Self {
            index: c.index,
            tube: x.grid.tubes[p.tube].id.clone(),
            style: p.style,
            sensor_count: p.style.sensor_count(),
            outer_radius_mm: p.outer_radius_mm,
            inner_radius_mm: p.inner_radius_mm,
            notch_arc_mm: p.notch_arc_mm,
            sensor_arc_mm: p.sensor_arc_mm,
            notch_count: p.notch_count,
            notch_width_mm: p.notch_width_mm,
            notch_spacing_mm: p.notch_spacing_mm,
            joint_length_mm: p.joint_length_mm(),
            sensitivity_ohm_per_deg: m.sensitivity_ohm_per_deg,
            range_deg: m.range_deg,
            range_limited_by: m.range_limited_by,
            tendon_force_per_deg_n: m.tendon_force_per_deg_n,
            stroke_per_deg_mm: m.stroke_per_deg_mm,
            closing_deg: m.closing_deg,
            material_limit_deg: m.material_limit_deg,
            saturation_limit_deg: m.saturation_limit_deg,
            file,
            predicted: m.predicted,
        }
    }
}

/// The `--json` document: the counts and the front.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExploreSummary {
    /// Candidates in the grid.
    pub candidates: u64,
    /// Refused by the geometry.
    pub geometry_refused: u64,
    /// Failing a constraint of the spec.
    pub failed_constraints: u64,
    /// Meeting the constraints but breaking a design rule.
    pub failed_rules: u64,
    /// Feasible.
    pub feasible: u64,
    /// The Pareto front, best first by the first objective.
    pub front: Vec<Row>,
}

const CSV_HEADER: &str = "index,tube,style,sensor_count,outer_radius_mm,inner_radius_mm,notch_arc_mm,sensor_arc_mm,notch_count,notch_width_mm,notch_spacing_mm,joint_length_mm,sensitivity_ohm_per_deg,range_deg,range_limited_by,tendon_force_per_deg_n,stroke_per_deg_mm,closing_deg,material_limit_deg,saturation_limit_deg,on_front\n";

fn csv_line(out: &mut String, r: &Row, on_front: bool) {
    let style = match r.style {
        dlw_geometry::NotchStyle::Uan => "uan",
        dlw_geometry::NotchStyle::Bsn => "bsn",
    };
    let limit = match r.range_limited_by {
        dlw_geometry::RangeLimit::NotchClosing => "notch_closing",
        dlw_geometry::RangeLimit::Material => "material",
        dlw_geometry::RangeLimit::SensorSaturation => "sensor_saturation",
    };
    let _ = writeln!(
        out,
        "{},{},{style},{},{},{},{},{},{},{},{},{:.6},{:.6},{:.4},{limit},{:.6e},{:.6e},{:.4},{:.4},{:.4},{}",
        r.index,
        r.tube,
        r.sensor_count,
        r.outer_radius_mm,
        r.inner_radius_mm,
        r.notch_arc_mm,
        r.sensor_arc_mm,
        r.notch_count,
        r.notch_width_mm,
        r.notch_spacing_mm,
        r.joint_length_mm,
        r.sensitivity_ohm_per_deg,
        r.range_deg,
        r.tendon_force_per_deg_n,
        r.stroke_per_deg_mm,
        r.closing_deg,
        r.material_limit_deg,
        r.saturation_limit_deg,
        u8::from(on_front)
    );
}

/// The output folder's files and the summary: `designs.csv`, `front.csv`, `best-<k>.toml` for
/// the best `top_k`, `report.html` and its SVGs.
///
/// # Errors
/// A chart that cannot be drawn, or a design that cannot be written as TOML.
pub fn files(
    x: &Exploration,
    screen: &Screen,
    feasible: &[Candidate],
    front: &[usize],
    top_k: usize,
) -> Result<(Files, ExploreSummary), ChartError> {
    let best = x.best(feasible, front, top_k);
    let mut files = Vec::new();
    let mut names = vec![None; feasible.len()];
    for (rank, &i) in best.iter().enumerate() {
        let name = format!("best-{}.toml", rank + 1);
        files.push((
            name.clone(),
            design_toml(x, &feasible[i], rank + 1).into_bytes(),
        ));
        names[i] = Some(name);
    }
    let mut on_front = vec![false; feasible.len()];
    for &i in front {
        on_front[i] = true;
    }
    let mut all = String::from(CSV_HEADER);
    for (i, c) in feasible.iter().enumerate() {
        csv_line(&mut all, &Row::of(c, x, names[i].clone()), on_front[i]);
    }
    let ordered = front_order(x, feasible, front);
    let front_rows: Vec<Row> = ordered
        .iter()
        .map(|&i| Row::of(&feasible[i], x, names[i].clone()))
        .collect();
    let mut front_csv = String::from(CSV_HEADER);
    for r in &front_rows {
        csv_line(&mut front_csv, r, true);
    }
    files.push(("designs.csv".into(), all.into_bytes()));
    files.push(("front.csv".into(), front_csv.into_bytes()));
    let summary = ExploreSummary {
        candidates: screen.evaluated,
        geometry_refused: screen.geometry_refused,
        failed_constraints: screen.evaluated
            - screen.geometry_refused
            - screen.survivors.len() as u64,
        failed_rules: (screen.survivors.len() - feasible.len()) as u64,
        feasible: feasible.len() as u64,
        front: front_rows,
    };
    let page = page(x, &summary, feasible, front)?;
    files.extend(page.files()?);
    Ok((files, summary))
}

/// The front in the order `best` uses (all of it).
fn front_order(x: &Exploration, feasible: &[Candidate], front: &[usize]) -> Vec<usize> {
    x.best(feasible, front, front.len())
}

/// A written design: the base with the candidate's parameters, and a header saying where it
/// came from.
fn design_toml(x: &Exploration, c: &Candidate, rank: usize) -> String {
    let name = format!("{} explore {rank}", x.base.name);
    let file: DesignFile = c.params.apply(&x.base, name);
    let m = &c.metrics;
    let header = format!(
        "# Written by dlw explore from {} (candidate {} of the grid, rank {rank} on the front).\n\
         # Tube {}; sensitivity {:.4} Ω/° at GF = {} and R0 = {} Ω; usable range {:.2}° (limited by {});\n\
         # tendon force {:.5} N/°, stroke {:.5} mm/° (docs/mechanics.md, friction ignored).\n",
        x.spec_path.display(),
        c.index,
        x.grid.tubes[c.params.tube].id,
        m.sensitivity_ohm_per_deg,
        x.model.gauge_factor,
        x.model.r0_ohm,
        m.range_deg,
        m.range_limited_by.describe(),
        m.tendon_force_per_deg_n,
        m.stroke_per_deg_mm,
    );
    // Serializing a validated design file cannot fail (plain keys and values).
    header + &toml::to_string(&file).unwrap_or_default()
}

/// The paper's joints scored with the spec's model (feasible or not), as plot markers.
fn paper_points(x: &Exploration) -> Vec<(&'static str, super::DesignMetrics)> {
    PAPER_JOINTS
        .iter()
        .filter_map(|(label, text)| {
            let f = DesignFile::from_toml(text).ok()?;
            let p = Params {
                tube: 0,
                outer_radius_mm: f.outer_radius_mm,
                inner_radius_mm: f.inner_radius_mm,
                style: f.style,
                notch_arc_mm: f.notch_arc_mm,
                sensor_arc_mm: f.sensor_arc_mm,
                notch_count: f.notch_count,
                notch_width_mm: f.notch_width_mm,
                notch_spacing_mm: f.notch_spacing_mm,
            };
            let model = super::Model {
                tendon_offset_mm: None,
                ..x.model
            };
            evaluate(&p, &model).map(|(m, _)| (*label, m))
        })
        .collect()
}

/// The metric pairs to plot: every pair of objectives, or the one objective against the range
/// (or the sensitivity, when the range is the objective).
fn plot_pairs(x: &Exploration) -> Vec<(Metric, Metric)> {
    let metrics: Vec<Metric> = x.spec.objectives.signed().iter().map(|p| p.0).collect();
    if metrics.len() == 1 {
        let other = if metrics[0] == Metric::RangeDeg {
            Metric::SensitivityOhmPerDeg
        } else {
            Metric::RangeDeg
        };
        return vec![(other, metrics[0])];
    }
    let mut pairs = Vec::new();
    for i in 0..metrics.len() {
        for j in i + 1..metrics.len() {
            pairs.push((metrics[i], metrics[j]));
        }
    }
    pairs
}

fn page(
    x: &Exploration,
    s: &ExploreSummary,
    feasible: &[Candidate],
    front: &[usize],
) -> Result<Page, ChartError> {
    let mut page = Page::new(format!("dlw explore: {}", x.spec_path.display()));
    let objectives: Vec<String> = x
        .spec
        .objectives
        .signed()
        .iter()
        .map(|(m, sign)| {
            format!(
                "{} {}",
                if *sign > 0.0 { "maximize" } else { "minimize" },
                m.key()
            )
        })
        .collect();
    page.text(format!(
        "{} candidates from base design {:?}: {} refused by the geometry, {} failing a constraint, {} breaking a design rule; {} feasible, {} on the Pareto front of: {}. Sensitivity at GF = {} and R0 = {} Ω; mechanics from docs/mechanics.md (friction ignored).",
        s.candidates,
        x.base.name,
        s.geometry_refused,
        s.failed_constraints,
        s.failed_rules,
        s.feasible,
        front.len(),
        objectives.join(", "),
        x.model.gauge_factor,
        x.model.r0_ohm
    ));
    let paper = paper_points(x);
    page.heading("Objectives");
    for (k, (mx, my)) in plot_pairs(x).into_iter().enumerate() {
        page.figure(
            format!("scatter-{}", k + 1),
            scatter(feasible, front, &paper, mx, my),
            format!(
                "{} against {}: grey, every feasible candidate; blue, the Pareto front; the paper's joints (scored with the same model, feasible or not) as labelled markers.",
                my.key(),
                mx.key()
            ),
        );
    }
    if x.predicts() {
        predicted_section(&mut page, x, feasible, front, &paper);
    }
    page.heading("The front");
    let mut t = Table::new([
        "file",
        "tube",
        "style",
        "s_n (mm)",
        "s_s (mm)",
        "N",
        "h (mm)",
        "c (mm)",
        "Ω/°",
        "range (°)",
        "limited by",
        "N/°",
        "mm/°",
    ]);
    for r in s.front.iter().take(REPORT_TABLE_ROWS) {
        t.row([
            r.file.clone().unwrap_or_default(),
            r.tube.clone(),
            format!("{:?}", r.style).to_lowercase(),
            format!("{}", r.notch_arc_mm),
            format!("{}", r.sensor_arc_mm),
            r.notch_count.to_string(),
            format!("{}", r.notch_width_mm),
            format!("{}", r.notch_spacing_mm),
            format!("{:.2}", r.sensitivity_ohm_per_deg),
            format!("{:.1}", r.range_deg),
            r.range_limited_by.describe().to_string(),
            format!("{:.4}", r.tendon_force_per_deg_n),
            format!("{:.5}", r.stroke_per_deg_mm),
        ]);
    }
    page.table(t);
    page.heading("The paper's joints under this model");
    let mut t = Table::new(["joint", "Ω/°", "range (°)", "limited by", "N/°", "mm/°"]);
    for (label, m) in &paper {
        t.row([
            label.to_string(),
            format!("{:.2}", m.sensitivity_ohm_per_deg),
            format!("{:.1}", m.range_deg),
            m.range_limited_by.describe().to_string(),
            format!("{:.4}", m.tendon_force_per_deg_n),
            format!("{:.5}", m.stroke_per_deg_mm),
        ]);
    }
    page.table(t);
    Ok(page)
}

/// Table IV's measured RMSE of the paper's joints (the better of linear and PI), for the
/// predicted-accuracy plot: Joint A 1.76° (PI), B 2.65° (PI), C 5.25° (linear).
fn measured_deg(label: &str) -> Option<f64> {
    let i = match label {
        "Joint A" => 0,
        "Joint B/D" => 1,
        "Joint C" => 2,
        _ => return None,
    };
    let [linear, pi] = crate::reproduce::paper::TABLE_IV[i];
    Some(linear.min(pi))
}

/// The predicted accuracy: the front's predicted error against the sensitivity, the paper's
/// joints at their measured errors, and what the prediction cost.
fn predicted_section(
    page: &mut Page,
    x: &Exploration,
    feasible: &[Candidate],
    front: &[usize],
    paper: &[(&str, super::DesignMetrics)],
) {
    page.heading("Predicted accuracy");
    let predicted: Vec<&Candidate> = feasible
        .iter()
        .filter(|c| c.metrics.predicted.is_some())
        .collect();
    let failed = x.prediction_cost.map_or(0, |(n, _)| n) - predicted.len();
    if let Some((n, seconds)) = x.prediction_cost {
        page.text(format!(
            "The twin of the paper's bench (designs/scenarios/paper-bench.toml) simulated on each \
             of the {n} candidates of the grid's Pareto front: characterization, linear and PI fits \
             and the random pattern's estimation (Table IV), and the closed loop on Joint D's plant \
             (Table VI), every protocol once at the paper's timings and scaled by the twin's \
             full/short ratios. {:.1} s in all, {:.2} s per front candidate (wall clock, rayon). \
             {failed} candidates could not be simulated (predicted: cannot tell). The front below \
             is the Pareto front of these candidates on every objective.",
            seconds,
            seconds / n.max(1) as f64
        ));
    }
    let point = |c: &Candidate, f: fn(&super::Predicted) -> f64| {
        (
            c.metrics.sensitivity_ohm_per_deg,
            c.metrics.predicted.as_ref().map_or(f64::NAN, f),
        )
    };
    let mut chart = Chart::new(
        "predicted error vs sensitivity",
        Metric::SensitivityOhmPerDeg.label(),
        "angle RMSE (°)",
    );
    chart.push(Series::dots(
        "front: predicted, linear",
        predicted
            .iter()
            .map(|c| point(c, |p| p.linear_rmse_deg))
            .collect(),
        FEASIBLE_GREY,
    ));
    let mut pi = Series::dots(
        "front: predicted, PI",
        predicted
            .iter()
            .map(|c| point(c, |p| p.pi_rmse_deg))
            .collect(),
        PALETTE[0],
    );
    pi.style = crate::report::SeriesStyle::Dots(4);
    chart.push(pi);
    for (k, (label, m)) in paper.iter().enumerate() {
        if let Some(measured) = measured_deg(label) {
            let mut s = Series::dots(
                format!("{label}: measured (Table IV)"),
                vec![(m.sensitivity_ohm_per_deg, measured)],
                PALETTE[(k + 1) % PALETTE.len()],
            );
            s.style = crate::report::SeriesStyle::Dots(7);
            chart.push(s);
        }
    }
    page.figure(
        "predicted-accuracy",
        chart,
        "The twin's predicted angle RMSE of each front candidate (grey: linear model; blue: PI) \
         against its sensitivity under the spec's model; the paper's joints at the sensitivity of \
         the same model and the RMSE the paper measured (the better of linear and PI, Table IV).",
    );
    let mut t = Table::new([
        "index",
        "Ω/°",
        "borrowed sensor",
        "linear (°)",
        "PI (°)",
        "closed loop (°)",
    ]);
    let mut rows: Vec<&Candidate> = front
        .iter()
        .map(|&i| &feasible[i])
        .filter(|c| c.metrics.predicted.is_some())
        .collect();
    rows.sort_by(|a, b| {
        b.metrics
            .sensitivity_ohm_per_deg
            .total_cmp(&a.metrics.sensitivity_ohm_per_deg)
    });
    for c in rows.iter().take(REPORT_TABLE_ROWS) {
        if let Some(p) = c.metrics.predicted {
            t.row([
                c.index.to_string(),
                format!("{:.1}", c.metrics.sensitivity_ohm_per_deg),
                format!("Joint {}", p.borrowed),
                format!("{:.2}", p.linear_rmse_deg),
                format!("{:.2}", p.pi_rmse_deg),
                format!("{:.2}", p.closed_loop_rmse_deg),
            ]);
        }
    }
    page.table(t);
}

fn scatter(
    feasible: &[Candidate],
    front: &[usize],
    paper: &[(&str, super::DesignMetrics)],
    mx: Metric,
    my: Metric,
) -> Chart {
    let point = |c: &Candidate| (c.metrics.get(mx), c.metrics.get(my));
    let mut chart = Chart::new(
        format!("{} vs {}", my.key(), mx.key()),
        mx.label(),
        my.label(),
    )
    .with(Series::dots(
        "feasible",
        feasible.iter().map(point).collect(),
        FEASIBLE_GREY,
    ));
    let mut front_series = Series::dots(
        "Pareto front",
        front.iter().map(|&i| point(&feasible[i])).collect(),
        PALETTE[0],
    );
    front_series.style = crate::report::SeriesStyle::Dots(4);
    chart.push(front_series);
    for (k, (label, m)) in paper.iter().enumerate() {
        let mut s = Series::dots(
            *label,
            vec![(m.get(mx), m.get(my))],
            PALETTE[(k + 1) % PALETTE.len()],
        );
        s.style = crate::report::SeriesStyle::Dots(7);
        chart.push(s);
    }
    chart
}
