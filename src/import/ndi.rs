//! The CSV log that NDI's Combined API sample and NDI Track write for an Aurora EM tracker.
//!
//! Each row has `Frame#`, optional `timespec_s` and `timespec_ns`, and per tool a block
//! `PortHandle, Face#, TransformStatus, Q0, Qx, Qy, Qz, Tx, Ty, Tz, Error`. Columns are found
//! by their header names (real logs carry more, such as `ToolInfo` or `#Markers`); the `n`-th
//! `Q0` column belongs to tool `n` (1-based, in the order the log lists the tools). A lost tool
//! is written as `Missing` with empty fields. Quaternions are **scalar-first** (`Q0` is the
//! scalar part).
//!
//! Time: `τ = (Frame# − first Frame#) / frame_hz`, following NDI's guidance that frame numbers
//! are regular and the host clock is not; or the timespec difference when both timespec
//! columns are present.

use thiserror::Error;

/// How far a quaternion's norm may be from 1 before the row is refused.
pub const MAX_QUATERNION_NORM_ERROR: f64 = 1e-3;

/// Errors reading a tracker log.
#[derive(Debug, Error)]
pub enum NdiError {
    /// The log has no header row.
    #[error("tracker log is empty (no header row)")]
    Empty,
    /// A column the reader needs is not in the header.
    #[error("tracker log header has no {column:?} column (found: {found})")]
    NoColumn {
        /// The column looked for.
        column: String,
        /// The header's columns.
        found: String,
    },
    /// The tool asked for is not in the log.
    #[error("tracker log has no tool {tool} (it lists {tools} tool(s))")]
    NoTool {
        /// The tool asked for (1-based).
        tool: usize,
        /// The tools in the log.
        tools: usize,
    },
    /// A field is not a number.
    #[error("tracker log row {row}: {column} = {text:?} is not a number")]
    Number {
        /// The data row (1-based, header excluded).
        row: usize,
        /// The column.
        column: String,
        /// The field.
        text: String,
    },
    /// A quaternion is not of unit length.
    #[error("tracker log row {row}: tool {tool}'s quaternion has norm {norm:.6} (must be 1 within {MAX_QUATERNION_NORM_ERROR})")]
    NotUnit {
        /// The data row (1-based).
        row: usize,
        /// The tool (1-based).
        tool: usize,
        /// The norm found.
        norm: f64,
    },
    /// Frame numbers or times do not increase.
    #[error("tracker log row {row}: time {tau_s} s does not increase (previous {previous_s} s)")]
    TimeNotIncreasing {
        /// The data row (1-based).
        row: usize,
        /// Its time.
        tau_s: f64,
        /// The previous row's time.
        previous_s: f64,
    },
    /// The frame rate is not positive and finite.
    #[error("tracker frame rate {hz} Hz must be finite and greater than 0")]
    FrameRate {
        /// The rate given.
        hz: f64,
    },
}

/// One tool's orientation at one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolFrame {
    /// The unit quaternion, scalar first: `[q0, qx, qy, qz]`.
    pub quaternion: [f64; 4],
}

impl ToolFrame {
    /// The tool's z axis (the axis a 5-DOF Aurora sensor reports) in the tracker's frame: the
    /// third column of the rotation matrix of `quaternion`.
    pub fn z_axis(&self) -> [f64; 3] {
        let [w, x, y, z] = self.quaternion;
        [
            2.0 * (x * z + w * y),
            2.0 * (y * z - w * x),
            1.0 - 2.0 * (x * x + y * y),
        ]
    }
}

/// The frames of the tools asked for, one entry per logged row.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackerLog {
    /// The tracker's own time from its first logged row (s).
    pub tau_s: Vec<f64>,
    /// Per tool asked for, per row: the frame, or `None` where the log says `Missing`.
    pub tools: Vec<Vec<Option<ToolFrame>>>,
}

impl TrackerLog {
    /// Parses `text`, keeping `tools` (1-based, in the log's order); `frame_hz` turns frame
    /// numbers into time when the log has no timespec columns.
    ///
    /// # Errors
    /// [`NdiError`] naming the row, the column and the value.
    pub fn parse(text: &str, tools: &[usize], frame_hz: f64) -> Result<Self, NdiError> {
        if !(frame_hz.is_finite() && frame_hz > 0.0) {
            return Err(NdiError::FrameRate { hz: frame_hz });
        }
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        let header: Vec<&str> = lines
            .next()
            .ok_or(NdiError::Empty)?
            .split(',')
            .map(str::trim)
            .collect();
        let find = |name: &str| header.iter().position(|h| h.eq_ignore_ascii_case(name));
        let no_column = |name: &str| NdiError::NoColumn {
            column: name.to_string(),
            found: header.join(","),
        };
        let frame_col = find("Frame#").ok_or_else(|| no_column("Frame#"))?;
        let timespec = find("timespec_s").zip(find("timespec_ns"));
        let q0_cols: Vec<usize> = (0..header.len())
            .filter(|&i| header[i].eq_ignore_ascii_case("Q0"))
            .collect();
        let status_cols: Vec<usize> = (0..header.len())
            .filter(|&i| header[i].eq_ignore_ascii_case("TransformStatus"))
            .collect();
        let mut chosen = Vec::with_capacity(tools.len());
        for &tool in tools {
            let q0 = *q0_cols.get(tool.wrapping_sub(1)).ok_or(NdiError::NoTool {
                tool,
                tools: q0_cols.len(),
            })?;
            // The status column of this tool's block: the last one before its Q0.
            let status = status_cols.iter().rev().find(|&&c| c < q0).copied();
            chosen.push((tool, q0, status));
        }
        let mut log = TrackerLog {
            tau_s: Vec::new(),
            tools: vec![Vec::new(); tools.len()],
        };
        let mut first: Option<(f64, f64)> = None;
        for (r, line) in lines.enumerate() {
            let row = r + 1;
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            let field = |c: usize| fields.get(c).copied().unwrap_or("");
            let number = |c: usize| -> Result<f64, NdiError> {
                let text = field(c);
                // Values such as `Port:1` keep their number after the colon.
                let text = text.rsplit(':').next().unwrap_or(text);
                text.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| NdiError::Number {
                        row,
                        column: header.get(c).copied().unwrap_or("?").to_string(),
                        text: crate::limits::quote(field(c)),
                    })
            };
            // Differences are taken before scaling, so that frame 101 of a log starting at 100
            // is exactly one period in (and an epoch's seconds do not eat the nanoseconds).
            let stamp = match timespec {
                Some((s, ns)) => (number(s)?, number(ns)? * 1e-9),
                None => (number(frame_col)?, 0.0),
            };
            let (s0, ns0) = *first.get_or_insert(stamp);
            let tau = match timespec {
                Some(_) => (stamp.0 - s0) + (stamp.1 - ns0),
                None => (stamp.0 - s0) / frame_hz,
            };
            if let Some(&previous_s) = log.tau_s.last() {
                if tau <= previous_s {
                    return Err(NdiError::TimeNotIncreasing {
                        row,
                        tau_s: tau,
                        previous_s,
                    });
                }
            }
            log.tau_s.push(tau);
            for (k, &(tool, q0, status)) in chosen.iter().enumerate() {
                let missing = status.is_some_and(|c| field(c).eq_ignore_ascii_case("Missing"))
                    || field(q0).is_empty();
                if missing {
                    log.tools[k].push(None);
                    continue;
                }
                let q = [
                    number(q0)?,
                    number(q0 + 1)?,
                    number(q0 + 2)?,
                    number(q0 + 3)?,
                ];
                let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
                if (norm - 1.0).abs() > MAX_QUATERNION_NORM_ERROR {
                    return Err(NdiError::NotUnit { row, tool, norm });
                }
                log.tools[k].push(Some(ToolFrame { quaternion: q }));
            }
        }
        Ok(log)
    }

    /// Rows where tool `k` (index into the tools asked for) is missing.
    pub fn missing(&self, k: usize) -> usize {
        self.tools
            .get(k)
            .map_or(0, |t| t.iter().filter(|f| f.is_none()).count())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const HEADER: &str = "#Tools,ToolInfo,Frame#,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error";

    fn log() -> String {
        let h = (10f64.to_radians() / 2.0).sin_cos();
        format!(
            "{HEADER}\n\
             2,x,100,Port:1,0,OK,1,0,0,0,1,2,3,0.1,Port:2,0,OK,{c},{s},0,0,0,0,0,0.1\n\
             2,x,101,Port:1,0,Missing,,,,,,,,,Port:2,0,OK,1,0,0,0,0,0,0,0.1\n\
             2,x,103,Port:1,0,OK,{c},0,{s},0,1,2,3,0.1,Port:2,0,OK,1,0,0,0,0,0,0,0.1\n",
            c = h.1,
            s = h.0
        )
    }

    #[test]
    fn reads_tools_by_header_names_with_missing_frames_and_frame_time() {
        let log = TrackerLog::parse(&log(), &[1, 2], 40.0).unwrap();
        assert_eq!(log.tau_s, vec![0.0, 0.025, 0.075]);
        assert_eq!(log.missing(0), 1);
        assert_eq!(log.missing(1), 0);
        assert!(log.tools[0][1].is_none());
        // Tool 1, row 3: 10° about y tilts z towards +x.
        let z = log.tools[0][2].unwrap().z_axis();
        assert_relative_eq!(z[0], 10f64.to_radians().sin(), epsilon = 1e-12);
        assert_relative_eq!(z[2], 10f64.to_radians().cos(), epsilon = 1e-12);
        // Tool 2, row 1: 10° about x tilts z towards −y.
        let z = log.tools[1][0].unwrap().z_axis();
        assert_relative_eq!(z[1], -10f64.to_radians().sin(), epsilon = 1e-12);
    }

    #[test]
    fn a_missing_status_wins_over_stale_numbers_and_empty_fields_are_missing() {
        let text =
            "Frame#,TransformStatus,Q0,Qx,Qy,Qz\n1,Missing,1,0,0,0\n2,OK,,,,\n3,OK,1,0,0,0\n";
        let log = TrackerLog::parse(text, &[1], 40.0).unwrap();
        assert_eq!(log.missing(0), 2);
        assert!(log.tools[0][2].is_some());
    }

    #[test]
    fn timespec_columns_give_the_time_when_present() {
        let text = "Frame#,timespec_s,timespec_ns,TransformStatus,Q0,Qx,Qy,Qz\n\
                    7,1000,500000000,OK,1,0,0,0\n9,1000,530000000,OK,1,0,0,0\n";
        let log = TrackerLog::parse(text, &[1], 40.0).unwrap();
        assert_relative_eq!(log.tau_s[1], 0.03, epsilon = 1e-9);
    }

    #[test]
    fn bad_logs_name_the_row_and_value() {
        let table = [
            (
                log().replacen(",OK,1,0,0,0,1,2,3", ",OK,1.01,0,0,0,1,2,3", 1),
                "row 1: tool 1's quaternion has norm 1.01",
            ),
            (
                log().replacen(",103,", ",100,", 1),
                "row 3: time 0 s does not increase",
            ),
            (
                log().replacen(",OK,1,0,0,0,1,2,3", ",OK,one,0,0,0,1,2,3", 1),
                "row 1: Q0 = \"one\"",
            ),
            ("Frame\n1\n".to_string(), "no \"Frame#\" column"),
        ];
        for (text, needle) in table {
            let err = TrackerLog::parse(&text, &[1], 40.0)
                .unwrap_err()
                .to_string();
            assert!(err.contains(needle), "{needle}: {err}");
        }
        let err = TrackerLog::parse(&log(), &[3], 40.0)
            .unwrap_err()
            .to_string();
        assert!(err.contains("no tool 3 (it lists 2"), "{err}");
        assert!(TrackerLog::parse(&log(), &[1], 0.0).is_err());
    }
}
