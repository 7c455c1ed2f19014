//! The shared statistics: [`min_max`], [`moments`], [`slope`], [`rmse`], [`median`], and
//! linear interpolation in a time series ([`interpolate`], [`interpolate_held`]).
//!
//! # NaN policy (one for every function here)
//! A value that is not finite (NaN, ±∞) is **skipped**, and in the paired functions
//! ([`moments`], [`slope`], [`rmse`]) the whole pair is skipped when either of its values is not
//! finite. Pairs are taken over the two slices' common length. A statistic with nothing left to
//! compute it from says so in its type: [`min_max`] returns `(∞, −∞)` (an empty range, which
//! `lo <= hi` rejects), [`median`] and [`slope`] return `None`, [`moments`] returns `n = 0` with
//! NaN means, and [`rmse`] returns 0. So a gap marked by NaN, or an invalid tracker sample,
//! never turns a statistic into NaN; a caller that must refuse non-finite input checks it
//! before (the recording reader does).

/// Smallest and largest finite value; `(∞, −∞)` when there is none.
pub fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter()
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        })
}

/// The means and centred sums of squares and products of the finite pairs of `x` and `y`:
/// what a regression line and a correlation coefficient are made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Moments {
    /// Pairs used.
    pub n: usize,
    /// Mean of `x` (NaN when `n = 0`).
    pub mean_x: f64,
    /// Mean of `y` (NaN when `n = 0`).
    pub mean_y: f64,
    /// `Σ(x − x̄)²`.
    pub sxx: f64,
    /// `Σ(y − ȳ)²`.
    pub syy: f64,
    /// `Σ(x − x̄)(y − ȳ)`.
    pub sxy: f64,
}

fn finite_pairs<'a>(x: &'a [f64], y: &'a [f64]) -> impl Iterator<Item = (f64, f64)> + 'a {
    x.iter()
        .zip(y)
        .map(|(&a, &b)| (a, b))
        .filter(|(a, b)| a.is_finite() && b.is_finite())
}

/// [`Moments`] of the finite pairs of `x` and `y` (two passes: means, then centred sums).
pub fn moments(x: &[f64], y: &[f64]) -> Moments {
    let (mut n, mut sum_x, mut sum_y) = (0usize, 0.0, 0.0);
    for (a, b) in finite_pairs(x, y) {
        n += 1;
        sum_x += a;
        sum_y += b;
    }
    let nf = n as f64;
    let (mean_x, mean_y) = (sum_x / nf, sum_y / nf);
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for (a, b) in finite_pairs(x, y) {
        let (dx, dy) = (a - mean_x, b - mean_y);
        sxx += dx * dx;
        syy += dy * dy;
        sxy += dx * dy;
    }
    Moments {
        n,
        mean_x,
        mean_y,
        sxx,
        syy,
        sxy,
    }
}

/// Least-squares slope of `y` on `x` over the finite pairs, or `None` when fewer than two pairs
/// are left or `x` does not vary.
pub fn slope(x: &[f64], y: &[f64]) -> Option<f64> {
    let m = moments(x, y);
    (m.n >= 2 && m.sxx > 0.0).then(|| m.sxy / m.sxx)
}

/// `√(mean((a − b)²))` over the finite pairs (0 for none).
pub fn rmse(a: &[f64], b: &[f64]) -> f64 {
    let (mut n, mut sum) = (0usize, 0.0);
    for (x, y) in finite_pairs(a, b) {
        n += 1;
        sum += (x - y) * (x - y);
    }
    if n == 0 {
        return 0.0;
    }
    (sum / n as f64).sqrt()
}

/// The median of the finite values (the mean of the middle two for an even count), or `None`
/// when there is none. `v` is not reordered.
pub fn median(v: &[f64]) -> Option<f64> {
    let mut f: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    if f.is_empty() {
        return None;
    }
    f.sort_by(f64::total_cmp);
    let n = f.len();
    Some(if n % 2 == 1 {
        f[n / 2]
    } else {
        0.5 * (f[n / 2 - 1] + f[n / 2])
    })
}

/// The median absolute deviation from the median of the finite values (not scaled to a
/// standard deviation), or `None` when there is none.
pub fn median_abs_deviation(v: &[f64]) -> Option<f64> {
    let m = median(v)?;
    let dev: Vec<f64> = v
        .iter()
        .filter(|x| x.is_finite())
        .map(|x| (x - m).abs())
        .collect();
    median(&dev)
}

/// Pearson's correlation coefficient of `x` and `y`, or `None` with fewer than 3 pairs or a
/// constant series.
pub fn pearson(x: &[f64], y: &[f64]) -> Option<f64> {
    let m = moments(x, y);
    if m.n < 3 {
        return None;
    }
    let r = m.sxy / (m.sxx * m.syy).sqrt();
    r.is_finite().then_some(r)
}

/// Sample standard deviation (`n − 1`), or `None` under 2 values.
pub fn std_dev(v: &[f64]) -> Option<f64> {
    let n = v.len();
    if n < 2 {
        return None;
    }
    let mean = v.iter().sum::<f64>() / n as f64;
    let ss: f64 = v.iter().map(|x| (x - mean) * (x - mean)).sum();
    Some((ss / (n - 1) as f64).sqrt())
}

/// `values` (at increasing `time_s`) linearly interpolated at `t`; `None` outside
/// `[time_s[0], time_s[last]]` or for an empty series. At a sample's own time, its value.
///
/// The interpolation is not subject to the NaN policy above: it returns what lies between the
/// two samples around `t`, as they are.
pub fn interpolate(time_s: &[f64], values: &[f64], t: f64) -> Option<f64> {
    let (&first, &last) = (time_s.first()?, time_s.last()?);
    if !(first..=last).contains(&t) {
        return None;
    }
    // The first sample at or after t.
    let i = time_s.partition_point(|&x| x < t);
    if time_s[i] == t || i == 0 {
        return values.get(i).copied();
    }
    let (t0, t1) = (time_s[i - 1], time_s[i]);
    let w = (t - t0) / (t1 - t0);
    Some(values[i - 1] + w * (values[i] - values[i - 1]))
}

/// As [`interpolate`], with the first value held before the series and the last after it;
/// `None` only for an empty series.
pub fn interpolate_held(time_s: &[f64], values: &[f64], t: f64) -> Option<f64> {
    let (&first, &last) = (time_s.first()?, time_s.last()?);
    if t < first {
        values.first().copied()
    } else if t > last {
        values.get(time_s.len() - 1).copied()
    } else {
        interpolate(time_s, values, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_inside_and_refuses_outside() {
        let t = [0.0, 1.0, 2.0];
        let v = [0.0, 10.0, 30.0];
        let table = [
            (0.0, Some(0.0)),
            (0.25, Some(2.5)),
            (1.0, Some(10.0)),
            (1.5, Some(20.0)),
            (2.0, Some(30.0)),
            (-0.1, None),
            (2.1, None),
        ];
        for (x, want) in table {
            assert_eq!(interpolate(&t, &v, x), want, "{x}");
        }
        assert_eq!(interpolate(&[], &[], 0.0), None);
    }

    #[test]
    fn interpolation_between_at_and_beyond_the_samples() {
        let (t, v) = ([0.0, 1.0, 3.0], [10.0, 20.0, 0.0]);
        assert_eq!(interpolate(&t, &v, 0.5), Some(15.0));
        assert_eq!(interpolate(&t, &v, 2.0), Some(10.0));
        assert_eq!(interpolate(&t, &v, 1.0), Some(20.0));
        assert_eq!(interpolate(&t, &v, 3.0), Some(0.0));
        assert_eq!(interpolate(&t, &v, -0.1), None);
        assert_eq!(interpolate(&t, &v, 3.1), None);
        assert_eq!(interpolate(&t, &v, f64::NAN), None);
        assert_eq!(interpolate(&[], &[], 0.0), None);
        assert_eq!(interpolate_held(&t, &v, -5.0), Some(10.0));
        assert_eq!(interpolate_held(&t, &v, 5.0), Some(0.0));
        assert_eq!(interpolate_held(&t, &v, 2.0), Some(10.0));
        assert_eq!(interpolate_held(&[], &[], 2.0), None);
    }

    const NAN: f64 = f64::NAN;
    const INF: f64 = f64::INFINITY;

    #[test]
    fn min_max_skips_nan_and_infinities_alike() {
        assert_eq!(min_max(&[3.0, NAN, -1.0, INF, 2.0, -INF]), (-1.0, 3.0));
        let (lo, hi) = min_max(&[NAN, INF]);
        assert!(lo > hi, "no finite value gives an empty range");
    }

    #[test]
    fn moments_slope_and_rmse_skip_non_finite_pairs() {
        let x = [0.0, 1.0, 2.0, NAN, 3.0, 4.0];
        let y = [1.0, 3.0, 5.0, 100.0, INF, 9.0];
        let m = moments(&x, &y);
        assert_eq!(m.n, 4);
        assert!((m.mean_x - 7.0 / 4.0).abs() < 1e-12);
        assert_eq!(slope(&x, &y), Some(2.0));
        let fit: Vec<f64> = x.iter().map(|v| 1.0 + 2.0 * v).collect();
        assert_eq!(rmse(&fit, &y), 0.0);
        assert!((rmse(&[0.0, 0.0, NAN], &[3.0, 4.0, 1.0]) - (12.5f64).sqrt()).abs() < 1e-12);
        assert_eq!(slope(&[1.0, 1.0], &[0.0, 5.0]), None);
        assert_eq!(moments(&[NAN], &[1.0]).n, 0);
    }

    #[test]
    fn medians_of_finite_values() {
        assert_eq!(median(&[5.0, NAN, 1.0, 3.0]), Some(3.0));
        assert_eq!(median(&[4.0, 1.0, INF, 3.0, 2.0]), Some(2.5));
        assert_eq!(median(&[NAN]), None);
        assert_eq!(
            median_abs_deviation(&[1.0, 2.0, 3.0, 4.0, 100.0]),
            Some(1.0)
        );
    }

    #[test]
    fn pearson_std_dev_and_slope_known_values() {
        use approx::assert_relative_eq;
        let x = [1.0, 2.0, 3.0, 4.0];
        assert_relative_eq!(pearson(&x, &[2.0, 4.0, 6.0, 8.0]).unwrap(), 1.0);
        assert_relative_eq!(pearson(&x, &[8.0, 6.0, 4.0, 2.0]).unwrap(), -1.0);
        assert_relative_eq!(pearson(&x, &[1.0, -1.0, -1.0, 1.0]).unwrap(), 0.0);
        assert!(pearson(&x, &[1.0; 4]).is_none());
        assert_relative_eq!(std_dev(&x).unwrap(), (5.0f64 / 3.0).sqrt());
        assert_relative_eq!(slope(&x, &[1.0, 3.0, 5.0, 7.0]).unwrap(), 2.0);
    }
}
