"""CEGB, LightGBM's cost-efficient gradient boosting, as a test-cost learner.

LightGBM's CEGB (Peter et al., NeurIPS 2017) charges each split of its trees, besides its
loss gain, ``cegb_tradeoff`` times the price of the split's feature for every training
object in the leaf that has not used the feature yet (``cegb_penalty_feature_lazy``: one
price per feature, paid once per object, in any tree). This module makes it the peer of
the test-cost trees (``cargo xtask testcost --learners ...,cegb``) and gives Python users
the same two things the benchmark uses:

* :func:`features_used` -- for a fitted LightGBM model and a feature matrix, the distinct
  features on each object's paths through all the trees, in the order first met (trees in
  order, each path from its root); :func:`cost_of_tests` prices them, every feature once per
  object at its flat price. (Turney's group discounts are priced from the same ordered
  lists by the benchmark's Rust side, with ``cslearn::testcost::Basket``.)
* :func:`fit` -- CEGB at one misclassification cost or several, its tradeoff chosen by
  stratified k-fold cross-validation inside the training data among a stated grid
  (:data:`TRADEOFFS`), each choice minimising the mean total cost (test cost plus ``mc``
  times the error) on the held-out folds; the answer is the class of largest probability
  (least expected cost under a uniform ``mc``).

* :func:`sweep` -- CEGB trained at each tradeoff of a list, with no cross-validation: the
  points of its curve of accuracy against test cost (``cargo xtask budget --learners
  ...,cegb``).

Run as a script (``python cegb.py --worker``) it is the benchmark's worker: one JSON
request per line on stdin, one JSON response per line on stdout (:func:`serve`). It needs
numpy and lightgbm only (never the package's compiled extension), so it runs by path.

Every fit is bit-reproducible: ``deterministic``, one thread, row-wise histograms, and
every seed from the caller's.

>>> import numpy as np
>>> rng = np.random.default_rng(0)
>>> X = rng.normal(size=(300, 3))
>>> y = (X[:, 0] + X[:, 1] > 0).astype(int)       # features 0 and 1 tell the class
>>> prices = [1.0, 1.0, 50.0]
>>> cheap = fit(X, y, prices, [100.0], seed=1)[0]
>>> sorted({f for used in cheap.model.features_used(X) for f in used})
[0, 1]
>>> dear = fit(X, y, [100.0, 100.0, 100.0], [1.0], seed=1)[0]   # errors cost little
>>> dear.model.features_used(X[:2]), float(dear.model.cost_of_tests(X).mean())
([[], []], 0.0)
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
from dataclasses import asdict, dataclass
from typing import IO, Any, Optional, Sequence

import lightgbm as lgb
import numpy as np

__all__ = [
    "CegbModel",
    "Choice",
    "Settings",
    "TRADEOFFS",
    "cost_of_tests",
    "describe",
    "features_used",
    "fit",
    "handle",
    "serve",
    "sweep",
]

#: The tradeoffs cross-validation chooses among: no penalty, then 10^-4 to 10 in quarter
#: decades (22 in all). LightGBM's gain is in loss units summed over the leaf's objects
#: (a fraction of one per object for the log loss), the penalty ``tradeoff * price`` per
#: object newly paying: with prices of 1 to 100, 10^-4 changes few splits and 10 buys
#: nothing. Where the root's best split stops paying, the first round grows no tree and
#: boosting stops (the model answers the training data's class shares), so cost falls
#: from buying much to buying nothing within a factor of a few: quarter decades.
TRADEOFFS: tuple[float, ...] = (0.0,) + tuple(float(10.0 ** (-4 + k / 4)) for k in range(21))


@dataclass(frozen=True)
class Settings:
    """CEGB's settings: the boosting's and the cross-validation's.

    >>> Settings().trees, Settings().inner_folds, len(Settings().tradeoffs)
    (50, 5, 22)
    """

    #: Boosting rounds (one tree per round for two classes, one per class for more).
    trees: int = 50
    #: Shrinkage of each tree's output.
    learning_rate: float = 0.1
    #: The most leaves of a tree.
    num_leaves: int = 8
    #: The fewest training objects in a leaf (LightGBM's ``min_child_samples``).
    min_child_samples: int = 10
    #: The fewest training objects of a category on a side of a categorical split
    #: (LightGBM's ``min_data_per_group``, 100 by default there, which would forbid most
    #: categorical splits on data sets of a few hundred objects).
    min_data_per_group: int = 10
    #: The grid of ``cegb_tradeoff`` cross-validation chooses from.
    tradeoffs: tuple[float, ...] = TRADEOFFS
    #: Folds of the cross-validation inside the training data (stratified, seeded).
    inner_folds: int = 5

    @staticmethod
    def from_json(given: Any) -> Settings:
        """Settings from a request's ``settings`` object (absent keys: the defaults);
        a key that is not a setting, or a value out of range, raises ``ValueError``."""
        if given is None:
            return Settings()
        if not isinstance(given, dict):
            raise ValueError("settings: expected an object")
        known = set(Settings.__dataclass_fields__)
        unknown = sorted(set(given) - known)
        if unknown:
            raise ValueError(f"settings: unknown key {unknown[0]!r} (known: {sorted(known)})")
        values = dict(given)
        if "tradeoffs" in values:
            values["tradeoffs"] = tuple(float(t) for t in values["tradeoffs"])
        s = Settings(**values)
        s.check()
        return s

    def check(self) -> None:
        """Raise ``ValueError`` naming the first setting out of range."""
        if not (isinstance(self.trees, int) and self.trees >= 1):
            raise ValueError(f"settings: trees {self.trees!r} must be an integer of at least 1")
        if not (math.isfinite(self.learning_rate) and self.learning_rate > 0):
            raise ValueError(f"settings: learning_rate {self.learning_rate!r} must be positive")
        if not (isinstance(self.num_leaves, int) and self.num_leaves >= 2):
            raise ValueError(f"settings: num_leaves {self.num_leaves!r} must be at least 2")
        if not (isinstance(self.min_child_samples, int) and self.min_child_samples >= 1):
            raise ValueError(
                f"settings: min_child_samples {self.min_child_samples!r} must be at least 1"
            )
        if not (isinstance(self.min_data_per_group, int) and self.min_data_per_group >= 1):
            raise ValueError(
                f"settings: min_data_per_group {self.min_data_per_group!r} must be at least 1"
            )
        if not self.tradeoffs or any(not (math.isfinite(t) and t >= 0) for t in self.tradeoffs):
            raise ValueError("settings: tradeoffs must be finite, not negative, and at least one")
        if not (isinstance(self.inner_folds, int) and self.inner_folds >= 2):
            raise ValueError(f"settings: inner_folds {self.inner_folds!r} must be at least 2")


def describe(settings: Settings = Settings()) -> str:
    """One line naming LightGBM's version and the settings, for a report's header.

    >>> describe().startswith("LightGBM " + lgb.__version__ + ", 50 rounds")
    True
    """
    grid = _grid_words(settings.tradeoffs)
    return (
        f"LightGBM {lgb.__version__}, {settings.trees} rounds, learning rate "
        f"{settings.learning_rate:g}, at most {settings.num_leaves} leaves of at least "
        f"{settings.min_child_samples} objects (categories: at least "
        f"{settings.min_data_per_group} objects a side); cegb_tradeoff chosen by stratified "
        f"{settings.inner_folds}-fold cross-validation inside the training data among {grid}"
    )


def _grid_words(grid: Sequence[float]) -> str:
    """A grid in words: "0 and k values from a to b, geometric" where it is one (the
    default), else every value."""
    rest = [t for t in grid if t > 0]
    if len(rest) >= 3 and list(grid) == [0.0] + rest:
        ratios = [b / a for a, b in zip(rest, rest[1:])]
        if all(abs(r / ratios[0] - 1) < 1e-9 for r in ratios):
            return f"0 and {len(rest)} values from {rest[0]:g} to {rest[-1]:g}, geometric"
    return ", ".join(f"{t:g}" for t in grid)


# --- The features an object uses -------------------------------------------------------


def _booster(model: Any) -> Optional[lgb.Booster]:
    """The LightGBM booster of a Booster, a scikit-learn LightGBM model or a
    :class:`CegbModel` (``None`` for a model that answers without trees)."""
    if isinstance(model, CegbModel):
        return model.booster
    if isinstance(model, lgb.Booster):
        return model
    booster = getattr(model, "booster_", None)
    if isinstance(booster, lgb.Booster):
        return booster
    raise TypeError(f"expected a fitted LightGBM Booster or model, not {type(model).__name__}")


#: A path longer than this is impossible (a tree of at most 131072 leaves).
_DEPTH = 1 << 17


def _first_met(booster: lgb.Booster, X: np.ndarray) -> np.ndarray:
    """For each object and feature, where the object first meets the feature on its paths:
    ``tree * _DEPTH + depth`` (depth 0 at the root), ``inf`` where it never does."""
    n, features = X.shape
    first = np.full((n, features), np.inf)
    if n == 0:
        return first
    trees = booster.dump_model()["tree_info"]
    if not trees:
        return first
    leaves = np.asarray(booster.predict(X, pred_leaf=True, num_threads=1)).reshape(n, len(trees))
    for t, tree in enumerate(trees):
        node = tree["tree_structure"]
        if "leaf_value" in node and "split_feature" not in node:
            continue  # a tree of one leaf tests nothing
        # depth[leaf, feature]: the depth at which the leaf's path first tests the feature.
        depth = np.full((tree["num_leaves"], features), np.inf)
        stack: list[tuple[dict[str, Any], list[int]]] = [(node, [])]
        while stack:
            node, path = stack.pop()
            if "split_feature" in node:
                below = path + [int(node["split_feature"])]
                stack.append((node["right_child"], below))
                stack.append((node["left_child"], below))
            else:
                row = depth[int(node["leaf_index"])]
                for d, f in reversed(list(enumerate(path))):
                    row[f] = d
        np.minimum(first, depth[leaves[:, t]] + t * _DEPTH, out=first)
    return first


def features_used(model: Any, X: Any) -> list[list[int]]:
    """For each row of ``X``, the distinct features (column indices) on its paths through
    all of ``model``'s trees, in the order first met: trees in order (for several classes,
    LightGBM's order: round by round, class by class), each path from its root. A
    feature is used whether or not the object's value is missing (the tree asked for it).

    ``model`` is a ``lightgbm.Booster``, a fitted scikit-learn LightGBM model or a
    :class:`CegbModel`.

    >>> import lightgbm as lgb, numpy as np
    >>> X = np.array([[0.0, 5.0], [1.0, 5.0]] * 20)
    >>> params = dict(objective="binary", min_child_samples=2, verbosity=-1)
    >>> booster = lgb.train(params, lgb.Dataset(X, X[:, 0]), num_boost_round=2)
    >>> features_used(booster, X[:2])
    [[0], [0]]
    """
    X = _matrix(X, "X")
    booster = _booster(model)
    if booster is None:
        return [[] for _ in range(X.shape[0])]
    first = _first_met(booster, X)
    out = []
    for row in first:
        met = np.flatnonzero(np.isfinite(row))
        out.append([int(f) for f in met[np.argsort(row[met], kind="stable")]])
    return out


def cost_of_tests(model: Any, X: Any, prices: Sequence[float]) -> np.ndarray:
    """What each row of ``X`` pays for its tests: the sum of the flat prices of the
    features it uses (:func:`features_used`), each once. Group discounts are not priced
    here (the benchmark prices them from the ordered lists).

    >>> import lightgbm as lgb, numpy as np
    >>> X = np.array([[0.0, 5.0], [1.0, 5.0]] * 20)
    >>> params = dict(objective="binary", min_child_samples=2, verbosity=-1)
    >>> booster = lgb.train(params, lgb.Dataset(X, X[:, 0]), num_boost_round=2)
    >>> cost_of_tests(booster, X[:2], [3.0, 7.0]).tolist()
    [3.0, 3.0]
    """
    X = _matrix(X, "X")
    p = _prices(prices, X.shape[1])
    booster = _booster(model)
    if booster is None:
        return np.zeros(X.shape[0])
    return np.asarray(np.isfinite(_first_met(booster, X)) @ p, dtype=float)


# --- Fitting ---------------------------------------------------------------------------


@dataclass
class CegbModel:
    """A fitted CEGB model over ``classes`` classes: a LightGBM booster trained on the
    classes its training data has (``present``), or none when it has one class only (the
    model then answers that class and tests nothing)."""

    booster: Optional[lgb.Booster]
    #: The classes (indices into ``0..classes``) the booster was trained on, in order.
    present: list[int]
    #: The number of classes of the problem.
    classes: int
    #: The ``cegb_tradeoff`` it was trained with.
    tradeoff: float
    #: The flat price of each feature it was trained with.
    prices: list[float]

    def predict_proba(self, X: Any) -> np.ndarray:
        """Class probabilities, one column per class of the problem (0 for a class the
        training data did not have)."""
        X = _matrix(X, "X")
        out = np.zeros((X.shape[0], self.classes))
        if X.shape[0] == 0:
            return out
        if self.booster is None:
            out[:, self.present[0]] = 1.0
            return out
        p = np.asarray(self.booster.predict(X, num_threads=1), dtype=float)
        if len(self.present) == 2:
            p = np.column_stack([1.0 - p, p])
        out[:, self.present] = p.reshape(X.shape[0], len(self.present))
        return out

    def predict(self, X: Any) -> np.ndarray:
        """The class of largest probability (the first of equals): under a uniform
        misclassification cost, the class of least expected cost."""
        return np.asarray(np.argmax(self.predict_proba(X), axis=1), dtype=int)

    def features_used(self, X: Any) -> list[list[int]]:
        """:func:`features_used` of this model."""
        return features_used(self, X)

    def cost_of_tests(self, X: Any, prices: Optional[Sequence[float]] = None) -> np.ndarray:
        """:func:`cost_of_tests` of this model, at the prices it was trained with unless
        others are given."""
        return cost_of_tests(self, X, self.prices if prices is None else prices)

    @property
    def leaves(self) -> int:
        """Leaves over all the trees (1 for a model without trees)."""
        if self.booster is None:
            return 1
        return int(sum(t["num_leaves"] for t in self.booster.dump_model()["tree_info"]))

    @property
    def nodes(self) -> int:
        """Nodes over all the trees, leaves and splits (a tree of `l` leaves has `2l - 1`)."""
        if self.booster is None:
            return 1
        return int(sum(2 * t["num_leaves"] - 1 for t in self.booster.dump_model()["tree_info"]))


@dataclass
class Choice:
    """CEGB at one misclassification cost: the tradeoff cross-validation chose, the mean
    total cost per held-out object of every tradeoff of the grid (in its order), and the
    model trained with the chosen tradeoff on all the training objects."""

    mc: float
    tradeoff: float
    cv_costs: list[float]
    model: CegbModel


def _matrix(X: Any, what: str) -> np.ndarray:
    a = np.asarray(X, dtype=float)
    if a.ndim != 2:
        raise ValueError(f"{what}: expected a matrix (objects by features), got shape {a.shape}")
    return a


def _prices(prices: Sequence[float], features: int) -> np.ndarray:
    p = np.asarray(prices, dtype=float)
    if p.shape != (features,):
        got = f"{p.shape[0]}" if p.ndim == 1 else f"shape {p.shape}"
        raise ValueError(f"prices: expected one per feature ({features}), got {got}")
    if not np.all(np.isfinite(p) & (p >= 0)):
        raise ValueError("prices: every price must be finite and not negative")
    return p


def _training(
    X: Any, y: Any, prices: Sequence[float], classes: Optional[int], nominal: Sequence[int]
) -> tuple[np.ndarray, np.ndarray, int, np.ndarray]:
    """Training objects checked: the matrix, the class indices, the number of classes and
    the prices; ``ValueError`` naming the first argument at fault."""
    X = _matrix(X, "X")
    y = np.asarray(y)
    if y.shape != (X.shape[0],):
        raise ValueError(f"y: expected one class per object ({X.shape[0]}), got shape {y.shape}")
    if X.shape[0] == 0:
        raise ValueError("X: no training object")
    if not np.issubdtype(y.dtype, np.integer):
        if not np.all(np.equal(np.mod(y, 1), 0)):
            raise ValueError("y: classes must be integer indices")
        y = y.astype(int)
    if y.min() < 0:
        raise ValueError("y: classes must be indices from 0")
    k = int(y.max()) + 1 if classes is None else int(classes)
    if y.max() >= k:
        raise ValueError(f"y: class {int(y.max())} is not below classes = {k}")
    p = _prices(prices, X.shape[1])
    for f in nominal:
        if not (0 <= int(f) < X.shape[1]):
            raise ValueError(f"nominal: column {f} is not a column of X ({X.shape[1]})")
    return X, y, k, p


def _stratified_folds(y: np.ndarray, k: int, rng: np.random.Generator) -> list[np.ndarray]:
    """``k`` stratified folds of the objects: each class's objects shuffled and dealt in
    turn, the dealing going on from class to class, so that fold sizes differ by one."""
    folds: list[list[int]] = [[] for _ in range(k)]
    at = 0
    for c in np.unique(y):
        members = np.flatnonzero(y == c)
        for i in rng.permutation(members):
            folds[at % k].append(int(i))
            at += 1
    return [np.sort(np.asarray(f, dtype=int)) for f in folds]


def _train(
    X: np.ndarray,
    y: np.ndarray,
    classes: int,
    prices: np.ndarray,
    nominal: Sequence[int],
    tradeoffs: Sequence[float],
    settings: Settings,
    seed: int,
) -> list[CegbModel]:
    """One model per tradeoff, on one set of training objects (one LightGBM data set)."""
    present = [int(c) for c in np.unique(y)]
    if len(present) == 1:
        return [CegbModel(None, present, classes, t, list(prices)) for t in tradeoffs]
    code = {c: i for i, c in enumerate(present)}
    label = np.array([code[int(c)] for c in y], dtype=float)
    params: dict[str, Any] = {
        "learning_rate": settings.learning_rate,
        "num_leaves": settings.num_leaves,
        "min_child_samples": settings.min_child_samples,
        "min_data_per_group": settings.min_data_per_group,
        "cegb_penalty_feature_lazy": [float(p) for p in prices],
        "deterministic": True,
        "force_row_wise": True,
        "num_threads": 1,
        "seed": seed,
        "verbosity": -1,
    }
    if len(present) == 2:
        params["objective"] = "binary"
    else:
        params["objective"] = "multiclass"
        params["num_class"] = len(present)
    data = lgb.Dataset(
        X,
        label,
        categorical_feature=[int(f) for f in nominal] if nominal else "auto",
        params={"verbosity": -1, "seed": seed, "deterministic": True, "num_threads": 1},
        free_raw_data=False,
    )
    out = []
    for t in tradeoffs:
        booster = lgb.train(
            dict(params, cegb_tradeoff=float(t)), data, num_boost_round=settings.trees
        )
        out.append(CegbModel(booster, present, classes, float(t), list(prices)))
    return out


def _seed(seed: int) -> int:
    """LightGBM's seed (a 31-bit integer) from any integer."""
    return int(seed) % (2**31 - 1)


def fit(
    X: Any,
    y: Any,
    prices: Sequence[float],
    mc: Sequence[float],
    *,
    classes: Optional[int] = None,
    nominal: Sequence[int] = (),
    seed: int = 0,
    settings: Settings = Settings(),
) -> list[Choice]:
    """CEGB trained on ``X`` (NaN for a missing value) and ``y`` (class indices from 0),
    one :class:`Choice` per misclassification cost of ``mc`` (uniform: ``mc`` for every
    error), in order.

    The objects are dealt into ``settings.inner_folds`` stratified folds (seeded by
    ``seed``); for each fold, CEGB is trained on the others at every tradeoff of
    ``settings.tradeoffs`` and each held-out object pays the flat ``prices`` of the
    features it uses plus ``mc`` if its answer is wrong. At each ``mc`` the tradeoff of
    least mean total cost is chosen (ties, within a relative 1e-9, go to the larger
    tradeoff: the cheaper model), and CEGB is trained with it on all the objects (one
    model per distinct tradeoff chosen). The fits do not depend on ``mc``: the grid is
    trained once per fold whatever the number of costs.

    ``classes`` is the number of classes (default: the largest index plus one); a class
    the training data (or a fold of it) lacks is never answered there. ``nominal`` names
    the columns LightGBM splits as categories (non-negative integer codes).
    """
    X, y, k, p = _training(X, y, prices, classes, nominal)
    costs = [float(m) for m in mc]
    if not costs or any(not (math.isfinite(m) and m >= 0) for m in costs):
        raise ValueError("mc: at least one, each finite and not negative")
    settings.check()
    grid = list(settings.tradeoffs)
    rng = np.random.default_rng(seed)
    lgb_seed = _seed(seed)
    n = X.shape[0]
    # Per tradeoff: sum over held-out objects of test cost, and of errors.
    tests = np.zeros(len(grid))
    errors = np.zeros(len(grid))
    k_inner = min(settings.inner_folds, n)
    if k_inner >= 2:
        for held in _stratified_folds(y, k_inner, rng):
            if held.size == 0:
                continue
            train = np.setdiff1d(np.arange(n), held)
            for g, model in enumerate(
                _train(X[train], y[train], k, p, nominal, grid, settings, lgb_seed)
            ):
                tests[g] += float(model.cost_of_tests(X[held]).sum())
                errors[g] += float(np.sum(model.predict(X[held]) != y[held]))
    choices = []
    finals: dict[float, CegbModel] = {}
    for m in costs:
        mean = (tests + m * errors) / n
        best = 0
        for g in range(1, len(grid)):
            if mean[g] <= mean[best] * (1 + 1e-9) + 1e-12:
                if mean[g] < mean[best] * (1 - 1e-9) or grid[g] > grid[best]:
                    best = g
        t = grid[best]
        if t not in finals:
            finals[t] = _train(X, y, k, p, nominal, [t], settings, lgb_seed)[0]
        choices.append(Choice(m, t, [float(v) for v in mean], finals[t]))
    return choices


def sweep(
    X: Any,
    y: Any,
    prices: Sequence[float],
    tradeoffs: Sequence[float],
    *,
    classes: Optional[int] = None,
    nominal: Sequence[int] = (),
    seed: int = 0,
    settings: Settings = Settings(),
) -> list[CegbModel]:
    """CEGB trained on ``X`` and ``y`` at each tradeoff of ``tradeoffs``, in order: one
    model per tradeoff, every one on all the objects, no cross-validation (the sweep is
    the curve). Each model is the one :func:`fit` trains on all the objects once it has
    chosen that tradeoff (the same LightGBM seed, ``seed`` modulo 2^31 - 1), so a sweep
    over :func:`fit`'s grid holds its every possible final model. ``settings.tradeoffs``
    and ``settings.inner_folds`` play no part.

    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> X = rng.normal(size=(200, 2))
    >>> y = (X[:, 0] > 0).astype(int)
    >>> free, dear = sweep(X, y, [1.0, 1.0], [0.0, 100.0], seed=1)
    >>> bool(free.cost_of_tests(X).mean() > 0), float(dear.cost_of_tests(X).max())
    (True, 0.0)
    """
    X, y, k, p = _training(X, y, prices, classes, nominal)
    grid = [float(t) for t in tradeoffs]
    if not grid or any(not (math.isfinite(t) and t >= 0) for t in grid):
        raise ValueError("tradeoffs: at least one, each finite and not negative")
    settings.check()
    return _train(X, y, k, p, nominal, grid, settings, _seed(seed))


# --- The worker ------------------------------------------------------------------------


def _field(request: dict[str, Any], key: str) -> Any:
    if key not in request:
        raise ValueError(f"request: no {key!r}")
    return request[key]


def _rows(value: Any, what: str, features: Optional[int]) -> np.ndarray:
    """A matrix from a list of rows, ``null`` for a missing value."""
    if not isinstance(value, list):
        raise ValueError(f"{what}: expected a list of rows")
    if not value:
        return np.zeros((0, features or 0))
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{what}: rows of numbers (null for missing) expected: {e}") from None
    if a.ndim != 2:
        raise ValueError(f"{what}: every row must have the same number of features")
    if features is not None and a.shape[1] != features:
        raise ValueError(
            f"{what}: {a.shape[1]} features per row, the training rows have {features}"
        )
    if np.isinf(a).any():
        raise ValueError(f"{what}: a value is infinite")
    return a


def _fold_request(
    request: dict[str, Any], knob: str
) -> tuple[np.ndarray, np.ndarray, list[int], int, list[int], Any, list[Any], int]:
    """The fields of a fit or sweep request, checked in order: the training rows, the
    held-out rows, the classes and their count, the nominal columns, the prices, the list
    ``knob`` names (``mc`` or ``tradeoffs``) and the seed."""
    train = _rows(_field(request, "train"), "train", None)
    if train.shape[0] == 0:
        raise ValueError("train: no training row")
    features = train.shape[1]
    test = _rows(_field(request, "test"), "test", features)
    classes = _field(request, "classes")
    class_count = _field(request, "class_count")
    if not isinstance(class_count, int) or class_count < 1:
        raise ValueError("class_count: expected a positive integer")
    if (
        not isinstance(classes, list)
        or len(classes) != train.shape[0]
        or any(not isinstance(c, int) or not 0 <= c < class_count for c in classes)
    ):
        raise ValueError(
            f"classes: expected one class index below class_count ({class_count}) per training row"
        )
    nominal = _field(request, "nominal")
    if not isinstance(nominal, list) or any(
        not isinstance(f, int) or not 0 <= f < features for f in nominal
    ):
        raise ValueError(f"nominal: expected column indices below {features}")
    for f in nominal:
        for what, a in (("train", train), ("test", test)):
            col = a[:, f]
            known = col[~np.isnan(col)]
            if np.any(known < 0) or np.any(known != np.floor(known)):
                raise ValueError(f"{what}: nominal column {f} holds a value that is not a code")
    prices = _field(request, "prices")
    values = _field(request, knob)
    if not isinstance(values, list):
        raise ValueError(f"{knob}: expected a list")
    seed = _field(request, "seed")
    if not isinstance(seed, int) or seed < 0:
        raise ValueError("seed: expected a non-negative integer")
    return train, test, classes, class_count, nominal, prices, values, seed


def _answer(model: CegbModel, test: np.ndarray) -> dict[str, Any]:
    """A model's answer for the held-out rows: each row's class, class probabilities and
    ordered features, and the model's size."""
    proba = model.predict_proba(test)
    return {
        "predicted": [int(v) for v in np.argmax(proba, axis=1)] if len(test) else [],
        "probabilities": [[float(v) for v in row] for row in proba],
        "features": model.features_used(test),
        "leaves": model.leaves,
        "nodes": model.nodes,
    }


def handle(request: Any) -> dict[str, Any]:
    """The response to one worker request (a parsed JSON object).

    ``{"op": "describe"}`` (or ``"settings": {...}`` beside it) answers LightGBM's
    version, the settings (the defaults where not given) and :func:`describe`'s line. A
    fit request (``"op": "fit"``, the default) carries ``train`` (rows of numbers,
    ``null`` for missing), ``classes`` (one class index per training row),
    ``class_count``, ``nominal`` (column indices), ``prices`` (one per feature), ``test``
    (rows), ``mc`` (a list), ``seed`` and optionally ``settings`` and ``timing``; the
    answer has, per ``mc``, the ``tradeoff`` chosen, its ``cv_costs`` over the grid, the
    model's ``leaves`` and ``nodes``, and per held-out row its ``predicted`` class, its
    class ``probabilities`` and the ordered ``features`` it uses. A sweep request
    (``"op": "sweep"``) carries ``tradeoffs`` (a list) in place of ``mc``; the answer has,
    per tradeoff in order (:func:`sweep`), the ``tradeoff``, the model's ``leaves`` and
    ``nodes`` and the same three lists per held-out row. With ``"timing": true`` either
    answer also has ``learn_seconds`` and ``classify_seconds`` (measured, so not
    reproducible). A request it cannot serve raises ``ValueError`` (the worker answers
    ``{"error": ...}``).
    """
    if not isinstance(request, dict):
        raise ValueError("request: expected a JSON object")
    settings = Settings.from_json(request.get("settings"))
    op = request.get("op", "fit")
    if op == "describe":
        return {
            "lightgbm": lgb.__version__,
            "numpy": np.__version__,
            "settings": {**asdict(settings), "tradeoffs": list(settings.tradeoffs)},
            "description": describe(settings),
        }
    if op not in ("fit", "sweep"):
        raise ValueError(f"request: unknown op {op!r} (known: 'describe', 'fit', 'sweep')")
    knob = "mc" if op == "fit" else "tradeoffs"
    train, test, classes, class_count, nominal, prices, values, seed = _fold_request(request, knob)
    timing = bool(request.get("timing", False))
    out: dict[str, Any]
    if op == "sweep":
        start = time.perf_counter()
        models = sweep(
            train,
            np.asarray(classes, dtype=int),
            prices,
            values,
            classes=class_count,
            nominal=nominal,
            seed=seed,
            settings=settings,
        )
        learn = time.perf_counter() - start
        start = time.perf_counter()
        out = {"by_tradeoff": [{"tradeoff": m.tradeoff, **_answer(m, test)} for m in models]}
        classify = time.perf_counter() - start
    else:
        start = time.perf_counter()
        choices = fit(
            train,
            np.asarray(classes, dtype=int),
            prices,
            values,
            classes=class_count,
            nominal=nominal,
            seed=seed,
            settings=settings,
        )
        learn = time.perf_counter() - start
        start = time.perf_counter()
        by_mc = []
        answered: dict[int, dict[str, Any]] = {}
        for c in choices:
            key = id(c.model)
            if key not in answered:
                answered[key] = _answer(c.model, test)
            by_mc.append(
                {"mc": c.mc, "tradeoff": c.tradeoff, "cv_costs": c.cv_costs, **answered[key]}
            )
        classify = time.perf_counter() - start
        out = {"by_mc": by_mc}
    if timing:
        out["learn_seconds"] = learn
        out["classify_seconds"] = classify
    return out


def serve(lines: IO[str], out: IO[str]) -> None:
    """Answer each request line of ``lines`` with one line on ``out`` (flushed), until
    the end of ``lines``: :func:`handle`'s response, or ``{"error": message}`` for a line
    that is not JSON or a request it cannot serve (the worker goes on with the next)."""
    for line in lines:
        if not line.strip():
            continue
        try:
            response = handle(json.loads(line))
        except Exception as e:  # every failure is an answer, never a hang
            response = {"error": f"{type(e).__name__}: {e}"}
        out.write(json.dumps(response, allow_nan=False, separators=(",", ":")) + "\n")
        out.flush()


def _main(argv: Sequence[str]) -> int:
    if list(argv) != ["--worker"]:
        sys.stderr.write("usage: python cegb.py --worker  (JSON requests on stdin, one per line)\n")
        return 2
    # The responses own the standard output: anything else written to it (by Python code
    # or by the C library under it) goes to the standard error instead.
    sys.stdout.flush()
    protocol = os.fdopen(os.dup(1), "w", encoding="utf-8")
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    serve(sys.stdin, protocol)
    return 0


if __name__ == "__main__":
    sys.exit(_main(sys.argv[1:]))
