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
    use super::Summary;

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
