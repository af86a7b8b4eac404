"""CS-QL on Gymnasium's Taxi, from its published model (docs/python.md)."""

import gymnasium as gym
import csrl

env = gym.make("Taxi-v4")
taxi = csrl.World.from_gymnasium(
    env, lambda s: list(env.unwrapped.decode(s)), feature_costs=[1, 1, 2, 2],
    feature_names=["row", "col", "passenger", "destination"],
)
settings = {"temperature": 8.0, "extensions": {"detector": "action"}}
report = csrl.run(world=taxi, strategy="lazy", seed=1, settings=settings)
print(report["converged"], report["trials"], round(report["total_cost"]), report["policy_quality"])
print(report["table1"])
