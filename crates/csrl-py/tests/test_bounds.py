"""Finite but huge numbers never come back as inf or NaN: rewards and prices whose sums
could overflow are refused up front, naming the bound, and those within it give finite
results."""

import math

import numpy as np
import pytest

import csrl
from csrl import _csrl


def corridor(reward=0.0, price=1.0):
    # 0 - 1 - 2 - 3, 3 the goal; action 0 stays in state 0 with `reward`.
    n = 4
    T = [[[(1.0, max(s - 1, 0))], [(1.0, min(s + 1, n - 1))]] for s in range(n)]
    R = [[reward if s == 0 else 0.0, 1.0 if s == n - 2 else 0.0] for s in range(n)]
    terminal = [s == n - 1 for s in range(n)]
    readings = np.arange(n).reshape(n, 1)
    return csrl.World.from_arrays(T, R, terminal, readings, [price])


def test_the_bounds_are_stated():
    assert _csrl.MAX_REWARD == 1e200 and _csrl.MAX_PRICE == 1e200
    assert _csrl.MAX_TOTAL_COST == 1e300


@pytest.mark.parametrize("reward", [1e308, -1e308, 1.5e200])
def test_a_world_whose_rewards_could_overflow_is_refused(reward):
    with pytest.raises(csrl.WorldError, match="MAX_REWARD"):
        corridor(reward=reward)


@pytest.mark.parametrize("price", [1e308, 1.5e200])
def test_a_world_whose_prices_could_overflow_is_refused(price):
    with pytest.raises(csrl.WorldError, match="MAX_PRICE"):
        corridor(price=price)


def test_factor_costs_that_could_overflow_are_refused():
    with pytest.raises(csrl.WorldError, match="MAX_PRICE"):
        csrl.World("frozenlake4x4", sensing="factors", factor_costs=[1.0, 1e308])
    with pytest.raises(ValueError, match="MAX_PRICE"):
        csrl.run(world="frozenlake4x4",
                 settings={"world": {"sensing": "factors", "factor_costs": [1.0, 1e308]}})


@pytest.mark.parametrize("reward,price", [(1e200, 1.0), (-1e200, 1.0), (0.0, 1e200)])
def test_values_at_the_bound_are_finite(reward, price):
    w = corridor(reward=reward, price=price)
    assert all(math.isfinite(v) for v in w.optimal_values(0.9))
    assert math.isfinite(csrl.value_floor(w, 0.9))
    r = csrl.run(world=w, strategy="lazy", seed=1, max_trials=50)
    assert isinstance(r["policy_quality"], float) and math.isfinite(r["policy_quality"])
    assert math.isfinite(r["total_cost"])


def test_the_agent_refuses_rewards_and_prices_that_could_overflow():
    with pytest.raises(csrl.SettingsError, match="MAX_PRICE"):
        csrl.CsQlAgent([1.0, 1e308], [2, 2], num_actions=2, seed=1)
    agent = csrl.CsQlAgent([1.0, 2.0], [2, 2], num_actions=2, seed=1)
    agent.act(lambda f: 0)
    with pytest.raises(ValueError, match="MAX_REWARD"):
        agent.update(1e308, False, False, sensor=lambda f: 0)
    for _ in range(200):
        agent.update(1e200, False, False, sensor=lambda f: 0)
        agent.act(lambda f: 0)
    assert all(math.isfinite(q) for row in agent.q_table() for q in row)
    assert all(math.isfinite(v) for v in agent.values())


def test_a_classifier_whose_training_cost_could_overflow_is_refused():
    sk = pytest.importorskip("csrl.sklearn")
    X = np.array([[0, 1], [1, 0], [1, 1], [0, 0]] * 5)
    y = np.array([0, 1, 1, 0] * 5)
    with pytest.raises(csrl.DataError, match="MAX_TOTAL_COST"):
        sk.CsId3Classifier(feature_costs=[1e308, 1e308]).fit(X, y)
    # Each price within the bound, but not their sum over every object and pass.
    with pytest.raises(csrl.DataError, match="training_cost_"):
        sk.CsId3Classifier(feature_costs=[1e298, 1e298], passes=10).fit(X, y)
    clf = sk.CsId3Classifier(feature_costs=[1e297, 1e297], passes=10).fit(X, y)
    assert math.isfinite(clf.training_cost_)
    # The compiled classifier checks the same bound, call after call.
    model = _csrl.Classifier("cs-id3", [1e299, 1e299])
    model.learn([[0, 1]] * 2, [0, 0])
    with pytest.raises(csrl.DataError, match="MAX_TOTAL_COST"):
        model.learn([[0, 1]] * 4, [0, 0, 0, 0])
