//! `angles.csv`: what `dlw fluoro` writes and `dlw estimate --truth` reads
//! (`crate::recording::read_angles`, beside the recordings it is compared with).
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

use super::AngleSeries;
use crate::fixed::push_fixed;

/// The header `dlw fluoro` writes.
pub const ANGLES_HEADER: &str = "time_s,angle_deg,raw_deg,area_px,axis_ratio,flags";

/// `angles.csv` as bytes.
pub fn angles_csv_bytes(series: &AngleSeries) -> Vec<u8> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluoro::{Baseline, Row};
    use std::path::Path;

    #[test]
    fn writes_and_reads_back() {
        let series = AngleSeries {
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
        let t = crate::recording::parse_angles(&text, Path::new("a.csv")).unwrap();
        assert_eq!(
            (t.time_s, t.angle_deg, t.skipped),
            (vec![0.0, 1.0], vec![0.25, -3.0], 1)
        );
    }
}
