"""csrl.sklearn: scikit-learn's estimator checks, costs, DOT and the heart data."""

import pickle
import subprocess
import sys
import warnings

import numpy as np
import pytest
from sklearn.exceptions import SkipTestWarning
from sklearn.model_selection import cross_val_score
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import KBinsDiscretizer
from sklearn.utils.estimator_checks import check_estimator

import csrl
from csrl.sklearn import CsIblClassifier, CsId3Classifier

# Checks scikit-learn itself skips here, with its reason.
SKIPPED = {
    "check_array_api_input": "needs SCIPY_ARRAY_API and the array API packages; the estimators take numpy arrays",
}


@pytest.mark.parametrize("estimator", [CsId3Classifier(), CsIblClassifier()], ids=lambda e: type(e).__name__)
def test_scikit_learn_checks(estimator):
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


def test_the_cheap_feature_is_measured_first():
    rng = np.random.default_rng(1)
    X = rng.integers(0, 3, size=(300, 4))
    y = (X[:, 2] > 0).astype(int)  # decided by feature 2
    costs = [50.0, 40.0, 1.0, 30.0]
    clf = CsId3Classifier(feature_costs=costs).fit(X, y)
    assert clf.score(X, y) == 1.0
    assert clf.predict_cost(X).tolist() == [1.0] * len(X)
    blind = CsId3Classifier().fit(X, y)  # every price 1: nothing favours feature 2
    assert clf.training_cost_ < CsId3Classifier(feature_costs=[1, 1, 50, 1]).fit(X, y).training_cost_
    assert blind.n_passes_ >= 1 and clf.training_errors_[-1] == 0


def test_missing_and_unseen_values():
    X = np.array([[0.0, 1.0], [1.0, 1.0], [np.nan, 0.0], [1.0, 0.0]] * 3)
    y = np.array(["a", "b", "a", "b"] * 3)
    for clf in (CsId3Classifier(), CsIblClassifier()):
        clf.fit(X, y)
        pred = clf.predict(np.array([[7.0, 1.0], [np.nan, np.nan]]))
        assert set(pred) <= {"a", "b"}


def test_feature_costs_are_checked():
    X = np.zeros((4, 2))
    with pytest.raises(ValueError, match="2 features"):
        CsId3Classifier(feature_costs=[1.0]).fit(X, [0, 1, 0, 1])
    with pytest.raises(csrl.DataError, match="feature_costs"):
        CsId3Classifier(feature_costs=[1.0, -1.0]).fit(X, [0, 1, 0, 1])
    with pytest.raises(ValueError, match="passes"):
        CsId3Classifier(passes=0).fit(X, [0, 1, 0, 1])


def test_pickled_estimator_predicts_the_same():
    rng = np.random.default_rng(2)
    X = rng.integers(0, 4, size=(80, 5))
    y = (X[:, 0] + X[:, 3]) % 3
    for clf in (CsId3Classifier(feature_costs=[1, 2, 3, 4, 5]), CsIblClassifier(tolerance=0)):
        clf.fit(X, y)
        back = pickle.loads(pickle.dumps(clf))
        assert np.array_equal(back.predict(X), clf.predict(X))
        assert np.array_equal(back.predict_cost(X), clf.predict_cost(X))


def test_export_graphviz_names_features_values_and_classes():
    X = np.array([[0, 5], [1, 5], [0, 6], [1, 6]] * 2)
    y = np.array(["no", "yes", "no", "yes"] * 2)
    dot = CsId3Classifier(feature_costs=[1, 9]).fit(X, y).export_graphviz(feature_names=["cheap", "dear"])
    assert dot.startswith("digraph") and "cheap" in dot and "dear" not in dot
    assert '"yes' in dot and 'label="1"' in dot


NUMERIC = ["age", "trestbps", "chol", "thalch", "oldpeak"]


def heart(repo):
    """The Cleveland records as objects (text, NaN where missing), the class (num > 0)
    and the price of each column's test."""
    import csv

    folder = repo / "data" / "heart-disease"
    with open(folder / "cleveland.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    with open(folder / "costs.csv", encoding="utf-8") as f:
        costs = {r["feature"]: float(r["cost"]) for r in csv.DictReader(f)}
    names = [c for c in rows[0] if c != "num"]
    X = np.array(
        [[np.nan if r[c] in ("", "?") else (float(r[c]) if c in NUMERIC else r[c]) for c in names] for r in rows],
        dtype=object,
    )
    y = np.array([int(float(r["num"]) > 0) for r in rows])
    return X, y, names, costs


def heart_pipeline(names, costs):
    from sklearn.compose import ColumnTransformer
    from sklearn.preprocessing import OrdinalEncoder

    numeric = [names.index(c) for c in NUMERIC]
    other = [j for j in range(len(names)) if j not in numeric]
    prepare = ColumnTransformer(
        [
            ("bins", KBinsDiscretizer(n_bins=4, encode="ordinal", strategy="uniform"), numeric),
            ("codes", OrdinalEncoder(handle_unknown="use_encoded_value", unknown_value=-1), other),
        ]
    )
    # The transformer puts the binned columns first: the prices follow them.
    prices = [costs[names[j]] for j in numeric + other]
    return make_pipeline(prepare, CsId3Classifier(feature_costs=prices))


def test_heart_data_in_a_pipeline(repo):
    X, y, names, costs = heart(repo)
    pipe = heart_pipeline(names, costs)
    scores = cross_val_score(pipe, X, y, cv=5)
    assert scores.mean() > 0.6, scores
    pipe.fit(X, y)
    per_patient = pipe[-1].predict_cost(pipe[0].transform(X)).mean()
    assert per_patient < sum(costs.values()) / 10, per_patient  # far less than every test


# A fit that would run for an hour (CS-IBL on 300,000 objects of as many classes: each is
# compared with every one stored before it), and a
# helper thread that sends SIGINT once the main thread is inside the compiled learner
# (its innermost Python frame is `fit`, at the line that calls `model.learn`). The child
# first takes Python's own Ctrl-C handler: a process started in the background by a shell
# inherits SIGINT ignored, and Python then leaves it ignored.
FIT_INTERRUPTED = """
import inspect, os, signal, sys, threading
signal.signal(signal.SIGINT, signal.default_int_handler)
import numpy as np
from csrl.sklearn import CsIblClassifier
source, first = inspect.getsourcelines(CsIblClassifier.fit)
line = first + next(i for i, text in enumerate(source) if "model.learn(" in text)
main = threading.main_thread().ident
def learning():
    frame = sys._current_frames().get(main)
    return frame is not None and frame.f_code.co_name == "fit" and frame.f_lineno == line
def helper():
    while not learning():
        os.sched_yield()
    print("learning", flush=True)
    os.kill(os.getpid(), signal.SIGINT)
threading.Thread(target=helper, daemon=True).start()
n = 300_000
X = np.arange(3 * n).reshape(n, 3) % 1000
CsIblClassifier(passes=1).fit(X, np.arange(n))
print("finished", flush=True)
"""


def test_ctrl_c_stops_a_long_fit_inside_the_compiled_learner():
    # The timeout guards against a hang only: a fit deaf to Ctrl-C runs past it and fails.
    proc = subprocess.run(
        [sys.executable, "-c", FIT_INTERRUPTED], capture_output=True, text=True, timeout=300
    )
    assert "learning" in proc.stdout, (proc.stdout, proc.stderr)
    assert "KeyboardInterrupt" in proc.stderr, proc.stderr
    assert "finished" not in proc.stdout
    assert proc.returncode != 0
