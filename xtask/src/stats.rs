//! Summary statistics over runs.

use csql::{RunReport, Table1Row};

/// Mean, sample standard deviation, minimum and maximum of some values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub n: usize,
    pub mean: f64,
    pub sd: f64,
    pub min: f64,
    pub max: f64,
}

impl Summary {
    /// `None` when there is no value.
    pub fn of(values: &[f64]) -> Option<Summary> {
        if values.is_empty() {
            return None;
        }
        let n = values.len();
        let mean = values.iter().sum::<f64>() / n as f64;
        let sd = if n > 1 {
            (values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
        } else {
            0.0
        };
        let min = values.iter().copied().fold(f64::INFINITY, f64::min);
        let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Some(Summary {
            n,
            mean,
            sd,
            min,
            max,
        })
    }

    /// `mean ± sd [min–max]` with `decimals` digits.
    pub fn show(&self, decimals: usize) -> String {
        format!(
            "{:.d$} ± {:.d$} [{:.d$}–{:.d$}]",
            self.mean,
            self.sd,
            self.min,
            self.max,
            d = decimals
        )
    }
}

/// `P(|T| < t)` for Student's t with `df` degrees of freedom (at least 1), by the finite
/// series of integer degrees of freedom (Abramowitz and Stegun 26.7.3 and 26.7.4).
fn t_within(t: f64, df: usize) -> f64 {
    let theta = (t / (df as f64).sqrt()).atan();
    let (sin, cos2) = (theta.sin(), theta.cos().powi(2));
    // The sum's terms: each the last times cos^2 and the next ratio of the products.
    let mut term = 1.0;
    let mut sum = 1.0;
    if df % 2 == 1 {
        if df == 1 {
            return theta * std::f64::consts::FRAC_2_PI;
        }
        // theta + sin cos (1 + 2/3 cos^2 + 2 4/(3 5) cos^4 + ...), up to cos^(df - 2).
        for k in (2..df - 1).step_by(2) {
            term *= cos2 * k as f64 / (k + 1) as f64;
            sum += term;
        }
        (theta + sin * theta.cos() * sum) * std::f64::consts::FRAC_2_PI
    } else {
        // sin (1 + 1/2 cos^2 + 1 3/(2 4) cos^4 + ...), up to cos^(df - 2).
        for k in (1..df - 1).step_by(2) {
            term *= cos2 * k as f64 / (k + 1) as f64;
            sum += term;
        }
        sin * sum
    }
}

/// The half-width of the 95% interval of the mean of `values` by Student's t: the t
/// quantile of 0.975 with `n - 1` degrees of freedom times the sample standard deviation
/// over the square root of `n`; `None` for fewer than two values.
pub fn ci95(values: &[f64]) -> Option<f64> {
    let s = Summary::of(values)?;
    if s.n < 2 {
        return None;
    }
    // The quantile by bisection: P(|T| < t) rises with t, from 0 to 1.
    let (mut lo, mut hi) = (0.0_f64, 1000.0_f64);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if t_within(mid, s.n - 1) < 0.95 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi) * s.sd / (s.n as f64).sqrt())
}

/// Table 1's rows as the reproduction prints them: csql's one definition of the rows
/// (number, label, the paper's value, where ours comes from), with the decimals of a
/// mean over runs (a mean of counts gets one).
pub(crate) fn rows() -> impl Iterator<Item = (String, usize, Table1Row)> {
    Table1Row::ALL.into_iter().map(|row| {
        let decimals = match row {
            Table1Row::TrialsToSufficient
            | Table1Row::Trials
            | Table1Row::Descriptions
            | Table1Row::MaxFeatures => 1,
            _ => row.decimals(),
        };
        (format!("{} {}", row.number(), row.label()), decimals, row)
    })
}

/// Mean, spread and range of one row over runs (the runs that reached it).
pub(crate) fn summary<R: std::borrow::Borrow<RunReport>>(
    runs: &[R],
    row: Table1Row,
) -> Option<Summary> {
    let values: Vec<f64> = runs
        .iter()
        .filter_map(|r| row.of(&r.borrow().table1))
        .collect();
    Summary::of(&values)
}

#[cfg(test)]
mod tests {
    use super::{Summary, ci95};

    #[test]
    fn the_interval_is_students() {
        // sd 1 and n values: the half-width is the t quantile over sqrt(n); the quantiles
        // of 0.975 from the tables, with 1, 2, 4, 19 and 99 degrees of freedom.
        for (n, t) in [
            (2, 12.706205),
            (3, 4.302653),
            (5, 2.776445),
            (20, 2.093024),
            (100, 1.984217),
        ] {
            let values: Vec<f64> = (0..n).map(f64::from).collect();
            let sd = Summary::of(&values).unwrap().sd;
            let w = ci95(&values).unwrap() * f64::from(n).sqrt() / sd;
            assert!((w - t).abs() < 1e-5, "{n} values: {w} against {t}");
        }
        assert_eq!(ci95(&[1.0]), None);
        assert_eq!(ci95(&[0.5, 0.5, 0.5]), Some(0.0));
    }

    #[test]
    fn summary_of_known_values() {
        let s = Summary::of(&[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert_eq!((s.n, s.mean, s.min, s.max), (4, 2.5, 1.0, 4.0));
        assert!((s.sd - 1.2909944487358056).abs() < 1e-12);
        assert_eq!(s.show(1), "2.5 ± 1.3 [1.0–4.0]");
        assert!(Summary::of(&[]).is_none());
        assert_eq!(Summary::of(&[5.0]).unwrap().sd, 0.0);
    }
}
