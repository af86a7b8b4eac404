"""CS-QL stepped from a Gymnasium loop: FrozenLake-v1 sensed by row and column
(docs/python.md)."""

import gymnasium as gym
import csrl

env = gym.make("FrozenLake-v1", is_slippery=False)  # 4x4, at most 100 moves a trial
agent = csrl.CsQlAgent(feature_costs=[1.0, 2.0], feature_values=[4, 4],
                       num_actions=4, strategy="lazy", seed=1)
sensor = lambda obs: (lambda f: divmod(obs, 4)[f])  # feature 0: row, 1: column
obs, _ = env.reset(seed=1)
wins = []
for episode in range(300):
    while True:
        obs2, reward, terminated, truncated, _ = env.step(agent.act(sensor(obs)))
        agent.update(reward, terminated, truncated, sensor=sensor(obs2))
        obs = obs2
        if terminated or truncated:
            wins.append(reward == 1.0)
            obs, _ = env.reset()
            break
print(sum(wins[-100:]), "of the last 100 episodes reach the goal")
print(len(agent.descriptions()), "descriptions, sensing cost", agent.sensing_cost)
print(agent.last_trial())
