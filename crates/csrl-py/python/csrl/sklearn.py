"""scikit-learn estimators that pay for what they measure.

Two kinds of learner, both charging each object the price of the features (tests) it
needs measured:

* **CS-ID3 and CS-IBL** (:class:`CsId3Classifier`, :class:`CsIblClassifier`) learn
  incrementally, as the paper's framework does: every training object is first classified
  with as few (and as cheap) measurements as the library allows, then learned with its
  class; a wrong prediction makes the learner measure more features of the object until
  the examples that misled it no longer agree with it. ``fit`` streams the training data
  in order, ``passes`` times at most (it stops after a pass without a mistake). Values
  are compared for equality only: each column's distinct values become categories (a
  value not seen in ``fit`` is a category of its own, which no example has). NaN is a
  missing value. Bin continuous columns first (``KBinsDiscretizer(encode="ordinal")`` in
  a pipeline) for a tree that generalises.

>>> import numpy as np
>>> from csrl.sklearn import CsId3Classifier
>>> X = np.array([[0, 0], [1, 0], [0, 1], [1, 1]] * 3)
>>> y = X[:, 0]  # the cheap feature decides the class
>>> clf = CsId3Classifier(feature_costs=[1.0, 100.0]).fit(X, y)
>>> clf.predict([[1, 1], [0, 1]]).tolist(), clf.predict_cost([[1, 1], [0, 1]]).tolist()
([1, 0], [1.0, 1.0])
>>> clf.score(X, y)
1.0

* **The test-cost tree family** (``cslearn::testcost``) learns in batch: one decision
  tree grown on all the training objects, by ID3 (:class:`Id3Classifier`), C4.5
  (:class:`C45Classifier`), IDX (:class:`IdxClassifier`), batch CS-ID3
  (:class:`CsId3BatchClassifier`), EG2 (:class:`Eg2Classifier`), DTMC
  (:class:`DtmcClassifier`), ICET (:class:`IcetClassifier`), ACT
  (:class:`ActClassifier`), CVT (:class:`CvtClassifier`) or VOI
  (:class:`VoiClassifier`); or by any of them named
  by :class:`TestCostTreeClassifier`'s ``learner``. Numeric columns are split at
  thresholds as they are (no binning); columns holding strings (or named in
  ``nominal_features``, or of pandas' ``category`` dtype) are nominal, one branch per
  value. NaN (or ``None``) is a missing value: the object goes down every branch, paying
  for the tests of each, as C4.5 does. Features may share a group
  (``feature_groups``): the first test of a group ordered for an object is paid in full,
  later ones at their ``feature_discounts`` price. Every node answers the class of least
  expected ``misclassification_cost``; ``total_cost(X, y)`` is the mean of what the
  tests and the errors cost.

>>> from csrl.sklearn import C45Classifier, Eg2Classifier
>>> x = np.arange(40.0)
>>> X = np.column_stack([x, -x])  # both columns tell the class; the second is cheap
>>> y = np.where(x < 20, "no", "yes")
>>> costs = dict(feature_costs=[90.0, 2.0], misclassification_cost=500.0)
>>> C45Classifier(**costs).fit(X, y).predict_cost(X[:3]).tolist()
[90.0, 90.0, 90.0]
>>> eg2 = Eg2Classifier(**costs).fit(X, y)
>>> eg2.predict([[5.0, -5.0], [30.0, -30.0]]).tolist(), eg2.total_cost(X, y)
(['no', 'yes'], 2.0)
"""

from __future__ import annotations

import math
import numbers
import warnings
from collections.abc import Mapping
from typing import Any, Optional

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import (
    check_array,
    check_is_fitted,
    check_X_y,
    column_or_1d,
    validate_data,
)

from . import _csrl

__all__ = [
    "C45Classifier",
    "CsId3BatchClassifier",
    "CsId3Classifier",
    "CsIblClassifier",
    "DtmcClassifier",
    "Eg2Classifier",
    "IcetClassifier",
    "ActClassifier",
    "CvtClassifier",
    "VoiClassifier",
    "Id3Classifier",
    "IdxClassifier",
    "TestCostTreeClassifier",
]


class _CostSensitiveClassifier(ClassifierMixin, BaseEstimator):
    _kind = ""

    def _costs(self, n: int) -> list:
        fc = self.feature_costs
        if fc is None:
            return [1.0] * n
        if isinstance(fc, Mapping):
            names = getattr(self, "feature_names_in_", None)
            if names is None:
                raise ValueError(
                    "feature_costs given by column name needs X with column names "
                    "(a pandas DataFrame)"
                )
            missing = [str(c) for c in names if c not in fc]
            if missing:
                raise ValueError(f"feature_costs has no price for the columns {missing}")
            unknown = sorted(str(c) for c in set(fc) - set(names))
            if unknown:
                raise ValueError(f"feature_costs names columns X does not have: {unknown}")
            return [float(fc[c]) for c in names]
        costs = np.asarray(fc, dtype=float).ravel()
        if costs.shape[0] != n:
            raise ValueError(
                f"feature_costs has {costs.shape[0]} prices but X has {n} features"
            )
        return costs.tolist()

    def _encode(self, X: np.ndarray) -> list:
        """Each value as its category (NaN as missing, an unseen value as a new one)."""
        rows = np.empty(X.shape, dtype=object)
        for j, cats in enumerate(self.categories_):
            col = X[:, j]
            missing = np.isnan(col) if col.dtype.kind == "f" else np.zeros(len(col), bool)
            pos = np.searchsorted(cats, np.where(missing, cats[0] if len(cats) else 0, col))
            pos = np.minimum(pos, max(len(cats) - 1, 0))
            known = (cats[pos] == col) if len(cats) else np.zeros(len(col), bool)
            codes = np.where(known, pos, len(cats)).astype(object)
            codes[missing] = None
            rows[:, j] = codes
        return rows.tolist()

    def fit(self, X: Any, y: Any) -> "_CostSensitiveClassifier":
        """Learn from ``X`` (objects x features) and ``y`` (their classes)."""
        X, y = validate_data(self, X, y, dtype="numeric", ensure_all_finite="allow-nan")
        check_classification_targets(y)
        passes = self.passes
        if not isinstance(passes, (int, np.integer)) or passes < 1:
            raise ValueError(f"passes must be an integer at least 1, found {passes!r}")
        self.classes_, y_codes = np.unique(y, return_inverse=True)
        costs = self._costs(X.shape[1])
        self.categories_ = [
            np.unique(X[~np.isnan(X[:, j]), j] if X.dtype.kind == "f" else X[:, j])
            for j in range(X.shape[1])
        ]
        rows = self._encode(X)
        labels = [int(c) for c in y_codes]
        model = self._new_model(costs)
        # What every pass could charge in all, checked before the first: the training
        # cost is a sum of it, finite below the bound.
        most = float(sum(costs)) * len(rows) * int(passes)
        if not most <= _csrl.MAX_TOTAL_COST:
            raise _csrl.DataError(
                f"{len(rows)} objects at prices summing to {float(sum(costs)):g} over up to "
                f"{passes} passes could cost {most:g} in all, more than "
                f"{_csrl.MAX_TOTAL_COST:g} (so that training_cost_ stays finite)"
            )
        self.feature_costs_ = np.asarray(costs)
        self.training_errors_ = []
        self.training_cost_ = 0.0
        for _ in range(passes):
            errors, cost = model.learn(rows, labels)
            self.training_errors_.append(errors)
            self.training_cost_ += cost
            if errors == 0:
                break
        self.n_passes_ = len(self.training_errors_)
        # Where nothing can be predicted (no example agrees), the most common class.
        self.majority_class_ = int(np.argmax(np.bincount(y_codes)))
        self._fit_data = (rows, labels)
        self._model = model
        return self

    def _new_model(self, costs: list) -> "_csrl.Classifier":
        return _csrl.Classifier(self._kind, costs, getattr(self, "tolerance", 1))

    def _classify(self, X: Any):
        check_is_fitted(self, "classes_")
        X = validate_data(self, X, reset=False, dtype="numeric", ensure_all_finite="allow-nan")
        classes, costs = self._model.classify(self._encode(X))
        codes = np.array(
            [self.majority_class_ if c is None else c for c in classes], dtype=np.intp
        )
        return self.classes_[codes], np.asarray(costs, dtype=float)

    def predict(self, X: Any) -> np.ndarray:
        """The class of each object (measured as cheaply as the library allows; the
        learner does not learn from them)."""
        return self._classify(X)[0]

    def predict_cost(self, X: Any) -> np.ndarray:
        """What classifying each object costs: the prices of the features measured."""
        return self._classify(X)[1]

    def predict_with_cost(self, X: Any):
        """``(predict(X), predict_cost(X))`` in one classification."""
        return self._classify(X)

    def predict_proba(self, X: Any) -> np.ndarray:
        """The probability of each class (columns in the order of ``classes_``, rows
        summing to 1): the classes of the stored examples the prediction went by (for
        CS-ID3 the examples attended when it predicted, for CS-IBL the attended ones when
        they agree and the nearest ones otherwise), smoothed by Laplace's rule (one added
        to each class's count, then normalised). ``predict`` answers a class of largest
        probability (ties to the first in ``classes_``). Where no example speaks (never
        after ``fit``), the classes of the training objects, smoothed the same way, as
        ``predict`` then answers their majority.

        >>> import numpy as np
        >>> from csrl.sklearn import CsId3Classifier
        >>> X = np.array([[0, 0], [1, 0], [0, 1], [1, 1]] * 3)
        >>> clf = CsId3Classifier(feature_costs=[1.0, 100.0]).fit(X, X[:, 0])
        >>> clf.predict_proba([[1, 1]]).round(3).tolist()  # twelve examples of class 1 agree
        [[0.071, 0.929]]
        """
        check_is_fitted(self, "classes_")
        X = validate_data(self, X, reset=False, dtype="numeric", ensure_all_finite="allow-nan")
        k = len(self.classes_)
        classes, _, probabilities = self._model.classify_proba(self._encode(X), k)
        proba = np.asarray(probabilities, dtype=float).reshape(len(classes), k)
        if any(c is None for c in classes):
            counts = np.bincount(self._fit_data[1], minlength=k) + 1.0
            prior = counts / counts.sum()
            for i, c in enumerate(classes):
                if c is None:
                    proba[i] = prior
        return proba

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.input_tags.allow_nan = True
        return tags

    # The compiled model does not pickle; it is learned again from the same data, in
    # the same order, which gives the same model.
    def __getstate__(self) -> dict:
        state = self.__dict__.copy()
        state.pop("_model", None)
        return state

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        if "_fit_data" in state:
            rows, labels = state["_fit_data"]
            model = self._new_model(list(self.feature_costs_))
            for _ in range(self.n_passes_):
                model.learn(rows, labels)
            self._model = model


class CsId3Classifier(_CostSensitiveClassifier):
    """CS-ID3: decision-tree learning that weighs each feature's information against its
    price (I^2/C), one object at a time.

    Args:
        feature_costs: the price of each feature (a sequence, or a mapping from column
            name to price for a DataFrame); every price 1 when ``None``.
        passes: the most passes over the training data in ``fit``.

    Attributes:
        classes_, n_features_in_, feature_costs_: as scikit-learn's.
        training_errors_: the wrong predictions of each pass of ``fit``.
        training_cost_: everything measuring cost during ``fit``.
        n_passes_: passes made.
    """

    _kind = "cs-id3"

    def __init__(self, feature_costs: Optional[Any] = None, passes: int = 10) -> None:
        self.feature_costs = feature_costs
        self.passes = passes

    def export_graphviz(
        self,
        feature_names: Optional[list] = None,
        class_names: Optional[list] = None,
    ) -> str:
        """The cost-sensitive decision tree grown from the learned library, as Graphviz
        DOT text (``dot -Tsvg``), with the values each branch takes.

        >>> import numpy as np
        >>> from csrl.sklearn import CsId3Classifier
        >>> X = np.array([[0, 5], [1, 5], [0, 6], [1, 6]])
        >>> clf = CsId3Classifier(feature_costs=[1, 9]).fit(X, ["no", "yes", "no", "yes"])
        >>> print(clf.export_graphviz(feature_names=["cheap", "dear"]).splitlines()[0])
        digraph tree {
        """
        check_is_fitted(self, "classes_")
        if feature_names is None:
            names = getattr(self, "feature_names_in_", None)
            feature_names = [str(n) for n in names] if names is not None else [
                f"x{j}" for j in range(self.n_features_in_)
            ]
        if class_names is None:
            class_names = [str(c) for c in self.classes_]
        values = [[_fmt(v) for v in cats] for cats in self.categories_]
        return self._model.tree_dot(list(map(str, feature_names)), values, list(map(str, class_names)))


class CsIblClassifier(_CostSensitiveClassifier):
    """CS-IBL: instance-based learning that measures features cheapest-first until the
    nearest stored instances agree, tolerating up to ``tolerance`` wrong values.

    Args:
        feature_costs: as for :class:`CsId3Classifier`.
        tolerance: the mismatching values an instance may have and still be attended to.
        passes: the most passes over the training data in ``fit``.
    """

    _kind = "cs-ibl"

    def __init__(
        self, feature_costs: Optional[Any] = None, tolerance: int = 1, passes: int = 10
    ) -> None:
        self.feature_costs = feature_costs
        self.tolerance = tolerance
        self.passes = passes


def _fmt(v: Any) -> str:
    f = float(v)
    return str(int(f)) if f.is_integer() else repr(f)


# --- The test-cost tree family -------------------------------------------------------

_LEARNERS = ("id3-batch", "c45", "idx", "cs-id3-batch", "eg2", "dtmc", "icet", "act", "cvt", "voi")


def _is_missing(v: Any) -> bool:
    """None, NaN, and pandas' NA and NaT."""
    if v is None:
        return True
    if isinstance(v, (float, np.floating)):
        return bool(v != v)
    return type(v).__name__ in ("NAType", "NaTType")


def _is_number(v: Any) -> bool:
    """A real number (bools and numpy's numbers included; not complex)."""
    return isinstance(v, (numbers.Real, np.integer, np.floating, np.bool_))


def _value_name(v: Any) -> str:
    """The name of a nominal value: a string as it is, a number as it prints (a whole
    float as an int, so that 1 and 1.0 are one value), anything else by ``str``."""
    if isinstance(v, str):
        return v
    if isinstance(v, (bool, np.bool_)):
        return str(bool(v))
    if _is_number(v):
        return _fmt(v)
    return str(v)


def _price(what: str, v: Any) -> float:
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise ValueError(f"{what} is {v!r}, not a number") from None
    if not np.isfinite(f) or f < 0:
        raise ValueError(f"{what} is {f}: costs must be finite and not negative")
    return f


class TestCostTreeClassifier(ClassifierMixin, BaseEstimator):
    """A decision tree of the test-cost family: tests (features) have prices, errors
    have costs, and the tree is grown on all of ``fit``'s objects by the ``learner``
    named (``cslearn::testcost``).

    * ``"id3-batch"``: the test of largest information gain, blind to prices; no pruning.
    * ``"c45"``: the gain ratio among tests of at least average gain, blind to prices;
      C4.5's pessimistic pruning at ``confidence``.
    * ``"idx"`` (Norton 1989): gain / price; pruned as C4.5.
    * ``"cs-id3-batch"`` (Tan 1991): gain² / price; pruned as C4.5.
    * ``"eg2"`` (Núñez 1991): (2^gain − 1) / (price + 1)^w; pruned as C4.5.
    * ``"dtmc"`` (Ling, Yang, Wang and Zhang 2004): the largest reduction of the
      expected total cost (tests plus misclassification); a leaf where no test reduces
      it; no pruning.
    * ``"icet"`` (Turney 1995): EG2 with biased prices, ``w`` and pruning confidence
      found by a genetic search (``population``, ``generations``, ``seed``) whose
      fitness is the mean total cost on half the training objects of the tree grown on
      the other half.
    * ``"act"`` (Esmeir and Markovitch 2008): at each node, the test whose price plus
      the cheapest of ``act_samples`` trees sampled under each of its branches (by a
      stochastic EG2, from ``seed``) costs least, tests plus pessimistic errors; a leaf
      where answering costs less; pruned by total cost.
    * ``"cvt"``, the cost-validated tree: unpruned trees grown by seven growers (EG2 at
      w = 0, 0.5, 1 and 2, C4.5's gain ratio, DTMC and ACT's sampled lookahead), each
      cut back along its cost-complexity path or by ACT's pessimistic pruning by cost;
      the grower and the cut of least total cost on held-out objects
      (``cvt_folds``-fold cross-validation on the training objects, folds and samples
      drawn from ``seed``) give the tree.
    * ``"voi"``, the value-of-information tree: at each node, the test whose price plus,
      over its branches, the least of stopping and buying more (``voi_lookahead`` tests
      ahead: three on at most 21 features, two beyond) costs least, if that is less than stopping; stopping costs C4.5's
      pessimistic estimate of the errors at ``voi_confidence`` (0.25), or an m-estimate
      of the classes with ``voi_m``. A pair of tests that pays only together is bought.
      Nothing random: any ``seed``, the same tree.

    The price a learner sees at a node is the test's price on that node's path: nothing
    for a test already done, the discount after another test of its group. Every node
    answers the class of least expected misclassification cost. The named subclasses
    (:class:`C45Classifier`, :class:`Eg2Classifier`, ...) are this estimator with the
    learner fixed and only its parameters.

    Args:
        learner: the learner's name (above).
        feature_costs: the full price of each feature's test: a sequence, or a mapping
            from column name to price for a DataFrame; every price 1 when ``None``.
        feature_groups: the group of each feature (any hashable label, ``None`` for no
            group), as a sequence or a mapping from column name (columns it leaves out
            are in no group); ``None``: no groups.
        feature_discounts: the price of each grouped feature's test when another test of
            its group was done first for the object (Turney's discount), as a sequence
            (``None`` entries: the full price) or a mapping from column name; at most
            the full price, and only for features in a group.
        misclassification_cost: what a wrong answer costs: a number (every error the
            same), a ``k x k`` matrix indexed ``[actual][predicted]`` in the order of
            ``classes_`` (the sorted classes of ``y``), or a mapping
            ``{actual: {predicted: cost}}`` by class label (pairs it leaves out of the
            classes of ``y`` must be correct answers, which cost 0).
        nominal_features: columns to treat as nominal even though they hold numbers
            (integer codes), as indices, names (for a DataFrame) or a boolean mask.
        confidence: C4.5's pruning confidence, in (0, 1), for the pruned learners (not
            ``id3`` or ``dtmc``; ICET searches its own).
        w: EG2's weight of the price, in [0, 1] (0: cost-blind).
        seed: ICET's seed (its halves and its search), ACT's (its samples) and CVT's (its
            folds); the same seed, the same tree.
        population, generations: the size of ICET's search (Turney's 50 and 20).
        act_samples: ACT's trees sampled under each branch of each candidate test (its
            ``r``, 5; 0 values each branch as a leaf), at most 1000.
        selection_prices: the price a selection function sees for a test: ``"path"``
            (after the node's path: a test done once is free further down; the default)
            , ``"listed"`` (its listed price whatever the path, as the published
            implementations score tests) or ``"listed-once"`` (listed, but nothing for a
            test the path already did). An object pays after its path either way.
        icet_pruning: how ICET prunes its trees: ``"errors"`` (C4.5's, Turney's; the
            default) or ``"costs"`` (a test must pay for itself at the real prices).
        icet_search_objects: the most training objects ICET's search uses, half to grow
            and half to score (400; at least 2); the final tree grows on all of them.
        cvt_folds: the folds of CVT's cross-validation (5; at least 2).
        cvt_samples: the trees CVT's lookahead grower samples under each branch (5, as
            ACT's; at most 1000): fewer make CVT faster, its time being mostly the
            lookahead's, and grow other trees; 0 leaves the lookahead out, CVT choosing
            among its greedy growers only.
        voi_lookahead: how many tests ahead VOI values a test (``None``: three on data
            of at most 21 features, two beyond; or 1 to 3).
        voi_confidence: the confidence of VOI's pessimistic estimate of what stopping
            costs (``None``: 0.25; in (0, 1)).
        voi_m: estimate what stopping costs by an m-estimate of the classes instead, the
            class shares weighing this many objects (at least 0; not with
            ``voi_confidence``); ``None``: the pessimistic estimate.
        n_jobs: the threads one ACT or CVT fit uses (``None``: one; ``-1``: every core;
            else at least 1): ACT values the candidate tests of a node at the same time,
            CVT grows its trees on all the objects and on each fold at the same time, and
            the tree does not depend on it. Other learners use one.
        max_test_cost: the most one object may pay for its tests (a number at least 0,
            after group discounts, a test done once free further down), or ``None``: no
            limit. ``predict``, ``predict_proba``, ``predict_cost`` and the rest never
            buy a test that would take an object past it: the node that asked for the
            test answers (its class, and its smoothed class weights as probabilities);
            below a missing value, the object's branches share one purse. The greedy
            learners (``id3-batch``, ``c45``, ``idx``, ``cs-id3-batch``, ``eg2``,
            ``dtmc``) also grow within it: no path of their trees costs more.
        max_tests: the most distinct tests one object may buy (an integer at least 0),
            held as ``max_test_cost`` is; ``None``: no limit. A budget of 0 answers
            every object from the root, paying nothing.

    Attributes:
        classes_, n_features_in_, feature_names_in_: as scikit-learn's.
        nominal_features_: a boolean per feature, True where it is nominal.
        categories_: per feature, ``None`` if numeric, else its values' names (sorted).
        feature_costs_: the full price of each feature.
        misclassification_costs_: the ``k x k`` matrix ``[actual][predicted]``.
        icet_genome_: for ICET, the best individual of its search: a dict of the biased
            ``prices``, ``w``, ``confidence`` and its ``fitness`` (mean total cost on
            the held-out half of the training objects).
        cvt_choice_: for CVT, what its cross-validation chose: a dict of the ``grower``
            (``"eg2-w0"``, ``"eg2-w0.5"``, ``"eg2-w1"``, ``"eg2-w2"``, ``"c45"``,
            ``"dtmc"`` or ``"act"``), the ``alpha`` (price per leaf) its tree was cut
            back at (``None`` where it was pruned by its pessimistic cost instead) and
            the ``held_out_cost`` (mean total cost per held-out object).

    ``predict_proba`` gives the probability of each class: the class weights of the
    leaf that answers, smoothed by Laplace's rule (one added to each class's training
    weight, then normalised); below a missing value, the mix of the leaves reached,
    weighted as the object reached them. A node answers the class of least expected
    misclassification cost, which is a class of largest probability when every error
    costs the same, and need not be otherwise.
    """

    # Not a pytest test class, for all that its name starts with "Test".
    __test__ = False

    _learner: Optional[str] = None

    def __init__(
        self,
        learner: str = "eg2",
        feature_costs: Optional[Any] = None,
        feature_groups: Optional[Any] = None,
        feature_discounts: Optional[Any] = None,
        misclassification_cost: Any = 100.0,
        nominal_features: Optional[Any] = None,
        confidence: float = 0.25,
        w: float = 1.0,
        seed: int = 0,
        population: int = 50,
        generations: int = 20,
        act_samples: int = 5,
        selection_prices: str = "path",
        icet_pruning: str = "errors",
        icet_search_objects: int = 400,
        cvt_folds: int = 5,
        voi_lookahead: Optional[int] = None,
        voi_confidence: Optional[float] = None,
        voi_m: Optional[float] = None,
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
        n_jobs: Optional[int] = None,
        cvt_samples: int = 5,
    ) -> None:
        self.learner = learner
        self.feature_costs = feature_costs
        self.feature_groups = feature_groups
        self.feature_discounts = feature_discounts
        self.misclassification_cost = misclassification_cost
        self.nominal_features = nominal_features
        self.confidence = confidence
        self.w = w
        self.seed = seed
        self.population = population
        self.generations = generations
        self.act_samples = act_samples
        self.selection_prices = selection_prices
        self.icet_pruning = icet_pruning
        self.icet_search_objects = icet_search_objects
        self.cvt_folds = cvt_folds
        self.voi_lookahead = voi_lookahead
        self.voi_confidence = voi_confidence
        self.voi_m = voi_m
        self.max_test_cost = max_test_cost
        self.max_tests = max_tests
        self.n_jobs = n_jobs
        self.cvt_samples = cvt_samples

    # -- parameters -------------------------------------------------------------------

    def _budget_params(self) -> dict:
        """``max_test_cost`` and ``max_tests`` checked, as ``_csrl.TestCostTree`` takes
        them."""
        max_test_cost = getattr(self, "max_test_cost", None)
        max_tests = getattr(self, "max_tests", None)
        if max_test_cost is not None:
            if (
                isinstance(max_test_cost, bool)
                or not isinstance(max_test_cost, (numbers.Real, np.integer, np.floating))
                or not (math.isfinite(float(max_test_cost)) and float(max_test_cost) >= 0)
            ):
                raise ValueError(
                    f"max_test_cost must be None or a finite number at least 0, found {max_test_cost!r}"
                )
            max_test_cost = float(max_test_cost)
        if max_tests is not None:
            integer = isinstance(max_tests, (numbers.Integral, np.integer)) and not isinstance(max_tests, bool)
            if not integer or not 0 <= max_tests < 2**64:
                raise ValueError(f"max_tests must be None or an integer at least 0, found {max_tests!r}")
            max_tests = int(max_tests)
        return {"max_test_cost": max_test_cost, "max_tests": max_tests}

    def _learner_name(self) -> str:
        name = self._learner or self.learner
        if name not in _LEARNERS:
            raise ValueError(f"learner must be one of {', '.join(_LEARNERS)}; found {name!r}")
        return name

    def _per_feature(self, what: str, given: Any, n: int, fill: Any, complete: bool) -> list:
        """One entry per feature from a sequence, or from a mapping by column name."""
        names = getattr(self, "feature_names_in_", None)
        if isinstance(given, Mapping):
            if names is None:
                raise ValueError(
                    f"{what} given by column name needs X with column names (a pandas DataFrame)"
                )
            unknown = sorted(str(c) for c in given if c not in set(names))
            if unknown:
                raise ValueError(f"{what} names columns X does not have: {unknown}")
            if complete:
                missing = [str(c) for c in names if c not in given]
                if missing:
                    raise ValueError(f"{what} has no entry for the columns {missing}")
            return [given.get(c, fill) for c in names]
        if isinstance(given, (str, bytes)) or not hasattr(given, "__len__"):
            raise ValueError(
                f"{what} must be a sequence with one entry per feature or a mapping "
                f"from column name; found {type(given).__name__}"
            )
        values = list(given.ravel()) if isinstance(given, np.ndarray) else list(given)
        if len(values) != n:
            raise ValueError(f"{what} has {len(values)} entries but X has {n} features")
        return values

    def _feature_label(self, j: int) -> str:
        names = getattr(self, "feature_names_in_", None)
        return repr(str(names[j])) if names is not None else f"feature {j}"

    def _prices(self, n: int):
        """``(full, discount, group)`` per feature, and the group names."""
        if self.feature_costs is None:
            full = [1.0] * n
        else:
            given = self._per_feature("feature_costs", self.feature_costs, n, None, True)
            full = [
                _price(f"feature_costs: the price of {self._feature_label(j)}", v)
                for j, v in enumerate(given)
            ]
        groups: list = [None] * n
        group_names: list = []
        if self.feature_groups is not None:
            labels = self._per_feature("feature_groups", self.feature_groups, n, None, False)
            index: dict = {}
            for j, label in enumerate(labels):
                if label is None or _is_missing(label):
                    continue
                try:
                    key = index.setdefault(label, len(index))
                except TypeError:
                    raise ValueError(
                        f"feature_groups: the group of {self._feature_label(j)} is {label!r}, "
                        "which is not hashable"
                    ) from None
                groups[j] = key
            group_names = [str(label) for label in index]
        discounts = list(full)
        if self.feature_discounts is not None:
            given = self._per_feature("feature_discounts", self.feature_discounts, n, None, False)
            for j, v in enumerate(given):
                if v is None:
                    continue
                what = f"feature_discounts: the discount of {self._feature_label(j)}"
                d = _price(what, v)
                if d > full[j]:
                    raise ValueError(f"{what} is {d}, above its full price {full[j]}")
                if groups[j] is None and d != full[j]:
                    raise ValueError(
                        f"{what} is {d}, but feature_groups puts it in no group "
                        "(a discount applies after another test of the same group)"
                    )
                discounts[j] = d
        return [(f, d, g) for f, d, g in zip(full, discounts, groups)], group_names

    def _misclassification(self, classes: np.ndarray) -> np.ndarray:
        k = len(classes)
        mc = self.misclassification_cost
        if isinstance(mc, Mapping):
            matrix = np.zeros((k, k))
            labels = classes.tolist()
            for a, actual in enumerate(labels):
                row = mc.get(actual, {})
                if not isinstance(row, Mapping):
                    raise ValueError(
                        f"misclassification_cost[{actual!r}] must be a mapping from the "
                        f"predicted class to the cost; found {type(row).__name__}"
                    )
                for p, predicted in enumerate(labels):
                    if predicted in row:
                        what = f"misclassification_cost[{actual!r}][{predicted!r}]"
                        matrix[a, p] = _price(what, row[predicted])
                    elif a != p:
                        raise ValueError(
                            f"misclassification_cost has no cost for answering {predicted!r} "
                            f"to an object of class {actual!r}"
                        )
            return matrix
        if np.ndim(mc) == 0:
            cost = _price("misclassification_cost", mc)
            return cost * (1.0 - np.eye(k))
        try:
            matrix = np.asarray(mc, dtype=float)
        except (TypeError, ValueError):
            raise ValueError(
                "misclassification_cost must be a number, a k x k matrix or a mapping; "
                f"found {mc!r}"
            ) from None
        if matrix.shape != (k, k):
            raise ValueError(
                f"misclassification_cost is a matrix of shape {matrix.shape}, but y has {k} "
                f"classes {classes.tolist()}: it must be {k} x {k}, indexed "
                "[actual][predicted] in the order of classes_"
            )
        bad = ~np.isfinite(matrix) | (matrix < 0)
        if bad.any():
            a, p = np.argwhere(bad)[0]
            raise ValueError(
                f"misclassification_cost[{a}][{p}] is {matrix[a, p]}: costs must be finite "
                "and not negative"
            )
        return matrix

    def _nominal_mask(self, n: int, categorical: Optional[list]) -> np.ndarray:
        mask = np.zeros(n, dtype=bool)
        if categorical is not None:
            mask |= np.asarray(categorical, dtype=bool)
        given = self.nominal_features
        if given is None:
            return mask
        if isinstance(given, (str, bytes)) or not hasattr(given, "__iter__"):
            given = [given]
        given = list(given)
        if given and all(isinstance(g, (bool, np.bool_)) for g in given):
            if len(given) != n:
                raise ValueError(f"nominal_features is a mask of {len(given)} entries but X has {n} features")
            return mask | np.asarray(given, dtype=bool)
        names = getattr(self, "feature_names_in_", None)
        for g in given:
            if isinstance(g, (numbers.Integral, np.integer)) and not isinstance(g, bool):
                if not 0 <= g < n:
                    raise ValueError(f"nominal_features: {g} is not a column index of X ({n} features)")
                mask[int(g)] = True
            elif names is not None and g in set(names):
                mask[list(names).index(g)] = True
            else:
                raise ValueError(f"nominal_features: {g!r} is not a column of X")
        return mask

    # -- data -------------------------------------------------------------------------

    def _read(self, X: Any, y: Any = None, fitting: bool = False):
        """X as a 2-D array (and y), validated; on ``fit``, also which columns are nominal
        and their values' names (``None`` for a numeric column)."""
        original, categorical = X, None
        if hasattr(X, "dtypes") and hasattr(X, "columns"):
            # A DataFrame, column by column: scikit-learn would make one dtype of them
            # all, and fail on pandas' nullable ints beside strings.
            categorical = [getattr(dt, "name", "") == "category" for dt in X.dtypes]
            if all(isinstance(dt, np.dtype) and dt.kind in "biuf" for dt in X.dtypes):
                X = X.to_numpy()
            else:
                frame = X
                X = np.empty(frame.shape, dtype=object)
                for j in range(frame.shape[1]):
                    X[:, j] = frame.iloc[:, j].to_numpy(dtype=object)
        elif isinstance(X, (list, tuple)):
            # Rows of numbers and strings stay as they are (numpy would make them all
            # strings).
            X = np.asarray(X, dtype=object)
        if fitting:
            X, y = check_X_y(X, y, dtype=None, ensure_all_finite=False, estimator=self)
        else:
            X = check_array(X, dtype=None, ensure_all_finite=False, estimator=self)
        # Column names and their number, as scikit-learn checks them.
        named = original if categorical is not None else X
        validate_data(self, named, reset=fitting, skip_check_array=True)
        if X.dtype.kind in "USV":
            X = X.astype(object)
        if X.dtype.kind not in "biufO":
            raise ValueError(f"X has dtype {X.dtype}: expected numbers, strings or objects")
        if not fitting:
            return X, self.categories_
        mask = self._nominal_mask(X.shape[1], categorical)
        if X.dtype.kind == "O":
            for j in range(X.shape[1]):
                if not mask[j]:
                    present = (v for v in X[:, j] if not _is_missing(v))
                    mask[j] = not all(_is_number(v) for v in present)
        categories = [
            np.array(sorted({_value_name(v) for v in X[:, j] if not _is_missing(v)}), dtype=object)
            if mask[j]
            else None
            for j in range(X.shape[1])
        ]
        return X, y, mask, categories

    def _columns(self, X: np.ndarray, categories: list) -> list:
        """The columns as ``_csrl.TestCostTree`` takes them."""
        columns = []
        for j, cats in enumerate(categories):
            col = X[:, j]
            if cats is None:
                if col.dtype.kind == "O":
                    cells = []
                    for v in col:
                        if _is_missing(v):
                            cells.append(np.nan)
                        elif _is_number(v):
                            cells.append(float(v))
                        else:
                            raise ValueError(
                                f"{self._feature_label(j)} is numeric, but X holds {v!r} in it "
                                "(name it in nominal_features, or fit on strings, for a nominal column)"
                            )
                    x = np.asarray(cells, dtype=float)
                else:
                    x = col.astype(float)
                if np.isinf(x).any():
                    raise ValueError(f"Input X contains infinity (in {self._feature_label(j)})")
                columns.append((None, x.tolist()))
            else:
                index = {name: i for i, name in enumerate(cats)}
                unseen = len(cats)
                codes = [-1 if _is_missing(v) else index.get(_value_name(v), unseen) for v in col]
                columns.append(([str(c) for c in cats], codes))
        return columns

    def _names(self, n: int) -> list:
        names = getattr(self, "feature_names_in_", None)
        return [str(c) for c in names] if names is not None else [f"x{j}" for j in range(n)]

    # -- the estimator ----------------------------------------------------------------

    def fit(self, X: Any, y: Any) -> "TestCostTreeClassifier":
        """Grow the tree on ``X`` (objects x features) and ``y`` (their classes)."""
        for fitted in ("classes_", "_model", "_budget", "icet_genome_", "cvt_choice_"):  # unfitted if this fit fails
            self.__dict__.pop(fitted, None)
        learner = self._learner_name()
        X, y, nominal, categories = self._read(X, y, fitting=True)
        check_classification_targets(y)
        classes, y_codes = np.unique(y, return_inverse=True)
        if len(classes) > _csrl.MAX_CLASSES:
            # A continuous target given by mistake: its cost matrix grows with the square.
            raise ValueError(
                f"y has {len(classes)} distinct classes, more than the {_csrl.MAX_CLASSES} a "
                "test-cost tree learns (a continuous target? bin it into classes first)"
            )
        n = X.shape[1]
        prices, group_names = self._prices(n)
        matrix = self._misclassification(classes)
        confidence = getattr(self, "confidence", 0.25)
        w = getattr(self, "w", 1.0)
        seed = getattr(self, "seed", 0)
        population = getattr(self, "population", 50)
        generations = getattr(self, "generations", 20)
        act_samples = getattr(self, "act_samples", 5)
        selection_prices = getattr(self, "selection_prices", "path")
        icet_pruning = getattr(self, "icet_pruning", "errors")
        icet_search_objects = getattr(self, "icet_search_objects", 400)
        cvt_folds = getattr(self, "cvt_folds", 5)
        cvt_samples = getattr(self, "cvt_samples", 5)
        voi_lookahead = getattr(self, "voi_lookahead", None)
        voi_confidence = getattr(self, "voi_confidence", None)
        voi_m = getattr(self, "voi_m", None)
        n_jobs = getattr(self, "n_jobs", None)
        whole = isinstance(n_jobs, (numbers.Integral, np.integer)) and not isinstance(n_jobs, bool)
        if n_jobs is None:
            threads = 1
        elif whole and n_jobs == -1:
            threads = 0
        elif whole and 1 <= n_jobs < 2**32:
            threads = int(n_jobs)
        else:
            raise ValueError(f"n_jobs must be None, -1 or an integer at least 1, found {n_jobs!r}")
        if selection_prices not in ("path", "listed", "listed-once"):
            raise ValueError(
                f"selection_prices must be 'path', 'listed' or 'listed-once', found {selection_prices!r}"
            )
        if icet_pruning not in ("errors", "costs"):
            raise ValueError(f"icet_pruning must be 'errors' or 'costs', found {icet_pruning!r}")
        if not (isinstance(confidence, numbers.Real) and 0 < confidence < 1):
            raise ValueError(f"confidence must be a number in (0, 1), found {confidence!r}")
        if not (isinstance(w, numbers.Real) and 0 <= w <= 1):
            raise ValueError(f"w must be a number in [0, 1], found {w!r}")
        for what, v, least in (
            ("seed", seed, 0),
            ("population", population, 2),
            ("generations", generations, 1),
            ("act_samples", act_samples, 0),
            ("icet_search_objects", icet_search_objects, 2),
            ("cvt_folds", cvt_folds, 2),
            ("cvt_samples", cvt_samples, 0),
        ):
            integer = isinstance(v, (numbers.Integral, np.integer)) and not isinstance(v, bool)
            if not integer or not least <= v < 2**64:
                raise ValueError(f"{what} must be an integer at least {least}, found {v!r}")
        if act_samples > 1000:
            raise ValueError(f"act_samples must be at most 1000, found {act_samples!r}")
        if cvt_samples > 1000:
            raise ValueError(f"cvt_samples must be at most 1000, found {cvt_samples!r}")
        if voi_lookahead is not None and (
            isinstance(voi_lookahead, bool)
            or not (isinstance(voi_lookahead, (numbers.Integral, np.integer)) and 1 <= voi_lookahead <= 3)
        ):
            raise ValueError(f"voi_lookahead must be None or an integer from 1 to 3, found {voi_lookahead!r}")
        if voi_confidence is not None and (
            isinstance(voi_confidence, bool)
            or not isinstance(voi_confidence, numbers.Real)
            or not 0 < voi_confidence < 1
        ):
            raise ValueError(f"voi_confidence must be None or a number in (0, 1), found {voi_confidence!r}")
        if voi_m is not None and (
            isinstance(voi_m, bool)
            or not isinstance(voi_m, numbers.Real)
            or not (math.isfinite(float(voi_m)) and voi_m >= 0)
        ):
            raise ValueError(f"voi_m must be None or a finite number at least 0, found {voi_m!r}")
        if voi_confidence is not None and voi_m is not None:
            raise ValueError(
                "voi_confidence and voi_m cannot both be given: VOI estimates what stopping "
                "costs pessimistically (a confidence) or by an m-estimate (an m)"
            )
        if learner == "cvt" and cvt_folds > X.shape[0]:
            # Each fold holds at least one object (the library refuses it too).
            raise ValueError(
                f"cvt_folds={cvt_folds} needs at least {cvt_folds} samples, found n_samples = {X.shape[0]}"
            )
        if learner == "cvt":
            counts = np.bincount(y_codes, minlength=len(classes))
            lone = [classes[c] for c in np.flatnonzero(counts == 1)]
            if lone:
                # As scikit-learn's StratifiedKFold warns of a class smaller than its folds.
                warnings.warn(
                    f"class '{lone[0]}' has one object: the fold of CVT's cross-validation "
                    "that holds it out learns without the class, and counts it as an error there",
                    UserWarning,
                    stacklevel=2,
                )
        budget = self._budget_params()
        model = _csrl.TestCostTree.fit(
            learner,
            self._names(n),
            self._columns(X, categories),
            [int(c) for c in y_codes],
            [str(c) for c in classes],
            prices,
            group_names,
            matrix.tolist(),
            confidence=float(confidence),
            w=float(w),
            seed=int(seed),
            population=int(population),
            generations=int(generations),
            samples=int(act_samples),
            selection_prices=str(selection_prices),
            icet_pruning=str(icet_pruning),
            search_objects=int(icet_search_objects),
            folds=int(cvt_folds),
            threads=threads,
            voi_lookahead=None if voi_lookahead is None else int(voi_lookahead),
            voi_confidence=None if voi_confidence is None else float(voi_confidence),
            voi_m=None if voi_m is None else float(voi_m),
            cvt_samples=int(cvt_samples),
            **budget,
        )
        self.classes_ = classes
        self.nominal_features_ = nominal
        self.categories_ = categories
        self.feature_costs_ = np.array([p[0] for p in prices])
        self.misclassification_costs_ = matrix
        self._model = model
        self._budget = budget
        genome = model.icet_genome
        if genome is not None:
            prices_, w_, confidence_, fitness = genome
            self.icet_genome_ = {
                "prices": np.asarray(prices_),
                "w": w_,
                "confidence": confidence_,
                "fitness": fitness,
            }
        choice = model.cvt_choice
        if choice is not None:
            grower, alpha, held_out_cost = choice
            self.cvt_choice_ = {"grower": grower, "alpha": alpha, "held_out_cost": held_out_cost}
        return self

    def _classify(self, X: Any):
        check_is_fitted(self, "classes_")
        X, categories = self._read(X)
        codes, costs, tests, rows = self._model.classify(
            self._columns(X, categories), **getattr(self, "_budget", {})
        )
        proba = np.asarray(rows, dtype=float).reshape(len(codes), len(self.classes_))
        return np.asarray(codes, dtype=np.intp), np.asarray(costs, dtype=float), tests, proba

    def predict(self, X: Any) -> np.ndarray:
        """The class of each object."""
        codes = self._classify(X)[0]
        return self.classes_[codes]

    def predict_proba(self, X: Any) -> np.ndarray:
        """The probability of each class (columns in the order of ``classes_``, rows
        summing to 1): the Laplace-smoothed class weights of the leaf that answers, or of
        the mix of leaves an object with a missing value reaches (see the class
        documentation). Under a uniform ``misclassification_cost``, ``predict`` answers a
        class of largest probability.

        >>> import numpy as np
        >>> from csrl.sklearn import Id3Classifier
        >>> X = np.array([[0.0], [1.0], [2.0], [3.0], [np.nan]])
        >>> clf = Id3Classifier().fit(X[:4], ["a", "a", "b", "b"])
        >>> clf.predict_proba(X).tolist()  # leaves of two objects; the NaN reaches both
        [[0.75, 0.25], [0.75, 0.25], [0.25, 0.75], [0.25, 0.75], [0.5, 0.5]]
        """
        return self._classify(X)[3]

    def explain(self, X: Any) -> list:
        """How each object is classified, test by test: a dict per object with
        ``tests`` (one dict per test bought, in order: ``feature``, its index; ``paid``,
        its price after the tests before it; ``node``, the node that asked for it, and
        ``probabilities`` there, in the order of ``classes_``, both ``None`` for a test
        bought on a branch below a missing value; ``expected_gain``, what the learner
        expected the test to save per object, VOI's trees only, ``None`` otherwise),
        ``stopped_at`` (the node it answered from, ``None`` where a missing value sent it
        down several branches), ``class``, ``test_cost`` and ``probabilities`` (as
        ``predict``, ``predict_cost`` and ``predict_proba`` give them).

        >>> import numpy as np
        >>> from csrl.sklearn import VoiClassifier
        >>> X = np.arange(20.0).reshape(-1, 1)
        >>> clf = VoiClassifier(feature_costs=[5.0], misclassification_cost=100.0)
        >>> why = clf.fit(X, ["a"] * 10 + ["b"] * 10).explain([[17.0]])[0]
        >>> [(t["feature"], t["paid"], t["node"]) for t in why["tests"]], why["class"]
        ([(0, 5.0, 0)], 'b')
        >>> why["tests"][0]["expected_gain"] > 40  # an error on half the objects, saved
        True
        """
        codes, costs, _, proba = self._classify(X)
        X, categories = self._read(X)
        explained = self._model.explain(
            self._columns(X, categories), **getattr(self, "_budget", {})
        )
        names = self.classes_.tolist()
        out = []
        for i, (steps, stopped_at) in enumerate(explained):
            tests = [
                {
                    "feature": feature,
                    "paid": paid,
                    "node": node,
                    "probabilities": None if p is None else np.asarray(p, dtype=float),
                    "expected_gain": gain,
                }
                for feature, paid, node, p, gain in steps
            ]
            out.append(
                {
                    "tests": tests,
                    "stopped_at": stopped_at,
                    "class": names[codes[i]],
                    "test_cost": float(costs[i]),
                    "probabilities": proba[i],
                }
            )
        return out

    def predict_cost(self, X: Any) -> np.ndarray:
        """What classifying each object costs: the prices of the tests on its path (a
        test done once, once; the discount for a later test of a group; every branch's
        tests below a missing value)."""
        return self._classify(X)[1]

    def predict_with_cost(self, X: Any):
        """``(predict(X), predict_cost(X))`` in one classification."""
        codes, costs = self._classify(X)[:2]
        return self.classes_[codes], costs

    def predict_tests(self, X: Any) -> list:
        """The tests done for each object: feature indices, in the order done."""
        return self._classify(X)[2]

    def total_cost(self, X: Any, y: Any) -> float:
        """The mean total cost of classifying ``X`` whose classes are ``y``: the tests'
        prices plus the misclassification cost of each answer."""
        codes, costs = self._classify(X)[:2]
        y = column_or_1d(y, warn=True)
        if len(y) != len(codes):
            raise ValueError(f"X has {len(codes)} objects but y has {len(y)} classes")
        index = {c: i for i, c in enumerate(self.classes_.tolist())}
        actual = [index.get(c, -1) for c in y.tolist()]
        unknown = sorted({str(c) for c, a in zip(y.tolist(), actual) if a < 0})
        if unknown:
            raise ValueError(f"y has classes the estimator was not fitted on: {unknown}")
        return float(np.mean(costs + self.misclassification_costs_[actual, codes]))

    def export_text(
        self,
        feature_names: Optional[list] = None,
        class_names: Optional[list] = None,
        decimals: int = 2,
    ) -> str:
        """The tree as text, one line per branch, each test with its full price.

        >>> from csrl.sklearn import IdxClassifier
        >>> X = [[1.0, "red"], [2.0, "red"], [8.0, "blue"], [9.0, "blue"]] * 3
        >>> clf = IdxClassifier(feature_costs=[5.0, 1.0]).fit(X, ["a", "a", "b", "b"] * 3)
        >>> print(clf.export_text(feature_names=["size", "colour"]))
        |--- colour = blue (price 1)
        |   |--- class: b
        |--- colour = red (price 1)
        |   |--- class: a
        """
        check_is_fitted(self, "classes_")
        if feature_names is None:
            feature_names = self._names(self.n_features_in_)
        if class_names is None:
            class_names = [str(c) for c in self.classes_]
        nodes = self._model.nodes()
        lines: list = []

        def price(f: int) -> str:
            return f"{float(self.feature_costs_[f]):g}"

        def walk(i: int, depth: int) -> None:
            label, _, split = nodes[i]
            indent = "|   " * depth + "|--- "
            if split is None:
                lines.append(f"{indent}class: {class_names[label]}")
                return
            feature, at, children = split
            name = feature_names[feature]
            if at is None:
                values = self.categories_[feature]
                for value, child in zip(values, children):
                    lines.append(f"{indent}{name} = {value} (price {price(feature)})")
                    walk(child, depth + 1)
            else:
                for sign, child in (("<=", children[0]), (">", children[1])):
                    lines.append(f"{indent}{name} {sign} {at:.{decimals}f} (price {price(feature)})")
                    walk(child, depth + 1)

        walk(0, 0)
        return "\n".join(lines)

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.input_tags.allow_nan = True
        tags.input_tags.string = True
        # IDX and CS-ID3 divide the gain by the price on the path, and a numeric test
        # already done is free there: they split again on the first feature bought while
        # it gains anything, and fall short of scikit-learn's "reasonable" accuracy (0.83
        # on its three blobs, at equal prices: 0.76).
        tags.classifier_tags.poor_score = (self._learner or getattr(self, "learner", None)) in (
            "idx",
            "cs-id3-batch",
        )
        return tags


class _Unpruned(TestCostTreeClassifier):
    def __init__(
        self,
        feature_costs: Optional[Any] = None,
        feature_groups: Optional[Any] = None,
        feature_discounts: Optional[Any] = None,
        misclassification_cost: Any = 100.0,
        nominal_features: Optional[Any] = None,
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
    ) -> None:
        self.feature_costs = feature_costs
        self.feature_groups = feature_groups
        self.feature_discounts = feature_discounts
        self.misclassification_cost = misclassification_cost
        self.nominal_features = nominal_features
        self.max_test_cost = max_test_cost
        self.max_tests = max_tests


class Id3Classifier(_Unpruned):
    """ID3 as a batch tree: the test of largest information gain, blind to its price;
    no pruning. The baseline of the family (:class:`TestCostTreeClassifier` with
    ``learner="id3-batch"``, whose documentation the parameters follow).
    ``max_test_cost`` and ``max_tests`` hold every object to a budget: the tree grows
    within it and classifies within it."""

    _learner = "id3-batch"


class _Pruned(TestCostTreeClassifier):
    def __init__(
        self,
        feature_costs: Optional[Any] = None,
        feature_groups: Optional[Any] = None,
        feature_discounts: Optional[Any] = None,
        misclassification_cost: Any = 100.0,
        nominal_features: Optional[Any] = None,
        confidence: float = 0.25,
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
    ) -> None:
        self.feature_costs = feature_costs
        self.feature_groups = feature_groups
        self.feature_discounts = feature_discounts
        self.misclassification_cost = misclassification_cost
        self.nominal_features = nominal_features
        self.confidence = confidence
        self.max_test_cost = max_test_cost
        self.max_tests = max_tests


class C45Classifier(_Pruned):
    """C4.5: the gain ratio among tests of at least average gain, blind to prices;
    pessimistic pruning at ``confidence`` (:class:`TestCostTreeClassifier` with
    ``learner="c45"``).
    ``max_test_cost`` and ``max_tests`` hold every object to a budget: the tree grows
    within it and classifies within it."""

    _learner = "c45"


class IdxClassifier(_Pruned):
    """IDX (Norton 1989): the test of largest gain / price; pruned as C4.5
    (:class:`TestCostTreeClassifier` with ``learner="idx"``).
    ``max_test_cost`` and ``max_tests`` hold every object to a budget: the tree grows
    within it and classifies within it."""

    _learner = "idx"


class CsId3BatchClassifier(_Pruned):
    """CS-ID3 (Tan 1991) as a batch tree: the test of largest gain² / price; pruned as
    C4.5 (:class:`TestCostTreeClassifier` with ``learner="cs-id3-batch"``). The
    incremental CS-ID3 of the paper is :class:`CsId3Classifier`.
    ``max_test_cost`` and ``max_tests`` hold every object to a budget: the tree grows
    within it and classifies within it."""

    _learner = "cs-id3-batch"


class Eg2Classifier(TestCostTreeClassifier):
    """EG2 (Núñez 1991): the test of largest (2^gain − 1) / (price + 1)^w; pruned as
    C4.5 (:class:`TestCostTreeClassifier` with ``learner="eg2"``, whose documentation
    the parameters follow, ``selection_prices`` included).
    ``max_test_cost`` and ``max_tests`` hold every object to a budget: the tree grows
    within it and classifies within it."""

    _learner = "eg2"

    def __init__(
        self,
        feature_costs: Optional[Any] = None,
        feature_groups: Optional[Any] = None,
        feature_discounts: Optional[Any] = None,
        misclassification_cost: Any = 100.0,
        nominal_features: Optional[Any] = None,
        confidence: float = 0.25,
        w: float = 1.0,
        selection_prices: str = "path",
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
    ) -> None:
        self.feature_costs = feature_costs
        self.feature_groups = feature_groups
        self.feature_discounts = feature_discounts
        self.misclassification_cost = misclassification_cost
        self.nominal_features = nominal_features
        self.confidence = confidence
        self.w = w
        self.selection_prices = selection_prices
        self.max_test_cost = max_test_cost
        self.max_tests = max_tests


class DtmcClassifier(_Unpruned):
    """DTMC (Ling, Yang, Wang and Zhang 2004): the test that most reduces the expected
    total cost (tests plus misclassification) of a node's objects, and a leaf where none
    reduces it; no pruning. Its tree depends on ``misclassification_cost``
    (:class:`TestCostTreeClassifier` with ``learner="dtmc"``).
    ``max_test_cost`` and ``max_tests`` hold every object to a budget: the tree grows
    within it and classifies within it."""

    _learner = "dtmc"


class IcetClassifier(TestCostTreeClassifier):
    """ICET (Turney 1995): EG2 grown with biased prices, ``w`` and pruning confidence
    found by a genetic search (``population`` individuals, ``generations`` generations)
    whose fitness is the mean total cost, on one half of the training objects, of the
    tree grown on the other; ``seed`` fixes the halves and the search. Its tree depends
    on ``misclassification_cost`` (:class:`TestCostTreeClassifier` with
    ``learner="icet"``, whose documentation the parameters follow: ``icet_pruning``,
    ``icet_search_objects`` and ``selection_prices`` reproduce the published
    benchmark's ICET with ``"costs"``, 1000 and ``"listed"``). ``icet_genome_`` is the
    individual the tree was grown from.
    ``max_test_cost`` and ``max_tests`` hold every object to a budget when it is
    classified (the tree is grown free, and cut where an object runs out)."""

    _learner = "icet"

    def __init__(
        self,
        feature_costs: Optional[Any] = None,
        feature_groups: Optional[Any] = None,
        feature_discounts: Optional[Any] = None,
        misclassification_cost: Any = 100.0,
        nominal_features: Optional[Any] = None,
        seed: int = 0,
        population: int = 50,
        generations: int = 20,
        selection_prices: str = "path",
        icet_pruning: str = "errors",
        icet_search_objects: int = 400,
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
    ) -> None:
        self.feature_costs = feature_costs
        self.feature_groups = feature_groups
        self.feature_discounts = feature_discounts
        self.misclassification_cost = misclassification_cost
        self.nominal_features = nominal_features
        self.seed = seed
        self.population = population
        self.generations = generations
        self.selection_prices = selection_prices
        self.icet_pruning = icet_pruning
        self.icet_search_objects = icet_search_objects
        self.max_test_cost = max_test_cost
        self.max_tests = max_tests


class ActClassifier(TestCostTreeClassifier):
    """ACT (Esmeir and Markovitch 2008): at each node, the test whose price plus the
    cheapest of ``act_samples`` trees sampled under each of its branches (by a
    stochastic EG2 of weight ``w``, drawn from ``seed``) costs least in tests and
    pessimistic errors, or a leaf where answering costs less; pruned by total cost. Its
    tree depends on ``misclassification_cost`` (:class:`TestCostTreeClassifier` with
    ``learner="act"``). More samples, better estimates, more time.
    ``max_test_cost`` and ``max_tests`` hold every object to a budget when it is
    classified (the tree is grown free, and cut where an object runs out). ``n_jobs``
    values the candidate tests of a node at the same time (``-1``: every core): the
    same tree on any number of threads."""

    _learner = "act"

    def __init__(
        self,
        feature_costs: Optional[Any] = None,
        feature_groups: Optional[Any] = None,
        feature_discounts: Optional[Any] = None,
        misclassification_cost: Any = 100.0,
        nominal_features: Optional[Any] = None,
        w: float = 1.0,
        seed: int = 0,
        act_samples: int = 5,
        selection_prices: str = "path",
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
        n_jobs: Optional[int] = None,
    ) -> None:
        self.feature_costs = feature_costs
        self.feature_groups = feature_groups
        self.feature_discounts = feature_discounts
        self.misclassification_cost = misclassification_cost
        self.nominal_features = nominal_features
        self.w = w
        self.seed = seed
        self.act_samples = act_samples
        self.selection_prices = selection_prices
        self.max_test_cost = max_test_cost
        self.max_tests = max_tests
        self.n_jobs = n_jobs


class CvtClassifier(TestCostTreeClassifier):
    """CVT, the cost-validated tree: unpruned trees grown by seven growers (EG2 at w = 0,
    0.5, 1 and 2, C4.5's gain ratio, DTMC and ACT's sampled lookahead), each cut back
    along its cost-complexity path (a price per leaf, tests inside the cost) or by ACT's
    pessimistic pruning by cost; the grower and the cut of least total cost on held-out
    objects, by ``cvt_folds``-fold cross-validation on the training objects with folds
    and samples drawn from ``seed``, give the tree, grown on all of them. Its tree depends on ``misclassification_cost``
    (:class:`TestCostTreeClassifier` with ``learner="cvt"``). ``cvt_choice_`` says what
    it chose.
    ``max_test_cost`` and ``max_tests`` hold every object to a budget when it is
    classified (the tree is grown free, and cut where an object runs out). ``n_jobs``
    grows its trees on all the objects and on each fold at the same time (``-1``: every
    core), each from its own seed: the same tree on any number of threads.
    ``cvt_samples`` sets the lookahead grower's samples per branch (5, as ACT's): its
    time is most of CVT's, so fewer are faster, and 0 leaves the lookahead out.

    >>> import numpy as np
    >>> from csrl.sklearn import CvtClassifier
    >>> x = np.arange(60.0)
    >>> X = np.column_stack([x % 2, x])  # the first column tells the class
    >>> y = (x % 2).astype(int)
    >>> cvt = CvtClassifier(feature_costs=[2.0, 1.0], misclassification_cost=10.0).fit(X, y)
    >>> cvt.predict_cost(X[:2]).tolist(), cvt.score(X, y)
    ([2.0, 2.0], 1.0)
    >>> round(cvt.cvt_choice_["held_out_cost"], 6)
    2.0
    """

    _learner = "cvt"

    def __init__(
        self,
        feature_costs: Optional[Any] = None,
        feature_groups: Optional[Any] = None,
        feature_discounts: Optional[Any] = None,
        misclassification_cost: Any = 100.0,
        nominal_features: Optional[Any] = None,
        seed: int = 0,
        cvt_folds: int = 5,
        selection_prices: str = "path",
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
        n_jobs: Optional[int] = None,
        cvt_samples: int = 5,
    ) -> None:
        self.feature_costs = feature_costs
        self.feature_groups = feature_groups
        self.feature_discounts = feature_discounts
        self.misclassification_cost = misclassification_cost
        self.nominal_features = nominal_features
        self.seed = seed
        self.cvt_folds = cvt_folds
        self.selection_prices = selection_prices
        self.max_test_cost = max_test_cost
        self.max_tests = max_tests
        self.n_jobs = n_jobs
        self.cvt_samples = cvt_samples


class VoiClassifier(TestCostTreeClassifier):
    """VOI, the value-of-information tree: at each node, the test whose price plus, over
    its branches, the least of stopping and buying more (``voi_lookahead`` tests ahead)
    costs least, if that is less than stopping, so that a pair of tests that pays only
    together is bought; stopping costs C4.5's pessimistic estimate of the node's errors
    at ``voi_confidence`` (``None``: 0.25), or, with ``voi_m``, the expected cost of
    the best answer under an m-estimate of the classes. Its tree depends on
    ``misclassification_cost`` (:class:`TestCostTreeClassifier` with
    ``learner="voi"``); nothing in it is random. ``max_test_cost`` and ``max_tests``
    hold every object to a budget: the tree grows within it and classifies within it.

    >>> import numpy as np
    >>> from csrl.sklearn import VoiClassifier
    >>> a, b = np.arange(40) % 2, np.arange(40) // 2 % 2
    >>> X = np.column_stack([a, b]).astype(float)
    >>> y = a ^ b  # only the pair tells the class
    >>> voi = VoiClassifier(feature_costs=[2.0, 3.0], misclassification_cost=100.0).fit(X, y)
    >>> voi.predict_cost(X[:2]).tolist(), voi.score(X, y)
    ([5.0, 5.0], 1.0)
    >>> VoiClassifier(voi_lookahead=1, feature_costs=[2.0, 3.0]).fit(X, y).predict_cost(X[:1]).tolist()
    [0.0]
    """

    _learner = "voi"

    def __init__(
        self,
        feature_costs: Optional[Any] = None,
        feature_groups: Optional[Any] = None,
        feature_discounts: Optional[Any] = None,
        misclassification_cost: Any = 100.0,
        nominal_features: Optional[Any] = None,
        voi_lookahead: Optional[int] = None,
        voi_confidence: Optional[float] = None,
        voi_m: Optional[float] = None,
        selection_prices: str = "path",
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
    ) -> None:
        self.feature_costs = feature_costs
        self.feature_groups = feature_groups
        self.feature_discounts = feature_discounts
        self.misclassification_cost = misclassification_cost
        self.nominal_features = nominal_features
        self.voi_lookahead = voi_lookahead
        self.voi_confidence = voi_confidence
        self.voi_m = voi_m
        self.selection_prices = selection_prices
        self.max_test_cost = max_test_cost
        self.max_tests = max_tests
