//! A ground-truth angle series (`angles.csv`, what `dlw fluoro` writes, or another tool's CSV
//! with `time_s` and `angle_deg` columns), read to compare a recording's estimates with
//! (`dlw estimate --truth`).
//!
//! The reader needs only the columns `time_s` and `angle_deg`, in any order; a row with an
//! empty `angle_deg` is a frame without an angle and is left out.

use std::path::{Path, PathBuf};

/// Why a ground-truth CSV could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TruthError {
    /// The file could not be read.
    #[error("cannot read {path}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The CSV is malformed at one line.
    #[error("{path} line {line}: {reason}")]
    CsvLine {
        /// The file.
        path: PathBuf,
        /// 1-based line number (the header is line 1).
        line: usize,
        /// What is wrong, naming the value.
        reason: String,
    },
    /// The CSV has no frame with an angle.
    #[error("{path} has no frame with an angle")]
    CsvEmpty {
        /// The file.
        path: PathBuf,
    },
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
/// [`TruthError::Read`], or see [`parse_angles`].
pub fn read_angles(path: &Path) -> Result<TruthAngles, TruthError> {
    let text = crate::output::read_limited(path, crate::limits::MAX_RECORDING_BYTES).map_err(
        |source| TruthError::Read {
            path: path.to_path_buf(),
            source,
        },
    )?;
    parse_angles(&text, path)
}

/// Parses a ground-truth CSV's text; `path` names it in errors.
///
/// # Errors
/// [`TruthError::CsvLine`] for a header without `time_s` or `angle_deg`, a row with the wrong
/// number of fields, a field that is not a finite number, a time that does not increase;
/// [`TruthError::CsvEmpty`] when no row has an angle.
pub fn parse_angles(text: &str, path: &Path) -> Result<TruthAngles, TruthError> {
    let bad = |line: usize, reason: String| TruthError::CsvLine {
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
        let number = |name: &str, f: &str| -> Result<f64, TruthError> {
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
        return Err(TruthError::CsvEmpty {
            path: path.to_path_buf(),
        });
    }
    Ok(truth)
}

#[cfg(test)]
mod tests {
    use super::*;

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
