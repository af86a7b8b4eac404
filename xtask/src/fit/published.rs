//! The table a layout is fitted to: the paper's Table 1 (its rows 1 to 4, 6 and 7, as
//! csql's `Table1Row::paper` gives them), or a target read from a CSV of the same form.

use anyhow::{Context, Result, ensure};
use csql::StrategyKind;

use super::{Fitted, fitted_row};

/// A target table: per fitted row, one value per strategy (resetting, lazy, random,
/// eager).
#[derive(Clone, Debug, PartialEq)]
pub struct Target(pub Fitted<[f64; 4]>);

impl Target {
    /// The paper's Table 1.
    pub fn paper() -> Target {
        Target(Fitted::from_fn(|row| {
            StrategyKind::ALL.map(|k| row.paper(k).map_or(f64::NAN, |p| p.value()))
        }))
    }

    /// Parse a target CSV (see [`super::FitArgs::target`]).
    pub fn parse_csv(text: &str, source: &str) -> Result<Target> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, header) = lines
            .next()
            .with_context(|| format!("{source}: empty file"))?;
        let header: Vec<&str> = header.split(',').map(str::trim).collect();
        ensure!(
            header == ["row", "resetting", "lazy", "random", "eager"],
            "{source}:1: the header must be `row,resetting,lazy,random,eager`"
        );
        let mut rows: Fitted<Option<[f64; 4]>> = Fitted::from_fn(|_| None);
        for (i, line) in lines {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            ensure!(
                cells.len() == 5,
                "{source}:{}: expected 5 fields, found {}",
                i + 1,
                cells.len()
            );
            let row: usize = cells[0].parse().with_context(|| {
                format!("{source}:{}: `{}` is not a row number", i + 1, cells[0])
            })?;
            let Some(slot) = fitted_row(&row.to_string()).and_then(|r| rows.get_mut(r)) else {
                continue;
            };
            let mut values = [0.0; 4];
            for (j, cell) in cells[1..].iter().enumerate() {
                let v: f64 = cell
                    .parse()
                    .with_context(|| format!("{source}:{}: `{cell}` is not a number", i + 1))?;
                ensure!(
                    v.is_finite() && v > 0.0,
                    "{source}:{}: target values must be positive, found {v}",
                    i + 1
                );
                values[j] = v;
            }
            ensure!(
                slot.is_none(),
                "{source}:{}: row {row} appears twice",
                i + 1
            );
            *slot = Some(values);
        }
        for (row, values) in rows.iter() {
            values.with_context(|| format!("{source}: row {} is missing", row.number()))?;
        }
        let t = Fitted::try_from_fn(|row| rows.get(row).copied().flatten());
        Ok(Target(t.context("every fitted row is there")?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use csql::Table1Row;

    #[test]
    fn target_csv_round_trip_and_errors() {
        let csv = "row,resetting,lazy,random,eager\n1,1,2,3,4\n2,1,2,3,4\n3,1,2,3,4\n4,1,2,3,4\n5,50,50,50,50\n6,1,2,3,4\n7,1,2,3,5\n";
        let t = Target::parse_csv(csv, "t.csv").unwrap();
        assert_eq!(t.0.get(Table1Row::MaxFeatures), Some(&[1.0, 2.0, 3.0, 5.0]));
        let missing = csv.replace("7,1,2,3,5\n", "");
        let e = Target::parse_csv(&missing, "t.csv").unwrap_err();
        assert!(e.to_string().contains("row 7 is missing"), "{e}");
        let bad = csv.replace("2,1,2,3,4", "2,1,x,3,4");
        let e = Target::parse_csv(&bad, "t.csv").unwrap_err();
        assert!(e.to_string().contains("t.csv:3"), "{e}");
        assert!(Target::parse_csv("row,a\n", "t.csv").is_err());
    }
}
