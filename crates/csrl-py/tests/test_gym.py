"""csrl.gym.SensingEnv: Gymnasium's checker, pricing, seeding, terminated and truncated."""

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import csrl
import csrl.gym


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(world="frozenlake4x4", sensing="factors"),
        dict(world="tan8x8", render_mode="ansi"),
        dict(world="taxi", render_mode="rgb_array", cost_scale=0.5),
        dict(world="frozenlake8x8", sensing="local", render_mode="rgb_array"),
    ],
)
def test_the_gymnasium_checker_passes(kwargs):
    env = gym.make("csrl/Sensing-v0", **kwargs)
    check_env(env.unwrapped)
    env.close()


def test_sensing_costs_its_price_scaled():
    env = csrl.gym.SensingEnv(csrl.World("frozenlake4x4", sensing="factors", factor_costs=[1.0, 3.0]),
                              cost_scale=0.5)
    obs, info = env.reset(seed=4)
    assert obs["mask"].tolist() == [0, 0] and info["sensing_cost"] == 0.0
    obs, r, term, trunc, info = env.step(1)
    assert (r, info["sensing_cost"]) == (-1.5, 3.0)
    assert obs["mask"].tolist() == [0, 1] and obs["values"].tolist() == [0, 0]  # start (0, 0)
    assert env.observation_space.contains(obs)
    # A move: the reading is forgotten, the reward is the world's.
    obs, r, term, trunc, info = env.step(2 + 2)  # right
    assert obs["mask"].tolist() == [0, 0] and r == 0.0 and info["sensing_cost"] == 0.0
    obs, *_ = env.step(1)
    assert obs["values"].tolist() == [0, 1]


def test_terminated_and_truncated_are_kept_apart():
    env = csrl.gym.SensingEnv("frozenlake4x4", sensing="factors", max_moves=3)
    env.reset(seed=0)
    nf = env.num_features
    results = [env.step(nf + 0) for _ in range(3)]  # left at the start: stays
    assert [r[2] for r in results] == [False] * 3
    assert [r[3] for r in results] == [False, False, True]
    env.reset(seed=0)
    # Down, down, right: (2,0) then (2,1)... the hole at (1,... ) ends it: (1,1) is a hole.
    env.step(nf + 2)  # right to (0,1)
    _, r, term, trunc, _ = env.step(nf + 1)  # down into the hole (1,1)
    assert term and not trunc and r == 0.0


def test_sensing_alone_is_truncated_by_max_steps():
    env = csrl.gym.SensingEnv("frozenlake4x4", sensing="factors", max_steps=5)
    env.reset(seed=0)
    truncs = [env.step(0)[3] for _ in range(5)]
    assert truncs == [False] * 4 + [True]


def test_seeding_through_reset_only():
    env = csrl.gym.SensingEnv("frozenlake4x4", sensing="factors")
    env_slip = csrl.gym.SensingEnv(csrl.World("frozenlake4x4", sensing="factors", slip=2 / 3))

    def walk(e, seed):
        e.reset(seed=seed)
        seen = []
        for _ in range(30):
            obs, r, term, trunc, _ = e.step(e.num_features + 1)
            e.step(0)
            seen.append((int(e.step(1)[0]["values"][1]), term))
            if term or trunc:
                e.reset()
        return seen

    assert walk(env_slip, 1) == walk(env_slip, 1)
    assert walk(env_slip, 1) != walk(env_slip, 2)
    assert walk(env, 1) == walk(env, 2)  # a deterministic lake draws nothing


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="render_mode"):
        csrl.gym.SensingEnv(render_mode="human")
    with pytest.raises(ValueError, match="cost_scale"):
        csrl.gym.SensingEnv(cost_scale=-1.0)
    with pytest.raises(csrl.WorldError):
        csrl.gym.SensingEnv("no-such-world")
    env = csrl.gym.SensingEnv()
    env.reset(seed=0)
    for bad in (env.action_space.n, -1):
        with pytest.raises(ValueError, match="action"):
            env.step(bad)


def test_renders():
    env = gym.make("csrl/Sensing-v0", world="frozenlake4x4", sensing="factors", render_mode="ansi")
    env.reset(seed=0)
    env.step(0)
    text = env.render()
    assert "state (0,0)" in text and "row=0" in text
    env = gym.make("csrl/Sensing-v0", world="frozenlake4x4", sensing="factors", render_mode="rgb_array")
    env.reset(seed=0)
    before = env.render()
    env.step(1)
    after = env.render()
    assert before.shape == (16, 32, 3) and before.dtype == np.uint8
    assert not np.array_equal(before, after)


def test_counts_and_actions_are_integers_never_truncated():
    for bad in (0, -1, 1.5, True, "3"):
        with pytest.raises(ValueError, match="max_steps"):
            csrl.gym.SensingEnv("frozenlake4x4", sensing="factors", max_steps=bad)
    for bad in (0, -3, 1.7):
        with pytest.raises(ValueError, match="max_moves"):
            csrl.gym.SensingEnv("frozenlake4x4", sensing="factors", max_moves=bad)
    env = csrl.gym.SensingEnv("frozenlake4x4", sensing="factors", max_steps=np.int64(4))
    assert env.max_steps == 4
    env.reset(seed=0)
    for bad in (1.7, 1.0, True, "1", None):
        with pytest.raises(ValueError, match="action"):
            env.step(bad)
    # A refused action is no step.
    _obs, _r, _term, trunc, _info = env.step(np.int64(1))
    assert env._steps == 1 and not trunc
