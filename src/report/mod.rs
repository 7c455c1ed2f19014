//! Reports for people: SVG plots drawn with `plotters` and HTML pages that hold them.
//!
//! One layer shared by every analysis (`fit`, `characterize`, `control`, `discover`,
//! `reproduce`): an analysis describes its figures as [`Chart`]s and its numbers as [`Table`]s,
//! puts them on a [`Page`], and writes the page with [`Page::write`] (or collects several pages'
//! files into one folder with [`Page::files`]). Nothing here knows about joints or sensors.
//!
//! Plots keep the files small and the browser fast: a series longer than
//! [`MAX_POINTS_PER_SERIES`] is thinned by [`thin`], which keeps each bucket's minimum and
//! maximum so that spikes and envelopes survive.

mod chart;
mod page;

/// Charts: line and scatter series on x-y axes, rendered to SVG by `plotters`.
pub use chart::{
    thin, Chart, ChartError, Legend, Series, SeriesStyle, MAX_POINTS_PER_SERIES, PALETTE,
};
/// HTML pages of headings, text, tables and figures.
pub use page::{Block, Page, ReportError, Table, PAGE_FILE};
