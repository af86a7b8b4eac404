"""csrl.cegb: LightGBM's CEGB as a test-cost learner, and the benchmark's worker.

The features an object uses are checked against an independent walk of the dumped trees
(LightGBM's own decision rules, numeric and categorical, missing values included), itself
checked to reach the leaves whose values make LightGBM's raw scores. The worker is run by
path, as `cargo xtask testcost` runs it."""

import json
import math
import pathlib
import subprocess
import sys

import lightgbm as lgb
import numpy as np
import pytest

from csrl import cegb

REPO = pathlib.Path(__file__).resolve().parents[3]
SCRIPT = REPO / "crates" / "csrl-py" / "python" / "csrl" / "cegb.py"


def worker(lines):
    """Run the worker by path on request lines; its response lines (it must write
    nothing else, and end cleanly at the end of its input)."""
    out = subprocess.run(
        [sys.executable, str(SCRIPT), "--worker"],
        input="".join(line + "\n" for line in lines),
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.returncode == 0, out.stderr
    assert out.stderr == ""
    return out.stdout.splitlines()


def data(n=240, seed=0, classes=3):
    """Numeric features with missing values, a nominal one (codes 0 to 5, some missing)
    and an irrelevant one; the class follows features 0, 1 and 2."""
    rng = np.random.default_rng(seed)
    x0 = rng.normal(size=n)
    x1 = rng.integers(0, 6, n).astype(float)
    x2 = rng.normal(size=n)
    x3 = rng.normal(size=n)
    score = x0 + (x1 % 3) + 0.5 * x2
    y = np.digitize(score, np.quantile(score, np.linspace(0, 1, classes + 1)[1:-1]))
    X = np.column_stack([x0, x1, x2, x3])
    X[rng.random(n) < 0.15, 0] = np.nan
    X[rng.random(n) < 0.10, 1] = np.nan
    return X, y.astype(int)


def request(X, y, test, classes, **extra):
    cells = lambda A: [[None if math.isnan(v) else float(v) for v in row] for row in A]  # noqa: E731
    r = {
        "train": cells(X),
        "classes": [int(c) for c in y],
        "class_count": classes,
        "nominal": [1],
        "prices": [5.0, 2.0, 20.0, 1.0],
        "test": cells(test),
        "mc": [10.0, 1000.0],
        "seed": 12345678901234567890,
    }
    r.update(extra)
    return r


# --- The features an object uses, against an independent walk ---------------------------


def walk(node, row):
    """The features on `row`'s path through one dumped tree, root first, and its leaf's
    value, by LightGBM's decision rules."""
    path = []
    while "split_feature" in node:
        f = node["split_feature"]
        path.append(f)
        v = row[f]
        if node["decision_type"] == "==":
            # Categorical: the listed categories go left; missing or negative go right.
            left = {int(c) for c in str(node["threshold"]).split("||")}
            go_left = not math.isnan(v) and v >= 0 and int(v) in left
        else:
            missing = node["missing_type"]
            if math.isnan(v) and missing != "NaN":
                v = 0.0
            if (missing == "Zero" and abs(v) <= 1e-35) or (missing == "NaN" and math.isnan(v)):
                go_left = node["default_left"]
            else:
                go_left = v <= node["threshold"]
        node = node["left_child" if go_left else "right_child"]
    return path, node["leaf_value"]


def walked(booster, X):
    """Each row's features in the order first met, and its raw score per class, from
    the walk alone."""
    trees = booster.dump_model()["tree_info"]
    per = booster.num_model_per_iteration()
    used, raw = [], np.zeros((X.shape[0], per))
    for i, row in enumerate(X):
        order = []
        for t, tree in enumerate(trees):
            path, value = walk(tree["tree_structure"], row)
            raw[i, t % per] += value
            for f in path:
                if f not in order:
                    order.append(f)
        used.append(order)
    return used, raw


@pytest.mark.parametrize("classes", [2, 3])
def test_features_used_are_the_walks_in_the_order_first_met(classes):
    X, y = data(classes=classes)
    params = dict(
        objective="binary" if classes == 2 else "multiclass",
        num_class=1 if classes == 2 else classes,
        num_leaves=8,
        min_child_samples=5,
        min_data_per_group=5,
        cegb_tradeoff=0.01,
        cegb_penalty_feature_lazy=[5.0, 2.0, 20.0, 1.0],
        deterministic=True,
        num_threads=1,
        verbosity=-1,
    )
    booster = lgb.train(params, lgb.Dataset(X, y, categorical_feature=[1]), num_boost_round=20)
    used, raw = walked(booster, X)
    # The walk reaches LightGBM's leaves: their values make its raw scores.
    theirs = booster.predict(X, raw_score=True).reshape(X.shape[0], -1)
    np.testing.assert_allclose(raw, theirs, rtol=1e-9, atol=1e-9)
    # Several features, categorical splits and missing values took part.
    dumped = json.dumps(booster.dump_model())
    assert '"decision_type": "=="' in dumped
    assert len({f for u in used for f in u}) >= 3
    assert cegb.features_used(booster, X) == used
    prices = [5.0, 2.0, 20.0, 1.0]
    expected = [sum(prices[f] for f in u) for u in used]
    assert cegb.cost_of_tests(booster, X, prices).tolist() == expected
    # The scikit-learn model's booster is read the same way.
    clf = lgb.LGBMClassifier(n_estimators=5, num_leaves=4, verbosity=-1, deterministic=True, n_jobs=1)
    clf.fit(X, y)
    assert cegb.features_used(clf, X) == walked(clf.booster_, X)[0]


def test_a_booster_that_can_use_one_feature_uses_it_alone():
    rng = np.random.default_rng(3)
    X = np.column_stack([np.full(100, 2.0), rng.normal(size=100), np.full(100, -1.0)])
    y = (X[:, 1] > 0).astype(int)
    booster = lgb.train(dict(objective="binary", verbosity=-1, min_child_samples=5), lgb.Dataset(X, y), 10)
    assert cegb.features_used(booster, X) == [[1]] * 100
    assert cegb.cost_of_tests(booster, X, [9.0, 4.0, 7.0]).tolist() == [4.0] * 100
    with pytest.raises(TypeError, match="LightGBM"):
        cegb.features_used(object(), X)
    with pytest.raises(ValueError, match="one per feature"):
        cegb.cost_of_tests(booster, X, [1.0])


# --- The fit: its tradeoff chosen by cross-validation -----------------------------------


def test_the_tradeoff_follows_the_misclassification_cost():
    X, y = data(n=200, seed=1, classes=2)
    prices = [10.0, 10.0, 10.0, 10.0]
    cheap_errors, dear_errors = cegb.fit(X, y, prices, [1.0, 5000.0], nominal=[1], seed=4)
    # An error that costs less than a test: buy nothing, answer the larger class.
    assert cheap_errors.model.cost_of_tests(X).max() == 0.0
    assert cheap_errors.model.features_used(X) == [[]] * len(y)
    assert cheap_errors.model.booster is None or cheap_errors.model.nodes == 1
    # Dear errors: buy the tests that tell the class, with a smaller tradeoff.
    assert dear_errors.tradeoff < cheap_errors.tradeoff
    assert dear_errors.model.cost_of_tests(X).mean() > 10.0
    assert np.mean(dear_errors.model.predict(X) == y) > 0.8
    # The choice is the least cross-validated cost of the grid.
    for c in (cheap_errors, dear_errors):
        assert len(c.cv_costs) == len(cegb.TRADEOFFS)
        assert c.cv_costs[cegb.TRADEOFFS.index(c.tradeoff)] == pytest.approx(min(c.cv_costs), rel=1e-9)


def test_a_huge_price_buys_nothing():
    X, y = data(n=150, seed=2, classes=2)
    choice = cegb.fit(X, y, [1e6] * 4, [1000.0], nominal=[1], seed=5)[0]
    assert choice.model.features_used(X) == [[]] * len(y)
    # It answers the larger class of the training data.
    assert set(choice.model.predict(X).tolist()) == {int(np.bincount(y).argmax())}


def test_settings_are_checked():
    with pytest.raises(ValueError, match="unknown key 'leaves'"):
        cegb.Settings.from_json({"leaves": 4})
    with pytest.raises(ValueError, match="inner_folds"):
        cegb.Settings.from_json({"inner_folds": 1})
    with pytest.raises(ValueError, match="tradeoffs"):
        cegb.Settings.from_json({"tradeoffs": [-1.0]})
    assert cegb.Settings.from_json({"trees": 3}).trees == 3


# --- The worker --------------------------------------------------------------------------


def test_the_worker_gives_the_same_bytes_for_the_same_request():
    X, y = data(n=120, seed=4)
    line = json.dumps(request(X[:90], y[:90], X[90:], 3))
    first = worker([line, line])
    assert len(first) == 2 and first[0] == first[1]
    # Another process, the same bytes.
    assert worker([line]) == first[:1]
    response = json.loads(first[0])
    assert "error" not in response and "learn_seconds" not in response
    # Another seed deals other inner folds (the answers may agree; the costs seen do not).
    other = json.loads(worker([json.dumps(request(X[:90], y[:90], X[90:], 3, seed=7))])[0])
    assert [a["cv_costs"] for a in other["by_mc"]] != [a["cv_costs"] for a in response["by_mc"]]


def test_the_worker_answers_every_class_for_several_classes_and_a_missing_one():
    X, y = data(n=200, seed=5, classes=3)
    # Classes 0, 1 and 2 of 5: class 3 never occurs, class 4 once (missing from most
    # inner training folds).
    y = y.copy()
    y[7] = 4
    r = request(X[:150], y[:150], X[150:], 5, timing=True)
    response = json.loads(worker([json.dumps(r)])[0])
    assert "error" not in response, response
    assert response["learn_seconds"] > 0 and response["classify_seconds"] > 0
    assert [a["mc"] for a in response["by_mc"]] == [10.0, 1000.0]
    for a in response["by_mc"]:
        assert a["tradeoff"] in cegb.TRADEOFFS
        assert len(a["predicted"]) == len(a["probabilities"]) == len(a["features"]) == 50
        for c, p, used in zip(a["predicted"], a["probabilities"], a["features"]):
            assert len(p) == 5 and sum(p) == pytest.approx(1.0)
            assert p[3] == 0.0, "a class with no training object has no probability"
            assert c == int(np.argmax(p))
            assert len(used) == len(set(used)) and all(0 <= f < 4 for f in used)
        assert a["nodes"] >= 1 and a["leaves"] >= 1
    # At mc 1000 the features that tell the class are bought, and answer well.
    dear = response["by_mc"][1]
    assert np.mean(np.array(dear["predicted"]) == y[150:]) > 0.6
    # One class alone: no trees; it answers that class and buys nothing.
    alone = json.loads(worker([json.dumps(request(X[:20], [2] * 20, X[20:23], 3))])[0])
    for a in alone["by_mc"]:
        assert a["predicted"] == [2, 2, 2]
        assert a["probabilities"] == [[0.0, 0.0, 1.0]] * 3
        assert a["features"] == [[], [], []]


def test_the_worker_answers_a_bad_request_with_an_error_line_and_goes_on():
    X, y = data(n=60, seed=6, classes=2)
    good = request(X[:40], y[:40], X[40:], 2, settings={"trees": 2, "tradeoffs": [0.0, 1.0]})
    lines = worker(
        [
            "not json",
            json.dumps({k: v for k, v in good.items() if k != "prices"}),
            json.dumps(dict(good, prices=[1.0])),
            json.dumps(dict(good, classes=[5] * 40)),
            json.dumps(dict(good, test=[[1.0, 2.0]])),
            json.dumps(dict(good, settings={"leaves": 3})),
            json.dumps({"op": "describe"}),
            json.dumps(good),
        ]
    )
    assert len(lines) == 8
    errors = [json.loads(line).get("error", "") for line in lines[:6]]
    for error, said in zip(errors, ["JSON", "'prices'", "one per feature", "classes", "features per row", "unknown key"]):
        assert said in error, error
    described = json.loads(lines[6])
    assert described["lightgbm"] == lgb.__version__
    assert described["settings"]["trees"] == 50
    assert described["description"] == cegb.describe()
    assert len(json.loads(lines[7])["by_mc"]) == 2


def test_the_worker_runs_without_the_compiled_package():
    """Run by path, the module imports numpy and lightgbm only."""
    out = subprocess.run(
        [
            sys.executable,
            "-c",
            "import runpy, sys; runpy.run_path(sys.argv[1]);"
            " print(sorted(m for m in sys.modules if m == 'csrl' or m.startswith('csrl.')))",
            str(SCRIPT),
        ],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=REPO,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


# --- The sweep: CEGB's curve over its tradeoff ------------------------------------------


def sweep_request(X, y, test, classes, tradeoffs, **extra):
    r = request(X, y, test, classes, op="sweep", tradeoffs=list(tradeoffs), **extra)
    del r["mc"]
    return r


def test_the_sweep_gives_the_same_bytes_for_the_same_request():
    X, y = data(n=120, seed=7)
    line = json.dumps(sweep_request(X[:90], y[:90], X[90:], 3, [0.0, 0.01, 1.0]))
    first = worker([line, line])
    assert len(first) == 2 and first[0] == first[1]
    assert worker([line]) == first[:1]
    response = json.loads(first[0])
    assert "error" not in response and "learn_seconds" not in response
    assert [a["tradeoff"] for a in response["by_tradeoff"]] == [0.0, 0.01, 1.0]
    for a in response["by_tradeoff"]:
        assert len(a["predicted"]) == len(a["probabilities"]) == len(a["features"]) == 30
        assert a["nodes"] >= 1 and a["leaves"] >= 1
    # Timed, it says how long it took, and answers the same otherwise.
    timed = json.loads(worker([json.dumps(sweep_request(X[:90], y[:90], X[90:], 3, [0.0, 0.01, 1.0], timing=True))])[0])
    assert timed.pop("learn_seconds") > 0 and timed.pop("classify_seconds") > 0
    assert timed == response


@pytest.mark.parametrize("classes", [2, 3])
def test_a_sweeps_point_is_the_fit_at_that_tradeoff(classes):
    """At each tradeoff, the sweep's answers are those of the model `fit` trains on all
    the objects once it has that tradeoff: held to a grid of that one value, and where its
    cross-validation chose it from the whole grid."""
    X, y = data(n=200, seed=8, classes=classes)
    train, test = slice(0, 150), slice(150, 200)
    prices = [5.0, 2.0, 20.0, 1.0]
    grid = list(cegb.TRADEOFFS)
    r = sweep_request(X[train], y[train], X[test], classes, grid)
    response = json.loads(worker([json.dumps(r)])[0])
    assert "error" not in response, response
    points = {a["tradeoff"]: a for a in response["by_tradeoff"]}
    assert list(points) == grid

    def same(point, model):
        assert point["features"] == model.features_used(X[test])
        assert point["probabilities"] == model.predict_proba(X[test]).tolist()
        assert point["predicted"] == model.predict(X[test]).tolist()
        assert (point["nodes"], point["leaves"]) == (model.nodes, model.leaves)

    bought = []
    for t in grid[::3] + [grid[-1]]:
        held = cegb.fit(
            X[train], y[train], prices, [100.0], classes=classes, nominal=[1], seed=r["seed"],
            settings=cegb.Settings(tradeoffs=(t,)),
        )[0]
        assert held.tradeoff == t
        same(points[t], held.model)
        bought.append(sum(len(f) for f in points[t]["features"]))
    # The penalty buys less as it grows, down to nothing.
    assert bought[0] > 0 and bought[-1] == 0
    assert all(a >= b for a, b in zip(bought, bought[1:])), bought
    # The benchmark's fit chooses among the same grid: its model is the sweep's point.
    for choice in cegb.fit(X[train], y[train], prices, [10.0, 1000.0], classes=classes, nominal=[1], seed=r["seed"]):
        same(points[choice.tradeoff], choice.model)


def test_a_huge_tradeoff_buys_nothing():
    X, y = data(n=150, seed=9, classes=2)
    response = json.loads(worker([json.dumps(sweep_request(X[:100], y[:100], X[100:], 2, [0.0, 1e9]))])[0])
    free, huge = response["by_tradeoff"]
    assert any(free["features"]) and len({c for c in free["predicted"]}) == 2
    assert huge["features"] == [[]] * 50
    # No tree: every object gets the training data's class shares, the larger class.
    majority = int(np.bincount(y[:100]).argmax())
    assert huge["predicted"] == [majority] * 50
    assert len({tuple(p) for p in huge["probabilities"]}) == 1
    # In Python: the same models.
    models = cegb.sweep(X[:100], y[:100], [5.0, 2.0, 20.0, 1.0], [0.0, 1e9], nominal=[1], seed=12345678901234567890)
    assert models[1].features_used(X[100:]) == huge["features"]
    assert models[0].features_used(X[100:]) == free["features"]


def test_a_bad_sweep_request_is_answered_with_an_error_line():
    X, y = data(n=60, seed=10, classes=2)
    good = sweep_request(X[:40], y[:40], X[40:], 2, [0.0, 1.0], settings={"trees": 2})
    lines = worker(
        [
            json.dumps({k: v for k, v in good.items() if k != "tradeoffs"}),
            json.dumps(dict(good, tradeoffs=0.5)),
            json.dumps(dict(good, tradeoffs=[0.1, -1.0])),
            json.dumps(dict(good, tradeoffs=[])),
            json.dumps(dict(good, op="sweeps")),
            json.dumps(good),
        ]
    )
    assert len(lines) == 6
    errors = [json.loads(line).get("error", "") for line in lines[:5]]
    for error, said in zip(errors, ["'tradeoffs'", "tradeoffs: expected a list", "not negative", "at least one", "'sweep'"]):
        assert said in error, error
    assert len(json.loads(lines[5])["by_tradeoff"]) == 2
