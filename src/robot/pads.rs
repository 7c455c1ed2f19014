//! The robot's pad section, after its last joint. Row 0 holds the last joint's own pads, where
//! its design puts them; the other joints' leads pass between them and end in rows after it,
//! each row holding as many pads as fit round the tube with the leads for later rows passing
//! between its pads.
//!
//! In the rows after row 0 every pad lies above its lead's terminal (towards larger `s`).
//! Going round the tube in the leads' order, lead `k` ends in row `1 + k mod R`; in row `r`
//! the items are the pads of that row and the leads passing on to later rows, and neighbours
//! keep `pad_gap_mm` between two pads and a trace width plus the clearance (the pitch) next to
//! a lead. `R` is the fewest rows whose items fit round the circumference.

/// The rows after row 0 for `m` leads in order round the tube.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Rows {
    /// Rows after row 0.
    pub count: usize,
    /// The row of each lead, from 1.
    pub row: Vec<usize>,
    /// Each lead's terminal `s`, increasing, the first at 0; add a common turn to place them.
    pub s: Vec<f64>,
}

/// Why the pads do not fit.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NoFit {
    /// What one row of pads and the leads between needs at best, with as many rows as leads.
    pub needed_mm: f64,
}

/// Packs the pads of `m` leads (`m ≥ 1`) in the fewest rows that fit round `c`.
pub(crate) fn pack(
    m: usize,
    c: f64,
    pad_mm: f64,
    pad_gap_mm: f64,
    pitch_mm: f64,
) -> Result<Rows, NoFit> {
    let mut best_needed = f64::INFINITY;
    for count in 1..=m {
        let row: Vec<usize> = (0..m).map(|k| 1 + k % count).collect();
        let (s, needed) = positions(&row, count, pad_mm, pad_gap_mm, pitch_mm);
        if needed <= c + 1e-12 {
            // Spread the room left evenly between neighbours.
            let extra = (c - needed) / m as f64;
            let s = s
                .iter()
                .enumerate()
                .map(|(k, v)| v + k as f64 * extra)
                .collect();
            return Ok(Rows { count, row, s });
        }
        best_needed = best_needed.min(needed);
    }
    Err(NoFit {
        needed_mm: best_needed,
    })
}

/// The tightest terminals for leads in rows `row`, and the circumference they need.
fn positions(
    row: &[usize],
    count: usize,
    pad_mm: f64,
    pad_gap_mm: f64,
    pitch_mm: f64,
) -> (Vec<f64>, f64) {
    let m = row.len();
    // Constraints s[b] ≥ s[a] + sep for consecutive items of each row (a < b), and round the
    // tube from the last back to the first.
    let sep = |a: usize, b: usize, r: usize| {
        if row[a] == r {
            pad_mm + if row[b] == r { pad_gap_mm } else { pitch_mm }
        } else {
            pitch_mm
        }
    };
    let mut forward: Vec<(usize, usize, f64)> = Vec::new();
    let mut wrap: Vec<(usize, usize, f64)> = Vec::new();
    for r in 1..=count {
        let items: Vec<usize> = (0..m).filter(|&k| row[k] >= r).collect();
        for w in items.windows(2) {
            forward.push((w[0], w[1], sep(w[0], w[1], r)));
        }
        if let (Some(&first), Some(&last)) = (items.first(), items.last()) {
            wrap.push((last, first, sep(last, first, r)));
        }
    }
    let mut s = vec![0.0; m];
    for b in 1..m {
        s[b] = forward
            .iter()
            .filter(|(_, to, _)| *to == b)
            .map(|(a, _, d)| s[*a] + d)
            .fold(s[b - 1], f64::max);
    }
    let needed = wrap
        .iter()
        .map(|(last, first, d)| s[*last] + d - s[*first])
        .fold(0.0, f64::max);
    (s, needed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_row_when_it_fits_and_more_when_not() {
        // Four 0.8 mm pads with 0.3 mm gaps need 4.4 mm: one row on a 5.03 mm tube.
        let r = pack(4, 5.03, 0.8, 0.3, 0.13).unwrap();
        assert_eq!(r.count, 1);
        assert!((r.s[1] - r.s[0] - 1.1).abs() < 0.2);
        // Six need two rows: a pad, a passing lead, … 3 × 1.1 = 3.3 mm in the second row.
        let r = pack(6, 5.03, 0.8, 0.3, 0.13).unwrap();
        assert_eq!(r.count, 2);
        assert_eq!(r.row, vec![1, 2, 1, 2, 1, 2]);
        for k in 0..6 {
            let next = if k == 5 { r.s[0] + 5.03 } else { r.s[k + 1] };
            let need = if r.row[k] == 1 { 0.8 + 0.13 } else { 0.13 };
            assert!(next - r.s[k] >= need - 1e-9, "{r:?}");
        }
        // A tube too small for even one pad and a lead.
        assert!(pack(2, 0.9, 0.8, 0.3, 0.13).is_err());
    }
}
