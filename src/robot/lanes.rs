//! Where leads may run over a joint: its corridors, the arcs of its backbone beside its own
//! sensors that keep the clearance from every notch and from its U-traces, and the lanes in
//! them nearest the joint's neutral plane.
//!
//! In the joint's own frame (`s = 0` at its `+y`), a lead's centre must stay
//! `w/2 + clearance` from every notch's arc (the cut rule) and `w + clearance` from the arc its
//! U-traces span from arm to arm (the bridge closes it: a lead inside would cross it). What is
//! left are the corridors. Lanes in one corridor are a trace width plus the clearance apart
//! (the pitch). A lead at surface arc `s` sits at height `y = r_o·cos(s/r_o)` in the joint's
//! bending plane; it reads the joint's bending in proportion to `y − ȳ` (`docs/robots.md`), so
//! lanes are placed to make `Σ |y − ȳ|` least: on the surface lines `y = ȳ` where the backbone
//! reaches them, else as near as it allows.

use std::f64::consts::TAU;

use super::assemble::RobotJoint;

/// Corridors are shrunk by this on each side, so a lead on a corridor's edge keeps the
/// clearance despite rounding (mm): far below any feature, far above float noise.
const EDGE_MM: f64 = 1e-7;

/// Samples per corridor when placing a block of lanes, besides the exact candidates.
const SAMPLES: usize = 64;

/// An arc of the circle where a lane's centre may lie, `[lo, hi]` in `s` (mm), `lo ≤ hi`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Corridor {
    pub lo: f64,
    pub hi: f64,
}

impl Corridor {
    /// How many lanes `pitch_mm` apart fit.
    pub fn room(&self, pitch_mm: f64) -> usize {
        if self.hi < self.lo {
            0
        } else {
            ((self.hi - self.lo) / pitch_mm + 1e-9).floor() as usize + 1
        }
    }
}

/// The free arcs of a circle of `circumference_mm` that the `forbidden` arcs (unwrapped, any
/// turn) leave, each shrunk by [`EDGE_MM`]; arcs narrower than that vanish.
pub(crate) fn free_arcs(forbidden: &[(f64, f64)], circumference_mm: f64) -> Vec<Corridor> {
    let c = circumference_mm;
    if forbidden.is_empty() {
        return vec![Corridor {
            lo: 0.0,
            hi: c - EDGE_MM,
        }];
    }
    if forbidden.iter().any(|(a, b)| b - a >= c) {
        return Vec::new();
    }
    let mut arcs: Vec<(f64, f64)> = forbidden
        .iter()
        .map(|&(a, b)| {
            let start = a.rem_euclid(c);
            (start, start + (b - a))
        })
        .collect();
    arcs.sort_by(|p, q| p.0.total_cmp(&q.0));
    let first = arcs[0].0;
    let mut end = arcs[0].1;
    let mut out = Vec::new();
    let mut push = |lo: f64, hi: f64| {
        let (lo, hi) = (lo + EDGE_MM, hi - EDGE_MM);
        if hi >= lo {
            out.push(Corridor { lo, hi });
        }
    };
    for &(a, b) in &arcs[1..] {
        if a > end {
            push(end, a);
        }
        end = end.max(b);
    }
    if first + c > end {
        push(end, first + c);
    }
    out
}

/// The corridors over `joint` in its own frame: what its notches and U-traces leave, at
/// `cut_reach_mm` from notches and `pitch_mm` from its traces.
pub(crate) fn corridors(joint: &RobotJoint, pitch_mm: f64, cut_reach_mm: f64) -> Vec<Corridor> {
    let design = joint.design();
    let section = design.joint.section();
    let r_o = section.outer_radius_mm();
    let c = section.circumference_mm();
    let half_notch = section.notch_arc_mm() / 2.0;
    let half_sensor = section.sensor_arc_mm() / 2.0;
    let mut forbidden = Vec::new();
    for side in 0..design.joint.style().notches_per_level() as usize {
        let centre = if side == 0 {
            std::f64::consts::PI * r_o
        } else {
            0.0
        };
        forbidden.push((
            centre - half_notch - cut_reach_mm,
            centre + half_notch + cut_reach_mm,
        ));
    }
    for sensor in 0..joint.sensor_count() {
        let centre = if sensor == 0 {
            0.0
        } else {
            std::f64::consts::PI * r_o
        };
        forbidden.push((
            centre - half_sensor - pitch_mm,
            centre + half_sensor + pitch_mm,
        ));
    }
    free_arcs(&forbidden, c)
}

/// `|y − ȳ|` of a lane at `s` in a joint's frame (mm).
fn lane_cost(s: f64, r_o: f64, y_bar: f64) -> f64 {
    (r_o * (s / r_o).cos() - y_bar).abs()
}

/// The surface arcs where `y = ȳ`, copied by whole turns near `[lo, hi]`.
fn neutral_lines(r_o: f64, y_bar: f64, lo: f64, hi: f64) -> Vec<f64> {
    let phi = (y_bar / r_o).clamp(-1.0, 1.0).acos();
    let c = TAU * r_o;
    let mut out = Vec::new();
    for base in [r_o * phi, -r_o * phi] {
        let k0 = ((lo - base) / c).floor() as i64;
        for k in k0..=k0 + 2 {
            out.push(base + k as f64 * c);
        }
    }
    out.retain(|s| *s >= lo - c && *s <= hi + c);
    out
}

/// Where the first of `k` lanes `pitch` apart in `corridor` may lie, to try: the corridor's
/// ends, each lane on a line `y = ȳ`, and evenly spaced samples between; empty when they do
/// not fit.
fn block_candidates(corridor: Corridor, k: usize, pitch: f64, r_o: f64, y_bar: f64) -> Vec<f64> {
    if k == 0 {
        return vec![corridor.lo];
    }
    let span = (k - 1) as f64 * pitch;
    let (lo, hi) = (corridor.lo, corridor.hi - span);
    if hi < lo - 1e-12 {
        return Vec::new();
    }
    let hi = hi.max(lo);
    let mut candidates = vec![lo, hi];
    for s in neutral_lines(r_o, y_bar, lo, hi + span) {
        for m in 0..k {
            candidates.push((s - m as f64 * pitch).clamp(lo, hi));
        }
    }
    candidates.extend((0..=SAMPLES).map(|i| lo + (hi - lo) * i as f64 / SAMPLES as f64));
    candidates
}

/// `Σ |y − ȳ|` of `k` lanes `pitch` apart from `u`.
fn block_cost(u: f64, k: usize, pitch: f64, r_o: f64, y_bar: f64) -> f64 {
    (0..k)
        .map(|m| lane_cost(u + m as f64 * pitch, r_o, y_bar))
        .sum()
}

/// The least `Σ |y − ȳ|` of `k` lanes `pitch` apart in `corridor`, and where the first lies.
fn best_block(
    corridor: Corridor,
    k: usize,
    pitch: f64,
    r_o: f64,
    y_bar: f64,
) -> Option<(f64, f64)> {
    block_candidates(corridor, k, pitch, r_o, y_bar)
        .into_iter()
        .map(|u| (block_cost(u, k, pitch, r_o, y_bar), u))
        .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)))
}

/// Why `n` lanes do not fit over a joint.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NoRoom {
    /// How many fit.
    pub room: usize,
    /// The corridors' widths (mm).
    pub widths: Vec<f64>,
}

/// Lanes over one joint: its corridors (its own frame), how many lanes each holds, and where
/// each corridor's block of lanes starts; with the other starts worth trying.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LanePlan {
    pub corridors: Vec<Corridor>,
    pub counts: Vec<usize>,
    pub starts: Vec<f64>,
    pub candidates: Vec<Vec<f64>>,
    pitch: f64,
    rotation_s: f64,
    c: f64,
}

impl LanePlan {
    /// The lanes in the robot's `s` (mm), sorted, with the blocks starting at `starts`.
    pub fn lanes(&self, starts: &[f64]) -> Vec<f64> {
        let mut lanes = Vec::new();
        for (i, &k) in self.counts.iter().enumerate() {
            lanes.extend(
                (0..k).map(|m| {
                    (starts[i] + m as f64 * self.pitch + self.rotation_s).rem_euclid(self.c)
                }),
            );
        }
        lanes.sort_by(f64::total_cmp);
        lanes
    }
}

/// `n` lanes over `joint`: lanes are added one at a time to the corridor where the total
/// `Σ |y − ȳ|` grows least, each corridor's block placed where that sum is least.
pub(crate) fn plan_lanes(
    joint: &RobotJoint,
    n: usize,
    pitch_mm: f64,
    cut_reach_mm: f64,
) -> Result<LanePlan, NoRoom> {
    let corridors = corridors(joint, pitch_mm, cut_reach_mm);
    let room: usize = corridors.iter().map(|c| c.room(pitch_mm)).sum();
    let no_room = || NoRoom {
        room,
        widths: corridors.iter().map(|c| c.hi - c.lo).collect(),
    };
    if room < n {
        return Err(no_room());
    }
    let section = joint.design().joint.section();
    let (r_o, y_bar) = (section.outer_radius_mm(), section.neutral_axis_mm());
    let block = |i: usize, k: usize| best_block(corridors[i], k, pitch_mm, r_o, y_bar);
    let mut counts = vec![0usize; corridors.len()];
    for _ in 0..n {
        let pick = (0..corridors.len())
            .filter_map(|i| {
                let now = block(i, counts[i])?.0;
                let next = block(i, counts[i] + 1)?.0;
                Some((next - now, i))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        match pick {
            Some((_, i)) => counts[i] += 1,
            None => return Err(no_room()),
        }
    }
    let starts = (0..corridors.len())
        .map(|i| block(i, counts[i]).map_or(corridors[i].lo, |(_, u)| u))
        .collect();
    let candidates = (0..corridors.len())
        .map(|i| block_candidates(corridors[i], counts[i], pitch_mm, r_o, y_bar))
        .collect();
    Ok(LanePlan {
        corridors,
        counts,
        starts,
        candidates,
        pitch: pitch_mm,
        rotation_s: joint.s(0.0),
        c: section.circumference_mm(),
    })
}

/// Lanes for leads arriving at `arrivals` (sorted, increasing) in the interval `[lo, hi]`,
/// at least `pitch` apart, each as near its arrival as the others allow; `None` if they do
/// not fit.
pub(crate) fn lanes_near(arrivals: &[f64], lo: f64, hi: f64, pitch: f64) -> Option<Vec<f64>> {
    let n = arrivals.len();
    if n == 0 {
        return Some(Vec::new());
    }
    if lo + (n - 1) as f64 * pitch > hi + 1e-12 {
        return None;
    }
    let mut out: Vec<f64> = Vec::with_capacity(n);
    for (k, &a) in arrivals.iter().enumerate() {
        let floor = out.last().map_or(lo, |p| p + pitch);
        let ceiling = hi - (n - 1 - k) as f64 * pitch;
        out.push(a.max(floor).min(ceiling));
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn free_arcs_are_the_complement_round_the_circle() {
        let mut f = free_arcs(&[(-1.0, 1.0), (4.0, 6.0)], 10.0);
        f.sort_by(|a, b| a.lo.rem_euclid(10.0).total_cmp(&b.lo.rem_euclid(10.0)));
        assert_eq!(f.len(), 2);
        assert_relative_eq!(f[0].lo.rem_euclid(10.0), 1.0, epsilon = 1e-6);
        assert_relative_eq!(f[0].hi - f[0].lo, 3.0, epsilon = 1e-6);
        assert_relative_eq!(f[1].lo, 6.0, epsilon = 1e-6);
        assert_relative_eq!(f[1].hi, 9.0, epsilon = 1e-6);
        assert!(free_arcs(&[(0.0, 10.0)], 10.0).is_empty());
        assert_eq!(f[0].room(1.0), 3);
    }

    #[test]
    fn lanes_near_arrivals_keep_the_pitch_and_the_interval() {
        assert_eq!(
            lanes_near(&[0.0, 0.05, 3.0], 0.0, 2.0, 0.1).unwrap(),
            vec![0.0, 0.1, 2.0]
        );
        assert!(lanes_near(&[0.0, 0.0, 0.0], 0.0, 0.15, 0.1).is_none());
    }
}
