"""scikit-learn estimators that pay for what they measure: CS-ID3 and CS-IBL.

Both learn incrementally, as the paper's framework does: every training object is first
classified with as few (and as cheap) measurements as the library allows, then learned
with its class; a wrong prediction makes the learner measure more features of the object
until the examples that misled it no longer agree with it. ``fit`` streams the training
data in order, ``passes`` times at most (it stops after a pass without a mistake).

Values are compared for equality only: each column's distinct values become categories
(a value not seen in ``fit`` is a category of its own, which no example has). NaN is a
missing value. Bin continuous columns first (``KBinsDiscretizer(encode="ordinal")`` in a
pipeline) for a tree that generalises.

>>> import numpy as np
>>> from csrl.sklearn import CsId3Classifier
>>> X = np.array([[0, 0], [1, 0], [0, 1], [1, 1]] * 3)
>>> y = X[:, 0]  # the cheap feature decides the class
>>> clf = CsId3Classifier(feature_costs=[1.0, 100.0]).fit(X, y)
>>> clf.predict([[1, 1], [0, 1]]).tolist(), clf.predict_cost([[1, 1], [0, 1]]).tolist()
([1, 0], [1.0, 1.0])
>>> clf.score(X, y)
1.0
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Optional

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import check_is_fitted, validate_data

from . import _csrl

__all__ = ["CsId3Classifier", "CsIblClassifier"]


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
