"""csrl.World: names, files, arrays and Gymnasium's published models."""

import json
import pickle

import gymnasium as gym
import numpy as np
import pytest

import csrl


def test_names_list_the_built_ins():
    assert "tan8x8" in csrl.map_names()
    assert csrl.world_names() == ["frozenlake4x4", "frozenlake8x8", "taxi", "cliffwalking"]


def test_world_by_name_with_options():
    lake = csrl.World("frozenlake4x4", sensing="factors", factor_costs=[1.0, 2.0])
    assert (lake.name, lake.num_states, lake.num_actions) == ("frozenlake4x4", 16, 4)
    assert lake.feature_names == ["row", "col"] and lake.prices == [1.0, 2.0]
    local = csrl.World("frozenlake4x4")
    assert local.num_features != lake.num_features
    slippery = csrl.World("frozenlake4x4", slip=2 / 3)
    assert len(slippery.outcomes(0, 1)) > len(local.outcomes(0, 1))
    grid = csrl.World("tan3x3")
    assert grid.num_states == 9 and len(grid.states()) == 8


def test_bad_names_and_options_are_world_or_settings_errors():
    with pytest.raises(csrl.WorldError, match="no-such"):
        csrl.World("no-such")
    with pytest.raises(csrl.SettingsError) as info:
        csrl.World("frozenlake4x4", slip=1.5)
    assert isinstance(info.value, ValueError)
    with pytest.raises(csrl.SettingsError, match="sensing"):
        csrl.World("tan3x3", sensing="factors")


def test_files_round_trip(tmp_path):
    taxi = csrl.World("taxi")
    path = tmp_path / "taxi.json"
    taxi.save(path)
    back = csrl.World.from_file(path)
    assert back.to_json() == taxi.to_json()
    assert csrl.World(str(path)).to_json() == taxi.to_json()
    assert pickle.loads(pickle.dumps(taxi)).to_json() == taxi.to_json()
    spec = json.loads(taxi.to_json())
    spec["transitions"][0][2][0][0] = 0.5
    with pytest.raises(csrl.WorldError, match="sum to 0.5"):
        csrl.World.from_spec(spec)


def corridor():
    # 0 - 1 - 2 - 3, 3 the goal; action 0 left, 1 right; one feature: the position.
    n = 4
    T = [[[(1.0, max(s - 1, 0))], [(1.0, min(s + 1, n - 1))]] for s in range(n)]
    R = [[0.0, 1.0 if s == n - 2 else 0.0] for s in range(n)]
    terminal = [s == n - 1 for s in range(n)]
    readings = np.arange(n).reshape(n, 1)
    return T, R, terminal, readings


def test_from_arrays_builds_the_model_given():
    T, R, terminal, readings = corridor()
    w = csrl.World.from_arrays(T, R, terminal, readings, [2.0], name="corridor",
                               feature_names=["pos"], action_names=["left", "right"])
    assert w.name == "corridor" and w.states() == [0, 1, 2]
    assert w.outcomes(2, 1) == [(1.0, 3, 1.0, True)]
    assert w.outcomes(1, 0) == [(1.0, 0, 0.0, False)]
    assert w.readings() == [[0], [1], [2], [3]] and w.prices == [2.0]
    values = w.optimal_values(0.9)
    assert values[2] == pytest.approx(1.0) and values[0] == pytest.approx(0.81)
    r = csrl.run(world=w, strategy="lazy", seed=1)
    assert r["converged"] and r["map"] == "corridor"


def test_from_arrays_takes_probability_rows_and_names_errors():
    T, R, terminal, readings = corridor()
    rows = np.zeros((4, 2, 4))
    for s in range(4):
        for a in range(2):
            for p, t in T[s][a]:
                rows[s, a, t] += p
    w = csrl.World.from_arrays(rows, R, terminal, readings, [1.0])
    assert w.outcomes(2, 1) == [(1.0, 3, 1.0, True)]
    rows[1, 0, 0] = 0.7
    with pytest.raises(csrl.WorldError, match="state 1, action 0"):
        csrl.World.from_arrays(rows, R, terminal, readings, [1.0])
    with pytest.raises(csrl.WorldError, match="price"):
        csrl.World.from_arrays(T, R, terminal, readings, [-1.0])
    with pytest.raises(csrl.WorldError, match="readings"):
        csrl.World.from_arrays(T, R, terminal, readings[:3], [1.0])


def lake_features(s):
    return divmod(s, 4)


def test_from_gymnasium_frozenlake_is_the_built_in_lake():
    env = gym.make("FrozenLake-v1", is_slippery=True)
    w = csrl.World.from_gymnasium(env, lake_features, [1.0, 1.0], feature_names=["row", "col"])
    built_in = csrl.World("frozenlake4x4", sensing="factors", slip=2 / 3)
    assert w.name == "FrozenLake-v1"
    assert w.terminal() == built_in.terminal() and w.states() == built_in.states()
    assert w.readings() == built_in.readings() and w.start() == built_in.start()
    for s in w.states():
        for a in range(4):
            ours = sorted(w.outcomes(s, a))
            theirs = env.unwrapped.P[s][a]
            # Gymnasium lists the three slips; the same next state may come twice.
            merged = {}
            for p, t, r, d in theirs:
                merged[t] = merged.get(t, 0.0) + p
            assert {t: pytest.approx(p) for t, p in merged.items()} == {
                t: p for p, t, _r, _d in _merge(ours)
            }


def _merge(outs):
    merged = {}
    for p, t, r, d in outs:
        merged[t] = (merged.get(t, (0.0,))[0] + p, t, r, d)
    return list(merged.values())


def test_cs_ql_on_the_gymnasium_lake_learns_as_on_the_built_in_one():
    env = gym.make("FrozenLake-v1", is_slippery=False)
    w = csrl.World.from_gymnasium(env, lake_features, [1.0, 1.0], feature_names=["row", "col"])
    ours = csrl.run(world=w, strategy="lazy", seed=3)
    built_in = csrl.run(world=csrl.World("frozenlake4x4", sensing="factors"), strategy="lazy", seed=3)
    for key in ("converged", "trials", "moves", "total_cost", "table1"):
        assert ours[key] == built_in[key], key
    assert ours["converged"] and ours["policy_quality"] == 1


def test_from_gymnasium_taxi_and_cliffwalking():
    taxi = gym.make("Taxi-v4")
    w = csrl.World.from_gymnasium(taxi, lambda s: list(taxi.unwrapped.decode(s)), [1, 1, 2, 2])
    assert w.num_states == 500 and w.num_actions == 6 and len(w.start()) == 300
    assert w.prices == [1.0, 1.0, 2.0, 2.0]
    cliff = gym.make("CliffWalking-v1")
    c = csrl.World.from_gymnasium(cliff, lambda s: divmod(s, 12), [1, 1])
    assert c.start() == [(1.0, 36)] and c.terminal()[47]


def test_from_gymnasium_refuses_a_world_without_a_model():
    env = gym.make("CartPole-v1")
    with pytest.raises(csrl.WorldError, match="publishes no model"):
        csrl.World.from_gymnasium(env, lambda s: [0], [1.0])
    lake = gym.make("FrozenLake-v1")
    with pytest.raises(csrl.WorldError, match="readings"):
        csrl.World.from_gymnasium(lake, lambda s: [0] * (1 + s % 2), [1.0])


def test_a_world_object_refuses_world_settings():
    w = csrl.World("frozenlake4x4")
    with pytest.raises(csrl.SettingsError, match=r"the world frozenlake4x4 given to the run and \[world\] slip"):
        csrl.run(world=w, settings={"world": {"slip": 0.1}})
    # Given at its default, a key is given all the same: the world reads none of them.
    for key, value in [("slip", 0.0), ("slide", 0.0), ("sensing", "local")]:
        with pytest.raises(csrl.SettingsError, match=rf"given to the run and \[world\] {key}"):
            csrl.run(world=w, settings={"world": {key: value}})


def test_a_world_refuses_options_it_does_not_read_even_at_their_defaults():
    with pytest.raises(csrl.WorldError, match="reads no slip"):
        csrl.World("taxi", slip=0.0)
    with pytest.raises(csrl.SettingsError, match=r"the grid map tan3x3 and \[world\] slide = 0"):
        csrl.World("tan3x3", slide=0.0)
    assert csrl.World("frozenlake4x4", slip=0.0).outcomes(0, 1) == csrl.World("frozenlake4x4").outcomes(0, 1)


@pytest.mark.parametrize("gamma", [1.0, 2.0, -0.5, float("nan"), float("inf")])
def test_value_floor_refuses_a_discount_outside_zero_to_one(gamma):
    with pytest.raises(csrl.SettingsError, match="discount of value_floor"):
        csrl.value_floor(csrl.World("taxi"), gamma)
    assert csrl.value_floor(csrl.World("taxi"), 0.0) == -1.0


class _Huge:
    """A sequence that says it is long and holds nothing: reading it would fail."""

    def __init__(self, n):
        self.n = n

    def __len__(self):
        return self.n

    def __iter__(self):
        raise AssertionError("a size beyond the limit was read instead of refused")

    def __getitem__(self, i):
        raise AssertionError("a size beyond the limit was read instead of refused")


def test_sizes_beyond_the_limits_are_refused_before_anything_is_built():
    T, R, terminal, readings = corridor()
    with pytest.raises(csrl.WorldError, match="states: 10000000, more than the limit of 65536"):
        csrl.World.from_arrays(_Huge(10**7), R, _Huge(10**7), readings, [1.0])
    with pytest.raises(csrl.WorldError, match="features: 5000, more than the limit of 4096"):
        csrl.World.from_arrays(T, R, terminal, readings, _Huge(5000))

    class Space:
        def __init__(self, n):
            self.n = n

    class Env:
        def __init__(self, states, actions):
            self.unwrapped = self
            self.P = {}
            self.observation_space = Space(states)
            self.action_space = Space(actions)

    with pytest.raises(csrl.WorldError, match="states: 1000000000"):
        csrl.World.from_gymnasium(Env(10**9, 4), lambda s: [s], [1.0])
    with pytest.raises(csrl.WorldError, match="actions: 100, more than the limit of 64"):
        csrl.World.from_gymnasium(Env(4, 100), lambda s: [s], [1.0])


def test_from_arrays_refuses_what_it_would_coerce():
    T, R, terminal, readings = corridor()

    def refused(match, T=T, R=R, readings=readings, **kw):
        with pytest.raises(csrl.WorldError, match=match):
            csrl.World.from_arrays(T, R, terminal, readings, kw.pop("costs", [1.0]), **kw)

    rows = np.zeros((4, 2, 4))
    for s in range(4):
        for a in range(2):
            for p, t in T[s][a]:
                rows[s, a, t] += p
    for bad in (np.nan, -0.5, np.inf):
        r = rows.copy()
        r[1, 0, 2] = bad
        refused(r"transitions\[1\]\[0\]\[2\]: probability", T=r)
    pairs = [[list(o) for o in row] for row in T]
    pairs[1][1] = [(float("nan"), 2)]
    refused(r"transitions\[1\]\[1\], outcome 0: probability nan", T=pairs)
    pairs[1][1] = [(1.0, 1.7)]
    refused(r"state 1, action 1, outcome 0: next state 1.7 is not an integer", T=pairs)
    pairs[1][1] = [(1.0, 9)]
    refused(r"next state 9 is not in 0 to 3", T=pairs)
    bad = readings.astype(float)
    bad[2, 0] = 1.7
    refused(r"readings\[0\]\[0\]: reading 0.0 is not an integer", readings=bad)
    refused(r"readings\[2\]\[0\]: reading 4294967295 is not in 0 to 4294967294",
            readings=[[0], [1], [2**32 - 1], [3]])
    refused(r"readings\[1\]\[0\]: reading -1", readings=[[0], [-1], [2], [3]])
    refused(r"feature_costs\[0\]: price nan is not finite", costs=[float("nan")])
    refused(r"rewards\[2\]\[1\], outcome 0: reward inf", R=[[0.0, 0.0], [0.0, 0.0], [0.0, float("inf")], [0.0, 0.0]])
    refused(r"start: state 1.5 is not an integer", start=1.5)
    refused(r"start\[0\]: probability -1.0", start=[(-1.0, 0), (2.0, 1)])
    # Names given twice.
    refused('action name "go" is also', action_names=["go", "go"])
    refused('feature name "x" is also', T=T, readings=[[0, 0], [1, 1], [2, 2], [3, 3]],
            costs=[1.0, 1.0], feature_names=["x", "x"])
    refused('state label "a" is also', state_labels=["a", "b", "a", "c"])
    # A large reading is a reading: the world runs, and says how many readings it has.
    w = csrl.World.from_arrays(T, R, terminal, [[0], [1], [2], [2**32 - 2]], [1.0])
    assert w.arities == [2**32 - 1]
    assert csrl.run(world=w, strategy="lazy", seed=1)["converged"]


def test_from_gymnasium_refuses_what_it_would_coerce():
    env = gym.make("FrozenLake-v1", is_slippery=False)
    u = env.unwrapped
    saved = u.P[0][0]
    try:
        u.P[0][0] = [(float("nan"), 0, 0.0, False)]
        with pytest.raises(csrl.WorldError, match=r"P\[0\]\[0\]\[0\]: probability nan"):
            csrl.World.from_gymnasium(env, lake_features, [1.0, 1.0])
        u.P[0][0] = [(1.0, 0.5, 0.0, False)]
        with pytest.raises(csrl.WorldError, match=r"P\[0\]\[0\]\[0\]: next state 0.5 is not an integer"):
            csrl.World.from_gymnasium(env, lake_features, [1.0, 1.0])
    finally:
        u.P[0][0] = saved
    with pytest.raises(csrl.WorldError, match=r"features\(0\)\[1\]: reading 0.5"):
        csrl.World.from_gymnasium(env, lambda s: (s // 4, s % 4 + 0.5), [1.0, 1.0])
    start = u.initial_state_distrib.copy()
    try:
        u.initial_state_distrib[1] = -0.5
        with pytest.raises(csrl.WorldError, match=r"initial_state_distrib\[1\]: probability -0.5"):
            csrl.World.from_gymnasium(env, lake_features, [1.0, 1.0])
    finally:
        u.initial_state_distrib[:] = start
    assert csrl.World.from_gymnasium(env, lake_features, [1.0, 1.0]).num_states == 16
