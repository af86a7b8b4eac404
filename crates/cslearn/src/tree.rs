//! Cost-sensitive decision trees built from a library by greedy I^2/C.
//!
//! The paper builds one from CS-QL's final state descriptions "using CS-ID3's class
//! prediction function" for efficient classification (section "Integrating CS-learning
//! with Q-learning"). Here the tree is grown greedily from the root: at each node the
//! feature with the best I^2/C over the node's examples ([`InfoCost`]) splits them, until
//! the examples of a node agree on a class.

use std::fmt::Write as _;

use crate::attend::Semantics;
use crate::example::Library;
use crate::learner::Classified;
use crate::select::{InfoCost, MissingRule};
use crate::sensing::Sensor;
use crate::types::{ClassId, Cost, Costs, FeatureId, Value};

/// How a tree reads its examples.
///
/// ```
/// use cslearn::{MissingRule, Semantics, TreeOptions};
/// assert_eq!(TreeOptions::observations().semantics, Semantics::Observation);
/// assert_eq!(TreeOptions::rules().missing, MissingRule::C45);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TreeOptions {
    /// What a feature an example lacks means.
    pub semantics: Semantics,
    /// How the gain treats examples lacking the feature.
    pub missing: MissingRule,
}

impl TreeOptions {
    /// For a library of observations, as CS-ID3 reads it: examples lacking the split
    /// feature form a branch of their own, which an object whose value is missing follows.
    ///
    /// ```
    /// assert_eq!(cslearn::TreeOptions::observations().missing, cslearn::MissingRule::OwnBranch);
    /// ```
    pub fn observations() -> TreeOptions {
        TreeOptions {
            semantics: Semantics::Observation,
            missing: MissingRule::OwnBranch,
        }
    }

    /// For a set of rules (csql's descriptions): a rule lacking the split feature goes
    /// down every branch, including the "any other value" one.
    ///
    /// ```
    /// assert_eq!(cslearn::TreeOptions::rules().semantics, cslearn::Semantics::Rule);
    /// ```
    pub fn rules() -> TreeOptions {
        TreeOptions {
            semantics: Semantics::Rule,
            missing: MissingRule::C45,
        }
    }
}

/// A node's index in its tree; the root is `NodeId(0)`.
///
/// ```
/// assert_eq!(cslearn::NodeId(0).0, 0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct NodeId(pub usize);

/// Which way an edge leaves a split node.
///
/// ```
/// use cslearn::{Branch, Value};
/// assert_ne!(Branch::Value(Value(0)), Branch::Other);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Branch {
    /// The object has this value.
    Value(Value),
    /// The object's value is missing.
    Missing,
    /// Any value without a branch of its own (and, for rules, a missing value).
    Other,
}

/// A node of a [`DecisionTree`].
///
/// ```
/// use cslearn::{ClassId, Example, FeatureCosts, Library, Node, TreeOptions, DecisionTree};
/// let lib = Library::from(vec![Example::new(ClassId(3))]);
/// let costs = FeatureCosts::new(Vec::new());
/// let tree = DecisionTree::build(&lib, &costs, TreeOptions::observations());
/// assert!(matches!(tree.node(tree.root()), Node::Leaf { class: Some(ClassId(3)), examples: 1 }));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    /// Classification ends here.
    Leaf {
        /// The class predicted; `None` where no example reached (a rule tree's "other"
        /// branch that no rule covers).
        class: Option<ClassId>,
        /// How many library examples reached this node.
        examples: usize,
    },
    /// Measure `feature` and follow the matching branch.
    Split {
        /// The feature measured.
        feature: FeatureId,
        /// Its cost, charged on classification.
        cost: Cost,
        /// One child per value the node's examples have, by ascending value.
        branches: Vec<(Value, NodeId)>,
        /// Where an object whose value is missing goes, if not to `other`.
        missing: Option<NodeId>,
        /// Where any other value goes.
        other: NodeId,
        /// How many library examples reached this node.
        examples: usize,
    },
}

impl Node {
    /// The children with the branch leading to each: values first, then missing, then
    /// other. A leaf has none.
    ///
    /// ```
    /// use cslearn::{ClassId, Example, FeatureCosts, FeatureId, Library, TreeOptions, DecisionTree, Value};
    /// let lib = Library::from(vec![
    ///     Example::from_pairs([(FeatureId(0), Value(0))], ClassId(0)),
    ///     Example::from_pairs([(FeatureId(0), Value(1))], ClassId(1)),
    /// ]);
    /// let tree = DecisionTree::build(&lib, &FeatureCosts::from_f64(&[1.0]).unwrap(), TreeOptions::observations());
    /// assert_eq!(tree.node(tree.root()).children().count(), 3); // values 0 and 1, other
    /// ```
    pub fn children(&self) -> impl Iterator<Item = (Branch, NodeId)> + '_ {
        let (branches, missing, other): (&[(Value, NodeId)], _, _) = match self {
            Node::Leaf { .. } => (&[], None, None),
            Node::Split {
                branches,
                missing,
                other,
                ..
            } => (branches, *missing, Some(*other)),
        };
        branches
            .iter()
            .map(|&(v, n)| (Branch::Value(v), n))
            .chain(missing.map(|n| (Branch::Missing, n)))
            .chain(other.map(|n| (Branch::Other, n)))
    }
}

/// Names for the features, values and classes in a DOT picture.
///
/// Every method has a default that prints the number; [`Dataset`](crate::Dataset) gives
/// the column and category names of a CSV file.
///
/// ```
/// use cslearn::{ClassId, Labels};
/// struct Yes;
/// impl Labels for Yes {
///     fn class(&self, class: ClassId) -> String { if class.0 == 1 { "yes".into() } else { "no".into() } }
/// }
/// assert_eq!(Yes.class(ClassId(1)), "yes");
/// assert_eq!(Yes.feature(cslearn::FeatureId(2)), "f2");
/// ```
pub trait Labels {
    /// The name of a feature.
    fn feature(&self, feature: FeatureId) -> String {
        feature.to_string()
    }
    /// The name of a feature's value.
    fn value(&self, _feature: FeatureId, value: Value) -> String {
        value.to_string()
    }
    /// The name of a class.
    fn class(&self, class: ClassId) -> String {
        class.to_string()
    }
}

/// The default [`Labels`]: numbers only.
///
/// ```
/// use cslearn::Labels;
/// assert_eq!(cslearn::PlainLabels.value(cslearn::FeatureId(0), cslearn::Value(3)), "3");
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct PlainLabels;

impl Labels for PlainLabels {}

/// A cost-sensitive decision tree.
///
/// Built greedily from a library ([`build`](DecisionTree::build)): a node whose examples
/// share a class is a leaf; otherwise the feature with the best I^2/C among those that
/// split the node's examples into at least two groups and that are not yet used on the
/// path is measured there. With no such feature the node is a leaf with the majority class
/// (ties to the lowest id).
///
/// * [`TreeOptions::observations`]: a child per value holds the examples with that value;
///   the examples lacking the feature get a child of their own, which an object whose value
///   is missing follows; any other value ends in a leaf with the node's majority class (as
///   CS-ID3 predicts when nothing is left attended). Every library example is then
///   classified to its own class unless two examples with the same values disagree.
/// * [`TreeOptions::rules`]: a rule lacking the feature goes down every value branch and
///   the "other" branch. Over pairwise-disjoint rules (each pair has some feature with
///   different values), every object that matches exactly one rule is classified to that
///   rule's class. The tree can hold a rule many times over, so rule trees are meant for
///   sets of rules of moderate size.
///
/// ```
/// use cslearn::{ClassId, DecisionTree, Example, FeatureCosts, FeatureId, Library, TreeOptions, Value};
/// let costs = FeatureCosts::from_f64(&[10.0, 1.0]).unwrap();
/// // Either feature decides the class; the tree measures the cheap one.
/// let lib = Library::from(vec![
///     Example::from_pairs([(FeatureId(0), Value(0)), (FeatureId(1), Value(0))], ClassId(0)),
///     Example::from_pairs([(FeatureId(0), Value(1)), (FeatureId(1), Value(1))], ClassId(1)),
/// ]);
/// let tree = DecisionTree::build(&lib, &costs, TreeOptions::observations());
/// let result = tree.classify(&lib[1]);
/// assert_eq!((result.class, result.cost.get()), (Some(ClassId(1)), 1.0));
/// assert_eq!(tree.expected_cost(&lib).get(), 1.0);
/// assert!(tree.to_dot(&cslearn::PlainLabels).starts_with("digraph"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct DecisionTree {
    nodes: Vec<Node>,
}

struct Builder<'a, C: ?Sized> {
    library: &'a Library,
    costs: &'a C,
    semantics: Semantics,
    select: InfoCost,
    path: Vec<FeatureId>,
    nodes: Vec<Node>,
}

/// The class shared by all `examples`, or their majority (ties to the lowest id).
fn majority(library: &Library, examples: &[usize]) -> Option<ClassId> {
    let mut classes: Vec<ClassId> = examples.iter().map(|&i| library[i].class()).collect();
    classes.sort_unstable();
    let mut best: Option<(usize, ClassId)> = None;
    for run in classes.chunk_by(|a, b| a == b) {
        if best.is_none_or(|(n, _)| run.len() > n) {
            best = Some((run.len(), run[0]));
        }
    }
    best.map(|(_, c)| c)
}

impl<C: Costs + ?Sized> Builder<'_, C> {
    fn leaf(&mut self, class: Option<ClassId>, examples: usize) -> NodeId {
        self.nodes.push(Node::Leaf { class, examples });
        NodeId(self.nodes.len() - 1)
    }

    fn grow(&mut self, examples: &[usize]) -> NodeId {
        let lib = self.library;
        let first = examples.first().map(|&i| lib[i].class());
        if examples.iter().all(|&i| Some(lib[i].class()) == first) {
            return self.leaf(first, examples.len());
        }
        let path = &self.path;
        let chosen = self.select.select_from(
            examples.iter().map(|&i| &lib[i]),
            |f| path.contains(&f),
            self.costs,
        );
        let feature_and_cost = chosen.and_then(|f| self.costs.cost(f).map(|c| (f, c)));
        let Some((feature, cost)) = feature_and_cost else {
            return self.leaf(majority(lib, examples), examples.len());
        };
        // Reserve this node's slot so that a parent precedes its children.
        let id = self.leaf(None, examples.len());
        let mut values: Vec<Value> = examples
            .iter()
            .filter_map(|&i| lib[i].get(feature))
            .collect();
        values.sort_unstable();
        values.dedup();
        let lacking: Vec<usize> = examples
            .iter()
            .copied()
            .filter(|&i| !lib[i].has(feature))
            .collect();
        self.path.push(feature);
        let semantics = self.semantics;
        let branches = values
            .iter()
            .map(|&v| {
                let child: Vec<usize> = examples
                    .iter()
                    .copied()
                    .filter(|&i| semantics.keeps(&lib[i], feature, v))
                    .collect();
                (v, self.grow(&child))
            })
            .collect();
        let (missing, other) = match semantics {
            Semantics::Observation => {
                let missing = (!lacking.is_empty()).then(|| self.grow(&lacking));
                (missing, self.leaf(majority(lib, examples), 0))
            }
            Semantics::Rule => (None, self.grow(&lacking)),
        };
        self.path.pop();
        self.nodes[id.0] = Node::Split {
            feature,
            cost,
            branches,
            missing,
            other,
            examples: examples.len(),
        };
        id
    }
}

impl DecisionTree {
    /// Grow a tree over every example of `library`, greedily by I^2/C under `costs`.
    /// Features without a price are never used.
    ///
    /// ```
    /// use cslearn::{DecisionTree, FeatureCosts, Library, TreeOptions};
    /// let tree = DecisionTree::build(&Library::new(), &FeatureCosts::new(Vec::new()), TreeOptions::rules());
    /// assert_eq!(tree.len(), 1); // one leaf, predicting nothing
    /// ```
    pub fn build<C: Costs + ?Sized>(
        library: &Library,
        costs: &C,
        options: TreeOptions,
    ) -> DecisionTree {
        let mut builder = Builder {
            library,
            costs,
            semantics: options.semantics,
            select: InfoCost::new(options.missing).requiring_split(options.semantics),
            path: Vec::new(),
            nodes: Vec::new(),
        };
        let all: Vec<usize> = (0..library.len()).collect();
        builder.grow(&all);
        DecisionTree {
            nodes: builder.nodes,
        }
    }

    /// Classify the object behind `sensor`, charging the cost of each feature measured.
    ///
    /// ```
    /// use cslearn::{ClassId, DecisionTree, Example, FeatureCosts, FeatureId, Library, TreeOptions, Value};
    /// let lib = Library::from(vec![
    ///     Example::from_pairs([(FeatureId(0), Value(0))], ClassId(0)),
    ///     Example::from_pairs([(FeatureId(0), Value(1))], ClassId(1)),
    /// ]);
    /// let tree = DecisionTree::build(&lib, &FeatureCosts::from_f64(&[2.5]).unwrap(), TreeOptions::observations());
    /// let r = tree.classify(&[Some(Value(1))][..]);
    /// assert_eq!((r.class, r.cost.get()), (Some(ClassId(1)), 2.5));
    /// ```
    pub fn classify<T: Sensor>(&self, mut sensor: T) -> Classified {
        let mut at = self.root();
        let mut charged = Cost::ZERO;
        loop {
            match &self.nodes[at.0] {
                Node::Leaf { class, .. } => {
                    return Classified {
                        class: *class,
                        cost: charged,
                    };
                }
                Node::Split {
                    feature,
                    cost,
                    branches,
                    missing,
                    other,
                    ..
                } => {
                    charged += *cost;
                    at = match sensor.measure(*feature) {
                        Some(v) => branches
                            .binary_search_by_key(&v, |&(b, _)| b)
                            .map_or(*other, |k| branches[k].1),
                        None => missing.unwrap_or(*other),
                    };
                }
            }
        }
    }

    /// The mean classification cost over `objects` (0 for none).
    ///
    /// ```
    /// use cslearn::{DecisionTree, FeatureCosts, Library, TreeOptions, Value};
    /// let tree = DecisionTree::build(&Library::new(), &FeatureCosts::new(Vec::new()), TreeOptions::rules());
    /// let rows = [[Some(Value(0))]];
    /// assert_eq!(tree.mean_cost(rows.iter().map(|r| &r[..])).get(), 0.0);
    /// ```
    pub fn mean_cost<T: Sensor>(&self, objects: impl IntoIterator<Item = T>) -> Cost {
        let mut total = Cost::ZERO;
        let mut n = 0_u64;
        for object in objects {
            total += self.classify(object).cost;
            n += 1;
        }
        if n == 0 {
            Cost::ZERO
        } else {
            // A mean of valid costs is a valid cost.
            Cost::new(total.get() / n as f64).unwrap_or(Cost::ZERO)
        }
    }

    /// The expected classification cost: the mean over the library's examples, each
    /// classified as an object.
    ///
    /// ```
    /// use cslearn::{ClassId, DecisionTree, Example, FeatureCosts, FeatureId, Library, TreeOptions, Value};
    /// let lib = Library::from(vec![
    ///     Example::from_pairs([(FeatureId(0), Value(0))], ClassId(0)),
    ///     Example::from_pairs([(FeatureId(0), Value(1))], ClassId(1)),
    /// ]);
    /// let tree = DecisionTree::build(&lib, &FeatureCosts::from_f64(&[3.0]).unwrap(), TreeOptions::observations());
    /// assert_eq!(tree.expected_cost(&lib).get(), 3.0);
    /// ```
    pub fn expected_cost(&self, library: &Library) -> Cost {
        self.mean_cost(library.iter())
    }

    /// The root.
    ///
    /// ```
    /// use cslearn::{DecisionTree, FeatureCosts, Library, TreeOptions};
    /// let tree = DecisionTree::build(&Library::new(), &FeatureCosts::new(Vec::new()), TreeOptions::rules());
    /// assert_eq!(tree.root(), cslearn::NodeId(0));
    /// ```
    pub fn root(&self) -> NodeId {
        NodeId(0)
    }

    /// The node `id` (panics for an id not from this tree, like slice indexing).
    ///
    /// ```
    /// use cslearn::{DecisionTree, FeatureCosts, Library, Node, TreeOptions};
    /// let tree = DecisionTree::build(&Library::new(), &FeatureCosts::new(Vec::new()), TreeOptions::rules());
    /// assert!(matches!(tree.node(tree.root()), Node::Leaf { class: None, .. }));
    /// ```
    pub fn node(&self, id: NodeId) -> &Node {
        &self.nodes[id.0]
    }

    /// Every node, indexed by [`NodeId`]; a parent comes before its children.
    ///
    /// ```
    /// use cslearn::{DecisionTree, FeatureCosts, Library, TreeOptions};
    /// let tree = DecisionTree::build(&Library::new(), &FeatureCosts::new(Vec::new()), TreeOptions::rules());
    /// assert_eq!(tree.nodes().len(), 1);
    /// ```
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The number of nodes.
    ///
    /// ```
    /// use cslearn::{DecisionTree, FeatureCosts, Library, TreeOptions};
    /// let tree = DecisionTree::build(&Library::new(), &FeatureCosts::new(Vec::new()), TreeOptions::rules());
    /// assert_eq!(tree.len(), 1);
    /// ```
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Always false: a tree has at least its root.
    ///
    /// ```
    /// use cslearn::{DecisionTree, FeatureCosts, Library, TreeOptions};
    /// let tree = DecisionTree::build(&Library::new(), &FeatureCosts::new(Vec::new()), TreeOptions::rules());
    /// assert!(!tree.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The number of edges on the longest path from the root to a leaf.
    ///
    /// ```
    /// use cslearn::{DecisionTree, FeatureCosts, Library, TreeOptions};
    /// let tree = DecisionTree::build(&Library::new(), &FeatureCosts::new(Vec::new()), TreeOptions::rules());
    /// assert_eq!(tree.depth(), 0);
    /// ```
    pub fn depth(&self) -> usize {
        // Parents precede children, so one backward pass sees every child before its parent.
        let mut depth = vec![0_usize; self.nodes.len()];
        for (i, node) in self.nodes.iter().enumerate().rev() {
            depth[i] = node
                .children()
                .map(|(_, c)| depth[c.0] + 1)
                .max()
                .unwrap_or(0);
        }
        depth.first().copied().unwrap_or(0)
    }

    /// The tree in Graphviz DOT, with names from `labels`. Split nodes are boxes showing
    /// the feature and its cost; leaves are ellipses showing the class and how many
    /// library examples reached them.
    ///
    /// ```
    /// use cslearn::{ClassId, DecisionTree, Example, FeatureCosts, FeatureId, Library, PlainLabels, TreeOptions, Value};
    /// let lib = Library::from(vec![
    ///     Example::from_pairs([(FeatureId(0), Value(0))], ClassId(0)),
    ///     Example::from_pairs([(FeatureId(0), Value(1))], ClassId(1)),
    /// ]);
    /// let tree = DecisionTree::build(&lib, &FeatureCosts::from_f64(&[1.0]).unwrap(), TreeOptions::observations());
    /// let dot = tree.to_dot(&PlainLabels);
    /// assert!(dot.contains("n0 [shape=box, label=\"f0\\ncost 1\"]"));
    /// assert!(dot.contains("n0 -> n1 [label=\"0\"]"));
    /// ```
    pub fn to_dot<L: Labels + ?Sized>(&self, labels: &L) -> String {
        let mut out = String::from("digraph tree {\n    node [fontname=\"Helvetica\"];\n");
        for (i, node) in self.nodes.iter().enumerate() {
            // Writing to a String cannot fail.
            let _ = match node {
                Node::Leaf { class, examples } => {
                    let name = class.map_or_else(|| "no class".to_string(), |c| labels.class(c));
                    writeln!(
                        out,
                        "    n{i} [shape=ellipse, label=\"{}\\n({examples})\"];",
                        escape(&name)
                    )
                }
                Node::Split { feature, cost, .. } => writeln!(
                    out,
                    "    n{i} [shape=box, label=\"{}\\ncost {cost}\"];",
                    escape(&labels.feature(*feature))
                ),
            };
            let feature = match node {
                Node::Split { feature, .. } => *feature,
                Node::Leaf { .. } => continue,
            };
            for (branch, child) in node.children() {
                let label = match branch {
                    Branch::Value(v) => labels.value(feature, v),
                    Branch::Missing => "missing".to_string(),
                    Branch::Other => "other".to_string(),
                };
                let _ = writeln!(
                    out,
                    "    n{i} -> n{} [label=\"{}\"];",
                    child.0,
                    escape(&label)
                );
            }
        }
        out.push_str("}\n");
        out
    }
}

/// Escape a label for a double-quoted DOT string.
fn escape(text: &str) -> String {
    text.replace('\\', "\\\\").replace('"', "\\\"")
}
