//! The few statistics the analyses report.

/// Pearson's correlation coefficient of `x` and `y`, or `None` with fewer than 3 pairs or a
/// constant series.
pub fn pearson(x: &[f64], y: &[f64]) -> Option<f64> {
    let m = crate::fit::moments(x, y);
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

/// Least-squares slope of `y` on `x`: the fit's own ([`crate::fit::slope`]).
pub use crate::fit::slope;

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn known_values() {
        let x = [1.0, 2.0, 3.0, 4.0];
        assert_relative_eq!(pearson(&x, &[2.0, 4.0, 6.0, 8.0]).unwrap(), 1.0);
        assert_relative_eq!(pearson(&x, &[8.0, 6.0, 4.0, 2.0]).unwrap(), -1.0);
        assert_relative_eq!(pearson(&x, &[1.0, -1.0, -1.0, 1.0]).unwrap(), 0.0);
        assert!(pearson(&x, &[1.0; 4]).is_none());
        assert_relative_eq!(std_dev(&x).unwrap(), (5.0f64 / 3.0).sqrt());
        assert_relative_eq!(slope(&x, &[1.0, 3.0, 5.0, 7.0]).unwrap(), 2.0);
    }
}
