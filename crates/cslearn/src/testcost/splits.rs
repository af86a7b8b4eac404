//! The split trie: every node a tree could have, grown lazily and shared by the trees
//! grown over the same objects.
//!
//! Which objects reach a node depends only on the tests on its path, and the statistics
//! of a test at a node (its gain, its threshold, its split information; for DTMC the
//! misclassification cost it saves) depend only on those objects. So a learner that grows
//! many trees on the same objects with different prices (ICET's search) computes each
//! node's statistics once: a tree is a walk down the trie, choosing at each node by the
//! prices of the moment. A single tree grown through the trie costs what growing it
//! directly costs.

use super::criterion::Criterion;
use super::data::{Column, Frame, MISSING};
use super::prices::MisclassCosts;

/// The statistics of the best split of one feature at a node.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stat {
    pub feature: usize,
    /// The threshold of a numeric feature.
    pub at: Option<f64>,
    /// The information gain (times the share of known values); for DTMC the expected
    /// misclassification cost the split saves, before any test price.
    pub gain: f64,
    /// C4.5's split information.
    pub split_info: f64,
    /// `2^gain - 1`, EG2's numerator.
    pub exp2_gain: f64,
}

/// The children of a node for one test.
#[derive(Clone, Debug)]
pub(crate) struct Children {
    pub feature: usize,
    pub at: Option<f64>,
    /// The cell of each branch, `None` for a branch no object reaches.
    pub cells: Vec<Option<u32>>,
    /// The share of the objects with a known value in each branch.
    pub shares: Vec<f64>,
    /// The held-out objects' weight per class in each branch (no entry without them).
    pub held_out: Vec<Vec<f64>>,
}

/// A node of the trie: the objects reaching it (with C4.5's weights), what it knows of
/// them, and the children made so far.
pub(crate) struct Cell {
    rows: Vec<u32>,
    weights: Vec<f64>,
    /// For each numeric feature, the positions in `rows` of the objects whose value is
    /// known, in increasing order of the value (sorted once at the root, then kept in
    /// order as objects are dealt to children); empty for nominal features.
    order: Vec<Vec<u32>>,
    /// The tests on the path to it, in order.
    pub path: Vec<usize>,
    /// Weight per class.
    pub class_weights: Vec<f64>,
    /// The held-out objects reaching the cell (scored, never learned from), with weights.
    held_rows: Vec<u32>,
    held_weights: Vec<f64>,
    /// The held-out objects' weight per class.
    pub held_classes: Vec<f64>,
    stats: Option<Vec<Stat>>,
    children: Vec<Children>,
}

/// The trie over one set of objects, for one kind of statistics.
pub(crate) struct Splits<'a> {
    frame: &'a Frame,
    mc: &'a MisclassCosts,
    classes: usize,
    min_objects: f64,
    /// DTMC's statistics (costs) instead of information gain.
    cost_based: bool,
    /// C4.5's charge for choosing among thresholds.
    threshold_penalty: bool,
    cells: Vec<Cell>,
    scratch: Scratch,
    /// The cell of every children list made, in order, so that [`Splits::forget_since`]
    /// can drop the ones made after a [`Mark`].
    made: Vec<u32>,
}

/// A point in a trie's growth ([`Splits::mark`]) to forget what grew after it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mark {
    cells: usize,
    made: usize,
}

/// C4.5's least branch size for a split of `known` weight among `classes` classes.
fn min_split(min_objects: f64, classes: usize, known: f64) -> f64 {
    (0.1 * known / classes as f64).clamp(min_objects, 25.0_f64.max(min_objects))
}

/// `x log2 x`, read from a table for the small whole numbers that unweighted objects
/// give (0 at 0).
fn xlog2x(x: f64) -> f64 {
    const TABLE: usize = 4096;
    static VALUES: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    if x <= 0.0 {
        return 0.0;
    }
    // `x as usize` truncates (0 < x < TABLE here): a whole number comes back unchanged.
    if x < TABLE as f64 && (x as usize) as f64 == x {
        let table = VALUES.get_or_init(|| {
            (0..TABLE)
                .map(|i| {
                    if i == 0 {
                        0.0
                    } else {
                        i as f64 * (i as f64).log2()
                    }
                })
                .collect()
        });
        return table[x as usize];
    }
    x * x.log2()
}

/// `total * entropy(weights)`, as `total log2 total - sum w log2 w`, from the terms
/// `xlog2x(w)` of the weights (kept up to date as a threshold moves).
fn entropy_of_terms(terms: &[f64], total: f64) -> f64 {
    let mut h = xlog2x(total);
    for &t in terms {
        h -= t;
    }
    h.max(0.0)
}

pub(crate) fn entropy(weights: &[f64], total: f64) -> f64 {
    if total <= 0.0 {
        return 0.0;
    }
    let mut h = 0.0;
    for &w in weights {
        if w > 0.0 {
            let p = w / total;
            h -= p * p.log2();
        }
    }
    h
}

/// `-sum p log2 p` over the parts of a total.
fn split_information(parts: impl Iterator<Item = f64>, total: f64) -> f64 {
    let mut h = 0.0;
    for w in parts {
        if w > 0.0 {
            let p = w / total;
            h -= p * p.log2();
        }
    }
    h
}

/// Reusable buffers for scoring splits.
struct Scratch {
    /// Per value, per class (nominal features).
    branch: Vec<f64>,
    /// (value, class, weight) of the objects with a known value, for numeric features.
    sorted: Vec<(f64, u32, f64)>,
}

impl<'a> Splits<'a> {
    /// The trie over the objects `rows` (weighted) of `frame`, for trees grown with
    /// `criterion` and `min_objects`; `mc` labels nodes and, for DTMC, scores splits.
    pub fn new(
        frame: &'a Frame,
        rows: &[usize],
        weights: &[f64],
        mc: &'a MisclassCosts,
        criterion: Criterion,
        min_objects: f64,
    ) -> Splits<'a> {
        let rows: Vec<u32> = rows.iter().map(|&r| r as u32).collect();
        let order = (0..frame.feature_count())
            .map(|f| match frame.column(f) {
                Column::Numeric(x) => {
                    let mut known: Vec<u32> = (0..rows.len() as u32)
                        .filter(|&p| !x[rows[p as usize] as usize].is_nan())
                        .collect();
                    known.sort_by(|&a, &b| {
                        x[rows[a as usize] as usize].total_cmp(&x[rows[b as usize] as usize])
                    });
                    known
                }
                Column::Nominal { .. } => Vec::new(),
            })
            .collect();
        let mut splits = Splits {
            frame,
            mc,
            classes: frame.class_count(),
            min_objects,
            cost_based: matches!(criterion, Criterion::Dtmc),
            threshold_penalty: matches!(criterion, Criterion::C45),
            cells: Vec::new(),
            made: Vec::new(),
            scratch: Scratch {
                branch: Vec::new(),
                sorted: Vec::new(),
            },
        };
        let class_weights = splits.class_weights(&rows, weights);
        splits.cells.push(Cell {
            rows,
            weights: weights.to_vec(),
            order,
            path: Vec::new(),
            class_weights,
            held_rows: Vec::new(),
            held_weights: Vec::new(),
            held_classes: Vec::new(),
            stats: None,
            children: Vec::new(),
        });
        splits
    }

    /// Also sends the objects `held_out` of the frame down every split made, to score
    /// trees on them without classifying them one by one
    /// ([`CostTree::held_out_cost`](super::CostTree)); call before any split is made.
    pub fn hold_out(&mut self, held_out: &[usize]) {
        let rows: Vec<u32> = held_out.iter().map(|&r| r as u32).collect();
        let weights = vec![1.0; rows.len()];
        let classes = self.class_weights(&rows, &weights);
        let root = &mut self.cells[0];
        root.held_rows = rows;
        root.held_weights = weights;
        root.held_classes = classes;
    }

    /// Where the trie's growth stands now.
    pub fn mark(&self) -> Mark {
        Mark {
            cells: self.cells.len(),
            made: self.made.len(),
        }
    }

    /// Forget the cells and children lists made since `mark` (the statistics computed
    /// since for older cells stay): the trie is as it was then, as far as any walk can
    /// tell, and takes the memory it took then plus those statistics. Everything a walk
    /// reads is a function of the objects reaching a cell, so making a cell again gives
    /// it again.
    pub fn forget_since(&mut self, mark: Mark) {
        for &c in self.made[mark.made..].iter().rev() {
            self.cells[c as usize].children.pop();
        }
        self.made.truncate(mark.made);
        self.cells.truncate(mark.cells);
    }

    /// Whether the statistics are DTMC's.
    pub fn cost_based(&self) -> bool {
        self.cost_based
    }

    /// Cell `c`.
    pub fn cell(&self, c: u32) -> &Cell {
        &self.cells[c as usize]
    }

    /// Cell `c`, to change.
    pub fn cell_mut(&mut self, c: u32) -> &mut Cell {
        &mut self.cells[c as usize]
    }

    /// The weight of objects in cell `c`.
    pub fn total(&self, c: u32) -> f64 {
        self.cells[c as usize].weights.iter().sum()
    }

    /// The statistics of every feature that can split cell `c`.
    pub fn stats(&mut self, c: u32) -> &[Stat] {
        if self.cells[c as usize].stats.is_none() {
            let cell = std::mem::replace(&mut self.cells[c as usize], Cell::placeholder());
            let stats: Vec<Stat> = (0..self.frame.feature_count())
                .filter_map(|f| self.stat(f, &cell))
                .collect();
            self.cells[c as usize] = cell;
            self.cells[c as usize].stats = Some(stats);
        }
        self.cells[c as usize].stats.as_deref().unwrap_or(&[])
    }

    /// The weight per class of `rows`.
    fn class_weights(&self, rows: &[u32], weights: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.classes];
        for (&r, &w) in rows.iter().zip(weights) {
            out[self.frame.class(r as usize) as usize] += w;
        }
        out
    }

    /// The best split of `feature` for the node's objects, or `None` if it has none
    /// (too few objects with a known value, a single value, no gain).
    fn stat(&mut self, feature: usize, cell: &Cell) -> Option<Stat> {
        let (rows, weights) = (&cell.rows[..], &cell.weights[..]);
        let node_weights = &cell.class_weights[..];
        let k = self.classes;
        let total: f64 = weights.iter().sum();
        let dtmc = self.cost_based;
        match self.frame.column(feature) {
            Column::Nominal { values, codes } => {
                let v = values.len();
                let branch = &mut self.scratch.branch;
                branch.clear();
                branch.resize(v * k, 0.0);
                let mut known = vec![0.0; k];
                for (&r, &w) in rows.iter().zip(weights) {
                    let code = codes[r as usize];
                    if code != MISSING {
                        let c = self.frame.class(r as usize) as usize;
                        branch[code as usize * k + c] += w;
                        known[c] += w;
                    }
                }
                let known_total: f64 = known.iter().sum();
                if known_total <= 0.0 {
                    return None;
                }
                let sizes: Vec<f64> = (0..v)
                    .map(|b| branch[b * k..(b + 1) * k].iter().sum())
                    .collect();
                let min = min_split(self.min_objects, self.classes, known_total);
                if sizes.iter().filter(|&&s| s >= min).count() < 2 {
                    return None;
                }
                let share = known_total / total;
                if dtmc {
                    let after: f64 = (0..v)
                        .map(|b| {
                            let part = &branch[b * k..(b + 1) * k];
                            let with_missing: Vec<f64> = part
                                .iter()
                                .zip(node_weights.iter().zip(&known))
                                .map(|(w, (n, kn))| w + (n - kn) * sizes[b] / known_total)
                                .collect();
                            self.mc.best(&with_missing).1
                        })
                        .sum();
                    let before = self.mc.best(node_weights).1;
                    return Some(Stat {
                        feature,
                        at: None,
                        gain: before - after,
                        split_info: 1.0,
                        exp2_gain: 0.0,
                    });
                }
                let after: f64 = (0..v)
                    .map(|b| sizes[b] * entropy(&branch[b * k..(b + 1) * k], sizes[b]))
                    .sum::<f64>()
                    / known_total;
                let gain = share * (entropy(&known, known_total) - after);
                let split_info =
                    split_information(sizes.iter().copied().chain([total - known_total]), total);
                Some(Stat {
                    feature,
                    at: None,
                    gain,
                    split_info,
                    exp2_gain: gain.exp2() - 1.0,
                })
            }
            Column::Numeric(x) => {
                let sorted = &mut self.scratch.sorted;
                sorted.clear();
                for &p in &cell.order[feature] {
                    let r = rows[p as usize] as usize;
                    sorted.push((x[r], self.frame.class(r), weights[p as usize]));
                }
                if sorted.len() < 2 {
                    return None;
                }
                let mut known = vec![0.0; k];
                for &(_, c, w) in sorted.iter() {
                    known[c as usize] += w;
                }
                let known_total: f64 = known.iter().sum();
                let min = min_split(self.min_objects, self.classes, known_total);
                let base = entropy(&known, known_total);
                let missing: Vec<f64> = node_weights
                    .iter()
                    .zip(&known)
                    .map(|(n, kn)| n - kn)
                    .collect();
                let before_cost = if dtmc {
                    self.mc.best(node_weights).1
                } else {
                    0.0
                };
                let mut buffers = vec![0.0; 5 * k];
                let (left, rest) = buffers.split_at_mut(k);
                let (right, rest) = rest.split_at_mut(k);
                let (mixed, rest) = rest.split_at_mut(k);
                // `xlog2x` of each class's weight on the left and on the right, kept as
                // objects move left: each side's weighted entropy from the same terms
                // in the same order, computed once per object instead of once per
                // threshold.
                let (left_terms, right_terms) = rest.split_at_mut(k);
                if !dtmc {
                    for j in 0..k {
                        right_terms[j] = xlog2x(known[j]);
                    }
                }
                let mut left_total = 0.0;
                let mut best: Option<(f64, f64, f64)> = None; // (value, at, left_total)
                let mut tested = 0usize;
                for i in 0..sorted.len() - 1 {
                    let (value, c, w) = sorted[i];
                    left[c as usize] += w;
                    left_total += w;
                    if !dtmc {
                        let c = c as usize;
                        left_terms[c] = xlog2x(left[c]);
                        right_terms[c] = xlog2x(known[c] - left[c]);
                    }
                    let next = sorted[i + 1].0;
                    if next <= value {
                        continue;
                    }
                    let right_total = known_total - left_total;
                    if left_total < min || right_total < min {
                        continue;
                    }
                    tested += 1;
                    let quality = if dtmc {
                        for j in 0..k {
                            right[j] = known[j] - left[j];
                        }
                        let share_left = left_total / known_total;
                        let mut cost = 0.0;
                        for (side, s) in [(&*left, share_left), (&*right, 1.0 - share_left)] {
                            for j in 0..k {
                                mixed[j] = side[j] + missing[j] * s;
                            }
                            cost += self.mc.best(mixed).1;
                        }
                        -cost
                    } else {
                        -(entropy_of_terms(left_terms, left_total)
                            + entropy_of_terms(right_terms, right_total))
                    };
                    if best.is_none_or(|(q, _, _)| quality > q) {
                        best = Some((quality, (value + next) / 2.0, left_total));
                    }
                }
                let (quality, at, left_total) = best?;
                let right_total = known_total - left_total;
                if dtmc {
                    return Some(Stat {
                        feature,
                        at: Some(at),
                        gain: before_cost + quality,
                        split_info: 1.0,
                        exp2_gain: 0.0,
                    });
                }
                let share = known_total / total;
                let mut gain = share * (base + quality / known_total);
                if self.threshold_penalty && tested > 1 {
                    // C4.5 (release 8) charges the choice among thresholds.
                    gain -= (tested as f64).log2() / total;
                }
                let split_info = split_information(
                    [left_total, right_total, total - known_total].into_iter(),
                    total,
                );
                Some(Stat {
                    feature,
                    at: Some(at),
                    gain,
                    split_info,
                    exp2_gain: gain.exp2() - 1.0,
                })
            }
        }
    }

    /// The children of cell `c` for `stat`'s test, made on first use: the objects with a
    /// known value go to their branch, the others to every branch with their weight split
    /// as the known ones split.
    pub fn children(&mut self, c: u32, stat: &Stat) -> &Children {
        let index = self.made_children(c, stat);
        &self.cells[c as usize].children[index]
    }

    /// The index among cell `c`'s children lists of `stat`'s, made on first use.
    fn made_children(&mut self, c: u32, stat: &Stat) -> usize {
        let found = self.cells[c as usize]
            .children
            .iter()
            .position(|ch| ch.feature == stat.feature);
        match found {
            Some(i) => i,
            None => {
                let made = self.split(c, stat);
                self.cells[c as usize].children.push(made);
                self.made.push(c);
                self.cells[c as usize].children.len() - 1
            }
        }
    }

    fn split(&mut self, c: u32, stat: &Stat) -> Children {
        let frame = self.frame;
        let feature = stat.feature;
        let column = frame.column(feature);
        let branches = match column {
            Column::Nominal { values, .. } => values.len(),
            Column::Numeric(_) => 2,
        };
        let at = stat.at.unwrap_or(0.0);
        let branch_of = |r: u32| -> Option<usize> {
            match column {
                Column::Nominal { codes, .. } => {
                    let code = codes[r as usize];
                    (code != MISSING).then_some(code as usize)
                }
                Column::Numeric(x) => {
                    let v = x[r as usize];
                    (!v.is_nan()).then(|| usize::from(v > at))
                }
            }
        };
        let cell = &self.cells[c as usize];
        let n = cell.rows.len();
        // Each object's branch (`NONE` where its value is missing), counted per branch
        // first so that every child's vectors are made at their size.
        const NONE: u32 = u32::MAX;
        let mut branch_of_p: Vec<u32> = Vec::with_capacity(n);
        let mut known_by_branch = vec![0.0; branches];
        let mut counts = vec![0usize; branches];
        let mut unknown: Vec<usize> = Vec::new();
        for (p, (&r, &w)) in cell.rows.iter().zip(&cell.weights).enumerate() {
            match branch_of(r) {
                Some(b) => {
                    branch_of_p.push(b as u32);
                    known_by_branch[b] += w;
                    counts[b] += 1;
                }
                None => {
                    branch_of_p.push(NONE);
                    unknown.push(p);
                }
            }
        }
        let known_total: f64 = known_by_branch.iter().sum();
        let shares: Vec<f64> = known_by_branch.iter().map(|k| k / known_total).collect();
        let mut parts: Vec<(Vec<u32>, Vec<f64>)> = (0..branches)
            .map(|b| {
                let size = counts[b] + if shares[b] > 0.0 { unknown.len() } else { 0 };
                (Vec::with_capacity(size), Vec::with_capacity(size))
            })
            .collect();
        // Where each of the cell's objects with a known value sits in its child; the
        // objects with a missing value follow them in every branch of positive share, in
        // the order of `unknown`.
        let mut position: Vec<u32> = vec![NONE; n];
        for (p, (&r, &w)) in cell.rows.iter().zip(&cell.weights).enumerate() {
            let b = branch_of_p[p];
            if b != NONE {
                let part = &mut parts[b as usize];
                position[p] = part.0.len() as u32;
                part.0.push(r);
                part.1.push(w);
            }
        }
        let mut unknown_rank: Vec<u32> = vec![NONE; if unknown.is_empty() { 0 } else { n }];
        for (i, &p) in unknown.iter().enumerate() {
            unknown_rank[p] = i as u32;
            for (b, part) in parts.iter_mut().enumerate() {
                if shares[b] > 0.0 {
                    part.0.push(cell.rows[p]);
                    part.1.push(cell.weights[p] * shares[b]);
                }
            }
        }
        // The held-out objects follow the same rule, with the training shares.
        let mut held: Vec<(Vec<u32>, Vec<f64>)> = vec![(Vec::new(), Vec::new()); branches];
        for (&r, &w) in cell.held_rows.iter().zip(&cell.held_weights) {
            match branch_of(r) {
                Some(b) => {
                    held[b].0.push(r);
                    held[b].1.push(w);
                }
                None => {
                    for (b, part) in held.iter_mut().enumerate() {
                        if shares[b] > 0.0 {
                            part.0.push(r);
                            part.1.push(w * shares[b]);
                        }
                    }
                }
            }
        }
        // Without held-out objects (every tree but ICET's search) there is nothing to count.
        let held_out: Vec<Vec<f64>> = if cell.held_rows.is_empty() {
            Vec::new()
        } else {
            held.iter()
                .map(|(rows, weights)| self.class_weights(rows, weights))
                .collect()
        };
        // Each child's order of every numeric feature, in one pass over the cell's order
        // per feature: an object keeps its place among the known values in its branch
        // (at `position`), and one with a missing value sits after the known ones of
        // each branch it goes to (the `unknown_rank`-th of them).
        let mut child_orders: Vec<Vec<Vec<u32>>> = (0..branches)
            .map(|_| Vec::with_capacity(cell.order.len()))
            .collect();
        for sorted in &cell.order {
            let mut per_branch: Vec<Vec<u32>> = (0..branches)
                .map(|b| {
                    if sorted.is_empty() {
                        Vec::new()
                    } else {
                        Vec::with_capacity(parts[b].0.len())
                    }
                })
                .collect();
            for &p in sorted {
                let p = p as usize;
                let b = branch_of_p[p];
                if b != NONE {
                    per_branch[b as usize].push(position[p]);
                } else {
                    let rank = unknown_rank[p];
                    for (b, order) in per_branch.iter_mut().enumerate() {
                        if shares[b] > 0.0 {
                            order.push(counts[b] as u32 + rank);
                        }
                    }
                }
            }
            for (b, order) in per_branch.into_iter().enumerate() {
                child_orders[b].push(order);
            }
        }
        let mut child_orders = child_orders.into_iter();
        let mut path = cell.path.clone();
        path.push(feature);
        let mut made = Vec::with_capacity(branches);
        for (b, ((rows, weights), (held_rows, held_weights))) in
            parts.into_iter().zip(held).enumerate()
        {
            let order = child_orders.next().unwrap_or_default();
            if rows.is_empty() {
                made.push(None);
                continue;
            }
            let class_weights = self.class_weights(&rows, &weights);
            self.cells.push(Cell {
                rows,
                weights,
                order,
                path: path.clone(),
                class_weights,
                held_classes: held_out.get(b).cloned().unwrap_or_default(),
                held_rows,
                held_weights,
                stats: None,
                children: Vec::new(),
            });
            made.push(Some(self.cells.len() as u32 - 1));
        }
        Children {
            feature,
            at: stat.at,
            cells: made,
            shares,
            held_out,
        }
    }
}

impl Cell {
    /// The children made for a test of `feature`, if they were.
    pub fn children_for(&self, feature: usize) -> Option<&Children> {
        self.children.iter().find(|c| c.feature == feature)
    }

    fn placeholder() -> Cell {
        Cell {
            rows: Vec::new(),
            weights: Vec::new(),
            order: Vec::new(),
            path: Vec::new(),
            class_weights: Vec::new(),
            held_rows: Vec::new(),
            held_weights: Vec::new(),
            held_classes: Vec::new(),
            stats: None,
            children: Vec::new(),
        }
    }
}
