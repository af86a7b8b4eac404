//! What a classification costs: test prices with groups and discounts (Turney's cost
//! files), and misclassification costs.

use std::path::Path;

use crate::Error;

/// The price of one test.
///
/// ```
/// let blood = cslearn::testcost::TestPrice { full: 7.27, discount: 5.17, group: Some(0), delayed: true };
/// assert!(blood.discount < blood.full);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TestPrice {
    /// The price when no other test of its group was bought for the object.
    pub full: f64,
    /// The price when another test of its group was bought before it (equal to `full`
    /// for a test in no group).
    pub discount: f64,
    /// Its group, an index into [`TestPrices::group_names`].
    pub group: Option<u32>,
    /// Whether its result comes later (reported, never priced).
    pub delayed: bool,
}

/// The prices of every test of a [`Frame`](super::Frame), one per feature in column
/// order, with Turney's groups: the first test of a group ordered for an object is paid
/// in full, every later one of the same group at its discount price, and a test already
/// done costs nothing again.
///
/// ```
/// use cslearn::testcost::{Basket, TestPrices};
/// let prices = TestPrices::flat(&[1.0, 10.0]).unwrap();
/// let mut basket = Basket::new(&prices);
/// assert_eq!(basket.price(&prices, 1), 10.0);
/// basket.buy(&prices, 1);
/// assert_eq!(basket.price(&prices, 1), 0.0);
/// assert_eq!(prices.total(), 11.0);
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TestPrices {
    tests: Vec<TestPrice>,
    group_names: Vec<String>,
}

fn check_price(value: f64, what: &str) -> Result<(), Error> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(Error::Invalid {
            what: what.to_string(),
            reason: format!("price {value}: prices must be finite and not negative"),
        })
    }
}

impl TestPrices {
    /// One price per test, no groups.
    ///
    /// ```
    /// assert!(cslearn::testcost::TestPrices::flat(&[1.0, f64::NAN]).is_err());
    /// ```
    pub fn flat(prices: &[f64]) -> Result<TestPrices, Error> {
        TestPrices::new(
            prices
                .iter()
                .map(|&p| TestPrice {
                    full: p,
                    discount: p,
                    group: None,
                    delayed: false,
                })
                .collect(),
            Vec::new(),
        )
    }

    /// Flat prices the caller knows to be finite and not negative.
    pub(crate) fn flat_checked_by_caller(prices: &[f64]) -> TestPrices {
        TestPrices {
            tests: prices
                .iter()
                .map(|&p| TestPrice {
                    full: p,
                    discount: p,
                    group: None,
                    delayed: false,
                })
                .collect(),
            group_names: Vec::new(),
        }
    }

    /// Prices with groups, checked: finite, not negative, groups named.
    ///
    /// ```
    /// use cslearn::testcost::{TestPrice, TestPrices};
    /// let t = |full, discount| TestPrice { full, discount, group: Some(0), delayed: false };
    /// let prices = TestPrices::new(vec![t(10.0, 8.0), t(5.0, 3.0)], vec!["A".into()]).unwrap();
    /// assert_eq!(prices.total(), 13.0); // 10 for the first, 3 for the second
    /// assert!(TestPrices::new(vec![t(1.0, 1.0)], vec![]).is_err()); // group 0 has no name
    /// ```
    pub fn new(tests: Vec<TestPrice>, group_names: Vec<String>) -> Result<TestPrices, Error> {
        for (i, t) in tests.iter().enumerate() {
            check_price(t.full, &format!("test {i}"))?;
            check_price(t.discount, &format!("test {i}"))?;
            if let Some(g) = t.group
                && g as usize >= group_names.len()
            {
                return Err(Error::Invalid {
                    what: format!("test {i}"),
                    reason: format!("group {g}, but only {} groups", group_names.len()),
                });
            }
        }
        Ok(TestPrices { tests, group_names })
    }

    /// The number of tests.
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::TestPrices::flat(&[1.0]).unwrap().len(), 1);
    /// ```
    pub fn len(&self) -> usize {
        self.tests.len()
    }

    /// Whether there are no tests.
    ///
    /// ```
    /// assert!(cslearn::testcost::TestPrices::flat(&[]).unwrap().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.tests.is_empty()
    }

    /// Test `test`'s price entry.
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::TestPrices::flat(&[4.0]).unwrap().test(0).full, 4.0);
    /// ```
    pub fn test(&self, test: usize) -> &TestPrice {
        &self.tests[test]
    }

    /// The group names.
    ///
    /// ```
    /// assert!(cslearn::testcost::TestPrices::flat(&[4.0]).unwrap().group_names().is_empty());
    /// ```
    pub fn group_names(&self) -> &[String] {
        &self.group_names
    }

    /// The price of every test bought for one object, discounts applied: for each group,
    /// the cheapest order (the test that saves least by its discount bought first).
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::TestPrices::flat(&[1.0, 2.5]).unwrap().total(), 3.5);
    /// ```
    pub fn total(&self) -> f64 {
        let mut sum = 0.0;
        let mut first_extra = vec![f64::INFINITY; self.group_names.len()];
        for t in &self.tests {
            match t.group {
                None => sum += t.full,
                Some(g) => {
                    sum += t.discount;
                    let extra = &mut first_extra[g as usize];
                    *extra = extra.min(t.full - t.discount);
                }
            }
        }
        sum + first_extra.iter().filter(|x| x.is_finite()).sum::<f64>()
    }

    /// The same groups with new full prices (`full[i]` for test i) and every discount
    /// moved by the same amount as its full price (kept at least 0): the biased prices
    /// ICET's search proposes.
    ///
    /// ```
    /// let prices = cslearn::testcost::TestPrices::flat(&[1.0, 2.0]).unwrap();
    /// assert_eq!(prices.repriced(&[5.0, 0.0]).unwrap().total(), 5.0);
    /// ```
    pub fn repriced(&self, full: &[f64]) -> Result<TestPrices, Error> {
        if full.len() != self.tests.len() {
            return Err(Error::Invalid {
                what: "prices".into(),
                reason: format!("{} prices for {} tests", full.len(), self.tests.len()),
            });
        }
        let tests = self
            .tests
            .iter()
            .zip(full)
            .map(|(t, &f)| TestPrice {
                full: f,
                discount: (t.discount + f - t.full).max(0.0),
                ..*t
            })
            .collect();
        TestPrices::new(tests, self.group_names.clone())
    }

    /// Prices in Turney's (1995) format for the features `names` (a frame's feature
    /// names): `base` is the path without extension (`costs/heart-disease`), from which
    /// `.expense` (full and discount prices) is read, or `.cost` where there is no
    /// `.expense`, with `.group` and `.delay` where present. `extra` holds more lines in
    /// the same formats (for a feature the files leave out), read after the files.
    /// A name that is not a feature, a feature with no price, a bad or negative price, a
    /// grouped test without a discount price, or an unknown group is refused, naming the
    /// file and line.
    ///
    /// ```no_run
    /// let names: Vec<String> = ["age", "sex"].map(String::from).to_vec();
    /// let prices = cslearn::testcost::TestPrices::read_turney(
    ///     std::path::Path::new("data/uci/heart-disease/costs/heart-disease"), &names, &Default::default());
    /// ```
    pub fn read_turney(
        base: &Path,
        names: &[String],
        extra: &TurneyExtra,
    ) -> Result<TestPrices, Error> {
        let read = |ext: &str| -> Result<Option<(std::path::PathBuf, String)>, Error> {
            let path = base.with_extension(ext);
            if !path.exists() {
                return Ok(None);
            }
            std::fs::read_to_string(&path)
                .map(|text| Some((path.clone(), text)))
                .map_err(|source| Error::Io { path, source })
        };
        let expense = read("expense")?;
        let cost = if expense.is_none() {
            read("cost")?
        } else {
            None
        };
        let Some((price_path, price_text)) = expense.clone().or(cost) else {
            return Err(Error::BadInput {
                path: base.to_path_buf(),
                at: "files".into(),
                reason: "neither a .expense nor a .cost file".into(),
            });
        };
        let mut full: Vec<Option<(f64, Option<f64>)>> = vec![None; names.len()];
        let feature = |path: &Path, line: usize, name: &str| -> Result<usize, Error> {
            names
                .iter()
                .position(|n| n == name)
                .ok_or_else(|| Error::BadInput {
                    path: path.to_path_buf(),
                    at: format!("line {line}"),
                    reason: format!(
                        "`{name}` is not a column of the data (columns: {})",
                        names.join(", ")
                    ),
                })
        };
        let sources = [
            (price_path.clone(), price_text),
            (price_path.with_extension("extra"), extra.prices.clone()),
        ];
        for (path, text) in &sources {
            for (line, name, value) in entries(text) {
                let at = || format!("line {line}");
                let i = feature(path, line, name)?;
                let numbers: Vec<&str> = value.split(',').map(str::trim).collect();
                let parse = |cell: &str| -> Result<f64, Error> {
                    cell.parse::<f64>()
                        .ok()
                        .filter(|x| x.is_finite() && *x >= 0.0)
                        .ok_or_else(|| Error::BadInput {
                            path: path.clone(),
                            at: at(),
                            reason: format!(
                                "the price of `{name}` is `{cell}`, but prices must be finite, non-negative numbers"
                            ),
                        })
                };
                let entry = match numbers.as_slice() {
                    [f] => (parse(f)?, None),
                    [f, d] => (parse(f)?, Some(parse(d)?)),
                    _ => {
                        return Err(Error::BadInput {
                            path: path.clone(),
                            at: at(),
                            reason: format!(
                                "`{value}`: a price line is `name: full` or `name: full, discount`"
                            ),
                        });
                    }
                };
                if full[i].is_some() {
                    return Err(Error::BadInput {
                        path: path.clone(),
                        at: at(),
                        reason: format!("a second price for `{name}`"),
                    });
                }
                full[i] = Some(entry);
            }
        }
        if let Some(i) = full.iter().position(Option::is_none) {
            return Err(Error::BadInput {
                path: price_path,
                at: "end of file".into(),
                reason: format!("no price for column `{}`", names[i]),
            });
        }
        let mut group_names: Vec<String> = Vec::new();
        let mut group: Vec<Option<u32>> = vec![None; names.len()];
        let group_file = read("group")?;
        let mut group_sources: Vec<(std::path::PathBuf, String)> = group_file.into_iter().collect();
        group_sources.push((base.with_extension("group.extra"), extra.groups.clone()));
        for (n, (path, text)) in group_sources.iter().enumerate() {
            let mut lines = text
                .lines()
                .enumerate()
                .filter(|(_, l)| !l.trim().is_empty());
            if n == 0
                && let Some((_, first)) = lines.clone().next()
                && !first.contains(':')
            {
                lines.next();
                group_names.extend(
                    first
                        .trim()
                        .trim_end_matches('.')
                        .split(',')
                        .map(|g| g.trim().to_string())
                        .filter(|g| !g.is_empty()),
                );
            }
            for (line, name, value) in entries(text) {
                let i = feature(path, line, name)?;
                let g = value.trim_end_matches('.').trim();
                let Some(code) = group_names.iter().position(|n| n == g) else {
                    return Err(Error::BadInput {
                        path: path.clone(),
                        at: format!("line {line}"),
                        reason: format!(
                            "group `{g}` of `{name}` is not among the groups listed on the first line ({})",
                            group_names.join(", ")
                        ),
                    });
                };
                group[i] = Some(code as u32);
                if full[i].is_some_and(|(_, d)| d.is_none()) {
                    return Err(Error::BadInput {
                        path: path.clone(),
                        at: format!("line {line}"),
                        reason: format!(
                            "`{name}` is in group `{g}` but {} gives it no discount price (`name: full, discount`)",
                            price_path.display()
                        ),
                    });
                }
            }
        }
        let mut delayed = vec![false; names.len()];
        if let Some((path, text)) = read("delay")? {
            for (line, name, value) in entries(&text) {
                let i = feature(&path, line, name)?;
                delayed[i] = match value.trim_end_matches('.').trim() {
                    "immediate" => false,
                    "delayed" => true,
                    other => {
                        return Err(Error::BadInput {
                            path: path.clone(),
                            at: format!("line {line}"),
                            reason: format!("`{other}`: a delay is `immediate` or `delayed`"),
                        });
                    }
                };
            }
        }
        let tests = full
            .into_iter()
            .zip(group)
            .zip(delayed)
            .map(|((price, group), delayed)| {
                let (full, discount) = price.unwrap_or((0.0, None));
                TestPrice {
                    full,
                    discount: discount.unwrap_or(full),
                    group,
                    delayed,
                }
            })
            .collect();
        TestPrices::new(tests, group_names)
    }
}

/// Lines added to Turney's files by the caller, in the same formats: `prices` as in
/// `.expense` or `.cost`, `groups` as the `name: group.` lines of `.group`.
///
/// ```
/// let extra = cslearn::testcost::TurneyExtra { prices: "FTI: 23.82, 21.72".into(), groups: "FTI: A.".into() };
/// assert!(extra.groups.contains("FTI"));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TurneyExtra {
    /// More price lines.
    pub prices: String,
    /// More group lines.
    pub groups: String,
}

/// The `name: value` lines of a Turney file, with their 1-based line numbers.
fn entries(text: &str) -> impl Iterator<Item = (usize, &str, &str)> {
    text.lines().enumerate().filter_map(|(i, line)| {
        let (name, value) = line.split_once(':')?;
        Some((i + 1, name.trim(), value.trim()))
    })
}

/// The tests bought so far for one object, to price the next one.
///
/// ```
/// use cslearn::testcost::{Basket, TestPrice, TestPrices};
/// let t = |full, discount| TestPrice { full, discount, group: Some(0), delayed: false };
/// let prices = TestPrices::new(vec![t(10.0, 8.0), t(5.0, 3.0)], vec!["A".into()]).unwrap();
/// let mut basket = Basket::new(&prices);
/// assert_eq!(basket.buy(&prices, 1), 5.0);  // the first of group A: full price
/// assert_eq!(basket.buy(&prices, 0), 8.0);  // the second: discount
/// assert_eq!(basket.buy(&prices, 0), 0.0);  // already done
/// assert_eq!(basket.spent(), 13.0);
/// ```
#[derive(Clone, Debug)]
pub struct Basket {
    bought: Vec<bool>,
    groups: Vec<u32>,
    spent: f64,
}

impl Basket {
    /// An empty basket for these prices.
    ///
    /// ```
    /// let prices = cslearn::testcost::TestPrices::flat(&[1.0]).unwrap();
    /// assert_eq!(cslearn::testcost::Basket::new(&prices).spent(), 0.0);
    /// ```
    pub fn new(prices: &TestPrices) -> Basket {
        Basket {
            bought: vec![false; prices.len()],
            groups: vec![0; prices.group_names.len()],
            spent: 0.0,
        }
    }

    /// What test `test` would cost now.
    ///
    /// ```
    /// let prices = cslearn::testcost::TestPrices::flat(&[2.0]).unwrap();
    /// assert_eq!(cslearn::testcost::Basket::new(&prices).price(&prices, 0), 2.0);
    /// ```
    pub fn price(&self, prices: &TestPrices, test: usize) -> f64 {
        if self.bought[test] {
            return 0.0;
        }
        let t = &prices.tests[test];
        match t.group {
            Some(g) if self.groups[g as usize] > 0 => t.discount,
            _ => t.full,
        }
    }

    /// Whether test `test` was bought.
    ///
    /// ```
    /// let prices = cslearn::testcost::TestPrices::flat(&[2.0]).unwrap();
    /// assert!(!cslearn::testcost::Basket::new(&prices).has(0));
    /// ```
    pub fn has(&self, test: usize) -> bool {
        self.bought[test]
    }

    /// Buys test `test` and returns what it cost (0 if it was bought already).
    ///
    /// ```
    /// let prices = cslearn::testcost::TestPrices::flat(&[2.0]).unwrap();
    /// let mut basket = cslearn::testcost::Basket::new(&prices);
    /// assert_eq!((basket.buy(&prices, 0), basket.buy(&prices, 0)), (2.0, 0.0));
    /// ```
    pub fn buy(&mut self, prices: &TestPrices, test: usize) -> f64 {
        let price = self.price(prices, test);
        if !self.bought[test] {
            self.bought[test] = true;
            if let Some(g) = prices.tests[test].group {
                self.groups[g as usize] += 1;
            }
            self.spent += price;
        }
        price
    }

    /// Everything paid so far.
    ///
    /// ```
    /// let prices = cslearn::testcost::TestPrices::flat(&[2.0, 3.0]).unwrap();
    /// let mut basket = cslearn::testcost::Basket::new(&prices);
    /// basket.buy(&prices, 0);
    /// basket.buy(&prices, 1);
    /// assert_eq!(basket.spent(), 5.0);
    /// ```
    pub fn spent(&self) -> f64 {
        self.spent
    }
}

/// What a wrong answer costs: `cost(predicted, actual)`, 0 on the diagonal unless a file
/// says otherwise.
///
/// ```
/// let mc = cslearn::testcost::MisclassCosts::uniform(2, 500.0).unwrap();
/// assert_eq!((mc.cost(0, 1), mc.cost(1, 1)), (500.0, 0.0));
/// assert_eq!(mc.max(), 500.0);
/// ```
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MisclassCosts {
    classes: usize,
    /// `by_predicted[predicted * classes + actual]`.
    by_predicted: Vec<f64>,
}

impl MisclassCosts {
    /// `mc` for every wrong answer among `classes` classes.
    ///
    /// ```
    /// assert!(cslearn::testcost::MisclassCosts::uniform(3, -1.0).is_err());
    /// ```
    pub fn uniform(classes: usize, mc: f64) -> Result<MisclassCosts, Error> {
        check_price(mc, "misclassification cost")?;
        let mut by_predicted = vec![mc; classes * classes];
        for c in 0..classes {
            by_predicted[c * classes + c] = 0.0;
        }
        Ok(MisclassCosts {
            classes,
            by_predicted,
        })
    }

    /// A full matrix, `rows[actual][predicted]` (as a confusion matrix reads).
    ///
    /// ```
    /// let mc = cslearn::testcost::MisclassCosts::from_rows(&[vec![0.0, 10.0], vec![100.0, 0.0]]).unwrap();
    /// assert_eq!(mc.cost(1, 0), 10.0); // answering 1 for an object of class 0
    /// assert!(cslearn::testcost::MisclassCosts::from_rows(&[vec![0.0, 1.0]]).is_err());
    /// ```
    pub fn from_rows(rows: &[Vec<f64>]) -> Result<MisclassCosts, Error> {
        let classes = rows.len();
        let mut by_predicted = vec![0.0; classes * classes];
        for (actual, row) in rows.iter().enumerate() {
            if row.len() != classes {
                return Err(Error::Invalid {
                    what: "misclassification matrix".into(),
                    reason: format!(
                        "row {} has {} entries, but there are {classes} classes",
                        actual + 1,
                        row.len()
                    ),
                });
            }
            for (predicted, &c) in row.iter().enumerate() {
                check_price(c, "misclassification matrix")?;
                by_predicted[predicted * classes + actual] = c;
            }
        }
        Ok(MisclassCosts {
            classes,
            by_predicted,
        })
    }

    /// A matrix from a CSV file whose header is `actual` and the class names, and whose
    /// rows are a class name and its costs (the answer in the column); `class_names` are
    /// the data's classes, each of which must have a row and a column.
    ///
    /// ```no_run
    /// let classes = vec!["sick".to_string(), "well".to_string()];
    /// let mc = cslearn::testcost::MisclassCosts::read_csv(std::path::Path::new("mc.csv"), &classes);
    /// ```
    pub fn read_csv(path: &Path, class_names: &[String]) -> Result<MisclassCosts, Error> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let bad = |line: usize, reason: String| Error::BadInput {
            path: path.to_path_buf(),
            at: format!("line {line}"),
            reason,
        };
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l))
            .filter(|(_, l)| !l.trim().is_empty());
        let Some((hl, header)) = lines.next() else {
            return Err(bad(1, "the file is empty".into()));
        };
        let header: Vec<&str> = header.split(',').map(str::trim).collect();
        let k = class_names.len();
        let index = |line: usize, name: &str| {
            class_names.iter().position(|c| c == name).ok_or_else(|| {
                bad(
                    line,
                    format!(
                        "`{name}` is not a class of the data (classes: {})",
                        class_names.join(", ")
                    ),
                )
            })
        };
        if header.len() != k + 1 {
            return Err(bad(
                hl,
                format!(
                    "the header has {} class columns, but the data has {k} classes",
                    header.len() - 1
                ),
            ));
        }
        let columns: Vec<usize> = header[1..]
            .iter()
            .map(|h| index(hl, h))
            .collect::<Result<_, _>>()?;
        let mut rows: Vec<Option<Vec<f64>>> = vec![None; k];
        for (line, text) in lines {
            let cells: Vec<&str> = text.split(',').map(str::trim).collect();
            if cells.len() != k + 1 {
                return Err(bad(
                    line,
                    format!("{} cells, but the header has {}", cells.len(), k + 1),
                ));
            }
            let actual = index(line, cells[0])?;
            let mut row = vec![0.0; k];
            for (j, cell) in cells[1..].iter().enumerate() {
                row[columns[j]] = cell
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite() && *x >= 0.0)
                    .ok_or_else(|| {
                        bad(
                            line,
                            format!("`{cell}`: costs must be finite, non-negative numbers"),
                        )
                    })?;
            }
            if rows[actual].replace(row).is_some() {
                return Err(bad(line, format!("a second row for `{}`", cells[0])));
            }
        }
        let rows: Vec<Vec<f64>> = rows
            .into_iter()
            .enumerate()
            .map(|(c, r)| {
                r.ok_or_else(|| bad(hl, format!("no row for class `{}`", class_names[c])))
            })
            .collect::<Result<_, _>>()?;
        MisclassCosts::from_rows(&rows)
    }

    /// The number of classes.
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::MisclassCosts::uniform(3, 1.0).unwrap().classes(), 3);
    /// ```
    pub fn classes(&self) -> usize {
        self.classes
    }

    /// What answering `predicted` costs for an object of class `actual`.
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::MisclassCosts::uniform(2, 9.0).unwrap().cost(1, 0), 9.0);
    /// ```
    pub fn cost(&self, predicted: usize, actual: usize) -> f64 {
        self.by_predicted[predicted * self.classes + actual]
    }

    /// The largest entry.
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::MisclassCosts::uniform(2, 9.0).unwrap().max(), 9.0);
    /// ```
    pub fn max(&self) -> f64 {
        self.by_predicted.iter().copied().fold(0.0, f64::max)
    }

    /// The answer of least expected cost for objects distributed as `weights` (one per
    /// class), with that cost; ties go to the class with more weight, then the lower index.
    ///
    /// ```
    /// let mc = cslearn::testcost::MisclassCosts::from_rows(&[vec![0.0, 1.0], vec![10.0, 0.0]]).unwrap();
    /// // 3 objects of class 0 and 1 of class 1: answering 0 costs 10, answering 1 costs 3.
    /// assert_eq!(mc.best(&[3.0, 1.0]), (1, 3.0));
    /// ```
    pub fn best(&self, weights: &[f64]) -> (usize, f64) {
        let mut best = (0, f64::INFINITY);
        for predicted in 0..self.classes {
            let row = &self.by_predicted[predicted * self.classes..(predicted + 1) * self.classes];
            let cost: f64 = row.iter().zip(weights).map(|(c, w)| c * w).sum();
            let better = cost < best.1 - 1e-9 * cost.abs().max(1.0)
                || (cost <= best.1 + 1e-9 * cost.abs().max(1.0)
                    && weights[predicted] > weights[best.0]);
            if better {
                best = (predicted, cost);
            }
        }
        best
    }

    /// Turney's standard cost of a data set with these class shares (summing to one) and
    /// these test prices: every test bought, then the answer of least risk, that is the
    /// price of all tests plus `min_i (1 - f_i) * max C`.
    ///
    /// ```
    /// let mc = cslearn::testcost::MisclassCosts::uniform(2, 100.0).unwrap();
    /// let prices = cslearn::testcost::TestPrices::flat(&[10.0, 20.0]).unwrap();
    /// assert_eq!(mc.standard_cost(&[0.75, 0.25], &prices), 30.0 + 25.0);
    /// ```
    pub fn standard_cost(&self, shares: &[f64], prices: &TestPrices) -> f64 {
        let least = shares.iter().map(|f| 1.0 - f).fold(f64::INFINITY, f64::min);
        prices.total() + least * self.max()
    }
}
