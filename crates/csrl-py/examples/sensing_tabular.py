"""A hand-written tabular Q-learner in csrl's sensing environment (docs/python.md).

The agent sees only what it has sensed since its last move, so it must learn both where
to go and what to pay to find out where it is.
"""

import numpy as np

import csrl.gym

env = csrl.gym.SensingEnv("tan3x3", cost_scale=0.01)
rng = np.random.default_rng(0)
n = env.action_space.n
Q = {}


def key(obs):
    return tuple(obs["values"]) + tuple(obs["mask"])


for episode in range(2000):
    obs, _ = env.reset(seed=episode)
    eps, done = max(0.05, 1 - episode / 1000), False
    while not done:
        q = Q.setdefault(key(obs), np.zeros(n))
        a = int(rng.integers(n)) if rng.random() < eps else int(np.argmax(q))
        obs2, r, term, trunc, _ = env.step(a)
        target = r + (0.0 if term else 0.9 * Q.setdefault(key(obs2), np.zeros(n)).max())
        q[a] += 0.2 * (target - q[a])
        obs, done = obs2, term or trunc

reached, moves, paid = 0, 0, 0.0
for episode in range(100):
    obs, _ = env.reset(seed=100_000 + episode)
    done = False
    while not done:
        a = int(np.argmax(Q.get(key(obs), np.zeros(n))))
        obs, r, term, trunc, info = env.step(a)
        moves += a >= env.num_features
        paid += info["sensing_cost"]
        done = term or trunc
    reached += term
print(f"reached the goal in {reached}/100 episodes, {moves / 100:.2f} moves and "
      f"{paid / moves:.2f} sensing per move")
