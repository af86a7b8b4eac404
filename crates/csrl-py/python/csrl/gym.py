"""A Gymnasium environment where sensing has a price: :class:`SensingEnv`.

Importing this module registers it as ``csrl/Sensing-v0``:

>>> import gymnasium as gym
>>> import csrl.gym
>>> env = gym.make("csrl/Sensing-v0", world="frozenlake4x4", sensing="factors")
>>> obs, info = env.reset(seed=1)
>>> obs["mask"].tolist()
[0, 0]
>>> obs, reward, terminated, truncated, info = env.step(0)  # sense feature 0 (the row)
>>> obs["mask"].tolist(), reward, info["sensing_cost"]
([1, 0], -1.0, 1.0)
"""

from __future__ import annotations

import bisect
import operator
from typing import Any, Optional, Union

import gymnasium
import numpy as np
from gymnasium import spaces

from .world import World

__all__ = ["SensingEnv"]

# A palette for readings in rgb_array pictures (reading v takes colour v mod 8).
_PALETTE = np.array(
    [
        [236, 240, 241],
        [44, 62, 80],
        [39, 174, 96],
        [41, 128, 185],
        [192, 57, 43],
        [243, 156, 18],
        [142, 68, 173],
        [22, 160, 133],
    ],
    dtype=np.uint8,
)
_UNKNOWN = np.array([150, 150, 150], dtype=np.uint8)


def _count(name: str, value: Any) -> int:
    """``value`` as a count of at least 1: an int (or a numpy integer), not a float that
    would be truncated nor a bool."""
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be an integer of at least 1, found {value!r}")
    try:
        n = operator.index(value)
    except TypeError:
        raise ValueError(f"{name} must be an integer of at least 1, found {value!r}") from None
    if n < 1:
        raise ValueError(f"{name} must be at least 1, found {value!r}")
    return n


class SensingEnv(gymnasium.Env):
    """A csrl world in which an agent must pay to see where it is.

    The agent starts every episode knowing nothing of its state. Each step it either
    **senses** one feature of the world (actions ``0 .. num_features - 1``), paying the
    feature's price, or **moves** (actions ``num_features ..``, the world's actions in
    order), which samples the world's outcome and forgets what was sensed.

    * Observation: ``{"values": MultiDiscrete(arities), "mask": MultiBinary(num_features)}``,
      the readings sensed since the last move (0 where not sensed) and which are known.
    * Reward: a move's reward from the world; a sensing step's ``-cost_scale * price``.
      ``info["sensing_cost"]`` is the price paid in the step (0 for a move, unscaled).
    * ``terminated`` when a move enters a terminal state; ``truncated`` after
      ``max_moves`` moves or ``max_steps`` steps (sensing included), whichever is first.
    * Seeded only by ``reset(seed=...)``, through ``self.np_random``.
    * ``render_mode``: ``"ansi"`` (text) or ``"rgb_array"`` (a strip of feature cells:
      grey where unknown, a colour per reading where known).

    Args:
        world: a :class:`csrl.World`, or a name :class:`csrl.World` takes.
        sensing: ``"local"`` or ``"factors"`` for a built-in world named by ``world``.
        cost_scale: what one unit of price costs in reward.
        max_moves: moves before truncation.
        max_steps: steps (sensing and moves) before truncation; by default
            ``max_moves * (num_features + 1)``.
        render_mode: ``None``, ``"ansi"`` or ``"rgb_array"``.
    """

    action_space: spaces.Discrete

    metadata = {"render_modes": ["ansi", "rgb_array"], "render_fps": 4}

    def __init__(
        self,
        world: Union[str, World] = "frozenlake4x4",
        sensing: Optional[str] = None,
        cost_scale: float = 1.0,
        max_moves: int = 100,
        max_steps: Optional[int] = None,
        render_mode: Optional[str] = None,
    ) -> None:
        if not isinstance(world, World):
            world = World(world, sensing=sensing)
        elif sensing is not None:
            raise ValueError(
                "sensing chooses how a world named by a string is sensed; "
                "a csrl.World already carries its sensing"
            )
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"render_mode {render_mode!r}: expected one of {self.metadata['render_modes']} or None"
            )
        if not (isinstance(cost_scale, (int, float)) and np.isfinite(cost_scale) and cost_scale >= 0):
            raise ValueError(f"cost_scale must be a finite number at least 0, found {cost_scale!r}")
        max_moves = _count("max_moves", max_moves)
        if max_steps is not None:
            max_steps = _count("max_steps", max_steps)
        nf = world.num_features
        if nf == 0:
            raise ValueError(f"world {world.name!r} has no features to sense")
        self.world = world
        self.render_mode = render_mode
        self.cost_scale = float(cost_scale)
        self.max_moves = int(max_moves)
        self.max_steps = int(max_steps) if max_steps is not None else self.max_moves * (nf + 1)
        self.num_features = nf
        self._prices = [float(p) for p in world.prices]
        self._penalty = [-self.cost_scale * p for p in self._prices]
        self._readings = world.readings()
        self._terminal = world.terminal()
        self._labels = world.state_labels
        self._feature_names = world.feature_names
        self._action_names = world.action_names
        # Per (state, move): cumulative probabilities and outcomes, for one draw per move.
        na = world.num_actions
        self._moves = []
        for s in range(world.num_states):
            row = []
            for a in range(na):
                outs = world.outcomes(s, a) if not self._terminal[s] else [(1.0, s, 0.0, True)]
                cum, acc = [], 0.0
                for p, _t, _r, _d in outs:
                    acc += p
                    cum.append(acc)
                row.append((cum, [(t, float(r), bool(d)) for _p, t, r, d in outs]))
            self._moves.append(row)
        start = world.start()
        self._start_states = [s for _p, s in start]
        acc, self._start_cum = 0.0, []
        for p, _s in start:
            acc += p
            self._start_cum.append(acc)
        arities = world.arities
        self.action_space = spaces.Discrete(nf + na)
        self.observation_space = spaces.Dict(
            {
                "values": spaces.MultiDiscrete(np.array(arities, dtype=np.int64)),
                "mask": spaces.MultiBinary(nf),
            }
        )
        self._values = np.zeros(nf, dtype=np.int64)
        self._mask = np.zeros(nf, dtype=np.int8)
        self._state = self._start_states[0]
        self._moves_made = 0
        self._steps = 0
        self._last = "reset"

    def _draw(self, cum: list) -> int:
        if len(cum) == 1:
            return 0
        i = bisect.bisect_right(cum, self.np_random.random() * cum[-1])
        return min(i, len(cum) - 1)

    def _obs(self) -> dict:
        return {"values": self._values.copy(), "mask": self._mask.copy()}

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        """Start an episode in a state drawn from the world's start distribution."""
        super().reset(seed=seed)
        self._state = self._start_states[self._draw(self._start_cum)]
        self._values[:] = 0
        self._mask[:] = 0
        self._moves_made = 0
        self._steps = 0
        self._last = "reset"
        return self._obs(), {"sensing_cost": 0.0}

    def step(self, action: Any):
        """Sense feature ``action`` (below ``num_features``) or make move
        ``action - num_features``."""
        # An action is an int (or a numpy integer): 1.7 is no action, nor is True.
        if isinstance(action, (bool, np.bool_)):
            raise ValueError(f"action {action!r} is not in {self.action_space}")
        try:
            a = operator.index(action)
        except TypeError:
            raise ValueError(f"action {action!r} is not an integer in {self.action_space}") from None
        nf = self.num_features
        if not 0 <= a < self.action_space.n:
            raise ValueError(f"action {action!r} is not in {self.action_space}")
        self._steps += 1
        if 0 <= a < nf:
            self._values[a] = self._readings[self._state][a]
            self._mask[a] = 1
            self._last = f"sensed {self._feature_names[a]}"
            truncated = self._steps >= self.max_steps
            return self._obs(), self._penalty[a], False, truncated, {"sensing_cost": self._prices[a]}
        cum, outs = self._moves[self._state][a - nf]
        nxt, reward, terminated = outs[self._draw(cum)]
        self._state = nxt
        self._values[:] = 0
        self._mask[:] = 0
        self._moves_made += 1
        self._last = f"moved {self._action_names[a - nf]}"
        truncated = not terminated and (
            self._moves_made >= self.max_moves or self._steps >= self.max_steps
        )
        return self._obs(), reward, terminated, truncated, {"sensing_cost": 0.0}

    def render(self):
        """Text (``"ansi"``) or a picture of the features (``"rgb_array"``)."""
        if self.render_mode is None:
            gymnasium.logger.warn("render() called without a render_mode")
            return None
        if self.render_mode == "ansi":
            known = ", ".join(
                f"{self._feature_names[f]}={self._values[f]}"
                for f in range(self.num_features)
                if self._mask[f]
            )
            return (
                f"{self.world.name}: state {self._labels[self._state]}, "
                f"move {self._moves_made}/{self.max_moves}, {self._last}; "
                f"known: {known or 'nothing'}\n"
            )
        cell = 16
        img = np.empty((cell, cell * self.num_features, 3), dtype=np.uint8)
        for f in range(self.num_features):
            colour = _PALETTE[self._values[f] % len(_PALETTE)] if self._mask[f] else _UNKNOWN
            img[:, f * cell : (f + 1) * cell] = colour
            img[:, f * cell] = 0  # a dark line between cells
        return img


if "csrl/Sensing-v0" not in gymnasium.registry:
    gymnasium.register(id="csrl/Sensing-v0", entry_point="csrl.gym:SensingEnv")
