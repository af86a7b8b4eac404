//! What a classification costs: test prices with groups and discounts (Turney's cost
//! files), and misclassification costs.

use std::path::{Path, PathBuf};

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

    /// Every one of `tests` tests priced 1, no groups: the costly-feature literature's
    /// prices, where a budget of `k` in price is a budget of `k` tests.
    ///
    /// ```
    /// let prices = cslearn::testcost::TestPrices::unit(3);
    /// assert_eq!((prices.len(), prices.total()), (3, 3.0));
    /// ```
    pub fn unit(tests: usize) -> TestPrices {
        TestPrices::flat_checked_by_caller(&vec![1.0; tests])
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

    /// The one pricing rule: nothing if `test` was `done`, its discount if a test of its
    /// group was bought (`group_bought`), its full price otherwise. [`Basket`] keeps
    /// counts for it; a tree's path asks it directly.
    pub(crate) fn price_when(
        &self,
        test: usize,
        done: bool,
        group_bought: impl Fn(u32) -> bool,
    ) -> f64 {
        if done {
            return 0.0;
        }
        let t = &self.tests[test];
        match t.group {
            Some(g) if group_bought(g) => t.discount,
            _ => t.full,
        }
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
        let read = |ext: &str| -> Result<Option<(PathBuf, String)>, Error> {
            let path = base.with_extension(ext);
            if !path.exists() {
                return Ok(None);
            }
            read_text(&path).map(|text| Some((path, text)))
        };
        let expense = read("expense")?;
        let cost = if expense.is_none() {
            read("cost")?
        } else {
            None
        };
        let Some(prices) = expense.or(cost) else {
            return Err(Error::BadInput {
                path: base.to_path_buf(),
                at: "files".into(),
                reason: "neither a .expense nor a .cost file".into(),
            });
        };
        let groups = read("group")?;
        let delays = read("delay")?;
        turney(prices, groups, delays, names, extra)
    }

    /// Prices in Turney's (1995) format from files named one by one: `prices` in the
    /// format of `.expense` (`name: full, discount`) or `.cost` (`name: price`), `groups`
    /// in that of `.group` (the group names on the first line, then `name: group.`) and
    /// `delays` in that of `.delay` (`name: immediate.` or `name: delayed.`), for the
    /// features `names` in column order. The same checks as
    /// [`read_turney`](TestPrices::read_turney), which reads the same files found by
    /// their extensions: a name that is not a feature, a feature with no price, a bad,
    /// negative or NaN price, a grouped test without a discount price, or an unknown
    /// group is refused, naming the file and line. Each file must be a regular file of at
    /// most [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES) bytes of UTF-8 text.
    ///
    /// ```
    /// use cslearn::testcost::TestPrices;
    /// let dir = tempfile::tempdir().unwrap();
    /// let (prices, groups) = (dir.path().join("p.expense"), dir.path().join("p.group"));
    /// std::fs::write(&prices, "a: 10, 2\nb: 8, 3\nc: 1\n").unwrap();
    /// std::fs::write(&groups, "G.\na: G.\nb: G.\n").unwrap();
    /// let names = ["a", "b", "c"].map(String::from);
    /// let p = TestPrices::read_turney_files(&prices, Some(&groups), None, &names).unwrap();
    /// assert_eq!(p.total(), 8.0 + 2.0 + 1.0); // b in full, then a at its discount, and c
    /// std::fs::write(&prices, "a: 10, 2\nb: 8\nc: 1\n").unwrap();
    /// let err = TestPrices::read_turney_files(&prices, Some(&groups), None, &names).unwrap_err();
    /// assert!(err.to_string().contains("p.group: line 3: `b` is in group `G` but"));
    /// ```
    pub fn read_turney_files(
        prices: &Path,
        groups: Option<&Path>,
        delays: Option<&Path>,
        names: &[String],
    ) -> Result<TestPrices, Error> {
        let read = |path: &Path| read_text(path).map(|text| (path.to_path_buf(), text));
        let prices = read(prices)?;
        let groups = groups.map(read).transpose()?;
        let delays = delays.map(read).transpose()?;
        turney(prices, groups, delays, names, &TurneyExtra::default())
    }

    /// Prices from a CSV file with the header `feature,cost` and one row per feature of
    /// `names` (the `--costs` file of `csrl classify`'s incremental learners), without
    /// groups; a row for `target` (the class column) is ignored. A name that is not a
    /// feature, a second row for one, a feature with no row, or a cost that is not a
    /// finite, non-negative number is refused, naming the file and line.
    ///
    /// ```
    /// use cslearn::testcost::TestPrices;
    /// let dir = tempfile::tempdir().unwrap();
    /// let path = dir.path().join("costs.csv");
    /// std::fs::write(&path, "feature,cost\nb,2.5\na,1\nclass,9\n").unwrap();
    /// let names = ["a", "b"].map(String::from);
    /// let p = TestPrices::read_csv(&path, &names, "class").unwrap();
    /// assert_eq!((p.test(0).full, p.test(1).full), (1.0, 2.5));
    /// std::fs::write(&path, "feature,cost\na,1\nb,NaN\n").unwrap();
    /// let err = TestPrices::read_csv(&path, &names, "class").unwrap_err();
    /// assert!(err.to_string().contains("costs.csv: line 3: the cost of `b` is `NaN`"));
    /// ```
    pub fn read_csv(path: &Path, names: &[String], target: &str) -> Result<TestPrices, Error> {
        let file = crate::dataset::open_regular(path)?;
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let costs = crate::dataset::read_costs(file, path, &names, target)?;
        let prices: Vec<f64> = costs.as_slice().iter().map(|c| c.get()).collect();
        TestPrices::flat(&prices)
    }

    /// Whether some test is in a group (so that its discount price is ever charged).
    ///
    /// ```
    /// assert!(!cslearn::testcost::TestPrices::flat(&[1.0]).unwrap().has_groups());
    /// ```
    pub fn has_groups(&self) -> bool {
        self.tests.iter().any(|t| t.group.is_some())
    }

    /// The same prices, checked as [`new`](TestPrices::new) checks them (for prices read
    /// by serde, which does not check: from a file, or a pickle).
    ///
    /// ```
    /// let prices: cslearn::testcost::TestPrices = serde_json::from_str(
    ///     r#"{"tests":[{"full":-1.0,"discount":-1.0,"group":null,"delayed":false}],"group_names":[]}"#,
    /// ).unwrap();
    /// assert!(prices.checked().is_err());
    /// let dearer: cslearn::testcost::TestPrices = serde_json::from_str(
    ///     r#"{"tests":[{"full":1.0,"discount":2.0,"group":0,"delayed":false}],"group_names":["A"]}"#,
    /// ).unwrap();
    /// assert!(dearer.checked().unwrap_err().to_string().contains("above its full price"));
    /// ```
    pub fn checked(self) -> Result<TestPrices, Error> {
        TestPrices::new(self.tests, self.group_names)?.discounts_checked()
    }

    /// The same prices, refused where a discount is above its full price (a price read
    /// from outside: a cost file, a model, a pickle; ICET's biased prices may round one
    /// above, and are not read).
    fn discounts_checked(self) -> Result<TestPrices, Error> {
        if let Some((i, t)) = self
            .tests
            .iter()
            .enumerate()
            .find(|(_, t)| t.discount > t.full)
        {
            return Err(Error::Invalid {
                what: format!("test {i}"),
                reason: format!(
                    "a discount price of {} above its full price {}",
                    t.discount, t.full
                ),
            });
        }
        Ok(self)
    }
}

/// The text of a regular file of at most [`MAX_FILE_BYTES`](crate::MAX_FILE_BYTES) bytes,
/// which must be UTF-8.
fn read_text(path: &Path) -> Result<String, Error> {
    let bytes = crate::dataset::read_bounded(crate::dataset::open_regular(path)?, path)?;
    String::from_utf8(bytes).map_err(|e| Error::NotUtf8 {
        path: path.to_path_buf(),
        line: 1 + e.as_bytes()[..e.utf8_error().valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count() as u64,
    })
}

/// Turney's prices from the texts of their files (each with its path, for messages), and
/// the caller's extra lines.
fn turney(
    (price_path, price_text): (PathBuf, String),
    groups: Option<(PathBuf, String)>,
    delays: Option<(PathBuf, String)>,
    names: &[String],
    extra: &TurneyExtra,
) -> Result<TestPrices, Error> {
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
            if let (f, Some(d)) = entry
                && d > f
            {
                return Err(Error::BadInput {
                    path: path.clone(),
                    at: at(),
                    reason: format!("`{name}`: a discount price of {d} above its full price {f}"),
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
    let mut group_sources: Vec<(PathBuf, String)> = groups.into_iter().collect();
    group_sources.push((
        price_path.with_extension("group.extra"),
        extra.groups.clone(),
    ));
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
    if let Some((path, text)) = delays {
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
        prices.price_when(test, self.bought[test], |g| self.groups[g as usize] > 0)
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
/// A uniform matrix (0 on the diagonal, one cost everywhere else) is kept as that one
/// cost, however many classes there are: its `classes x classes` entries are never
/// allocated (written out, it is the full matrix, as files have always held it, and a full
/// matrix read back or given by rows that is uniform is kept so). Every answer is the
/// full matrix's, to the bit.
///
/// ```
/// let mc = cslearn::testcost::MisclassCosts::uniform(2, 500.0).unwrap();
/// assert_eq!((mc.cost(0, 1), mc.cost(1, 1)), (500.0, 0.0));
/// assert_eq!(mc.max(), 500.0);
/// // A million classes cost no memory.
/// let many = cslearn::testcost::MisclassCosts::uniform(1_000_000, 5.0).unwrap();
/// assert_eq!((many.cost(999_999, 0), many.max()), (5.0, 5.0));
/// ```
#[derive(Clone, Debug, PartialEq, serde::Deserialize)]
#[serde(from = "StoredCosts")]
pub struct MisclassCosts {
    classes: usize,
    entries: Entries,
}

/// A matrix's entries.
#[derive(Clone, Debug, PartialEq)]
enum Entries {
    /// 0 on the diagonal, this everywhere else (0 with fewer than 2 classes, so that one
    /// matrix has one form).
    Uniform(f64),
    /// `by_predicted[predicted * classes + actual]`.
    Dense(Vec<f64>),
}

/// A matrix as files hold it: every entry, by predicted class then actual class.
#[derive(serde::Deserialize)]
struct StoredCosts {
    classes: usize,
    by_predicted: Vec<f64>,
}

impl From<StoredCosts> for MisclassCosts {
    fn from(stored: StoredCosts) -> MisclassCosts {
        MisclassCosts::of_entries(stored.classes, stored.by_predicted)
    }
}

impl serde::Serialize for MisclassCosts {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        /// The entries, one by one, without making the matrix.
        struct Every<'a>(&'a MisclassCosts);
        impl serde::Serialize for Every<'_> {
            fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                let mc = self.0;
                match &mc.entries {
                    Entries::Dense(by_predicted) => serializer.collect_seq(by_predicted),
                    Entries::Uniform(_) => {
                        let k = mc.classes;
                        serializer
                            .collect_seq((0..k.saturating_mul(k)).map(|i| mc.cost(i / k, i % k)))
                    }
                }
            }
        }
        let mut out = serializer.serialize_struct("MisclassCosts", 2)?;
        out.serialize_field("classes", &self.classes)?;
        out.serialize_field("by_predicted", &Every(self))?;
        out.end()
    }
}

impl MisclassCosts {
    /// `mc` for every wrong answer among `classes` classes.
    ///
    /// ```
    /// assert!(cslearn::testcost::MisclassCosts::uniform(3, -1.0).is_err());
    /// ```
    pub fn uniform(classes: usize, mc: f64) -> Result<MisclassCosts, Error> {
        check_price(mc, "misclassification cost")?;
        Ok(MisclassCosts {
            classes,
            entries: Entries::Uniform(if classes < 2 { 0.0 } else { mc }),
        })
    }

    /// The matrix of these entries (`by_predicted[predicted * classes + actual]`), kept as
    /// its one cost when it is uniform: every diagonal entry is 0 and every other the same,
    /// bit for bit. Entries of another number are kept as they are, for
    /// [`checked`](MisclassCosts::checked) to refuse.
    fn of_entries(classes: usize, by_predicted: Vec<f64>) -> MisclassCosts {
        let zero = 0.0_f64.to_bits();
        let uniform = classes.checked_mul(classes) == Some(by_predicted.len()) && {
            let off = (classes >= 2).then(|| by_predicted[1].to_bits());
            by_predicted.iter().enumerate().all(|(i, c)| {
                let bits = c.to_bits();
                if i / classes == i % classes {
                    bits == zero
                } else {
                    Some(bits) == off
                }
            })
        };
        let entries = match (uniform, classes) {
            (true, 0 | 1) => Entries::Uniform(0.0),
            (true, _) => Entries::Uniform(by_predicted[1]),
            (false, _) => Entries::Dense(by_predicted),
        };
        MisclassCosts { classes, entries }
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
        let mut by_predicted = vec![0.0; classes.saturating_mul(classes)];
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
        Ok(MisclassCosts::of_entries(classes, by_predicted))
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
        // A class named twice leaves another without a column, read as zeros.
        let mut seen = vec![false; k];
        for (j, &c) in columns.iter().enumerate() {
            if std::mem::replace(&mut seen[c], true) {
                return Err(bad(
                    hl,
                    format!("class `{}` names two columns", header[j + 1]),
                ));
            }
        }
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

    /// The same costs, checked: a square matrix of finite, non-negative entries (for
    /// costs read from a file by serde, which does not check).
    pub(crate) fn checked(self) -> Result<MisclassCosts, Error> {
        let by_predicted = match &self.entries {
            Entries::Uniform(mc) => {
                check_price(*mc, "misclassification matrix")?;
                return Ok(self);
            }
            Entries::Dense(by_predicted) => by_predicted,
        };
        if self.classes.checked_mul(self.classes) != Some(by_predicted.len()) {
            return Err(Error::Invalid {
                what: "misclassification matrix".into(),
                reason: format!(
                    "{} entries, but {} classes need {}",
                    by_predicted.len(),
                    self.classes,
                    self.classes.saturating_mul(self.classes)
                ),
            });
        }
        for &c in by_predicted {
            check_price(c, "misclassification matrix")?;
        }
        Ok(self)
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
        match &self.entries {
            Entries::Uniform(_) if predicted == actual => 0.0,
            Entries::Uniform(mc) => *mc,
            Entries::Dense(by_predicted) => by_predicted[predicted * self.classes + actual],
        }
    }

    /// The largest entry.
    ///
    /// ```
    /// assert_eq!(cslearn::testcost::MisclassCosts::uniform(2, 9.0).unwrap().max(), 9.0);
    /// ```
    pub fn max(&self) -> f64 {
        match &self.entries {
            Entries::Uniform(mc) => mc.max(0.0),
            Entries::Dense(by_predicted) => by_predicted.iter().copied().fold(0.0, f64::max),
        }
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
        let by_predicted = match &self.entries {
            Entries::Uniform(mc) => return self.best_uniform(*mc, weights),
            Entries::Dense(by_predicted) => by_predicted,
        };
        let mut best = (0, f64::INFINITY);
        for predicted in 0..self.classes {
            let row = &by_predicted[predicted * self.classes..(predicted + 1) * self.classes];
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

    /// [`best`](MisclassCosts::best) for a uniform matrix, in time linear in the classes:
    /// the full matrix's answer, to the bit. Under one cost `mc > 0` for every error, an
    /// answer's expected cost is `mc` times the weight of the other classes, so the
    /// scan of `best` keeps the first class of largest weight (a larger weight wins by
    /// cost or, within the scan's tolerance, by weight; an equal one never wins); with
    /// `mc = 0` every cost is 0 and the scan keeps the same class by weight. Its cost is
    /// then summed as `best` sums it: over its row, in order, the diagonal's 0 included.
    fn best_uniform(&self, mc: f64, weights: &[f64]) -> (usize, f64) {
        if self.classes == 0 {
            return (0, f64::INFINITY);
        }
        let mut label = 0;
        for (c, &w) in weights.iter().enumerate().take(self.classes).skip(1) {
            if w > weights[label] {
                label = c;
            }
        }
        let cost: f64 = weights
            .iter()
            .take(self.classes)
            .enumerate()
            .map(|(c, w)| (if c == label { 0.0 } else { mc }) * w)
            .sum();
        (label, cost)
    }

    /// Whether every total over `objects` objects stays a true number: at worst an object
    /// pays every test of `prices` in full and the dearest error, and that times the
    /// objects must be at most [`MAX_TOTAL_COST`](crate::MAX_TOTAL_COST). Checked before
    /// learning, so that no reported cost is infinite.
    ///
    /// ```
    /// use cslearn::testcost::{MisclassCosts, TestPrices};
    /// let prices = TestPrices::flat(&[1e300, 1e300]).unwrap();
    /// let mc = MisclassCosts::uniform(2, 1.0).unwrap();
    /// assert!(mc.check_totals(&TestPrices::flat(&[1.0]).unwrap(), 100).is_ok());
    /// let e = mc.check_totals(&prices, 100).unwrap_err().to_string();
    /// assert!(e.contains("2e300 per object") && e.contains("100 objects"), "{e}");
    /// ```
    pub fn check_totals(&self, prices: &TestPrices, objects: usize) -> Result<(), Error> {
        let per_object: f64 =
            (0..prices.len()).map(|t| prices.test(t).full).sum::<f64>() + self.max();
        let all = per_object * objects as f64;
        if all.is_finite() && all <= crate::MAX_TOTAL_COST {
            return Ok(());
        }
        Err(Error::Invalid {
            what: "the prices and misclassification costs".into(),
            reason: format!(
                "the prices and the dearest error sum to {per_object:e} per object, so a total \
                 over the {objects} objects cannot be represented (at most {:e})",
                crate::MAX_TOTAL_COST
            ),
        })
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The heart data's feature names, as Turney's files spell them.
    fn heart_names() -> Vec<String> {
        [
            "age", "sex", "cp", "trestbps", "chol", "fbs", "restecg", "thalach", "exang",
            "oldpeak", "slope", "ca", "thal",
        ]
        .map(String::from)
        .to_vec()
    }

    fn heart(ext: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../data/uci/heart-disease/costs/heart-disease")
            .with_extension(ext)
    }

    /// Files in a scratch directory, by name.
    fn files(entries: &[(&str, &str)]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        for (name, text) in entries {
            std::fs::write(dir.path().join(name), text).unwrap();
        }
        dir
    }

    #[test]
    fn named_files_read_as_the_files_found_by_extension() {
        let names = heart_names();
        let by_base = TestPrices::read_turney(&heart("x"), &names, &TurneyExtra::default())
            .expect("the shipped heart prices");
        let named = TestPrices::read_turney_files(
            &heart("expense"),
            Some(&heart("group")),
            Some(&heart("delay")),
            &names,
        )
        .unwrap();
        assert_eq!(named, by_base);
        // thalach (102.90, 1.00) and thal (102.90, 1.00) share group B.
        let thalach = named.test(7);
        assert_eq!((thalach.full, thalach.discount), (102.9, 1.0));
        assert_eq!(thalach.group, named.test(12).group);
        assert!(thalach.delayed && !named.test(0).delayed);
        assert!(named.has_groups());
        // Without the group file no discount is ever charged.
        let flat = TestPrices::read_turney_files(&heart("expense"), None, None, &names).unwrap();
        assert!(!flat.has_groups());
        assert!((flat.total() - 600.57).abs() < 1e-9, "{}", flat.total());
        assert!((named.total() - 323.97).abs() < 1e-9, "{}", named.total());
        // The .cost file: one price per test, the full ones.
        let cost = TestPrices::read_turney_files(&heart("cost"), None, None, &names).unwrap();
        assert_eq!(cost.total(), flat.total());
    }

    #[test]
    fn every_fault_names_its_file_and_line() {
        let names = ["a", "b"].map(String::from).to_vec();
        let dir = files(&[
            ("ok.expense", "a: 10, 2\nb: 8, 3\n"),
            ("unknown.expense", "a: 10, 2\n\nzed: 8, 3\n"),
            ("negative.expense", "a: 10, -2\nb: 8, 3\n"),
            ("nan.cost", "a: 1\nb: NaN\n"),
            ("short.cost", "a: 1\n"),
            ("twice.cost", "a: 1\nb: 2\na: 3\n"),
            ("three.expense", "a: 1, 2, 3\nb: 1\n"),
            ("flat.cost", "a: 10\nb: 8\n"),
            ("groups.group", "G, H.\na: G.\nb: G.\n"),
            ("unknown.group", "G.\na: G.\nb: K.\n"),
            ("column.group", "G.\nc: G.\n"),
            ("bad.delay", "a: soon.\n"),
        ]);
        let at = |name: &str| dir.path().join(name);
        let err = |prices: &str, groups: Option<&str>, delays: Option<&str>| {
            let groups = groups.map(at);
            let delays = delays.map(at);
            TestPrices::read_turney_files(&at(prices), groups.as_deref(), delays.as_deref(), &names)
                .unwrap_err()
                .to_string()
        };
        let cases = [
            (
                err("unknown.expense", None, None),
                "unknown.expense: line 3: `zed` is not a column",
            ),
            (
                err("negative.expense", None, None),
                "negative.expense: line 1: the price of `a` is `-2`",
            ),
            (
                err("nan.cost", None, None),
                "nan.cost: line 2: the price of `b` is `NaN`",
            ),
            (
                err("short.cost", None, None),
                "short.cost: end of file: no price for column `b`",
            ),
            (
                err("twice.cost", None, None),
                "twice.cost: line 3: a second price for `a`",
            ),
            (
                err("three.expense", None, None),
                "three.expense: line 1: `1, 2, 3`",
            ),
            (
                err("flat.cost", Some("groups.group"), None),
                "groups.group: line 2: `a` is in group `G` but",
            ),
            (
                err("ok.expense", Some("unknown.group"), None),
                "unknown.group: line 3: group `K` of `b` is not among the groups",
            ),
            (
                err("ok.expense", Some("column.group"), None),
                "column.group: line 2: `c` is not a column",
            ),
            (
                err("ok.expense", None, Some("bad.delay")),
                "bad.delay: line 1: `soon`",
            ),
            (
                err("absent.expense", None, None),
                "absent.expense: cannot read",
            ),
        ];
        for (message, expected) in cases {
            assert!(
                message.contains(expected),
                "`{expected}` not in `{message}`"
            );
        }
        let ok = TestPrices::read_turney_files(
            &at("ok.expense"),
            Some(&at("groups.group")),
            None,
            &names,
        )
        .unwrap();
        assert_eq!(ok.group_names(), ["G", "H"]);
        assert_eq!(ok.total(), 8.0 + 2.0);
    }

    #[test]
    fn a_path_that_is_not_a_regular_file_is_refused_before_it_is_read() {
        let names = ["a"].map(String::from).to_vec();
        let dir = tempfile::tempdir().unwrap();
        let err = TestPrices::read_turney_files(dir.path(), None, None, &names).unwrap_err();
        assert!(matches!(err, Error::NotAFile { .. }), "{err}");
        let latin = dir.path().join("latin.cost");
        std::fs::write(&latin, b"a: 1\n# caf\xe9\n").unwrap();
        let err = TestPrices::read_turney_files(&latin, None, None, &names).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("{}: line 2: not UTF-8 text", latin.display())
        );
    }

    #[test]
    fn the_feature_cost_csv_reads_as_flat_prices() {
        let names = ["a", "b"].map(String::from).to_vec();
        let dir = files(&[
            ("ok.csv", "feature,cost\nb,2\na,1\nt,7\n"),
            ("missing.csv", "feature,cost\na,1\n"),
            ("negative.csv", "feature,cost\na,1\nb,-1\n"),
        ]);
        let at = |name: &str| dir.path().join(name);
        let ok = TestPrices::read_csv(&at("ok.csv"), &names, "t").unwrap();
        assert_eq!(ok, TestPrices::flat(&[1.0, 2.0]).unwrap());
        let err = TestPrices::read_csv(&at("missing.csv"), &names, "t").unwrap_err();
        assert!(
            err.to_string()
                .ends_with("missing.csv: no cost for column `b`"),
            "{err}"
        );
        let err = TestPrices::read_csv(&at("negative.csv"), &names, "t").unwrap_err();
        assert!(
            err.to_string()
                .contains("negative.csv: line 3: the cost of `b` is `-1`"),
            "{err}"
        );
    }

    #[test]
    fn deserialised_costs_are_checked() {
        let bad: MisclassCosts =
            serde_json::from_str(r#"{"classes": 2, "by_predicted": [0.0, 1.0, 1.0]}"#).unwrap();
        assert!(bad.checked().unwrap_err().to_string().contains("3 entries"));
        let negative: MisclassCosts =
            serde_json::from_str(r#"{"classes": 1, "by_predicted": [-1.0]}"#).unwrap();
        assert!(negative.checked().is_err());
        let prices: TestPrices = serde_json::from_str(
            r#"{"tests": [{"full": 1.0, "discount": 1.0, "group": 3, "delayed": false}], "group_names": []}"#,
        )
        .unwrap();
        assert!(
            prices
                .checked()
                .unwrap_err()
                .to_string()
                .contains("group 3")
        );
    }

    /// The full matrix of a uniform cost, kept entry by entry as files hold it.
    fn dense(classes: usize, mc: f64) -> MisclassCosts {
        let mut by_predicted = vec![mc; classes * classes];
        for c in 0..classes {
            by_predicted[c * classes + c] = 0.0;
        }
        MisclassCosts {
            classes,
            entries: Entries::Dense(by_predicted),
        }
    }

    /// A uniform matrix kept as its one cost answers what its full matrix answers, to the
    /// bit: the label and expected cost of any weights (ties, zeros and weights a hair
    /// apart included), every entry, the largest; and it is written as the full matrix is.
    #[test]
    fn a_uniform_matrix_answers_as_its_full_matrix_to_the_bit() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(11);
        for round in 0..3000 {
            let classes = rng.random_range(1..9usize);
            let mc = match round % 4 {
                0 => 0.0,
                1 => 1e-300,
                _ => rng.random_range(0.0..1000.0),
            };
            let (uniform, full) = (
                MisclassCosts::uniform(classes, mc).unwrap(),
                dense(classes, mc),
            );
            assert!(matches!(uniform.entries, Entries::Uniform(_)));
            let weights: Vec<f64> = (0..classes)
                .map(|_| match rng.random_range(0..4) {
                    0 => 0.0,
                    1 => 3.0,
                    2 => 3.0 + 1e-12,
                    _ => rng.random_range(0.0..50.0),
                })
                .collect();
            let (a, b) = (uniform.best(&weights), full.best(&weights));
            assert_eq!(
                (a.0, a.1.to_bits()),
                (b.0, b.1.to_bits()),
                "{mc} {weights:?}"
            );
            assert_eq!(uniform.max().to_bits(), full.max().to_bits());
            for p in 0..classes {
                for q in 0..classes {
                    assert_eq!(uniform.cost(p, q).to_bits(), full.cost(p, q).to_bits());
                }
            }
            let json = serde_json::to_string(&uniform).unwrap();
            assert_eq!(json, serde_json::to_string(&full).unwrap());
            let read: MisclassCosts =
                serde_json::from_value(serde_json::to_value(&uniform).unwrap()).unwrap();
            assert_eq!(read, uniform);
        }
    }

    #[test]
    fn a_full_matrix_that_is_uniform_is_kept_as_its_one_cost() {
        let rows = [
            vec![0.0, 7.0, 7.0],
            vec![7.0, 0.0, 7.0],
            vec![7.0, 7.0, 0.0],
        ];
        let mc = MisclassCosts::from_rows(&rows).unwrap();
        assert_eq!(mc.entries, Entries::Uniform(7.0));
        assert_eq!(mc, MisclassCosts::uniform(3, 7.0).unwrap());
        // One entry apart, or a cost on the diagonal: full.
        let skew = [vec![0.0, 7.0], vec![7.5, 0.0]];
        assert!(matches!(
            MisclassCosts::from_rows(&skew).unwrap().entries,
            Entries::Dense(_)
        ));
        let diagonal = [vec![1.0, 7.0], vec![7.0, 0.0]];
        assert!(matches!(
            MisclassCosts::from_rows(&diagonal).unwrap().entries,
            Entries::Dense(_)
        ));
        // One class has one form whatever its cost.
        assert_eq!(
            MisclassCosts::uniform(1, 9.0).unwrap(),
            MisclassCosts::from_rows(&[vec![0.0]]).unwrap()
        );
        // A stored matrix of the wrong size stays as read, and is refused when checked.
        let bad: MisclassCosts =
            serde_json::from_str(r#"{"classes":2,"by_predicted":[0.0,1.0,1.0]}"#).unwrap();
        assert!(
            bad.checked()
                .unwrap_err()
                .to_string()
                .contains("3 entries, but 2 classes need 4")
        );
        let nan: MisclassCosts =
            serde_json::from_str(r#"{"classes":2,"by_predicted":[0.0,-1.0,-1.0,0.0]}"#).unwrap();
        assert!(nan.checked().is_err());
    }
}
