"""predict_proba on every classifier of csrl.sklearn: a distribution per object in the
order of classes_, whose most probable class is predict's under uniform costs, that
scikit-learn's ROC AUC scoring can use, and that is the command line's for the same tree."""

import json
import subprocess

import numpy as np
import pytest
from sklearn.base import clone
from sklearn.datasets import load_breast_cancer, load_iris
from sklearn.model_selection import cross_validate

from csrl import _csrl
from csrl import sklearn as cs

FAST = dict(population=6, generations=3)


def estimators():
    """Every classifier, ICET with a small search."""
    trees = [
        cs.TestCostTreeClassifier(),
        cs.Id3Classifier(),
        cs.C45Classifier(),
        cs.IdxClassifier(),
        cs.CsId3BatchClassifier(),
        cs.Eg2Classifier(),
        cs.DtmcClassifier(),
        cs.IcetClassifier(**FAST),
        cs.ActClassifier(act_samples=2),
        cs.CvtClassifier(cvt_folds=3),
        cs.VoiClassifier(),
    ]
    return trees + [cs.CsId3Classifier(), cs.CsIblClassifier()]


ESTIMATORS = estimators()
INCREMENTAL = (cs.CsId3Classifier, cs.CsIblClassifier)


def iris_with_gaps(binned: bool):
    """Iris with one value in ten missing (NaN); binned to whole numbers for the
    incremental learners, which compare values for equality."""
    X, y = load_iris(return_X_y=True)
    X = np.round(X) if binned else X.copy()
    rng = np.random.default_rng(3)
    X[rng.random(X.shape) < 0.1] = np.nan
    return X, np.array(["setosa", "versicolor", "virginica"])[y]


def check_distribution(clf, X):
    proba = clf.predict_proba(X)
    assert proba.shape == (len(X), len(clf.classes_))
    assert ((proba >= 0) & (proba <= 1)).all()
    np.testing.assert_allclose(proba.sum(axis=1), 1.0, rtol=0, atol=1e-12)
    return proba


@pytest.mark.parametrize("estimator", ESTIMATORS, ids=lambda e: type(e).__name__)
def test_probabilities_sum_to_one_and_predict_is_their_argmax(estimator):
    X, y = iris_with_gaps(binned=isinstance(estimator, INCREMENTAL))
    clf = clone(estimator).fit(X, y)
    proba = check_distribution(clf, X)
    predicted = clf.predict(X)
    index = {c: i for i, c in enumerate(clf.classes_)}
    mine = proba[np.arange(len(X)), [index[c] for c in predicted]]
    # Uniform costs (every estimator's default): the answer is a most probable class.
    assert (mine >= proba.max(axis=1) - 1e-12).all()
    # Not a degenerate distribution: the answers are confident where the data is clear.
    assert proba.max(axis=1).mean() > 0.6


def test_under_lopsided_costs_the_answer_is_not_always_the_most_probable():
    X, y = iris_with_gaps(binned=False)
    classes = ["setosa", "versicolor", "virginica"]
    # Calling a virginica anything else costs 100 times more than other errors.
    mc = {a: {p: (0 if a == p else (100.0 if a == "virginica" else 1.0)) for p in classes} for a in classes}
    clf = cs.Id3Classifier(misclassification_cost=mc).fit(X, y)
    proba = check_distribution(clf, X)
    argmax = clf.classes_[proba.argmax(axis=1)]
    assert (clf.predict(X) != argmax).any()


@pytest.mark.parametrize("estimator", ESTIMATORS, ids=lambda e: type(e).__name__)
def test_cross_validate_scores_roc_auc_on_two_classes(estimator):
    X, y = load_breast_cancer(return_X_y=True)
    if isinstance(estimator, INCREMENTAL):
        X = np.round(X / X.std(axis=0) * 2)
    scores = cross_validate(clone(estimator), X, y, cv=3, scoring=["roc_auc", "accuracy"])
    auc = scores["test_roc_auc"]
    assert np.isfinite(auc).all()
    assert auc.mean() > 0.8, auc


def test_an_incremental_distribution_counts_the_examples_it_went_by():
    # One pass: an example of a with nothing measured, then two of b with x0 = 1.
    clf = cs.CsId3Classifier(passes=1).fit([[0], [1], [1]], ["a", "b", "b"])
    proba = check_distribution(clf, [[1], [0], [5]])
    # x0 = 1: the two b examples agree, (2 + 1) / (2 + 2) for b.
    assert proba[0].tolist() == [0.25, 0.75]
    # x0 = 0, and a value never seen: no example has it, so the last attended set (all
    # three) speaks: (1 + 1) / (3 + 2) for a.
    assert proba[1].tolist() == proba[2].tolist() == [0.4, 0.6]
    assert clf.predict([[5]]).tolist() == ["b"]
    # A learner with no example (never after fit) answers the training majority, and
    # its distribution is the training classes' smoothed shares.
    clf._model = _csrl.Classifier("cs-id3", [1.0])
    assert clf.predict([[1]]).tolist() == ["b"]
    assert clf.predict_proba([[1]]).tolist() == [[0.4, 0.6]]


def test_probabilities_match_the_command_lines_json_for_the_same_trees(tmp_path, cli):
    # Three classes named in sorted order of first appearance (the command line numbers
    # classes as they come, scikit-learn sorted), numeric columns, some missing.
    rng = np.random.default_rng(11)
    n = 90
    y = np.array(["a", "b", "c"] * (n // 3))
    X = np.column_stack(
        [
            (y == "a") * 2.0 + rng.normal(0, 1, n),
            (y == "c") * 1.5 + rng.normal(0, 1, n),
            rng.normal(0, 1, n),
        ]
    ).round(2)
    X[rng.random(X.shape) < 0.08] = np.nan
    rows = ["x0,x1,x2,t"] + [
        ",".join("?" if np.isnan(v) else repr(float(v)) for v in row) + f",{t}"
        for row, t in zip(X, y)
    ]
    (tmp_path / "d.csv").write_text("\n".join(rows) + "\n")
    (tmp_path / "c.csv").write_text("feature,cost\nx0,4\nx1,2\nx2,1\n")
    for learner in ("c45", "eg2", "dtmc", "id3-batch"):
        out = subprocess.run(
            [cli, "classify", "--data", str(tmp_path / "d.csv"), "--costs", str(tmp_path / "c.csv"),
             "--target", "t", "--learner", learner, "--folds", "3", "--mc", "50", "--json"],
            capture_output=True, text=True, check=True,
        )
        report = json.loads(out.stdout)
        assert report["class_names"] == ["a", "b", "c"]
        predictions = report["predictions"]
        split = np.array([p["split"] for p in predictions])
        assert [p["object"] for p in predictions] == list(range(n))
        for j in range(3):
            train, test = split != j, split == j
            clf = cs.TestCostTreeClassifier(
                learner=learner, feature_costs=[4, 2, 1], misclassification_cost=50, seed=1 + j
            ).fit(X[train], y[train])
            proba = clf.predict_proba(X[test])
            expected = np.array(
                [[p["probabilities"][c] for c in clf.classes_] for p, t in zip(predictions, test) if t]
            )
            np.testing.assert_array_equal(proba, expected)
            answers = [p["class"] for p, t in zip(predictions, test) if t]
            assert clf.predict(X[test]).tolist() == answers


@pytest.mark.parametrize(
    "estimator",
    [e for e in ESTIMATORS if not isinstance(e, INCREMENTAL)],
    ids=lambda e: type(e).__name__,
)
def test_explain_gives_each_objects_tests_and_answer_as_predict_does(estimator):
    X, y = iris_with_gaps(binned=False)
    clf = clone(estimator).set_params(feature_costs=[3.0, 1.0, 5.0, 2.0])
    clf.fit(X, y)
    explained = clf.explain(X)
    assert len(explained) == len(X)
    np.testing.assert_array_equal([e["class"] for e in explained], clf.predict(X))
    np.testing.assert_array_equal([e["test_cost"] for e in explained], clf.predict_cost(X))
    np.testing.assert_array_equal(
        np.array([e["probabilities"] for e in explained]), clf.predict_proba(X)
    )
    assert [[t["feature"] for t in e["tests"]] for e in explained] == clf.predict_tests(X)
    valued = isinstance(clf, cs.VoiClassifier)
    missing_seen = False
    for e, row in zip(explained, X):
        assert sum(t["paid"] for t in e["tests"]) == pytest.approx(e["test_cost"], abs=1e-9)
        for t in e["tests"]:
            if t["node"] is None:
                assert t["probabilities"] is None
                continue
            np.testing.assert_allclose(t["probabilities"].sum(), 1.0, atol=1e-12)
            # VOI buys a test only where it is expected to pay; the others do not say.
            if valued:
                assert t["expected_gain"] > 0
            else:
                assert t["expected_gain"] is None
        tested_missing = any(np.isnan(row[t["feature"]]) for t in e["tests"])
        assert (e["stopped_at"] is None) == tested_missing
        missing_seen |= tested_missing
    assert missing_seen or all(len(e["tests"]) == 0 for e in explained)
