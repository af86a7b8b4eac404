//! `csrl classify`: stream a CSV table of objects through an incremental cost-sensitive
//! learner and report its errors and measuring costs.
//!
//! # Two accuracies
//!
//! * **Prequential** (always): every object is predicted before it is learned, in one
//!   seeded pass, and the mistakes made on the way count. This is how the learner fares
//!   while it learns; early objects are predicted from an almost empty library.
//! * **Held out** (`--holdout F` or `--folds K`): the learner streams the training part
//!   (predict, then learn), then classifies the test part without learning; accuracy and
//!   sensing cost per object are measured on the test part only. Beside it, a cost-blind
//!   tree (ID3's gain, every price taken as equal) grown on the fully measured training
//!   objects classifies the same test part, charged the real prices.
//!
//! # A tree from CS-ID3's library can misclassify a training object
//!
//! CS-ID3's library holds observations: an example records only the features measured
//! for it (specification §2). A tree grown from such a library follows a feature's value when an
//! object has it; at a node where no library example has the object's value (they lacked
//! the feature or had another value), the object falls into the branch for any other
//! value, which holds no example and predicts the node's majority. A training object that
//! was stored with fewer features than the tree now asks for can land there and be
//! misclassified, even after several passes: passes add an example only after a wrong
//! prediction by the learner, whose attending drops examples that lack a measured feature,
//! not by the tree. This is CS-ID3 as the paper defines it, not a defect of the tree; the
//! learner's own prediction (`ClassifierKind::classify`) is what the held-out figures use.

use std::io::Write;

use anyhow::{Context, Result};
use cslearn::{Dataset, DatasetOptions, LearnerKind};

use crate::classify_args::ClassifierKind;
pub use crate::classify_args::ClassifyArgs;
use crate::progress::progress_bar;

/// Accuracy and cost per object on one test part (or summed over folds).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
struct HeldOut {
    /// Test objects classified.
    objects: usize,
    /// Right predictions of the learner.
    correct: usize,
    /// Sensing cost of the learner's classifications.
    cost: f64,
    /// Right predictions of the cost-blind tree grown on the fully measured training part.
    tree_correct: usize,
    /// Sensing cost of the tree's classifications, at the real prices.
    tree_cost: f64,
}

impl HeldOut {
    fn add(&mut self, o: HeldOut) {
        self.objects += o.objects;
        self.correct += o.correct;
        self.cost += o.cost;
        self.tree_correct += o.tree_correct;
        self.tree_cost += o.tree_cost;
    }

    fn json(&self, scheme: &str) -> serde_json::Value {
        let n = self.objects.max(1) as f64;
        serde_json::json!({
            "scheme": scheme,
            "test_objects": self.objects,
            "accuracy": self.correct as f64 / n,
            "mean_cost": self.cost / n,
            "cost_blind_tree_accuracy": self.tree_correct as f64 / n,
            "cost_blind_tree_mean_cost": self.tree_cost / n,
        })
    }
}

/// A sensor over a fully known object that adds the real price of every measurement.
struct Charged<'a> {
    object: &'a [Option<cslearn::Value>],
    costs: &'a cslearn::FeatureCosts,
    total: f64,
}

impl cslearn::Sensor for Charged<'_> {
    fn measure(&mut self, feature: cslearn::FeatureId) -> Option<cslearn::Value> {
        use cslearn::Costs as _;
        self.total += self.costs.cost(feature).map_or(0.0, |c| c.get());
        self.object.get(feature.index()).copied().flatten()
    }
}

/// Train `learner` on `train` (predict, then learn, in that order), then classify `test`
/// without learning; and the cost-blind tree on the same split.
fn split_eval<A, S, P, D, U>(
    mut learner: cslearn::Learner<A, S, P, D, U>,
    data: &Dataset,
    train: &[usize],
    test: &[usize],
    bar: &indicatif::ProgressBar,
) -> HeldOut
where
    A: cslearn::Attend,
    S: cslearn::Select,
    P: cslearn::Predict,
    D: cslearn::Discriminate,
    U: cslearn::Update,
{
    for &i in train {
        learner.learn(data.object(i), data.labels()[i]);
        bar.inc(1);
    }
    let library: cslearn::Library = train
        .iter()
        .map(|&i| {
            cslearn::Example::from_pairs(
                data.object(i)
                    .iter()
                    .enumerate()
                    .filter_map(|(f, v)| v.map(|v| (cslearn::FeatureId(f as u32), v))),
                data.labels()[i],
            )
        })
        .collect();
    let tree = cslearn::DecisionTree::build(
        &library,
        &cslearn::CostBlind(data.costs()),
        cslearn::TreeOptions::observations(),
    );
    let mut out = HeldOut::default();
    for &i in test {
        bar.inc(1);
        let truth = Some(data.labels()[i]);
        let c = learner.classify(data.object(i));
        out.objects += 1;
        out.correct += usize::from(c.class == truth);
        out.cost += c.cost.get();
        let mut sensor = Charged {
            object: data.object(i),
            costs: data.costs(),
            total: 0.0,
        };
        out.tree_correct += usize::from(tree.classify(&mut sensor).class == truth);
        out.tree_cost += sensor.total;
    }
    out
}

/// The held-out evaluation asked for, if any: the scheme's name and the summed results.
fn held_out(args: &ClassifyArgs, data: &Dataset) -> Result<Option<(String, HeldOut)>> {
    use rand::SeedableRng;
    let n = data.len();
    // A generator of its own, so that the prequential pass is unchanged.
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(args.seed ^ 0x5EED_5B17);
    let order = data.shuffled(&mut rng);
    let splits: Vec<(Vec<usize>, Vec<usize>)> = match (args.holdout, args.folds) {
        (Some(f), _) => {
            anyhow::ensure!(
                f > 0.0 && f < 1.0,
                "--holdout must be a share strictly between 0 and 1, found {f}"
            );
            // Checked first: with one object there is no share to clamp into.
            anyhow::ensure!(n >= 2, "--holdout needs at least 2 objects, found {n}");
            let k = ((n as f64 * f).round() as usize).clamp(1, n - 1);
            vec![(order[k..].to_vec(), order[..k].to_vec())]
        }
        (None, Some(k)) => {
            anyhow::ensure!(
                k >= 2 && k <= n,
                "--folds must be between 2 and the number of objects ({n}), found {k}"
            );
            (0..k)
                .map(|j| {
                    let part = |in_test: bool| -> Vec<usize> {
                        order
                            .iter()
                            .enumerate()
                            .filter(|(p, _)| (p % k == j) == in_test)
                            .map(|(_, &i)| i)
                            .collect()
                    };
                    (part(false), part(true))
                })
                .collect()
        }
        (None, None) => return Ok(None),
    };
    let scheme = match (args.holdout, args.folds) {
        (Some(f), _) => format!("holdout {f}"),
        (_, Some(k)) => format!("{k}-fold"),
        _ => unreachable!("returned above"),
    };
    let mut total = HeldOut::default();
    // Each split streams its training part and classifies its test part: a sign of life
    // over all of them (CS-IBL's time per object grows with its library).
    let work: usize = splits.iter().map(|(a, b)| a.len() + b.len()).sum();
    let bar = progress_bar(work);
    for (j, (train, test)) in splits.iter().enumerate() {
        let costs = data.costs().clone();
        let part = match args.learner {
            ClassifierKind::CsId3 => split_eval(cslearn::cs_id3(costs), data, train, test, &bar),
            ClassifierKind::CsIbl => split_eval(
                cslearn::cs_ibl(costs, args.tolerance.unwrap_or(1)),
                data,
                train,
                test,
                &bar,
            ),
            // Id3 (the family's learners never come here).
            _ => split_eval(
                cslearn::id3(
                    costs,
                    rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(
                        args.seed.wrapping_add(j as u64),
                    ),
                ),
                data,
                train,
                test,
                &bar,
            ),
        };
        total.add(part);
    }
    bar.finish_and_clear();
    Ok(Some((scheme, total)))
}

/// Refuse a flag the chosen learner does not read, and an output that would overwrite an
/// input.
fn check_flags(args: &ClassifyArgs) -> Result<()> {
    let name = args.learner.name();
    if args.learner.family().is_some() {
        anyhow::ensure!(
            args.tolerance.is_none(),
            "--tolerance is read by --learner cs-ibl only, not by --learner {name}"
        );
        anyhow::ensure!(
            args.dot.is_none(),
            "--dot draws CS-ID3's decision tree: it needs --learner cs-id3, not --learner {name}"
        );
    } else {
        let family_only = [
            ("--groups", args.groups.is_some()),
            ("--mc", args.mc.is_some()),
            ("--mc-matrix", args.mc_matrix.is_some()),
            ("--cost-name", !args.cost_name.is_empty()),
            ("--selection-prices", args.selection_prices.is_some()),
            ("--icet-pruning", args.icet_pruning.is_some()),
            ("--act-samples", args.act_samples.is_some()),
            ("--cvt-folds", args.cvt_folds.is_some()),
            ("--voi-lookahead", args.voi_lookahead.is_some()),
            ("--voi-confidence", args.voi_confidence.is_some()),
            ("--voi-m", args.voi_m.is_some()),
            ("--act-threads", args.act_threads.is_some()),
            ("--cvt-threads", args.cvt_threads.is_some()),
            ("--cvt-samples", args.cvt_samples.is_some()),
            ("--max-test-cost", args.max_test_cost.is_some()),
            ("--max-tests", args.max_tests.is_some()),
            ("--max-classes", args.max_classes.is_some()),
            (
                "--max-lookahead-features",
                args.max_lookahead_features.is_some(),
            ),
        ];
        let family = cslearn::testcost::Method::ALL.map(cslearn::testcost::Method::name);
        let family = family.join(", ");
        if let Some((flag, _)) = family_only.iter().find(|(_, given)| *given) {
            anyhow::bail!(
                "{flag} is read by the test-cost family only (--learner {family}), not by --learner {name}"
            );
        }
        anyhow::ensure!(
            !crate::testcost::is_turney(&args.costs),
            "--costs {} is in Turney's format, which the test-cost family reads (--learner \
             {family}); --learner {name} reads a `feature,cost` CSV file",
            args.costs.display()
        );
    }
    // Turney's `.delay` file is read from beside `--costs` without a flag of its own.
    let delays =
        crate::testcost::is_turney(&args.costs).then(|| args.costs.with_extension("delay"));
    let inputs = [
        ("--data", Some(&args.data)),
        ("--costs", Some(&args.costs)),
        ("--groups", args.groups.as_ref()),
        ("--mc-matrix", args.mc_matrix.as_ref()),
        ("`.delay` (read beside --costs)", delays.as_ref()),
    ];
    for (flag, output) in [("--save", &args.save), ("--dot", &args.dot)] {
        let Some(output) = output else { continue };
        for (input, path) in inputs {
            if let Some(path) = path
                && same_file(output, path)
            {
                anyhow::bail!(
                    "{flag} {} names the {input} file: it would overwrite it; give the output \
                     a name of its own",
                    output.display()
                );
            }
        }
    }
    Ok(())
}

/// Whether two paths name one existing file (through links too).
pub(crate) fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    let (Ok(x), Ok(y)) = (std::fs::metadata(a), std::fs::metadata(b)) else {
        return false;
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        x.dev() == y.dev() && x.ino() == y.ino()
    }
    #[cfg(not(unix))]
    {
        let _ = (x, y);
        std::fs::canonicalize(a).ok() == std::fs::canonicalize(b).ok()
    }
}

/// Run `csrl classify`.
pub fn run(args: &ClassifyArgs, out: &mut dyn Write) -> Result<()> {
    check_flags(args)?;
    if let Some(method) = args.learner.family() {
        return crate::testcost::run(args, method, out);
    }
    let mut options = DatasetOptions::new(args.target.as_str());
    options.positive_if.clone_from(&args.positive_if);
    let data = Dataset::load(&args.data, &args.costs, &options).context("cannot load the data")?;
    let (kind, name) = match args.learner {
        ClassifierKind::CsId3 => (LearnerKind::CsId3, "cs-id3"),
        ClassifierKind::CsIbl => (
            LearnerKind::CsIbl {
                tolerance: args.tolerance.unwrap_or(1),
            },
            "cs-ibl",
        ),
        _ => (LearnerKind::Id3, "id3"),
    };
    anyhow::ensure!(
        args.dot.is_none() || args.learner == ClassifierKind::CsId3,
        "--dot draws CS-ID3's decision tree: it needs --learner cs-id3"
    );
    if let (Some(save), Some(dot)) = (&args.save, &args.dot) {
        // One would overwrite the other.
        let same = std::path::absolute(save).ok() == std::path::absolute(dot).ok();
        anyhow::ensure!(
            !same,
            "--save and --dot name the same file ({}): give each its own",
            save.display()
        );
    }
    let bar = progress_bar(data.len());
    let (report, library) =
        cslearn::stream_dataset_keeping(&data, kind, args.seed, &mut |done, _| {
            bar.set_position(done as u64);
        });
    bar.finish_and_clear();
    if let Some(path) = &args.dot {
        // Grown (I^2/C, observation semantics) from the library the prequential pass
        // learned.
        let tree = cslearn::DecisionTree::build(
            &library,
            data.costs(),
            cslearn::TreeOptions::observations(),
        );
        crate::write_file(path, tree.to_dot(&data))?;
        crate::note(format_args!(
            "wrote the CS-ID3 decision tree to {}",
            path.display()
        ));
    }
    if let Some(path) = &args.save {
        let examples = library.len();
        // The library goes into the model, not a copy of it.
        let text = cslearn::Model::new(&data, kind, library).to_json();
        anyhow::ensure!(
            text.len() as u64 <= cslearn::MAX_FILE_BYTES,
            "the model of {examples} examples would take {} bytes, more than the {} a model \
             file may have (`csrl predict` could not read it): learn from fewer objects",
            text.len(),
            cslearn::MAX_FILE_BYTES
        );
        crate::write_file(path, text)?;
        crate::note(format_args!(
            "saved the model ({name}, {examples} examples) to {}",
            path.display()
        ));
    }
    let held = held_out(args, &data)?;
    if args.json {
        let mut json = serde_json::json!({
            "learner": name,
            "evaluation": "prequential",
            "seed": args.seed,
            "data": args.data.display().to_string(),
            "features": data.feature_count(),
            "classes": data.class_count(),
            "objects": report.objects,
            "errors": report.errors,
            "accuracy": report.accuracy,
            "total_cost": report.total_cost,
            "mean_cost": report.mean_cost,
            "full_cost": report.full_cost,
        });
        if let Some((scheme, h)) = &held {
            json["held_out"] = h.json(scheme);
        }
        writeln!(out, "{json}")?;
    } else {
        writeln!(out, "learner     {name} (seed {})", args.seed)?;
        writeln!(
            out,
            "data        {} ({} features, {} classes)",
            args.data.display(),
            data.feature_count(),
            data.class_count()
        )?;
        writeln!(out, "objects     {}", report.objects)?;
        writeln!(out, "errors      {}", report.errors)?;
        writeln!(
            out,
            "accuracy    {:.3} prequential (each object predicted, then learned, in one pass)",
            report.accuracy
        )?;
        writeln!(out, "total cost  {:.2}", report.total_cost)?;
        writeln!(out, "mean cost   {:.2} per object", report.mean_cost)?;
        writeln!(
            out,
            "full cost   {:.2} per object (measuring every feature)",
            report.full_cost
        )?;
        if let Some((scheme, h)) = &held {
            let n = h.objects.max(1) as f64;
            writeln!(
                out,
                "held out    {scheme}: {} test objects, learned on the rest, classified without learning",
                h.objects
            )?;
            writeln!(
                out,
                "  {name:<9} accuracy {:.3}, cost {:.2} per object",
                h.correct as f64 / n,
                h.cost / n
            )?;
            writeln!(
                out,
                "  tree      accuracy {:.3}, cost {:.2} per object (cost-blind tree on the fully measured training objects)",
                h.tree_correct as f64 / n,
                h.tree_cost / n
            )?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use cslearn::{
        Branch, ClassId, DecisionTree, FeatureCosts, Node, NodeId, Sensor as _, TreeOptions, Value,
    };
    use rand::{RngExt, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// The leaf an object reaches in `tree`, and whether the last edge was "any other
    /// value" (an edge no library example took).
    fn walk(tree: &DecisionTree, object: &[Option<Value>]) -> (NodeId, bool) {
        let mut at = tree.root();
        let mut via_other = false;
        let mut sensor = object;
        loop {
            match tree.node(at) {
                Node::Leaf { .. } => return (at, via_other),
                node @ Node::Split { feature, .. } => {
                    let v = sensor.measure(*feature);
                    let next = node.children().find(|(b, _)| match (b, v) {
                        (Branch::Value(x), Some(y)) => *x == y,
                        (Branch::Missing, None) => true,
                        _ => false,
                    });
                    (at, via_other) = match next {
                        Some((_, id)) => (id, false),
                        None => (
                            node.children()
                                .find(|(b, _)| *b == Branch::Other)
                                .expect("every split has an other branch")
                                .1,
                            true,
                        ),
                    };
                }
            }
        }
    }

    /// The toy case of the docs: small data sets streamed twice through CS-ID3, then a
    /// tree grown from its library. Some training object is misclassified through an
    /// "any other value" branch that holds no example, because the library keeps only the
    /// features measured for each example; and CS-ID3's own prediction does not depend
    /// on that tree.
    #[test]
    fn a_tree_from_cs_id3s_library_can_misclassify_a_training_object() {
        let mut found = 0;
        for seed in 0..300_u64 {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
            let rows: Vec<(Vec<Option<Value>>, ClassId)> = (0..11)
                .map(|_| {
                    let o: Vec<Option<Value>> = (0..3)
                        .map(|_| Some(Value(rng.random_range(0..3))))
                        .collect();
                    let class =
                        ClassId(u32::from(o[0] == Some(Value(0)) || o[2] == Some(Value(2))));
                    (o, class)
                })
                .collect();
            let costs = FeatureCosts::from_f64(&[1.0, 2.0, 3.0]).unwrap();
            let mut learner = cslearn::cs_id3(costs.clone());
            for _ in 0..2 {
                for (o, c) in &rows {
                    learner.learn(&o[..], *c);
                }
            }
            let tree = DecisionTree::build(learner.library(), &costs, TreeOptions::observations());
            for (o, c) in &rows {
                let (leaf, via_other) = walk(&tree, o);
                let Node::Leaf { class, examples } = tree.node(leaf) else {
                    unreachable!("walks end at leaves")
                };
                assert_eq!(tree.classify(&o[..]).class, *class);
                if *class != Some(*c) && via_other {
                    assert_eq!(*examples, 0, "an other branch holds no example");
                    found += 1;
                }
            }
        }
        assert!(
            found > 0,
            "the toy case should occur in some of these data sets"
        );
    }
}
