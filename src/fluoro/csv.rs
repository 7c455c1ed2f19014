//! `angles.csv`: what `dlw fluoro` writes and `dlw estimate --truth` reads.
//!
//! ```text
//! time_s,angle_deg,raw_deg,area_px,axis_ratio,flags
//! 0.000000,0.0213,12.0431,2140,6.412,none
//! 0.500000,,,0,,no_pin
//! ```
//!
//! `time_s` to 1 µs, angles to 1e-4°, `axis_ratio` to 1e-3; `flags` joined by `|` (`none` when
//! clean). A skipped frame has empty `angle_deg` and `raw_deg` (and an empty `axis_ratio` when
//! nothing was found). The reader needs only the columns `time_s` and `angle_deg`, in any order,
//! so a ground truth made by another tool can be compared as well; a row with an empty
//! `angle_deg` is a frame without an angle and is left out.

use std::path::{Path, PathBuf};

use super::{FluoroError, Series};
use crate::fixed::push_fixed;

/// The header `dlw fluoro` writes.
pub const ANGLES_HEADER: &str = "time_s,angle_deg,raw_deg,area_px,axis_ratio,flags";

/// `angles.csv` as bytes.
pub fn angles_csv_bytes(series: &Series) -> Vec<u8> {
    let mut out = Vec::with_capacity(series.rows.len() * 48 + 64);
    out.extend_from_slice(ANGLES_HEADER.as_bytes());
    out.push(b'\n');
    let opt = |out: &mut Vec<u8>, v: Option<f64>, decimals| {
        if let Some(v) = v {
            push_fixed(out, v, decimals);
        }
    };
    for r in &series.rows {
        push_fixed(&mut out, r.time_s, 6);
        out.push(b',');
        opt(&mut out, r.angle_deg, 4);
        out.push(b',');
        opt(&mut out, r.raw_deg, 4);
        out.push(b',');
        out.extend_from_slice(r.area_px.to_string().as_bytes());
        out.push(b',');
        opt(&mut out, r.axis_ratio.filter(|a| a.is_finite()), 3);
        out.push(b',');
        if r.flags.is_empty() {
            out.extend_from_slice(b"none");
        } else {
            out.extend_from_slice(r.flags.join("|").as_bytes());
        }
        out.push(b'\n');
    }
    out
}

/// A ground-truth angle series read from a CSV.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TruthAngles {
    /// The file read.
    pub path: PathBuf,
    /// Times of the frames with an angle (s), increasing.
    pub time_s: Vec<f64>,
    /// Their angles (°).
    pub angle_deg: Vec<f64>,
    /// Rows without an angle (skipped frames).
    pub skipped: usize,
}

/// Reads a ground-truth CSV.
///
/// # Errors
/// [`FluoroError::Read`], or see [`parse_angles`].
pub fn read_angles(path: &Path) -> Result<TruthAngles, FluoroError> {
    let text = crate::output::read_limited(path, crate::limits::MAX_RECORDING_BYTES).map_err(
        |source| FluoroError::Read {
            path: path.to_path_buf(),
            source,
        },
    )?;
    parse_angles(&text, path)
}

/// Parses a ground-truth CSV's text; `path` names it in errors.
///
/// # Errors
/// [`FluoroError::CsvLine`] for a header without `time_s` or `angle_deg`, a row with the wrong
/// number of fields, a field that is not a finite number, a time that does not increase;
/// [`FluoroError::CsvEmpty`] when no row has an angle.
pub fn parse_angles(text: &str, path: &Path) -> Result<TruthAngles, FluoroError> {
    let bad = |line: usize, reason: String| FluoroError::CsvLine {
        path: path.to_path_buf(),
        line,
        reason,
    };
    let mut lines = text.lines().enumerate();
    let header: Vec<&str> = lines
        .next()
        .map_or("", |(_, l)| l)
        .split(',')
        .map(str::trim)
        .collect();
    let column = |name: &str| {
        header.iter().position(|h| *h == name).ok_or_else(|| {
            bad(
                1,
                format!(
                    "header {:?} has no {name} column",
                    crate::limits::quote(&header.join(","))
                ),
            )
        })
    };
    let (ti, ai) = (column("time_s")?, column("angle_deg")?);
    let mut truth = TruthAngles {
        path: path.to_path_buf(),
        ..TruthAngles::default()
    };
    let mut previous: Option<f64> = None;
    for (i, text) in lines {
        let line = i + 1;
        if text.trim().is_empty() {
            continue;
        }
        let fields: Vec<&str> = text.split(',').map(str::trim).collect();
        if fields.len() != header.len() {
            return Err(bad(
                line,
                format!("has {} fields, expected {}", fields.len(), header.len()),
            ));
        }
        let number = |name: &str, f: &str| -> Result<f64, FluoroError> {
            f.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(line, format!("{name} = {f:?} is not a finite number")))
        };
        let t = number("time_s", fields[ti])?;
        if let Some(p) = previous {
            if t <= p {
                return Err(bad(
                    line,
                    format!("time_s = {t} does not increase (previous row: {p})"),
                ));
            }
        }
        previous = Some(t);
        if fields[ai].is_empty() {
            truth.skipped += 1;
            continue;
        }
        truth.time_s.push(t);
        truth.angle_deg.push(number("angle_deg", fields[ai])?);
    }
    if truth.time_s.is_empty() {
        return Err(FluoroError::CsvEmpty {
            path: path.to_path_buf(),
        });
    }
    Ok(truth)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluoro::{Baseline, Row};

    #[test]
    fn writes_and_reads_back() {
        let series = Series {
            rows: vec![
                Row {
                    time_s: 0.0,
                    angle_deg: Some(0.25),
                    raw_deg: Some(10.5),
                    area_px: 2140,
                    axis_ratio: Some(6.4123),
                    flags: vec![],
                },
                Row {
                    time_s: 0.5,
                    angle_deg: None,
                    raw_deg: None,
                    area_px: 3,
                    axis_ratio: Some(1.0),
                    flags: vec!["too_small", "edge"],
                },
                Row {
                    time_s: 1.0,
                    angle_deg: Some(-3.0),
                    raw_deg: Some(7.25),
                    area_px: 2000,
                    axis_ratio: Some(6.0),
                    flags: vec![],
                },
            ],
            baseline: Baseline {
                mean_deg: 10.25,
                frames: 1,
                end_s: Some(0.5),
            },
        };
        let text = String::from_utf8(angles_csv_bytes(&series)).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], ANGLES_HEADER);
        assert_eq!(lines[1], "0.000000,0.2500,10.5000,2140,6.412,none");
        assert_eq!(lines[2], "0.500000,,,3,1.000,too_small|edge");
        let t = parse_angles(&text, Path::new("a.csv")).unwrap();
        assert_eq!(
            (t.time_s, t.angle_deg, t.skipped),
            (vec![0.0, 1.0], vec![0.25, -3.0], 1)
        );
    }

    #[test]
    fn names_bad_lines() {
        let table = [
            (
                "time,angle\n0,1\n",
                "line 1: header \"time,angle\" has no time_s",
            ),
            ("time_s,angle_deg\n0,1,2\n", "line 2: has 3 fields"),
            ("time_s,angle_deg\n0,x\n", "line 2: angle_deg = \"x\""),
            (
                "time_s,angle_deg\n0,1\n0,2\n",
                "line 3: time_s = 0 does not increase",
            ),
            ("time_s,angle_deg\n0,NaN\n", "not a finite number"),
            ("time_s,angle_deg\n0,\n", "has no frame with an angle"),
        ];
        for (text, needle) in table {
            let err = parse_angles(text, Path::new("a.csv"))
                .unwrap_err()
                .to_string();
            assert!(err.contains(needle), "{text:?}: {err}");
        }
        // Another tool's CSV: extra columns, any order.
        let t = parse_angles("frame,angle_deg,time_s\n1,2.5,0.5\n", Path::new("b.csv")).unwrap();
        assert_eq!((t.time_s, t.angle_deg), (vec![0.5], vec![2.5]));
    }
}
