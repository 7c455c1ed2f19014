//! The Pareto front: the candidates no other candidate beats in every objective.

use std::cmp::Ordering;

/// `a` dominates `b` when it is at least as good in every objective and better in one (every
/// objective already signed so that larger is better).
pub fn dominates(a: &[f64], b: &[f64]) -> bool {
    let mut better = false;
    for (x, y) in a.iter().zip(b) {
        if x < y {
            return false;
        }
        better |= x > y;
    }
    better
}

/// Indices into `points` of the non-dominated points (larger is better in every coordinate),
/// in descending lexicographic order of their coordinates. Equal points are all kept.
///
/// Sorting first means no later point can dominate an earlier one, so each point is tested only
/// against the front found so far: `O(n log n + n·|front|)`.
pub fn front(points: &[Vec<f64>]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&i, &j| lexicographic_desc(&points[i], &points[j]));
    let mut out: Vec<usize> = Vec::new();
    for i in order {
        if !out.iter().any(|&f| dominates(&points[f], &points[i])) {
            out.push(i);
        }
    }
    out
}

/// Objectives closer than this, relative to the larger magnitude, are ties: the metrics come
/// out of closed-form geometry whose rounding differs by a few ulps between designs that are
/// the same in that objective (14 × 0.6 mm and 12 × 0.7 mm notches: the same range to 1e-14°),
/// far below anything a design can be told apart by.
pub const TIE_RELATIVE: f64 = 1e-9;

/// [`front`] with objectives within `relative` of each other taken as equal: each objective's
/// values are grouped, in sorted order, wherever consecutive values lie within `relative` of
/// each other, and every value of a group stands for the group's first. Values within
/// `relative` are always tied (a long chain of such steps is one group too).
pub fn front_with_ties(points: &[Vec<f64>], relative: f64) -> Vec<usize> {
    front(&tied(points, relative))
}

/// `points` with each coordinate replaced by its tie group's first value, as
/// [`front_with_ties`] groups them.
pub fn tied(points: &[Vec<f64>], relative: f64) -> Vec<Vec<f64>> {
    let mut out = points.to_vec();
    let dims = points.iter().map(Vec::len).max().unwrap_or(0);
    for d in 0..dims {
        let mut order: Vec<usize> = (0..points.len()).filter(|&i| d < points[i].len()).collect();
        order.sort_by(|&i, &j| points[i][d].total_cmp(&points[j][d]));
        let mut group: Option<f64> = None;
        let mut previous = f64::NAN;
        for i in order {
            let v = points[i][d];
            let joins = (v - previous).abs() <= relative * v.abs().max(previous.abs());
            let g = match group {
                Some(g) if joins => g,
                _ => v,
            };
            group = Some(g);
            previous = v;
            out[i][d] = g;
        }
    }
    out
}

fn lexicographic_desc(a: &[f64], b: &[f64]) -> Ordering {
    for (x, y) in a.iter().zip(b) {
        match y.total_cmp(x) {
            Ordering::Equal => continue,
            o => return o,
        }
    }
    Ordering::Equal
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The sweep equals the definition, checked pair by pair, on random points with ties.
        #[test]
        fn front_is_the_brute_force_front(
            points in proptest::collection::vec(proptest::collection::vec(0u8..6, 3), 0..60)
        ) {
            let p: Vec<Vec<f64>> = points
                .iter()
                .map(|v| v.iter().map(|&x| f64::from(x)).collect())
                .collect();
            let mut got = front(&p);
            got.sort_unstable();
            let want: Vec<usize> = (0..p.len())
                .filter(|&i| !(0..p.len()).any(|j| dominates(&p[j], &p[i])))
                .collect();
            prop_assert_eq!(got, want);
        }
    }

    /// Issue 30: two designs of the same total notch width (14 × 0.6 mm, 12 × 0.7 mm) have
    /// the same range and tendon force to 1 ulp; the less sensitive one stayed on the front
    /// because its range came out 1e-14° larger. Objectives within 1e-9 relative are ties.
    #[test]
    fn objectives_equal_to_1e_9_relative_are_ties() {
        let range = 31.25_f64;
        let force = -0.0425_f64;
        let points = vec![
            // sensitivity (Ω/°), range (°), −force (N/°): the less sensitive design.
            vec![140.0, range.next_up(), force],
            vec![152.0, range, force.next_down()],
            // Apart by more than the tie: a real trade-off, both kept.
            vec![100.0, range * (1.0 + 1e-6), force],
        ];
        let mut f = front_with_ties(&points, TIE_RELATIVE);
        f.sort_unstable();
        assert_eq!(f, [1, 2]);
    }

    proptest! {
        /// Moving every objective by less than the tie leaves the front as it was.
        #[test]
        fn a_perturbation_inside_the_tie_keeps_the_front(
            points in proptest::collection::vec(proptest::collection::vec(1u8..6, 3), 1..40),
            wobble in proptest::collection::vec(-1.0f64..1.0, 120),
        ) {
            let exact: Vec<Vec<f64>> = points
                .iter()
                .map(|v| v.iter().map(|&x| f64::from(x)).collect())
                .collect();
            let moved: Vec<Vec<f64>> = exact
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    v.iter()
                        .enumerate()
                        .map(|(j, x)| x * (1.0 + 1e-11 * wobble[(3 * i + j) % wobble.len()]))
                        .collect()
                })
                .collect();
            let mut a = front(&exact);
            let mut b = front_with_ties(&moved, TIE_RELATIVE);
            a.sort_unstable();
            b.sort_unstable();
            prop_assert_eq!(a, b);
        }
    }

    #[test]
    fn front_of_a_small_set() {
        let p = vec![
            vec![1.0, 5.0],
            vec![2.0, 4.0],
            vec![2.0, 3.0], // dominated by (2, 4)
            vec![0.5, 5.0], // dominated by (1, 5)
            vec![3.0, 1.0],
            vec![3.0, 1.0], // a tie: kept
        ];
        let mut f = front(&p);
        f.sort_unstable();
        assert_eq!(f, [0, 1, 4, 5]);
    }
}
