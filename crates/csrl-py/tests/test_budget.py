"""A hard budget per object on csrl.sklearn's test-cost trees: ``max_test_cost`` and
``max_tests`` never let an object pay or buy past them (through ``predict``,
``predict_proba`` and ``predict_cost``), a budget of 0 answers from the root, no budget
is the old answer, and bad values are refused in ``fit``."""

import warnings

import numpy as np
import pytest
from sklearn.base import clone
from sklearn.exceptions import SkipTestWarning
from sklearn.utils.estimator_checks import check_estimator

from csrl import sklearn as cs

NAMED = [
    cs.Id3Classifier,
    cs.C45Classifier,
    cs.IdxClassifier,
    cs.CsId3BatchClassifier,
    cs.Eg2Classifier,
    cs.DtmcClassifier,
    cs.IcetClassifier,
    cs.ActClassifier,
    cs.CvtClassifier,
    cs.VoiClassifier,
]
SMALL = {
    cs.IcetClassifier: {"population": 6, "generations": 3},
    cs.CvtClassifier: {"cvt_folds": 2},
    cs.ActClassifier: {"act_samples": 2},
}
PRICES = [3.0, 5.0, 8.0, 13.0, 1.0]


def data(seed=0, n=160):
    """Five features that tell the class through noise, a tenth of the values missing."""
    rng = np.random.default_rng(seed)
    y = rng.integers(0, 3, size=n)
    X = np.column_stack([y + rng.normal(0, s, size=n) for s in (0.6, 0.8, 1.0, 1.4, 2.5)])
    X[rng.random(X.shape) < 0.1] = np.nan
    return X, y


def make(cls, **budget):
    return cls(feature_costs=PRICES, misclassification_cost=500.0, **SMALL.get(cls, {}), **budget)


@pytest.mark.parametrize("cls", NAMED, ids=lambda c: c.__name__)
def test_no_object_pays_past_the_budget(cls):
    X, y = data()
    free = make(cls).fit(X, y)
    free_costs = free.predict_cost(X)
    free_tests = [len(t) for t in free.predict_tests(X)]
    binding = 0
    for budget in ({"max_test_cost": 9.0}, {"max_tests": 1}, {"max_tests": 2, "max_test_cost": 16.0}):
        clf = make(cls, **budget).fit(X, y)
        costs = clf.predict_cost(X)
        tests = clf.predict_tests(X)
        limit = budget.get("max_test_cost", np.inf)
        assert (costs <= limit).all(), (budget, costs.max())
        assert max(len(t) for t in tests) <= budget.get("max_tests", 99)
        proba = clf.predict_proba(X)
        assert np.allclose(proba.sum(axis=1), 1.0)
        assert clf.predict(X).shape == y.shape
        binding += int((free_costs > limit).any() or max(free_tests) > budget.get("max_tests", 99))
    # The budgets bind: without them some object pays or buys more (IDX and CS-ID3
    # split again and again on the cheapest feature, which is then free, and stay within).
    if cls not in (cs.IdxClassifier, cs.CsId3BatchClassifier):
        assert binding >= 2


@pytest.mark.parametrize("cls", NAMED, ids=lambda c: c.__name__)
def test_a_budget_of_nothing_answers_from_the_root(cls):
    X, y = data(1)
    for budget in ({"max_test_cost": 0}, {"max_tests": 0}):
        clf = make(cls, **budget).fit(X, y)
        assert (clf.predict_cost(X) == 0.0).all()
        assert all(t == [] for t in clf.predict_tests(X))
        label, weights, _ = clf._model.nodes()[0]
        assert (clf.predict(X) == clf.classes_[label]).all()
        root = (np.asarray(weights) + 1.0) / (sum(weights) + len(weights))
        assert np.allclose(clf.predict_proba(X), root)


@pytest.mark.parametrize("cls", NAMED, ids=lambda c: c.__name__)
def test_no_budget_is_the_old_result(cls):
    X, y = data(2)
    old = make(cls).fit(X, y)
    new = make(cls, max_test_cost=None, max_tests=None).fit(X, y)
    assert (old.predict(X) == new.predict(X)).all()
    assert (old.predict_cost(X) == new.predict_cost(X)).all()
    assert (old.predict_proba(X) == new.predict_proba(X)).all()
    # A budget no object reaches changes nothing a greedy tree answers.
    if cls not in (cs.IcetClassifier, cs.ActClassifier, cs.CvtClassifier):
        rich = make(cls, max_test_cost=1e9, max_tests=100).fit(X, y)
        assert (old.predict_proba(X) == rich.predict_proba(X)).all()


def test_parameters_are_stored_as_given_and_checked_in_fit():
    X, y = data(3, n=40)
    for bad, message in (
        ({"max_test_cost": -1.0}, "max_test_cost must be None or a finite number at least 0"),
        ({"max_test_cost": float("nan")}, "max_test_cost"),
        ({"max_test_cost": True}, "max_test_cost"),
        ({"max_tests": -1}, "max_tests must be None or an integer at least 0"),
        ({"max_tests": 1.5}, "max_tests"),
    ):
        clf = cs.Eg2Classifier(**bad)
        assert clf.get_params()[next(iter(bad))] is next(iter(bad.values()))
        with pytest.raises(ValueError, match=message):
            clf.fit(X, y)
    clf = clone(cs.C45Classifier(max_tests=2, max_test_cost=4))
    assert clf.get_params()["max_tests"] == 2 and clf.get_params()["max_test_cost"] == 4


@pytest.mark.parametrize(
    "estimator",
    [cs.Eg2Classifier(max_tests=2, max_test_cost=50.0), cs.ActClassifier(max_test_cost=50.0)],
    ids=lambda e: type(e).__name__,
)
def test_scikit_learn_checks_pass_with_a_budget(estimator):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SkipTestWarning)
        results = check_estimator(estimator, on_fail=None)
    assert len(results) > 40
    failed = [r["check_name"] for r in results if r["status"] == "failed"]
    assert failed == []
