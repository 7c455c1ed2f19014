//! x-y charts rendered to SVG with `plotters`' SVG backend.

use plotters::prelude::*;

/// A series longer than this is thinned before it is drawn (see [`thin`]).
pub const MAX_POINTS_PER_SERIES: usize = 4000;

/// Colours for series in order: distinguishable, and readable on white (Tableau 10).
pub const PALETTE: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

/// Why a chart could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum ChartError {
    /// No series has a finite point.
    #[error("chart '{title}' has no finite point to draw")]
    Empty {
        /// The chart's title.
        title: String,
    },
    /// `plotters` refused to draw.
    #[error("chart '{title}': {message}")]
    Draw {
        /// The chart's title.
        title: String,
        /// What plotters said.
        message: String,
    },
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SeriesStyle {
    /// A polyline through the points in order.
    Line,
    /// A model or reference drawn over data (fits, truth).
    Reference,
    /// Unconnected dots of the given radius (px).
    Dots(u32),
}

/// One named series of `(x, y)` points.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// The points; non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
    /// Colour as RGB.
    pub color: (u8, u8, u8),
    /// Line or dots.
    pub style: SeriesStyle,
}

impl Series {
    /// A line series.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>, color: (u8, u8, u8)) -> Self {
        Self {
            label: label.into(),
            points,
            color,
            style: SeriesStyle::Line,
        }
    }

    /// A series of dots.
    pub fn dots(label: impl Into<String>, points: Vec<(f64, f64)>, color: (u8, u8, u8)) -> Self {
        Self {
            label: label.into(),
            points,
            color,
            style: SeriesStyle::Dots(2),
        }
    }

    /// A model or reference line.
    pub fn reference(
        label: impl Into<String>,
        points: Vec<(f64, f64)>,
        color: (u8, u8, u8),
    ) -> Self {
        Self {
            label: label.into(),
            points,
            color,
            style: SeriesStyle::Reference,
        }
    }

    /// `(x[i], y[i])` for `i` in `0..min(len)`.
    pub fn zip(xs: &[f64], ys: &[f64]) -> Vec<(f64, f64)> {
        xs.iter().copied().zip(ys.iter().copied()).collect()
    }
}

/// A chart: title, axis labels and series, drawn on shared axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    /// Title above the plot.
    pub title: String,
    /// x-axis label with its unit, e.g. `strain (%)`.
    pub x_label: String,
    /// y-axis label with its unit.
    pub y_label: String,
    /// The series, drawn in order (later on top).
    pub series: Vec<Series>,
    /// Size in px.
    pub size: (u32, u32),
    /// Fixed y range; otherwise from the data with a 5 % margin.
    pub y_range: Option<(f64, f64)>,
    /// Where the legend goes.
    pub legend: Legend,
}

/// The corner the legend is drawn in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// Top left (the default).
    #[default]
    UpperLeft,
    /// Top right.
    UpperRight,
    /// Bottom right.
    LowerRight,
    /// Bottom left.
    LowerLeft,
}

impl Chart {
    /// An empty 900 × 420 chart.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            size: (900, 420),
            y_range: None,
            legend: Legend::UpperLeft,
        }
    }

    /// Adds a series.
    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Adds a series in place.
    pub fn push(&mut self, series: Series) {
        self.series.push(series);
    }

    /// The chart as an SVG document.
    ///
    /// # Errors
    /// [`ChartError::Empty`] when no series has a finite point; [`ChartError::Draw`] when
    /// plotters fails.
    pub fn to_svg(&self) -> Result<String, ChartError> {
        let thinned: Vec<Vec<(f64, f64)>> = self
            .series
            .iter()
            .map(|s| {
                let finite: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|(x, y)| x.is_finite() && y.is_finite())
                    .collect();
                match s.style {
                    SeriesStyle::Dots(_) => thin_scatter(&finite, MAX_POINTS_PER_SERIES),
                    _ => thin(&finite, MAX_POINTS_PER_SERIES),
                }
            })
            .collect();
        let (x_range, y_range) =
            bounds(thinned.iter().flatten()).ok_or_else(|| ChartError::Empty {
                title: self.title.clone(),
            })?;
        let y_range = self.y_range.unwrap_or(y_range);
        let mut svg = String::new();
        self.draw(&mut svg, &thinned, x_range, y_range)
            .map_err(|message| ChartError::Draw {
                title: self.title.clone(),
                message,
            })?;
        Ok(svg)
    }

    fn draw(
        &self,
        svg: &mut String,
        series: &[Vec<(f64, f64)>],
        (x0, x1): (f64, f64),
        (y0, y1): (f64, f64),
    ) -> Result<(), String> {
        let err = |e: &dyn std::fmt::Display| e.to_string();
        let root = SVGBackend::with_string(svg, self.size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(72)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .light_line_style(RGBColor(235, 235, 235))
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(|e| err(&e))?;
        let mut labelled = false;
        for (s, points) in self.series.iter().zip(series) {
            let color = RGBColor(s.color.0, s.color.1, s.color.2);
            let legend_color = color;
            let anno = match s.style {
                SeriesStyle::Line => chart
                    .draw_series(LineSeries::new(
                        points.iter().copied(),
                        color.stroke_width(2),
                    ))
                    .map_err(|e| err(&e))?,
                SeriesStyle::Reference => chart
                    .draw_series(LineSeries::new(
                        points.iter().copied(),
                        color.stroke_width(2),
                    ))
                    .map_err(|e| err(&e))?,
                SeriesStyle::Dots(r) => chart
                    .draw_series(
                        points
                            .iter()
                            .map(|&p| Circle::new(p, r, color.mix(0.7).filled())),
                    )
                    .map_err(|e| err(&e))?,
            };
            if !s.label.is_empty() {
                labelled = true;
                anno.label(s.label.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], legend_color.stroke_width(3))
                });
            }
        }
        if labelled {
            chart
                .configure_series_labels()
                .position(match self.legend {
                    Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
                    Legend::UpperRight => SeriesLabelPosition::UpperRight,
                    Legend::LowerRight => SeriesLabelPosition::LowerRight,
                    Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
                })
                .border_style(RGBColor(160, 160, 160))
                .background_style(WHITE.mix(0.85))
                .label_font(("sans-serif", 13))
                .draw()
                .map_err(|e| err(&e))?;
        }
        root.present().map_err(|e| err(&e))?;
        Ok(())
    }
}

/// Thins a polyline to at most about `max` points, keeping each bucket's first point and its
/// minimum and maximum `y` in order, so peaks, spikes and envelopes survive.
pub fn thin(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    if points.len() <= max || max < 3 {
        return points.to_vec();
    }
    let buckets = (max / 3).max(1);
    let size = points.len().div_ceil(buckets);
    let mut out = Vec::with_capacity(buckets * 3 + 1);
    for chunk in points.chunks(size) {
        let (mut lo, mut hi) = (0, 0);
        for (i, p) in chunk.iter().enumerate() {
            if p.1 < chunk[lo].1 {
                lo = i;
            }
            if p.1 > chunk[hi].1 {
                hi = i;
            }
        }
        let mut idx = [0, lo, hi];
        idx.sort_unstable();
        let mut last = usize::MAX;
        for i in idx {
            if i != last {
                out.push(chunk[i]);
                last = i;
            }
        }
    }
    if let Some(&end) = points.last() {
        if out.last() != Some(&end) {
            out.push(end);
        }
    }
    out
}

/// Keeps every `k`-th point of a scatter so that at most `max` remain.
fn thin_scatter(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    if points.len() <= max || max == 0 {
        return points.to_vec();
    }
    let step = points.len().div_ceil(max);
    points.iter().copied().step_by(step).collect()
}

type Range = (f64, f64);

fn bounds<'a>(points: impl Iterator<Item = &'a (f64, f64)>) -> Option<(Range, Range)> {
    let mut b: Option<(Range, Range)> = None;
    for &(x, y) in points {
        b = Some(match b {
            None => ((x, x), (y, y)),
            Some(((x0, x1), (y0, y1))) => ((x0.min(x), x1.max(x)), (y0.min(y), y1.max(y))),
        });
    }
    b.map(|(x, y)| (pad(x, 0.0), pad(y, 0.05)))
}

/// Widens a range by `margin` of its span on each side, and a degenerate one to a unit span.
fn pad((lo, hi): Range, margin: f64) -> Range {
    let span = hi - lo;
    if span <= f64::EPSILON * lo.abs().max(hi.abs()).max(1.0) {
        let half = (lo.abs() * 0.05).max(0.5);
        return (lo - half, hi + half);
    }
    (lo - margin * span, hi + margin * span)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thin_keeps_extremes_and_ends() {
        let pts: Vec<(f64, f64)> = (0..100_000)
            .map(|i| (i as f64, if i == 54_321 { 1e3 } else { (i as f64).sin() }))
            .collect();
        let t = thin(&pts, 3000);
        assert!(t.len() <= 3002, "{}", t.len());
        assert!(t.contains(&(54_321.0, 1e3)));
        assert_eq!(t.first(), pts.first());
        assert_eq!(t.last(), pts.last());
        assert!(t.windows(2).all(|w| w[0].0 < w[1].0));
    }

    #[test]
    fn svg_has_title_labels_and_one_path_per_line() {
        let chart = Chart::new("Resistance against strain", "strain (%)", "R (kΩ)")
            .with(Series::line(
                "cycle 1",
                vec![(0.0, 1.0), (1.0, 2.0)],
                PALETTE[0],
            ))
            .with(Series::dots(
                "data",
                vec![(0.5, 1.5), (0.7, f64::NAN)],
                PALETTE[1],
            ));
        let svg = chart.to_svg().unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let texts: Vec<String> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .filter_map(|n| n.text().map(|t| t.trim().to_owned()))
            .collect();
        for want in [
            "Resistance against strain",
            "strain (%)",
            "R (kΩ)",
            "cycle 1",
        ] {
            assert!(texts.iter().any(|t| t == want), "{want} not in {texts:?}");
        }
        // The data series' dot and the NaN point skipped: one data circle.
        let circles = doc
            .descendants()
            .filter(|n| n.has_tag_name("circle"))
            .count();
        assert_eq!(circles, 1);
    }

    #[test]
    fn empty_chart_is_an_error_not_a_panic() {
        let chart = Chart::new("nothing", "x", "y").with(Series::line(
            "nan",
            vec![(f64::NAN, 1.0)],
            PALETTE[0],
        ));
        assert!(matches!(chart.to_svg(), Err(ChartError::Empty { .. })));
    }
}
