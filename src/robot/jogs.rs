//! Moving leads round the tube between two stretches where they run along it: which lead
//! goes to which lane, and in what order along `x` the leads make their circumferential jogs
//! so that no two cross or come closer than the pitch.
//!
//! A jog of lead `i` is a line round the tube at one `x`, from where it runs (`from`) to its
//! lane (`to`), covering the arc between. Any other lead `j` is at its `from` before its own
//! jog and at its `to` after it. So if `j`'s `from` lies on `i`'s arc (within the pitch), `j`
//! must jog first; if `j`'s `to` does, `j` must jog after `i`; if both, no order works and the
//! leads cross. Leads keep their order round the tube (no two can pass each other on one
//! surface), so only cyclic shifts of the lanes are tried. Jogs that need not be ordered
//! share a step along `x` when their arcs are a pitch apart. The steps are spread evenly over
//! the stretch of uncut tube they use.

use std::collections::VecDeque;

/// A move shorter than this is no move (mm).
pub(crate) const MOVE_TOL_MM: f64 = 1e-12;

/// The jogs of one stretch: each lead's target (unwrapped, `from + Δ`) and its step, `None` for
/// a lead that does not move.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Jogs {
    pub to: Vec<f64>,
    pub step: Vec<Option<usize>>,
    pub steps: usize,
}

/// Two leads that would cross: indices into the leads given.
pub(crate) type Crossing = (usize, usize);

/// Distance on a circle of `c` from `q` to the arc `[lo, hi]` (mm).
fn to_arc(q: f64, lo: f64, hi: f64, c: f64) -> f64 {
    let mid = (lo + hi) / 2.0;
    let q0 = q + c * ((mid - q) / c).round();
    [q0 - c, q0, q0 + c]
        .into_iter()
        .map(|x| (lo - x).max(x - hi).max(0.0))
        .fold(f64::INFINITY, f64::min)
}

/// Distance on a circle of `c` between the arcs `a` and `b` (mm).
fn between_arcs(a: (f64, f64), b: (f64, f64), c: f64) -> f64 {
    to_arc(b.0, a.0, a.1, c)
        .min(to_arc(b.1, a.0, a.1, c))
        .min(to_arc(a.0, b.0, b.1, c))
}

/// The order and steps of the jogs `from[i] → to[i]` (unwrapped) on a circle of `c`, leads at
/// least `pitch` apart.
///
/// # Errors
/// The first pair of leads that would cross.
pub(crate) fn order(from: &[f64], to: &[f64], c: f64, pitch: f64) -> Result<Jogs, Crossing> {
    let n = from.len();
    let reach = pitch - 1e-9;
    let moves: Vec<bool> = (0..n)
        .map(|i| (to[i] - from[i]).abs() > MOVE_TOL_MM)
        .collect();
    let arc = |i: usize| (from[i].min(to[i]), from[i].max(to[i]));
    let mut after: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut indegree = vec![0usize; n];
    for i in (0..n).filter(|&i| moves[i]) {
        let (lo, hi) = arc(i);
        for j in (0..n).filter(|&j| j != i) {
            let hit_from = to_arc(from[j], lo, hi, c) < reach;
            let hit_to = to_arc(to[j], lo, hi, c) < reach;
            let (first, then) = match (hit_from, hit_to) {
                (true, true) => return Err((i, j)),
                (true, false) => (j, i),
                (false, true) => (i, j),
                (false, false) => continue,
            };
            if !after[first].contains(&then) {
                after[first].push(then);
                indegree[then] += 1;
            }
        }
    }
    let mut queue: VecDeque<usize> = (0..n).filter(|&i| indegree[i] == 0).collect();
    let mut topo = Vec::with_capacity(n);
    while let Some(i) = queue.pop_front() {
        topo.push(i);
        for &j in &after[i] {
            indegree[j] -= 1;
            if indegree[j] == 0 {
                queue.push_back(j);
            }
        }
    }
    if topo.len() < n {
        // A cycle: name two of its leads.
        let stuck: Vec<usize> = (0..n).filter(|&i| indegree[i] > 0).collect();
        let a = stuck[0];
        let b = stuck
            .iter()
            .copied()
            .find(|&b| after[a].contains(&b) || after[b].contains(&a))
            .unwrap_or(stuck[stuck.len() - 1]);
        return Err((a, b));
    }
    let mut step: Vec<Option<usize>> = vec![None; n];
    let mut before: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, later) in after.iter().enumerate() {
        for &j in later {
            before[j].push(i);
        }
    }
    for &i in topo.iter().filter(|&&i| moves[i]) {
        let mut s = before[i]
            .iter()
            .filter_map(|&p| step[p].map(|k| k + 1))
            .max()
            .unwrap_or(0);
        while (0..n).any(|m| step[m] == Some(s) && between_arcs(arc(i), arc(m), c) < reach) {
            s += 1;
        }
        step[i] = Some(s);
    }
    let steps = step.iter().flatten().map(|s| s + 1).max().unwrap_or(0);
    Ok(Jogs {
        to: to.to_vec(),
        step,
        steps,
    })
}

/// Assigns the leads at `from` (unwrapped) to `lanes` (any turn), keeping their order round
/// the tube: every cyclic shift is tried, with the winding that moves the leads least; among
/// those whose jogs can be ordered, the one with the least `score` of the targets wins, then
/// the one that moves the leads least. Shifts scoring above `bound` are not tried (a caller
/// comparing lane sets passes the best score it has).
///
/// # Errors
/// A crossing pair of the last shift tried, when no shift within the bound can be ordered.
pub(crate) fn assign(
    from: &[f64],
    lanes: &[f64],
    c: f64,
    pitch: f64,
    score: &dyn Fn(&[f64]) -> f64,
    bound: f64,
) -> Result<Jogs, Crossing> {
    let n = from.len();
    debug_assert_eq!(n, lanes.len());
    if n == 0 {
        return Ok(Jogs {
            to: Vec::new(),
            step: Vec::new(),
            steps: 0,
        });
    }
    let mut by_s: Vec<usize> = (0..n).collect();
    by_s.sort_by(|&a, &b| from[a].rem_euclid(c).total_cmp(&from[b].rem_euclid(c)));
    let mut q: Vec<f64> = lanes.iter().map(|s| s.rem_euclid(c)).collect();
    q.sort_by(f64::total_cmp);
    // Every shift's targets, scored; then the jogs ordered best first, until one can be.
    let mut shifts: Vec<(f64, f64, Vec<f64>)> = (0..n)
        .map(|k| {
            let delta: Vec<f64> = (0..n)
                .map(|i| {
                    let t = q[(i + k) % n] + c * ((i + k) / n) as f64;
                    t - from[by_s[i]].rem_euclid(c)
                })
                .collect();
            let winding = [-2.0, -1.0, 0.0, 1.0, 2.0]
                .into_iter()
                .min_by(|a, b| {
                    let worst =
                        |m: f64| delta.iter().map(|d| (d - m * c).abs()).fold(0.0, f64::max);
                    worst(*a).total_cmp(&worst(*b))
                })
                .unwrap_or(0.0);
            let mut to = vec![0.0; n];
            for (i, d) in delta.iter().enumerate() {
                let lead = by_s[i];
                let d = d - winding * c;
                to[lead] = if d.abs() <= MOVE_TOL_MM {
                    from[lead]
                } else {
                    from[lead] + d
                };
            }
            let cost: f64 = (0..n).map(|i| (to[i] - from[i]).abs()).sum();
            (score(&to), cost, to)
        })
        .collect();
    shifts.sort_by(|a, b| {
        let same = (a.0 - b.0).abs() <= 1e-12;
        if same {
            a.1.total_cmp(&b.1)
        } else {
            a.0.total_cmp(&b.0)
        }
    });
    let mut last_err = (0, 0);
    for (s, _, to) in &shifts {
        if *s > bound + 1e-12 {
            break;
        }
        match order(from, to, c, pitch) {
            Ok(jogs) => return Ok(jogs),
            Err(e) => last_err = e,
        }
    }
    Err(last_err)
}

/// The `x` of step `k` of `steps` spread evenly over `[x0, x1]` (mm): one step sits in the
/// middle, as a joint's own leads jog halfway along.
pub(crate) fn step_x(x0: f64, x1: f64, k: usize, steps: usize) -> f64 {
    if steps == 1 {
        return (x0 + x1) / 2.0;
    }
    let (k, n) = ((k + 1) as f64, (steps + 1) as f64);
    (x0 * (n - k) + x1 * k) / n
}

#[cfg(test)]
mod tests {
    use super::*;

    const C: f64 = 10.0;

    #[test]
    fn the_lead_ahead_jogs_first_and_disjoint_jogs_share_a_step() {
        // Two leads moving up by 1 mm, 0.5 mm apart: the one ahead (at 0.5) must go first.
        let j = order(&[0.0, 0.5], &[1.0, 1.5], C, 0.13).unwrap();
        assert_eq!(j.step, vec![Some(1), Some(0)]);
        assert_eq!(j.steps, 2);
        // Far apart: one step.
        let j = order(&[0.0, 5.0], &[1.0, 4.0], C, 0.13).unwrap();
        assert_eq!(j.step, vec![Some(0), Some(0)]);
        // A lead that stays where another must pass: they cross.
        assert!(order(&[0.0, 0.5], &[1.0, 0.5], C, 0.13).is_err());
    }

    #[test]
    fn assignment_keeps_the_order_and_moves_least() {
        let j = assign(&[0.2, 9.8], &[0.5, 9.5], C, 0.13, &|_| 0.0, f64::INFINITY).unwrap();
        assert!((j.to[0] - 0.5).abs() < 1e-12 && (j.to[1] - 9.5).abs() < 1e-12);
        // Seen across the seam: 9.8 is just below 0.2 round the tube.
        let j = assign(&[-0.2, 0.2], &[5.0, 0.0], C, 0.13, &|_| 0.0, f64::INFINITY).unwrap();
        let moved: f64 =
            j.to.iter()
                .zip([-0.2, 0.2])
                .map(|(t, f)| (t - f).abs())
                .sum();
        assert!((moved - 5.0).abs() < 1e-9, "{j:?}");
    }

    #[test]
    fn one_step_sits_halfway() {
        assert_eq!(step_x(2.0, 3.0, 0, 1), 2.5);
        assert!((step_x(0.0, 3.0, 1, 2) - 2.0).abs() < 1e-12);
    }
}
