//! `csrl classify --learner id3-batch|c45|idx|cs-id3-batch|eg2|dtmc|icet`: the batch trees of the
//! test-cost family (`cslearn::testcost`), grown on training parts and judged on the
//! held-out objects by what their tests and their errors cost.
//!
//! The data is read with its numeric columns as numbers (no binning); the prices come
//! from a `feature,cost` CSV file or from Turney's files (`.expense` or `.cost`, with
//! `--groups`); a wrong answer costs `--mc` (by default the price of every test
//! together) or what `--mc-matrix` says. Every object is classified once by a tree grown
//! without it (`--folds K`, stratified, 10 by default; or `--holdout F`, a share of each
//! class), and the report gives, per test object, the price of the tests its tree did,
//! the error rate, the misclassification cost and their sum, the total cost. With
//! `--json` it lists every test object too: its answer, what its tests cost and the
//! probability of each class (the Laplace-smoothed class weights of the leaf, or mix of
//! leaves, that answered). With `--max-test-cost B` or `--max-tests K` every object is
//! held to that budget (the greedy learners grow within it, every tree classifies within
//! it), and the report says how many tests an object bought on average and that none
//! paid past the budget.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};
use cslearn::testcost::{
    ActParams, Budget, CvtParams, Frame, FrameSpec, IcetGenome, Method, MisclassCosts, Pruning,
    TestPrices, TreeModel,
};

use crate::classify_args::ClassifyArgs;

/// Folds when neither `--folds` nor `--holdout` is given.
const DEFAULT_FOLDS: usize = 10;

/// Whether `path` names prices in Turney's format (by its extension).
pub(crate) fn is_turney(path: &Path) -> bool {
    matches!(
        path.extension().and_then(|e| e.to_str()),
        Some("expense" | "cost")
    )
}

/// The training objects and the test objects of one split.
type TrainTest = (Vec<usize>, Vec<usize>);

/// What one split (a fold, or the holdout) measured on its test part.
#[derive(Clone, Debug, Default)]
struct Part {
    test_objects: usize,
    /// Test objects whose classification waited for a delayed test.
    delayed: usize,
    errors: usize,
    test_cost: f64,
    mc_cost: f64,
    tree_nodes: usize,
    genome: Option<IcetGenome>,
    cvt: Option<cslearn::testcost::CvtChoice>,
    /// Distinct tests bought, over the test objects.
    tests_bought: usize,
    /// Test objects that paid, or bought, more than the budget allows (none, by
    /// construction; counted so that the report says so from what it measured).
    over_budget: usize,
    /// Each test object's classification, with its place in the data.
    objects: Vec<(usize, cslearn::testcost::Classification)>,
}

/// The feature names the price files use: the data's, renamed by `--cost-name`.
fn cost_names(args: &ClassifyArgs, frame: &Frame) -> Result<Vec<String>> {
    let mut names = frame.names().to_vec();
    let mut renamed = vec![false; names.len()];
    for rule in &args.cost_name {
        let Some((column, name)) = rule
            .split_once('=')
            .map(|(c, n)| (c.trim(), n.trim()))
            .filter(|(c, n)| !c.is_empty() && !n.is_empty())
        else {
            anyhow::bail!("--cost-name {rule}: give COLUMN=NAME, as in `thalch=thalach`");
        };
        let Some(i) = frame.feature(column) else {
            anyhow::bail!(
                "--cost-name {rule}: `{column}` is not a feature column of {} (columns: {})",
                args.data.display(),
                frame.names().join(", ")
            );
        };
        anyhow::ensure!(
            !renamed[i],
            "--cost-name {rule}: column `{column}` is renamed twice"
        );
        renamed[i] = true;
        names[i] = name.to_string();
    }
    for (i, name) in names.iter().enumerate() {
        if let Some(j) = names[i + 1..].iter().position(|n| n == name) {
            anyhow::bail!(
                "--cost-name: columns `{}` and `{}` would both be called `{name}` in the price files",
                frame.names()[i],
                frame.names()[i + 1 + j]
            );
        }
    }
    Ok(names)
}

/// The prices of the data's features.
fn read_prices(args: &ClassifyArgs, frame: &Frame) -> Result<TestPrices> {
    let names = cost_names(args, frame)?;
    let costs = &args.costs;
    let turney = is_turney(costs);
    if let Some(groups) = &args.groups {
        let expense = costs.extension().and_then(|e| e.to_str()) == Some("expense");
        anyhow::ensure!(
            expense,
            "--groups {} needs discount prices: give --costs Turney's .expense file \
             (`name: full, discount`); {} has one price per test",
            groups.display(),
            costs.display()
        );
    }
    // Turney's `.delay` file beside the prices, when there is one: reported, never priced.
    let delays = costs.with_extension("delay");
    let delays = (turney && delays.is_file()).then_some(delays);
    let prices = if turney {
        TestPrices::read_turney_files(costs, args.groups.as_deref(), delays.as_deref(), &names)
    } else {
        TestPrices::read_csv(costs, &names, &args.target)
    }
    .map_err(|e| {
        if e.to_string().contains("is not a column of the data") {
            anyhow::anyhow!(
                "{e}; if the price files call a column by another name, say which with \
                 --cost-name COLUMN=NAME"
            )
        } else {
            anyhow::Error::new(e)
        }
        .context("cannot read the prices")
    })?;
    Ok(prices)
}

/// The misclassification costs, and the one cost of every wrong answer unless they are
/// a matrix.
fn read_mc(
    args: &ClassifyArgs,
    frame: &Frame,
    prices: &TestPrices,
) -> Result<(MisclassCosts, Option<f64>)> {
    let k = frame.class_count();
    if let Some(path) = &args.mc_matrix {
        let mc = MisclassCosts::read_csv(path, frame.class_names())
            .context("cannot read the misclassification costs")?;
        return Ok((mc, None));
    }
    let mc = args.mc.unwrap_or_else(|| default_mc(prices));
    let matrix = MisclassCosts::uniform(k, mc).map_err(|e| anyhow::anyhow!("--mc {mc}: {e}"))?;
    Ok((matrix, Some(mc)))
}

/// The default misclassification cost: the price of every test together, or 1.
fn default_mc(prices: &TestPrices) -> f64 {
    let all = prices.total();
    if all > 0.0 { all } else { 1.0 }
}

/// The training and test objects of each split.
fn splits(args: &ClassifyArgs, frame: &Frame) -> Result<(String, Vec<TrainTest>)> {
    use rand::{RngExt, SeedableRng};
    let n = frame.len();
    anyhow::ensure!(
        n >= 2,
        "{}: one object, which cannot be both learned from and held out: an evaluation \
         needs at least 2",
        args.data.display()
    );
    let complement = |test: &[usize]| -> Vec<usize> {
        let mut held = vec![false; n];
        for &r in test {
            held[r] = true;
        }
        (0..n).filter(|&r| !held[r]).collect()
    };
    if let Some(f) = args.holdout {
        anyhow::ensure!(
            f > 0.0 && f < 1.0,
            "--holdout must be a share strictly between 0 and 1, found {f}"
        );
        // The same share of each class, shuffled by the seed; each class keeps at least
        // one object for training.
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(args.seed);
        let mut by_class: Vec<Vec<usize>> = vec![Vec::new(); frame.class_count()];
        for r in 0..n {
            by_class[frame.class(r) as usize].push(r);
        }
        let mut test = Vec::new();
        let mut spare: Vec<usize> = Vec::new();
        for rows in &mut by_class {
            for i in (1..rows.len()).rev() {
                let j = rng.random_range(0..=i);
                rows.swap(i, j);
            }
            let m = rows.len();
            let take = ((m as f64 * f).round() as usize).min(m.saturating_sub(1));
            test.extend_from_slice(&rows[..take]);
            if take + 1 < m {
                spare.push(rows[take]);
            }
        }
        if test.is_empty() {
            // A share too small to hold out one object of any class: one object.
            let Some(&one) = spare.first() else {
                anyhow::bail!(
                    "--holdout {f}: no class of {} has 2 objects, so none can be held out",
                    args.data.display()
                );
            };
            test.push(one);
        }
        test.sort_unstable();
        let train = complement(&test);
        return Ok((format!("holdout {f}"), vec![(train, test)]));
    }
    let Some(k) = args.folds else {
        anyhow::ensure!(
            DEFAULT_FOLDS <= n,
            "{}: {n} objects, too few for the default {DEFAULT_FOLDS}-fold cross-validation \
             (each fold holds at least one): give --folds K, 2 to {n}, or --holdout F",
            args.data.display()
        );
        return Ok(dealt(frame, DEFAULT_FOLDS, args.seed, complement));
    };
    anyhow::ensure!(
        k >= 2 && k <= n,
        "--folds must be between 2 and the number of objects ({n}), found {k}"
    );
    Ok(dealt(frame, k, args.seed, complement))
}

/// The `k` stratified folds of `frame`, each with its training part.
fn dealt(
    frame: &Frame,
    k: usize,
    seed: u64,
    complement: impl Fn(&[usize]) -> Vec<usize>,
) -> (String, Vec<TrainTest>) {
    let parts = cslearn::testcost::folds(frame, k, seed)
        .into_iter()
        .map(|test| (complement(&test), test))
        .collect();
    (format!("{k}-fold"), parts)
}

/// Refuse a split whose training part lacks a class.
fn check_classes(args: &ClassifyArgs, frame: &Frame, splits: &[TrainTest]) -> Result<()> {
    let totals = frame.class_totals();
    for (j, (train, _)) in splits.iter().enumerate() {
        let mut seen = vec![0usize; frame.class_count()];
        for &r in train {
            seen[frame.class(r) as usize] += 1;
        }
        if let Some(c) = seen.iter().position(|&m| m == 0) {
            let name = &frame.class_names()[c];
            let part = if splits.len() == 1 {
                "the training part".to_string()
            } else {
                format!("the training part of fold {}", j + 1)
            };
            anyhow::bail!(
                "{}: {part} has no object of class `{name}` ({} in the data): a tree must see \
                 every class it is judged on{}",
                args.data.display(),
                totals[c],
                if totals[c] == 1 {
                    "; a class of one object cannot be both learned and held out"
                } else {
                    ""
                }
            );
        }
    }
    Ok(())
}

/// For CVT, a warning when a training part holds a class of one object: the stratified
/// dealing of CVT's own cross-validation leaves it out of every inner fold's training
/// part but one, where the object is held out and counts as an error whatever the tree.
fn warn_of_lone_classes(frame: &Frame, splits: &[TrainTest]) {
    for (j, (train, _)) in splits.iter().enumerate() {
        let mut seen = vec![0usize; frame.class_count()];
        for &r in train {
            seen[frame.class(r) as usize] += 1;
        }
        if let Some(c) = seen.iter().position(|&m| m == 1) {
            let part = if splits.len() == 1 {
                "the training part".to_string()
            } else {
                format!("the training part of fold {}", j + 1)
            };
            crate::note(format_args!(
                "warning: {part} has one object of class `{}`: CVT's inner fold that holds \
                 it out learns without the class, and counts it as an error",
                frame.class_names()[c]
            ));
            return;
        }
    }
}

/// The genome as JSON: ICET's biased price of each feature, its `w`, confidence and
/// fitness.
fn genome_json(genome: &IcetGenome, names: &[String]) -> serde_json::Value {
    let prices: serde_json::Map<String, serde_json::Value> = names
        .iter()
        .zip(&genome.prices)
        .map(|(n, p)| (n.clone(), serde_json::json!(p)))
        .collect();
    serde_json::json!({
        "prices": prices,
        "w": genome.w,
        "confidence": genome.confidence,
        "fitness": genome.fitness,
    })
}

/// The budget of `--max-test-cost` and `--max-tests` (unlimited without them).
fn read_budget(args: &ClassifyArgs) -> Result<Budget> {
    budget_from_flags(args.max_test_cost, args.max_tests)
}

/// A budget from the values of `--max-test-cost` and `--max-tests`, a bad price refused
/// naming its flag.
pub(crate) fn budget_from_flags(
    max_test_cost: Option<f64>,
    max_tests: Option<usize>,
) -> Result<Budget> {
    if let Some(b) = max_test_cost {
        anyhow::ensure!(
            b.is_finite() && b >= 0.0,
            "--max-test-cost {b}: a budget must be a finite price, not negative"
        );
    }
    Budget::new(max_test_cost, max_tests).map_err(|e| anyhow::anyhow!("--max-test-cost: {e}"))
}

/// A flag that only the learner `owner` reads: refused for any other `method`, read by
/// `read` when given (its refusal named by the flag), the learner's default when not.
fn learner_flag<V, T: Default>(
    value: Option<V>,
    flag: &str,
    owner: Method,
    method: Method,
    read: impl FnOnce(V) -> Result<T, cslearn::Error>,
) -> Result<T> {
    match value {
        Some(_) if method != owner => anyhow::bail!(
            "{flag} is read by --learner {} only, not by --learner {}",
            owner.name(),
            method.name()
        ),
        Some(v) => read(v).map_err(|e| anyhow::anyhow!("{flag}: {e}")),
        None => Ok(T::default()),
    }
}

/// CVT's choice as JSON: the grower, the price per leaf it was cut back at (`null` where
/// it was pruned by its pessimistic cost instead) and the mean total cost per held-out
/// object of its cross-validation.
fn cvt_json(choice: &cslearn::testcost::CvtChoice) -> serde_json::Value {
    serde_json::json!({
        "grower": choice.grower_name(),
        "alpha": choice.alpha,
        "held_out_cost": choice.held_out_cost,
    })
}

/// Every test object's classification, in the data's order: its place in the data
/// (`object`, from 0), the split that tested it (`split`, from 0), its class, the answer,
/// what its tests cost and the probability of each class by name
/// ([`Classification::probabilities`](cslearn::testcost::Classification::probabilities)).
fn predictions_json(frame: &Frame, results: &[Part]) -> serde_json::Value {
    let names = frame.class_names();
    let mut objects: Vec<(usize, usize, &cslearn::testcost::Classification)> = results
        .iter()
        .enumerate()
        .flat_map(|(j, p)| p.objects.iter().map(move |(r, c)| (*r, j, c)))
        .collect();
    objects.sort_by_key(|&(r, j, _)| (r, j));
    objects
        .into_iter()
        .map(|(r, j, c)| {
            let probabilities: serde_json::Map<String, serde_json::Value> = names
                .iter()
                .zip(&c.probabilities)
                .map(|(n, p)| (n.clone(), serde_json::json!(p)))
                .collect();
            serde_json::json!({
                "object": r,
                "split": j,
                "actual": names[frame.class(r) as usize],
                "class": names[c.class as usize],
                "test_cost": c.test_cost,
                "probabilities": probabilities,
            })
        })
        .collect()
}

/// CVT's choice as one line of text.
fn cvt_text(choice: &cslearn::testcost::CvtChoice) -> String {
    format!(
        "grown by {}, {}, {:.2} per object on held-out objects",
        choice.grower_name(),
        choice.cut_text(),
        choice.held_out_cost
    )
}

/// The genome as one line of text.
fn genome_text(genome: &IcetGenome, names: &[String]) -> String {
    let prices: Vec<String> = names
        .iter()
        .zip(&genome.prices)
        .map(|(n, p)| format!("{n} {p:.2}"))
        .collect();
    format!(
        "w {:.3}, confidence {:.3}, fitness {:.2}; biased prices {}",
        genome.w,
        genome.confidence,
        genome.fitness,
        prices.join(", ")
    )
}

/// Run `csrl classify` with a learner of the family.
pub(crate) fn run(args: &ClassifyArgs, method: Method, out: &mut dyn Write) -> Result<()> {
    let mut spec = FrameSpec::new(args.target.as_str());
    spec.max_classes = args.max_classes;
    let frame = Frame::read_csv(&args.data, &spec, args.positive_if.as_deref())
        .map_err(|e| {
            if e.to_string().contains("raise the limit") {
                anyhow::anyhow!("{e} (--max-classes N)")
            } else {
                e.into()
            }
        })
        .context("cannot load the data")?;
    let prices = read_prices(args, &frame)?;
    let (mc, uniform) = read_mc(args, &frame, &prices)?;
    // Every total printed must be a true one: at worst an object pays every test in full
    // and the dearest error.
    let n = frame.len();
    if let Err(e) = mc.check_totals(&prices, n) {
        let reason = match e {
            cslearn::Error::Invalid { reason, .. } => reason,
            other => other.to_string(),
        };
        anyhow::bail!("{}: {reason}", args.costs.display());
    }
    let (scheme, parts) = splits(args, &frame)?;
    check_classes(args, &frame, &parts)?;
    let selection_prices = match &args.selection_prices {
        Some(name) => cslearn::testcost::SelectionPrices::parse(name)
            .map_err(|e| anyhow::anyhow!("--selection-prices: {e}"))?,
        None => cslearn::testcost::SelectionPrices::default(),
    };
    let pruning = learner_flag(
        args.icet_pruning.as_deref(),
        "--icet-pruning",
        Method::Icet,
        method,
        Pruning::parse,
    )?;
    let act = learner_flag(
        args.act_samples,
        "--act-samples",
        Method::Act,
        method,
        ActParams::with_samples,
    )?;
    let cvt = learner_flag(
        args.cvt_folds,
        "--cvt-folds",
        Method::Cvt,
        method,
        CvtParams::with_folds,
    )?;
    // Each flag is VOI's alone; together they are checked by the library.
    let given = |v: Option<f64>, flag| {
        learner_flag(v, flag, Method::Voi, method, |x| {
            Ok::<_, cslearn::Error>(Some(x))
        })
    };
    let voi = cslearn::testcost::VoiParams::from_options(
        learner_flag(
            args.voi_lookahead,
            "--voi-lookahead",
            Method::Voi,
            method,
            |d| Ok::<_, cslearn::Error>(Some(d)),
        )?,
        given(args.voi_confidence, "--voi-confidence")?,
        given(args.voi_m, "--voi-m")?,
    )
    .map_err(|e| anyhow::anyhow!("--voi-lookahead / --voi-confidence / --voi-m: {e}"))?;
    // Without the flag, one thread (the library's default, not `usize`'s 0).
    let threads = |value: Option<usize>, flag, owner| -> Result<Option<usize>> {
        learner_flag(value, flag, owner, method, |n| {
            Ok::<_, cslearn::Error>(Some(n))
        })
    };
    let act = match threads(args.act_threads, "--act-threads", Method::Act)? {
        Some(n) => act.with_threads(n),
        None => act,
    };
    let cvt = match threads(args.cvt_threads, "--cvt-threads", Method::Cvt)? {
        Some(n) => cvt.with_threads(n),
        None => cvt,
    };
    let cvt = match args.cvt_samples {
        Some(_) => learner_flag(
            args.cvt_samples,
            "--cvt-samples",
            Method::Cvt,
            method,
            |r| cvt.with_samples(r),
        )?,
        None => cvt,
    };
    let budget = read_budget(args)?;
    if args.max_lookahead_features.is_some() && !matches!(method, Method::Act | Method::Cvt) {
        anyhow::bail!(
            "--max-lookahead-features is read by --learner act and cvt only, not by --learner {}",
            method.name()
        );
    }
    let params = cslearn::testcost::FamilyParams {
        max_lookahead_features: args
            .max_lookahead_features
            .unwrap_or(cslearn::testcost::FamilyParams::DEFAULT_MAX_LOOKAHEAD_FEATURES),
        budget,
        selection_prices,
        cvt,
        icet: cslearn::testcost::IcetParams {
            pruning,
            ..cslearn::testcost::IcetParams::default()
        },
        act,
        voi,
        ..cslearn::testcost::FamilyParams::default()
    };
    let smallest = parts
        .iter()
        .map(|(train, _)| train.len())
        .min()
        .unwrap_or(0);
    params.check(method, &frame, smallest).map_err(|e| {
        let hint = match &e {
            cslearn::Error::Invalid { what, .. } if what.contains("lookahead") => {
                "; --max-lookahead-features N raises the limit (eg2 and dtmc learn wide \
                     tables fast)"
            }
            _ => "",
        };
        anyhow::anyhow!("--learner {}: {e}{hint}", method.name())
    })?;
    if method == Method::Cvt {
        warn_of_lone_classes(&frame, &parts);
    }
    let bar = crate::progress::progress_bar(parts.len() + usize::from(args.save.is_some()));
    let mut results = Vec::with_capacity(parts.len());
    for (j, (train, test)) in parts.iter().enumerate() {
        let fitted = cslearn::testcost::fit(
            method,
            &frame,
            train,
            &prices,
            &mc,
            &params,
            args.seed.wrapping_add(j as u64),
        );
        let mut part = Part {
            test_objects: test.len(),
            tree_nodes: fitted.tree.len(),
            genome: fitted.genome.clone(),
            cvt: fitted.cvt,
            ..Part::default()
        };
        for &r in test {
            let c = fitted.tree.classify_within(&frame, r, &prices, &budget);
            let actual = frame.class(r);
            part.tests_bought += c.tests.len();
            part.over_budget += usize::from(
                budget.max_test_cost().is_some_and(|b| c.test_cost > b)
                    || budget.max_tests().is_some_and(|k| c.tests.len() > k),
            );
            part.errors += usize::from(c.class != actual);
            part.test_cost += c.test_cost;
            part.delayed += usize::from(c.tests.iter().any(|&t| prices.test(t).delayed));
            part.mc_cost += mc.cost(c.class as usize, actual as usize);
            if args.json {
                part.objects.push((r, c));
            }
        }
        results.push(part);
        bar.inc(1);
    }
    let mut saved = None;
    if let Some(path) = &args.save {
        let all: Vec<usize> = (0..n).collect();
        let fitted = cslearn::testcost::fit(method, &frame, &all, &prices, &mc, &params, args.seed);
        bar.inc(1);
        let model = TreeModel::new(
            method,
            &frame,
            &args.target,
            args.positive_if.as_deref(),
            &fitted,
            &prices,
        );
        crate::write_file(path, model.to_json())?;
        crate::note(format_args!(
            "saved the model ({}, {} nodes, grown on all {n} objects) to {}",
            method.name(),
            fitted.tree.len(),
            path.display()
        ));
        saved = Some(fitted);
    }
    bar.finish_and_clear();

    let tested: usize = results.iter().map(|p| p.test_objects).sum();
    let per = |x: f64| x / tested.max(1) as f64;
    let errors: usize = results.iter().map(|p| p.errors).sum();
    let delayed: usize = results.iter().map(|p| p.delayed).sum();
    let delayed_tests: Vec<&str> = (0..prices.len())
        .filter(|&t| prices.test(t).delayed)
        .map(|t| frame.names()[t].as_str())
        .collect();
    let test_cost = per(results.iter().map(|p| p.test_cost).sum());
    let tests_bought = per(results.iter().map(|p| p.tests_bought as f64).sum());
    let over_budget: usize = results.iter().map(|p| p.over_budget).sum();
    let mc_cost = per(results.iter().map(|p| p.mc_cost).sum());
    let error_rate = errors as f64 / tested.max(1) as f64;
    let nodes = results.iter().map(|p| p.tree_nodes).sum::<usize>() as f64 / results.len() as f64;
    let standard = cslearn::testcost::standard_cost(&frame, &prices, &mc);
    let names = frame.names();
    if args.json {
        let mut json = serde_json::json!({
            "learner": method.name(),
            "evaluation": scheme,
            "seed": args.seed,
            "data": args.data.display().to_string(),
            "costs": args.costs.display().to_string(),
            "groups": args.groups.as_ref().map(|p| p.display().to_string()),
            "features": frame.feature_count(),
            "classes": frame.class_count(),
            "class_names": frame.class_names(),
            "objects": n,
            "test_objects": tested,
            "mc": uniform,
            "mc_matrix": args.mc_matrix.as_ref().map(|p| p.display().to_string()),
            "selection_prices": params.selection_prices.name(),
            "icet_pruning": (method == cslearn::testcost::Method::Icet).then(|| params.icet.pruning.name()),
            "act_samples": (method == cslearn::testcost::Method::Act).then_some(params.act.samples),
            "cvt_folds": (method == cslearn::testcost::Method::Cvt).then_some(params.cvt.folds),
            "cvt_samples": (method == cslearn::testcost::Method::Cvt).then_some(params.cvt.samples),
            "voi_lookahead": (method == cslearn::testcost::Method::Voi).then_some(params.voi.lookahead_for(frame.feature_count())),
            "voi_leaf": (method == cslearn::testcost::Method::Voi).then_some(params.voi.leaf),
            "all_tests_cost": prices.total(),
            "test_cost_per_object": test_cost,
            "tests_per_object": tests_bought,
            "max_test_cost": budget.max_test_cost(),
            "max_tests": budget.max_tests(),
            "objects_over_budget": over_budget,
            "errors": errors,
            "error_rate": error_rate,
            "delayed_tests": delayed_tests,
            "objects_waiting_for_a_delayed_test": delayed,
            "misclassification_cost_per_object": mc_cost,
            "total_cost_per_object": test_cost + mc_cost,
            "standard_cost": standard,
            "tree_nodes": nodes,
            "splits": results.iter().map(|p| {
                let mut v = serde_json::json!({
                    "test_objects": p.test_objects,
                    "errors": p.errors,
                    "test_cost": p.test_cost,
                    "misclassification_cost": p.mc_cost,
                    "tree_nodes": p.tree_nodes,
                });
                if let Some(g) = &p.genome {
                    v["genome"] = genome_json(g, names);
                }
                if let Some(c) = &p.cvt {
                    v["cvt"] = cvt_json(c);
                }
                v
            }).collect::<Vec<_>>(),
        });
        json["predictions"] = predictions_json(&frame, &results);
        if let (Some(path), Some(fitted)) = (&args.save, &saved) {
            let mut v = serde_json::json!({
                "path": path.display().to_string(),
                "tree_nodes": fitted.tree.len(),
            });
            if let Some(g) = &fitted.genome {
                v["genome"] = genome_json(g, names);
            }
            if let Some(c) = &fitted.cvt {
                v["cvt"] = cvt_json(c);
            }
            json["saved"] = v;
        }
        writeln!(out, "{json}")?;
        return Ok(());
    }
    writeln!(out, "learner     {} (seed {})", method.name(), args.seed)?;
    writeln!(
        out,
        "data        {} ({} features, {} classes, {n} objects)",
        args.data.display(),
        frame.feature_count(),
        frame.class_count()
    )?;
    writeln!(
        out,
        "prices      {}{} (every test: {:.2})",
        args.costs.display(),
        args.groups
            .as_ref()
            .map_or(String::new(), |g| format!(", groups {}", g.display())),
        prices.total()
    )?;
    match (&args.mc_matrix, args.mc, uniform) {
        (Some(path), _, _) => writeln!(out, "mc          the matrix of {}", path.display())?,
        (None, Some(v), _) => writeln!(out, "mc          {v} per wrong answer")?,
        (None, None, v) => writeln!(
            out,
            "mc          {:.2} per wrong answer (the default: the price of every test)",
            v.unwrap_or_default()
        )?,
    }
    writeln!(
        out,
        "evaluation  {scheme}: {tested} test objects, each classified by a tree grown without it"
    )?;
    writeln!(out, "test cost   {test_cost:.2} per object")?;
    if !budget.is_unlimited() {
        let limits: Vec<String> = budget
            .max_test_cost()
            .map(|b| format!("at most {b} in price"))
            .into_iter()
            .chain(budget.max_tests().map(|k| format!("at most {k} tests")))
            .collect();
        writeln!(
            out,
            "budget      {} per object: {tests_bought:.2} tests bought per object, {}",
            limits.join(" and "),
            match over_budget {
                0 => "no object past the budget".to_string(),
                n => format!("{n} objects past the budget"),
            }
        )?;
    }
    if !delayed_tests.is_empty() {
        writeln!(
            out,
            "delayed     {delayed} of {tested} objects waited for a delayed test ({})",
            delayed_tests.join(", ")
        )?;
    }
    writeln!(out, "error rate  {error_rate:.3} ({errors} errors)")?;
    writeln!(out, "mc cost     {mc_cost:.2} per object")?;
    writeln!(
        out,
        "total cost  {:.2} per object ({:.1}% of Turney's standard cost, {standard:.2})",
        test_cost + mc_cost,
        100.0 * (test_cost + mc_cost) / standard.max(f64::MIN_POSITIVE)
    )?;
    writeln!(
        out,
        "tree size   {nodes:.1} nodes (mean over {} tree{})",
        results.len(),
        if results.len() == 1 { "" } else { "s" }
    )?;
    for (j, p) in results.iter().enumerate() {
        let at = if results.len() == 1 {
            "held out".to_string()
        } else {
            format!("fold {}", j + 1)
        };
        if let Some(g) = &p.genome {
            writeln!(out, "genome      {at}: {}", genome_text(g, names))?;
        }
        if let Some(c) = &p.cvt {
            writeln!(out, "cvt         {at}: {}", cvt_text(c))?;
        }
    }
    if let Some(g) = saved.as_ref().and_then(|f| f.genome.as_ref()) {
        writeln!(out, "genome      saved tree: {}", genome_text(g, names))?;
    }
    if let Some(c) = saved.as_ref().and_then(|f| f.cvt.as_ref()) {
        writeln!(out, "cvt         saved tree: {}", cvt_text(c))?;
    }
    Ok(())
}
