//! HTML report pages: headings, paragraphs, tables and SVG figures, written as one folder.

use std::fmt::Write as _;
use std::path::Path;

use super::chart::{Chart, ChartError};
use crate::output::{write_folder_atomic, OutputError};

/// The page's file name inside its folder.
pub const PAGE_FILE: &str = "report.html";

/// A table: a header row and rows of cells (already formatted, with units in the header).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    /// Column headings.
    pub header: Vec<String>,
    /// Rows; each as long as the header.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column headings.
    pub fn new<S: Into<String>>(header: impl IntoIterator<Item = S>) -> Self {
        Self {
            header: header.into_iter().map(Into::into).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    pub fn row<S: Into<String>>(&mut self, cells: impl IntoIterator<Item = S>) {
        self.rows.push(cells.into_iter().map(Into::into).collect());
    }
}

/// One piece of a page.
#[derive(Debug, Clone, PartialEq)]
pub enum Block {
    /// A section heading (`<h2>`).
    Heading(String),
    /// A paragraph of plain text (escaped).
    Text(String),
    /// A table.
    Table(Table),
    /// A figure: the chart is written as `<name>.svg` beside the page.
    Figure {
        /// File stem, unique on the page (letters, digits, `-`).
        name: String,
        /// The chart.
        chart: Chart,
        /// Caption under the figure.
        caption: String,
    },
}

/// An HTML page with its figures.
#[derive(Debug, Clone, PartialEq)]
pub struct Page {
    /// Title (`<title>` and `<h1>`).
    pub title: String,
    /// The content, in order.
    pub blocks: Vec<Block>,
}

impl Page {
    /// An empty page.
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            blocks: Vec::new(),
        }
    }

    /// Adds a heading.
    pub fn heading(&mut self, text: impl Into<String>) {
        self.blocks.push(Block::Heading(text.into()));
    }

    /// Adds a paragraph.
    pub fn text(&mut self, text: impl Into<String>) {
        self.blocks.push(Block::Text(text.into()));
    }

    /// Adds a table.
    pub fn table(&mut self, table: Table) {
        self.blocks.push(Block::Table(table));
    }

    /// Adds a figure; `name` becomes the SVG's file stem.
    pub fn figure(&mut self, name: impl Into<String>, chart: Chart, caption: impl Into<String>) {
        self.blocks.push(Block::Figure {
            name: name.into(),
            chart,
            caption: caption.into(),
        });
    }

    /// The page's files: `report.html` and one SVG per figure, names relative to the folder.
    ///
    /// # Errors
    /// [`ChartError`] when a figure cannot be drawn.
    pub fn files(&self) -> Result<Vec<(String, Vec<u8>)>, ChartError> {
        let mut files = Vec::new();
        let mut html = String::new();
        let _ = write!(
            html,
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
             <title>{t}</title>\n<style>{STYLE}</style></head>\n<body>\n<h1>{t}</h1>\n",
            t = escape(&self.title)
        );
        for block in &self.blocks {
            match block {
                Block::Heading(h) => {
                    let _ = writeln!(html, "<h2>{}</h2>", escape(h));
                }
                Block::Text(t) => {
                    let _ = writeln!(html, "<p>{}</p>", escape(t));
                }
                Block::Table(t) => table_html(&mut html, t),
                Block::Figure {
                    name,
                    chart,
                    caption,
                } => {
                    let file = format!("{name}.svg");
                    files.push((file.clone(), chart.to_svg()?.into_bytes()));
                    let _ = writeln!(
                        html,
                        "<figure style=\"width:{w}px\"><img src=\"{f}\" alt=\"{a}\" width=\"{w}\" \
                         height=\"{h}\"><figcaption>{c}</figcaption></figure>",
                        f = escape(&file),
                        a = escape(&chart.title),
                        w = chart.size.0,
                        h = chart.size.1,
                        c = escape(caption)
                    );
                }
            }
        }
        html.push_str("</body></html>\n");
        files.insert(0, (PAGE_FILE.to_owned(), html.into_bytes()));
        Ok(files)
    }

    /// Writes the page into the folder `dir` (replacing it), all files or none.
    ///
    /// # Errors
    /// A figure that cannot be drawn, or a file that cannot be written; `dir` is then as it was.
    pub fn write(&self, dir: &Path) -> Result<(), ReportError> {
        let files = self.files()?;
        write_folder_atomic(dir, &files)?;
        Ok(())
    }
}

/// Why a report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A figure could not be drawn.
    #[error(transparent)]
    Chart(#[from] ChartError),
    /// A file could not be written.
    #[error(transparent)]
    Output(#[from] OutputError),
}

const STYLE: &str = "body{font-family:sans-serif;max-width:960px;margin:2em auto;color:#222;\
line-height:1.45}h1{font-size:1.6em}h2{font-size:1.25em;margin-top:1.6em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;margin:1em 0}th,td{border:1px solid #bbb;padding:3px 9px;\
text-align:right;font-variant-numeric:tabular-nums}th{background:#f1f1f1}td:first-child,\
th:first-child{text-align:left}figure{display:inline-block;vertical-align:top;margin:1em 1em 1em 0;max-width:100%}\
img{max-width:100%;height:auto}figcaption{font-size:.9em;color:#555}";

fn table_html(html: &mut String, t: &Table) {
    html.push_str("<table><thead><tr>");
    for h in &t.header {
        let _ = write!(html, "<th>{}</th>", escape(h));
    }
    html.push_str("</tr></thead><tbody>\n");
    for row in &t.rows {
        html.push_str("<tr>");
        for c in row {
            let _ = write!(html, "<td>{}</td>", escape(c));
        }
        html.push_str("</tr>\n");
    }
    html.push_str("</tbody></table>\n");
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{Series, PALETTE};

    #[test]
    fn page_lists_figures_as_files_and_escapes_text() {
        let mut page = Page::new("Fit <Joint A>");
        page.text("R & ε");
        let mut t = Table::new(["parameter", "value"]);
        t.row(["GF", "15.3"]);
        page.table(t);
        let chart = Chart::new("c", "x", "y").with(Series::line(
            "a",
            vec![(0.0, 0.0), (1.0, 1.0)],
            PALETTE[0],
        ));
        page.figure("r-vs-strain", chart, "caption");
        let files = page.files().unwrap();
        let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["report.html", "r-vs-strain.svg"]);
        let html = String::from_utf8(files[0].1.clone()).unwrap();
        assert!(html.contains("<h1>Fit &lt;Joint A&gt;</h1>"));
        assert!(html.contains("<p>R &amp; ε</p>"));
        assert!(html.contains("<td>15.3</td>"));
        assert!(html.contains("src=\"r-vs-strain.svg\""));
    }
}
