"""csrl.sklearn's test-cost trees: scikit-learn's checks, prices on the path, groups,
misclassification costs, nominal columns, ICET's seed and pickling."""

import pickle
import subprocess
import sys
import warnings

import numpy as np
import pandas as pd
import pytest
from sklearn.base import clone
from sklearn.datasets import load_iris, make_blobs
from sklearn.exceptions import SkipTestWarning
from sklearn.model_selection import cross_val_score
from sklearn.preprocessing import StandardScaler
from sklearn.utils.estimator_checks import check_estimator

import csrl
from csrl import sklearn as cs

NAMED = {
    "id3-batch": cs.Id3Classifier,
    "c45": cs.C45Classifier,
    "idx": cs.IdxClassifier,
    "cs-id3-batch": cs.CsId3BatchClassifier,
    "eg2": cs.Eg2Classifier,
    "dtmc": cs.DtmcClassifier,
    "icet": cs.IcetClassifier,
    "act": cs.ActClassifier,
    "cvt": cs.CvtClassifier,
    "voi": cs.VoiClassifier,
}
ESTIMATORS = [cs.TestCostTreeClassifier(), *(cls() for cls in NAMED.values())]

# Checks scikit-learn itself skips here, with its reason.
SKIPPED = {
    "check_array_api_input": "needs SCIPY_ARRAY_API and the array API packages; the estimators take numpy arrays",
}


@pytest.mark.parametrize("estimator", ESTIMATORS, ids=lambda e: type(e).__name__)
def test_scikit_learn_checks(estimator):
    # IdxClassifier and CsId3BatchClassifier declare the `poor_score` tag (why: the
    # test below), which skips check_classifiers_train's accuracy bound and nothing else.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SkipTestWarning)
        results = check_estimator(estimator, on_fail=None)
    assert len(results) > 40
    failed = {
        r["check_name"]: f"{r['status']}: {r['exception']}"
        for r in results
        if r["status"] != "passed" and r["check_name"] not in SKIPPED
    }
    assert failed == {}


def test_idx_and_batch_cs_id3_split_again_on_a_test_already_paid_for():
    # scikit-learn's three blobs (check_classifiers_train's data), every price 1: once
    # x0 is bought it is free on the path, and gain / price prefers any split on it to a
    # better one on x1. EG2 divides by (price + 1)^w and does not.
    X, y = make_blobs(n_samples=300, random_state=0)
    X = StandardScaler().fit_transform(X)
    for learner in ("idx", "cs-id3-batch"):
        clf = NAMED[learner]().fit(X, y)
        assert clf.__sklearn_tags__().classifier_tags.poor_score
        assert all(t == [0] for t in clf.predict_tests(X))
        assert clf.score(X, y) < 0.83
    eg2 = cs.Eg2Classifier().fit(X, y)
    assert not eg2.__sklearn_tags__().classifier_tags.poor_score
    assert eg2.score(X, y) > 0.9
    assert cs.TestCostTreeClassifier(learner="idx").__sklearn_tags__().classifier_tags.poor_score


@pytest.mark.parametrize("learner", list(NAMED))
def test_iris_is_learned_by_every_learner(learner):
    X, y = load_iris(return_X_y=True)
    clf = NAMED[learner](feature_costs=[1.0, 2.0, 3.0, 4.0])
    assert clf.fit(X, y).score(X, y) >= 0.9
    # IDX and CS-ID3 keep splitting the cheapest feature once bought (see above).
    assert cross_val_score(clf, X, y, cv=5).mean() > (0.7 if learner in ("idx", "cs-id3-batch") else 0.9)
    assert set(clf.predict(X)) <= set(clf.classes_)
    # The named estimator is the general one with its learner fixed.
    general = cs.TestCostTreeClassifier(learner=learner, feature_costs=[1.0, 2.0, 3.0, 4.0]).fit(X, y)
    assert general._model.nodes() == clf._model.nodes()


def dear_and_cheap(n=200, seed=3):
    """Feature 0 decides the class and costs 50; feature 1 decides it for 90% of the
    objects and costs 1."""
    rng = np.random.default_rng(seed)
    dear = rng.uniform(0, 10, n)
    y = (dear > 5).astype(int)
    cheap = np.where(rng.random(n) < 0.9, y, 1 - y) * 4.0 + rng.uniform(0, 1, n)
    return np.column_stack([dear, cheap]), y


def test_the_cheap_feature_is_preferred_by_eg2_and_idx_but_not_by_c45():
    X, y = dear_and_cheap()
    costs = dict(feature_costs=[50.0, 1.0], misclassification_cost=100.0)
    root = {}
    for learner in ("c45", "id3-batch", "idx", "eg2"):
        clf = NAMED[learner](**costs).fit(X, y)
        root[learner] = clf._model.nodes()[0][2][0]
        assert clf.predict_cost(X).min() == (50.0 if root[learner] == 0 else 1.0)
    assert root == {"c45": 0, "id3-batch": 0, "idx": 1, "eg2": 1}
    c45 = cs.C45Classifier(**costs).fit(X, y)
    eg2 = cs.Eg2Classifier(**costs).fit(X, y)
    assert c45.score(X, y) > eg2.score(X, y)  # C4.5 pays for the better test
    assert eg2.total_cost(X, y) < c45.total_cost(X, y)  # EG2 costs less in all
    # EG2 with w = 0 does not look at prices.
    assert cs.Eg2Classifier(w=0.0, **costs).fit(X, y)._model.nodes()[0][2][0] == 0


def walk(clf, x):
    """The features a tree tests for object x (a row of floats, NaN where missing),
    found by following the tree: every branch below a missing value."""
    nodes = clf._model.nodes()
    tested, stack = [], [0]
    while stack:
        label, _, split = nodes[stack.pop()]
        if split is None:
            continue
        feature, at, children = split
        if feature not in tested:
            tested.append(feature)
        if np.isnan(x[feature]):
            stack.extend(children)
        else:
            stack.append(children[int(x[feature] > at)])
    return tested


def test_predict_cost_is_the_price_of_the_tests_on_the_path():
    rng = np.random.default_rng(4)
    X = rng.uniform(0, 1, size=(300, 5))
    y = ((X[:, 0] > 0.5) ^ (X[:, 3] > 0.3)) + (X[:, 4] > 0.8)
    prices = np.array([3.0, 5.0, 7.0, 11.0, 13.0])
    clf = cs.Id3Classifier(feature_costs=prices.tolist()).fit(X, y)
    Xt = rng.uniform(0, 1, size=(100, 5))
    Xt[::7, 0] = np.nan  # missing at the root: every branch's tests are paid for
    Xt[::5, 3] = np.nan
    classes, costs = clf.predict_with_cost(Xt)
    tests = clf.predict_tests(Xt)
    assert np.array_equal(classes, clf.predict(Xt))
    for x, cost, done in zip(Xt, costs, tests):
        path = walk(clf, x)
        assert sorted(done) == sorted(path)
        assert cost == pytest.approx(prices[path].sum())
    # An object missing the root's value pays for the tests of both sides.
    root, at, _ = clf._model.nodes()[0][2]
    x = Xt[:1].copy()
    x[0, root] = np.nan
    sides = [clf.predict_cost(np.where(np.arange(5) == root, v, x))[0] for v in (at - 0.01, at + 0.01)]
    assert clf.predict_cost(x)[0] >= max(sides) > min(sides)


def test_a_group_is_paid_in_full_once_then_at_its_discount():
    rng = np.random.default_rng(5)
    X = rng.uniform(0, 1, size=(400, 3))
    y = ((X[:, 0] > 0.5) & (X[:, 1] > 0.5)).astype(int)  # needs features 0 and 1
    full = [10.0, 8.0, 1.0]
    plain = cs.Id3Classifier(feature_costs=full).fit(X, y)
    grouped = cs.Id3Classifier(
        feature_costs=full,
        feature_groups=["blood", "blood", None],
        feature_discounts=[2.0, 3.0, None],
    ).fit(X, y)
    discount = {0: 2.0, 1: 3.0}
    both = 0
    for done, cost, plain_cost in zip(grouped.predict_tests(X), grouped.predict_cost(X), plain.predict_cost(X)):
        blood = [f for f in done if f in (0, 1)]
        expected = sum(full[f] for f in done if f == 2)
        if blood:  # the first test of the group in full, the later one at its discount
            expected += full[blood[0]] + sum(discount[f] for f in blood[1:])
        assert cost == pytest.approx(expected)
        both += len(blood) == 2
    assert both > 50
    # Without the groups, both tests are paid in full.
    assert plain.predict_cost(X).max() == pytest.approx(18.0)
    assert grouped.predict_cost(X).max() == pytest.approx(13.0)


def test_groups_and_prices_by_column_name_with_nominal_strings():
    X = pd.DataFrame(
        {
            "colour": ["red", "blue", "red", None, "blue", "green"] * 10,
            "size": [1.0, 2.0, np.nan, 4.0, 5.0, 6.0] * 10,
            "code": [1, 2, 1, 2, 1, 2] * 10,
        }
    )
    y = np.where(X["colour"].eq("red") | X["size"].gt(4.5), "yes", "no")
    clf = cs.TestCostTreeClassifier(
        learner="id3-batch",
        feature_costs={"colour": 2.0, "size": 3.0, "code": 5.0},
        feature_groups={"colour": "g", "size": "g"},
        feature_discounts={"size": 1.0},
        nominal_features=["code"],
    ).fit(X, y)
    assert clf.nominal_features_.tolist() == [True, False, True]
    assert clf.categories_[0].tolist() == ["blue", "green", "red"]
    assert clf.categories_[2].tolist() == ["1", "2"]
    assert clf.feature_costs_.tolist() == [2.0, 3.0, 5.0]
    assert clf.score(X, y) > 0.8
    # A value never seen goes down the largest branch; it still pays for the test.
    unseen = pd.DataFrame({"colour": ["purple"], "size": [9.0], "code": [3]})
    assert clf.predict(unseen)[0] in {"yes", "no"}
    assert clf.predict_cost(unseen)[0] >= 2.0
    with pytest.raises(ValueError, match="feature_costs has no entry for the columns"):
        cs.Id3Classifier(feature_costs={"colour": 1.0}).fit(X, y)
    with pytest.raises(ValueError, match="names columns X does not have"):
        cs.Id3Classifier(feature_groups={"weight": "g"}).fit(X, y)
    with pytest.raises(ValueError, match="is numeric, but X holds 'big'"):
        clf.predict(pd.DataFrame({"colour": ["red"], "size": ["big"], "code": [1]}))
    # A list of rows keeps its numbers numbers.
    rows = [[1.0, "a"], [2.0, "a"], [8.0, "b"], [9.0, "b"]] * 3
    fitted = cs.Id3Classifier().fit(rows, [0, 0, 1, 1] * 3)
    assert fitted.nominal_features_.tolist() == [False, True]


def test_pandas_nullable_and_category_columns():
    X = pd.DataFrame(
        {
            "count": pd.array([1, None, 3, 4] * 5, dtype="Int64"),  # numeric, NA missing
            "kind": pd.Categorical([1, 2, 1, 3] * 5),  # nominal for all its numbers
            "score": [1.5, 2.5, np.nan, 0.0] * 5,
        }
    )
    y = ["p", "q", "p", "q"] * 5
    clf = cs.Eg2Classifier().fit(X, y)
    assert clf.nominal_features_.tolist() == [False, True, False]
    assert clf.categories_[1].tolist() == ["1", "2", "3"]
    assert clf.score(X, y) == 1.0
    with pytest.raises(ValueError, match="Feature names must be in the same order"):
        clf.predict(X[["kind", "count", "score"]])


def test_misclassification_costs_label_the_leaves_and_count_in_the_total():
    X, y = dear_and_cheap()
    y = np.where(y == 1, "sick", "well")
    # A missed "sick" costs 1000, a false alarm 1: a stump on nothing answers "sick".
    matrix = [[0.0, 1000.0], [1.0, 0.0]]  # [actual][predicted], classes_ = [sick, well]
    clf = cs.DtmcClassifier(feature_costs=[1e6, 1e6], misclassification_cost=matrix).fit(X, y)
    assert clf.classes_.tolist() == ["sick", "well"]
    assert set(clf.predict(X)) == {"sick"}
    assert clf.total_cost(X, y) == pytest.approx(np.mean(y == "well") * 1.0)
    by_label = {"sick": {"well": 1000.0}, "well": {"sick": 1.0}}
    same = cs.DtmcClassifier(feature_costs=[1e6, 1e6], misclassification_cost=by_label).fit(X, y)
    assert np.array_equal(same.misclassification_costs_, np.array(matrix))
    # total_cost: the tests plus the cost of each answer.
    eg2 = cs.Eg2Classifier(feature_costs=[50.0, 1.0], misclassification_cost=matrix).fit(X, y)
    pred, cost = eg2.predict_with_cost(X)
    wrong = np.where(pred == y, 0.0, np.where(y == "sick", 1000.0, 1.0))
    assert eg2.total_cost(X, y) == pytest.approx(np.mean(cost + wrong))
    with pytest.raises(ValueError, match="not fitted on"):
        eg2.total_cost(X[:2], ["sick", "unknown"])


@pytest.mark.parametrize(
    "params, message",
    [
        ({"misclassification_cost": [[0, 1, 1], [1, 0, 1], [1, 1, 0]]}, r"must be 2 x 2, indexed \[actual\]\[predicted\]"),
        ({"misclassification_cost": [0, 1]}, "must be 2 x 2"),
        ({"misclassification_cost": -1.0}, "misclassification_cost is -1.0: costs must be finite and not negative"),
        ({"misclassification_cost": [[0, -5], [1, 0]]}, r"misclassification_cost\[0\]\[1\] is -5.0"),
        ({"misclassification_cost": {0: {1: 1.0}}}, "no cost for answering 0 to an object of class 1"),
        ({"feature_costs": [1.0, -2.0]}, "the price of feature 1 is -2.0: costs must be finite and not negative"),
        ({"feature_costs": [1.0, np.inf]}, "the price of feature 1 is inf"),
        ({"feature_costs": [1.0]}, "feature_costs has 1 entries but X has 2 features"),
        ({"feature_costs": {"a": 1.0}}, "needs X with column names"),
        ({"feature_groups": ["g", "g"], "feature_discounts": [-1.0, None]}, "discount of feature 0 is -1.0"),
        ({"feature_groups": ["g", "g"], "feature_discounts": [2.0, None]}, "above its full price 1.0"),
        ({"feature_discounts": [0.5, None]}, "puts it in no group"),
        ({"feature_groups": [["list"], None]}, "not hashable"),
        ({"learner": "c5"}, "learner must be one of id3-batch, c45"),
        ({"confidence": 0.0}, r"confidence must be a number in \(0, 1\)"),
        ({"w": 2.0}, r"w must be a number in \[0, 1\]"),
        ({"seed": -1}, "seed must be an integer at least 0"),
        ({"population": 1}, "population must be an integer at least 2"),
        ({"nominal_features": [5]}, "5 is not a column index"),
    ],
)
def test_bad_parameters_are_refused_with_a_clear_value_error(params, message):
    X = np.array([[0.0, 1.0], [1.0, 0.0]] * 4)
    with pytest.raises(ValueError, match=message):
        cs.TestCostTreeClassifier(**params).fit(X, [0, 1] * 4)


@pytest.mark.parametrize(
    "estimator, params, message",
    [
        ("IcetClassifier", {"population": 10**12}, "ICET population of 1000000000000: between 2 and 10000"),
        ("IcetClassifier", {"generations": 10**12}, "1000000000000 ICET generations: between 1 and 10000"),
        ("CvtClassifier", {"cvt_folds": 2**63}, "cvt_folds=9223372036854775808 needs at least 9223372036854775808 samples, found n_samples = 8"),
        ("CvtClassifier", {"cvt_folds": 9}, "cvt_folds=9 needs at least 9 samples, found n_samples = 8"),
    ],
)
def test_counts_beyond_what_the_data_allows_are_refused_before_anything_is_allocated(estimator, params, message):
    # Each once aborted on an allocation of gigabytes or ran without end.
    X = np.array([[0.0, 1.0], [1.0, 0.0]] * 4)
    with pytest.raises(ValueError, match=message):
        getattr(cs, estimator)(**params).fit(X, [0, 1] * 4)


def test_prices_whose_totals_overflow_are_refused_before_learning():
    # ICET once reported a total cost and a fitness of inf.
    X = np.array([[0.0, 1.0], [1.0, 0.0]] * 4)
    with pytest.raises(ValueError, match=r"sum to 2e308 per object|cannot be represented"):
        cs.IcetClassifier(feature_costs=[1e308, 1e308], population=4, generations=1).fit(X, [0, 1] * 4)
    with pytest.raises(ValueError, match="8 objects cannot be represented"):
        cs.IcetClassifier(feature_costs=[1e300, 1e300], population=4, generations=1).fit(X, [0, 1] * 4)


def test_a_continuous_target_is_refused_before_its_cost_matrix_is_made():
    # 10,000 classes once took 4 GB.
    # (scikit-learn warns first that y could be a regression target.)
    X = np.arange(20000, dtype=float).reshape(-1, 1)
    with pytest.warns(UserWarning, match="regression"), pytest.raises(ValueError, match="y has 20000 distinct classes, more than the 1000"):
        cs.TestCostTreeClassifier().fit(X, np.arange(20000))


def test_classes_times_objects_past_what_a_fit_may_hold_are_refused_before_learning():
    # 1000 classes of three objects: CVT's ten trees and tries on each of its six sets of
    # objects would keep 1000 weights at every node; EG2's one tree may.
    X = np.arange(3000, dtype=float).reshape(-1, 1)
    y = np.arange(3000) % 1000
    with pytest.raises(ValueError, match="1000 classes over 3000 training objects"):
        cs.CvtClassifier().fit(X, y)
    assert cs.Eg2Classifier().fit(X, y).score(X, y) > 0


def test_a_table_too_wide_for_the_lookahead_is_refused_before_learning():
    # ACT's sampled lookahead takes time in the square of the features: past 1000, ACT
    # with samples and CVT are refused; ACT without samples and EG2 learn.
    wide = csrl._csrl.MAX_LOOKAHEAD_FEATURES + 1
    X = np.arange(8 * wide, dtype=float).reshape(8, wide) % 5
    y = [0, 1] * 4
    with pytest.raises(ValueError, match=f"{wide} features for CVT's lookahead grower: at most 1000"):
        cs.CvtClassifier(cvt_folds=2).fit(X, y)
    with pytest.raises(ValueError, match=f"{wide} features for ACT's lookahead"):
        cs.ActClassifier().fit(X, y)
    assert cs.ActClassifier(act_samples=0).fit(X, y).predict(X).shape == (8,)
    assert cs.Eg2Classifier().fit(X, y).predict(X).shape == (8,)


def test_one_object_is_learned_as_a_leaf_and_a_class_of_one_object_is_said():
    # One object: a learner answers its class; CVT's cross-validation needs a fold per
    # object, so it refuses.
    for cls in (cs.Eg2Classifier, cs.DtmcClassifier, cs.IcetClassifier, cs.ActClassifier):
        clf = cls().fit([[1.0, 2.0]], ["only"])
        assert clf.predict([[5.0, 0.0]]).tolist() == ["only"], cls.__name__
        assert len(clf._model.nodes()) == 1
    with pytest.raises(ValueError, match="cvt_folds=5 needs at least 5 samples, found n_samples = 1"):
        cs.CvtClassifier().fit([[1.0, 2.0]], ["only"])
    # A class of one object: learned, and CVT says that one of its inner folds lacks it.
    X = np.arange(14, dtype=float).reshape(7, 2)
    y = ["a", "a", "a", "b", "b", "b", "c"]
    with pytest.warns(UserWarning, match="class 'c' has one object: the fold of CVT's cross-validation"):
        cvt = cs.CvtClassifier(cvt_folds=2).fit(X, y)
    assert set(cvt.classes_) == {"a", "b", "c"}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        cs.CvtClassifier(cvt_folds=2).fit(X[:6], y[:6])
        cs.ActClassifier().fit(X, y)


def test_the_published_benchmarks_settings_are_estimator_parameters():
    # Listed prices: a numeric test bought once costs its price again further down, so
    # IDX no longer splits on x0 alone (see the blobs test above).
    X, y = make_blobs(n_samples=300, random_state=0)
    X = StandardScaler().fit_transform(X)
    path = cs.TestCostTreeClassifier(learner="idx").fit(X, y)
    listed = cs.TestCostTreeClassifier(learner="idx", selection_prices="listed").fit(X, y)
    assert all(t == [0] for t in path.predict_tests(X))
    assert any(1 in t for t in listed.predict_tests(X))
    assert listed.score(X, y) > path.score(X, y)
    # ICET pruned by costs at a low misclassification cost keeps only tests that pay.
    X, y = load_iris(return_X_y=True)
    params = dict(feature_costs=[10.0, 20.0, 30.0, 40.0], misclassification_cost=20.0, population=10, generations=3, seed=1)
    errors = cs.IcetClassifier(**params).fit(X, y)
    costs = cs.IcetClassifier(icet_pruning="costs", **params).fit(X, y)
    assert costs.predict_cost(X).mean() <= errors.predict_cost(X).mean()
    general = cs.TestCostTreeClassifier(learner="icet", icet_pruning="costs", icet_search_objects=60, **params).fit(X, y)
    named = cs.IcetClassifier(icet_pruning="costs", icet_search_objects=60, **params).fit(X, y)
    assert general._model.nodes() == named._model.nodes()
    for bad, message in (
        (dict(selection_prices="free"), "selection_prices must be 'path', 'listed' or 'listed-once'"),
        (dict(icet_pruning="leaves"), "icet_pruning must be 'errors' or 'costs'"),
        (dict(icet_search_objects=1), "icet_search_objects must be an integer at least 2"),
    ):
        with pytest.raises(ValueError, match=message):
            cs.TestCostTreeClassifier(learner="icet", **bad).fit(X, y)


def test_icet_is_reproducible_from_its_seed():
    X, y = load_iris(return_X_y=True)
    params = dict(feature_costs=[1.0, 5.0, 20.0, 40.0], misclassification_cost=50.0, population=20, generations=5)
    a = cs.IcetClassifier(seed=7, **params).fit(X, y)
    b = cs.IcetClassifier(seed=7, **params).fit(X, y)
    c = cs.IcetClassifier(seed=8, **params).fit(X, y)
    assert a._model.nodes() == b._model.nodes()
    assert a.icet_genome_["w"] == b.icet_genome_["w"]
    assert np.array_equal(a.icet_genome_["prices"], b.icet_genome_["prices"])
    assert not np.array_equal(a.icet_genome_["prices"], c.icet_genome_["prices"])
    assert set(a.icet_genome_) == {"prices", "w", "confidence", "fitness"}
    assert len(a.icet_genome_["prices"]) == 4 and 0 < a.icet_genome_["confidence"] < 1
    assert not hasattr(cs.Eg2Classifier().fit(X, y), "icet_genome_")


def test_act_is_reproducible_from_its_seed_and_samples_cost_time_not_correctness():
    X, y = load_iris(return_X_y=True)
    params = dict(feature_costs=[1.0, 5.0, 20.0, 40.0], misclassification_cost=200.0)
    a = cs.ActClassifier(seed=7, **params).fit(X, y)
    b = cs.ActClassifier(seed=7, **params).fit(X, y)
    assert a._model.nodes() == b._model.nodes()
    assert a.score(X, y) >= 0.9
    # One sample per branch, or none (each branch valued as a leaf): still a tree that
    # pays for its tests.
    for samples in (0, 1):
        clf = cs.ActClassifier(seed=7, act_samples=samples, **params).fit(X, y)
        assert clf.score(X, y) >= 0.9
    general = cs.TestCostTreeClassifier(learner="act", seed=7, **params).fit(X, y)
    assert general._model.nodes() == a._model.nodes()
    with pytest.raises(ValueError, match="act_samples must be at most 1000"):
        cs.ActClassifier(act_samples=1001).fit(X, y)
    with pytest.raises(ValueError, match="act_samples must be an integer"):
        cs.ActClassifier(act_samples=-1).fit(X, y)


def test_cvt_is_reproducible_from_its_seed_and_says_what_it_chose():
    X, y = load_iris(return_X_y=True)
    params = dict(feature_costs=[1.0, 5.0, 20.0, 40.0], misclassification_cost=200.0)
    a = cs.CvtClassifier(seed=7, **params).fit(X, y)
    b = cs.CvtClassifier(seed=7, **params).fit(X, y)
    assert a._model.nodes() == b._model.nodes()
    assert a.cvt_choice_ == b.cvt_choice_
    assert a.cvt_choice_["grower"] in ("eg2-w0", "eg2-w0.5", "eg2-w1", "eg2-w2", "c45", "dtmc", "act")
    alpha = a.cvt_choice_["alpha"]
    assert (alpha is None or alpha >= 0) and a.cvt_choice_["held_out_cost"] > 0
    assert a.score(X, y) >= 0.9
    # Other folds measure other held-out costs.
    assert any(cs.CvtClassifier(seed=s, **params).fit(X, y).cvt_choice_ != a.cvt_choice_ for s in range(1, 6))
    general = cs.TestCostTreeClassifier(learner="cvt", seed=7, **params).fit(X, y)
    assert general._model.nodes() == a._model.nodes()
    assert not hasattr(cs.Eg2Classifier().fit(X, y), "cvt_choice_")
    with pytest.raises(ValueError, match="cvt_folds must be an integer at least 2"):
        cs.CvtClassifier(cvt_folds=1).fit(X, y)


def test_cvt_samples_set_its_lookahead_and_zero_leaves_it_out():
    X, y = load_iris(return_X_y=True)
    params = dict(feature_costs=[1.0, 5.0, 20.0, 40.0], misclassification_cost=200.0, seed=7)
    full = cs.CvtClassifier(**params).fit(X, y)
    assert full._model.nodes() == cs.CvtClassifier(cvt_samples=5, **params).fit(X, y)._model.nodes()
    greedy = cs.CvtClassifier(cvt_samples=0, **params).fit(X, y)
    assert greedy.cvt_choice_["grower"] != "act"
    # The greedy growers' trees and folds do not depend on the lookahead's samples.
    assert greedy.cvt_choice_["held_out_cost"] >= full.cvt_choice_["held_out_cost"] - 1e-9
    general = cs.TestCostTreeClassifier(learner="cvt", cvt_samples=0, **params).fit(X, y)
    assert general._model.nodes() == greedy._model.nodes()
    with pytest.raises(ValueError, match="cvt_samples must be at most 1000"):
        cs.CvtClassifier(cvt_samples=1001).fit(X, y)
    with pytest.raises(ValueError, match="cvt_samples must be an integer at least 0"):
        cs.CvtClassifier(cvt_samples=-1).fit(X, y)


@pytest.mark.parametrize("learner", [cs.ActClassifier, cs.CvtClassifier], ids=lambda c: c.__name__)
def test_act_and_cvt_on_several_threads_grow_the_same_tree(learner):
    X, y = load_iris(return_X_y=True)
    params = dict(feature_costs=[1.0, 5.0, 20.0, 40.0], misclassification_cost=200.0, seed=3)
    one = learner(**params).fit(X, y)
    assert len(one._model.nodes()) > 1
    for n_jobs in (2, 3, -1):
        many = learner(n_jobs=n_jobs, **params).fit(X, y)
        assert many._model.nodes() == one._model.nodes(), n_jobs
        assert getattr(many, "cvt_choice_", None) == getattr(one, "cvt_choice_", None), n_jobs
        assert many.predict_proba(X).tolist() == one.predict_proba(X).tolist()
    for bad in (0, -2, 1.5, True, "2"):
        with pytest.raises(ValueError, match="n_jobs must be None, -1 or an integer at least 1"):
            learner(n_jobs=bad).fit(X, y)


@pytest.mark.parametrize("estimator", ESTIMATORS, ids=lambda e: type(e).__name__)
def test_pickled_estimator_predicts_the_same(estimator):
    rng = np.random.default_rng(6)
    X = np.empty((120, 3), dtype=object)
    X[:, 0] = rng.normal(size=120)
    X[:, 1] = rng.choice(["a", "b", "c"], size=120)
    X[:, 2] = rng.integers(0, 5, size=120).astype(float)
    X[::11, 0] = np.nan
    y = np.where((X[:, 0].astype(float) > 0) | (X[:, 1] == "b"), "p", "q")
    clf = clone(estimator).set_params(feature_costs=[4.0, 1.0, 2.0]).fit(X, y)
    back = pickle.loads(pickle.dumps(clf))
    assert back._model.nodes() == clf._model.nodes()
    for method in ("predict", "predict_cost", "predict_tests"):
        assert np.array_equal(np.asarray(getattr(back, method)(X), dtype=object), np.asarray(getattr(clf, method)(X), dtype=object))
    assert back.total_cost(X, y) == clf.total_cost(X, y)


def test_a_saved_tree_is_checked_when_loaded():
    clf = cs.Id3Classifier().fit([[0.0], [1.0]], [0, 1])
    state = clf._model.state()
    assert csrl._csrl.TestCostTree.from_state(state).nodes() == clf._model.nodes()
    with pytest.raises(csrl.DataError, match="not a saved tree: no `kinds`"):
        csrl._csrl.TestCostTree.from_state({"learner": "id3-batch"})
    with pytest.raises(csrl.DataError, match="not a saved tree"):
        csrl._csrl.TestCostTree.from_state({"learner": object()})


def _tampered(state, edit):
    import copy

    state = copy.deepcopy(state)
    edit(state)
    return state


def _threshold(state):
    return next(n["split"]["Threshold"] for n in state["tree"]["nodes"] if n["split"])


@pytest.mark.parametrize(
    "edit, message",
    [
        (lambda s: _threshold(s).update(children=[1, 99]), "child 99: a child comes after its parent"),
        (lambda s: _threshold(s).update(children=[0, 0]), "child 0: a child comes after its parent"),
        (lambda s: _threshold(s).update(feature=7), "a test of feature 7, but there are 1 features"),
        (lambda s: _threshold(s).update(shares=[-0.5, 1.5]), "a share that is negative"),
        (lambda s: s["tree"]["nodes"].clear(), "no nodes"),
        (lambda s: s["tree"]["nodes"][0].update(weights=[]), "0 weights, but there are 2 classes"),
        (lambda s: s["tree"]["nodes"][0].update(label=5), "label 5, but there are 2 classes"),
        (lambda s: s.update(class_names=["a", "b", "c"]), "2 classes, but the model has 3"),
        (lambda s: s.update(kinds=[["x", "y"]]), "a threshold on nominal feature"),
        (lambda s: s["prices"]["tests"][0].update(full=-1.0, discount=-1.0), "price"),
    ],
)
def test_a_tampered_state_is_refused_when_loaded_never_panics_or_hangs(edit, message):
    clf = cs.Id3Classifier().fit([[0.0], [1.0]] * 4, [0, 1] * 4)
    state = _tampered(clf._model.state(), edit)
    with pytest.raises(csrl.DataError, match=message):
        csrl._csrl.TestCostTree.from_state(state)


def test_a_state_nested_without_end_is_refused_not_a_crash():
    deep: list = []
    for _ in range(100_000):
        deep = [deep]
    clf = cs.Id3Classifier().fit([[0.0], [1.0]] * 4, [0, 1] * 4)
    state = clf._model.state()  # a fresh dict at every call
    state["genome"] = deep
    with pytest.raises(csrl.DataError, match="nested deeper than the 32 levels"):
        csrl._csrl.TestCostTree.from_state(state)


def test_export_text_names_tests_prices_and_classes():
    X = pd.DataFrame({"size": [1.0, 2.0, 8.0, 9.0] * 3, "colour": ["red", "blue"] * 6})
    y = ["small", "small", "big", "big"] * 3
    text = cs.C45Classifier(feature_costs={"size": 1.5, "colour": 9.0}).fit(X, y).export_text()
    assert text.splitlines() == [
        "|--- size <= 5.00 (price 1.5)",
        "|   |--- class: small",
        "|--- size > 5.00 (price 1.5)",
        "|   |--- class: big",
    ]


# A child interpreter fits a test-cost tree that would grow for hours, while a helper
# thread waits, in Python, until the main thread is inside the compiled fit (its innermost
# Python frame is `fit`, at the line that calls `_csrl.TestCostTree.fit`), then sends the
# process SIGINT. No clock and no fixed wait: with the GIL held by the fit the helper
# could not run at all, and a fit deaf to Ctrl-C would run for hours; its ending proves
# both. The child first takes Python's own Ctrl-C handler: a process started in the
# background by a shell inherits SIGINT ignored, and Python then leaves it ignored.
FIT_STOPPED = """
import inspect, os, signal, sys, threading
signal.signal(signal.SIGINT, signal.default_int_handler)
import numpy as np
from csrl import sklearn as cs
source, first = inspect.getsourcelines(cs.TestCostTreeClassifier.fit)
line = first + next(i for i, text in enumerate(source) if "_csrl.TestCostTree.fit(" in text)
main = threading.main_thread().ident
def growing():
    frame = sys._current_frames().get(main)
    return frame is not None and frame.f_code.co_name == "fit" and frame.f_lineno == line
def helper():
    while not growing():
        os.sched_yield()
    print("growing", flush=True)
    os.kill(os.getpid(), signal.SIGINT)
threading.Thread(target=helper, daemon=True).start()
rng = np.random.default_rng(1)
X = rng.random((OBJECTS, FEATURES))
y = (X[:, 0] + X[:, 1] + rng.random(OBJECTS) > 1.5).astype(int)
clf = ESTIMATOR
try:
    clf.fit(X, y)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("fitted" if hasattr(clf, "classes_") else "unfitted", flush=True)
    raise
"""

# Fits of hours: ACT sampling 1000 trees under every branch of every candidate; ICET's
# largest search (10,000 individuals for 10,000 generations: 10^8 trees); CVT, whose
# lookahead grower grows on six sets of objects, on 300 features.
LONG_FITS = {
    "act": ("cs.ActClassifier(act_samples=1000)", 3000, 10),
    "icet": ("cs.IcetClassifier(population=10000, generations=10000)", 1000, 10),
    "cvt": ("cs.CvtClassifier()", 2000, 300),
}


@pytest.mark.parametrize("learner", LONG_FITS)
def test_ctrl_c_stops_a_long_fit_and_leaves_the_estimator_unfitted(learner):
    estimator, objects, features = LONG_FITS[learner]
    child = (
        FIT_STOPPED.replace("ESTIMATOR", estimator)
        .replace("OBJECTS", str(objects))
        .replace("FEATURES", str(features))
    )
    # The timeout guards against a hang only: a fit deaf to Ctrl-C runs past it and fails.
    proc = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, timeout=300)
    assert "growing" in proc.stdout, (proc.stdout, proc.stderr)
    assert "unfitted" in proc.stdout, (proc.stdout, proc.stderr)
    assert "KeyboardInterrupt" in proc.stderr, proc.stderr
    assert "finished" not in proc.stdout
    assert proc.returncode != 0
