"""How fast csrl is from Python, in one process (docs/python.md has the figures).

    python crates/csrl-py/bench/speed.py [--cli target/release/csrl] [--steps N] [--repeats R]

1. A step of csrl.gym.SensingEnv against a step of Gymnasium's own FrozenLake-v1, both
   unwrapped, on the same 4x4 lake (its factors sensed), with the same seeded random
   actions; the best of R rounds of N steps each.
2. csrl.run against `csrl run --json` for the same run: the command's wall time less the
   wall time of `csrl --version` (the process start), against csrl.run_json's wall time;
   the best of R interleaved rounds each.
3. A step of csrl.CsQlAgent (act, then update with a Python sensor of the state reached)
   on the same 4x4 lake sensed by its factors, its moves drawn by World.sample: the
   best of R rounds of N steps each, the world's draw included.
"""

import argparse
import pathlib
import subprocess
import time

import gymnasium as gym
import numpy as np

import csrl
import csrl.gym


def per_step(env, actions, seed):
    env.reset(seed=seed)
    step = env.step
    reset = env.reset
    start = time.perf_counter()
    for a in actions:
        _obs, _r, term, trunc, _info = step(a)
        if term or trunc:
            reset()
    return (time.perf_counter() - start) / len(actions)


def bench_steps(n, repeats):
    lake = gym.make("FrozenLake-v1").unwrapped  # slippery, as Gymnasium makes it by default
    sensing = gym.make("csrl/Sensing-v0", world=csrl.World("frozenlake4x4", sensing="factors", slip=2 / 3)).unwrapped
    rng = np.random.default_rng(1)
    lake_actions = [int(a) for a in rng.integers(0, lake.action_space.n, n)]
    sensing_actions = [int(a) for a in rng.integers(0, sensing.action_space.n, n)]
    t_lake = min(per_step(lake, lake_actions, 1) for _ in range(repeats))
    t_sensing = min(per_step(sensing, sensing_actions, 1) for _ in range(repeats))
    return t_lake, t_sensing


def agent_steps(n):
    lake = csrl.World("frozenlake4x4", sensing="factors")
    readings = lake.readings()
    agent = csrl.CsQlAgent.for_world(lake, strategy="lazy", seed=1)
    act, update, sample, rng = agent.act, agent.update, lake.sample, agent.rng
    x, moves = lake.sample_start(rng), 0
    start = time.perf_counter()
    for _ in range(n):
        a = act(lambda f, s=x: readings[s][f])
        nxt, reward, terminated = sample(x, a, rng)
        moves += 1
        truncated = moves == 100
        update(reward, terminated, truncated, lambda f, s=nxt: readings[s][f])
        if terminated or truncated:
            x, moves = lake.sample_start(rng), 0
        else:
            x = nxt
    return (time.perf_counter() - start) / n


def wall(cmd):
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def bench_run(cli, repeats, world, strategy, seed):
    """The best of `repeats` rounds, each timing the process start, the command and the
    in-process run one after the other (so that load from outside hits all three alike)."""
    flags = ["--world", world, "--strategy", strategy, "--seed", str(seed)]
    start_ups, clis, pys = [], [], []
    for _ in range(repeats):
        start_ups.append(wall([cli, "--version"]))
        clis.append(wall([cli, "run", "--json", *flags]))
        start = time.perf_counter()
        csrl.run_json(world=world, strategy=strategy, seed=seed)
        pys.append(time.perf_counter() - start)
    start_up = min(start_ups)
    return start_up, min(clis) - start_up, min(pys)


def main():
    here = pathlib.Path(__file__).resolve().parents[3]
    p = argparse.ArgumentParser()
    p.add_argument("--cli", default=str(here / "target" / "release" / "csrl"))
    p.add_argument("--steps", type=int, default=200_000)
    p.add_argument("--repeats", type=int, default=5)
    args = p.parse_args()

    t_lake, t_sensing = bench_steps(args.steps, args.repeats)
    print(f"FrozenLake-v1 step (unwrapped):   {t_lake * 1e6:.2f} us")
    print(f"SensingEnv step (unwrapped):      {t_sensing * 1e6:.2f} us")
    print(f"SensingEnv / FrozenLake:          {t_sensing / t_lake:.2f}")
    t_agent = min(agent_steps(args.steps) for _ in range(args.repeats))
    print(f"CsQlAgent step (Python sensor):   {t_agent * 1e6:.2f} us")
    for world, strategy, seed in [("random:32x32:0.2:1", "lazy", 1), ("frozenlake8x8", "lazy", 1)]:
        start_up, t_cli, t_py = bench_run(args.cli, args.repeats, world, strategy, seed)
        print(
            f"run {world} {strategy} seed {seed}: csrl run {t_cli:.3f} s (after {start_up * 1e3:.1f} ms of "
            f"process start), csrl.run_json {t_py:.3f} s, ratio {t_py / t_cli:.3f}"
        )


if __name__ == "__main__":
    main()
