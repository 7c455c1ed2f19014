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
