"""CS-QL driven one step at a time from Python: :class:`CsQlAgent`."""

from __future__ import annotations

from typing import Any, Callable, List, Mapping, Optional, Sequence, Tuple, Union

from . import _csrl
from ._csrl import AgentError, SensorError

__all__ = ["AgentError", "CsQlAgent", "SensorError", "Sensor"]

Sensor = Callable[[int], int]
"""A sensor: ``sensor(feature) -> value``, what a feature reads in one state (an int in
``range(feature_values[feature])``)."""


def _tolist(x: Any) -> Any:
    tolist = getattr(x, "tolist", None)
    return tolist() if callable(tolist) else x


class CsQlAgent:
    """CS-QL for an environment you step yourself, with no published model: the agent
    asks a sensor for the features it decides to measure (each charged its price) and
    returns an action; :meth:`update` tells it the outcome.

    It is the agent of :func:`csrl.run` (CLASSIFY, the strategy, the same main loop and
    generator, the same settings), stepped from outside. Driven over a world that draws
    its starts and outcomes from the agent's generator (:meth:`csrl.World.sample_start`
    and :meth:`csrl.World.sample` with ``rng=agent.rng``) it learns exactly what
    :func:`csrl.run` learns for the same seed, bit for bit.

    * ``feature_costs[i]``: the price of measuring feature ``i``; ``feature_values[i]``:
      how many values it reads (``0`` to ``feature_values[i] - 1``). The agent takes "the
      next cheapest feature" by ascending price, ties in your order.
    * ``num_actions``: actions are ``0`` to ``num_actions - 1``; at most 64 actions and
      4096 features, as in a world (:data:`csrl._csrl.MAX_ACTIONS`, ``MAX_FEATURES``).
    * ``strategy``, ``seed`` and ``settings`` as :func:`csrl.run` takes them (the paper's
      parameters by default; ``[world]`` settings, ``learner``, ``predict_sensing`` and
      ``memory`` are refused: the agent senses your environment, with CLASSIFY; so are
      the keys of a run your loop decides: ``map``, ``max_trials``, ``max_moves``,
      ``tolerance``, ``max_rows``, ``judge`` and ``costly``).
    * ``refine_from``: where a refinement reads the feature it adds. ``"left"`` (the
      paper's rule, the default): in the state the refined description was used for,
      which the move has just left; the agent asks again the sensor it was given for
      that state, during the next :meth:`update` (or :meth:`act`), so that sensor must
      still read that state -- as one that reads that step's observation does. ``"next"``:
      for sensors that only read the present; the feature is added the next time the
      description is given to a state, valued there.
    * ``initial_value``: where Q and V start (:func:`csrl.run` starts them at
      ``csrl.value_floor(world, gamma)``, 0 in worlds without negative rewards).

    Each step: ``a = agent.act(sensor)`` with ``sensor`` reading the state the agent is
    in, then ``agent.update(reward, terminated, truncated, sensor=...)`` with a sensor of
    the state reached. A ``terminated`` move reached the goal (nothing is sensed there); a
    ``truncated`` one was cut by your move cap and needs the sensor (the state reached is
    classified and bootstrapped from). Without ``sensor`` the move is learned from at the
    next :meth:`act`, whose sensor then reads the state reached. The next :meth:`act`
    after a trial ended starts a new trial.

    Errors are exceptions: :class:`csrl.SensorError` (a ``ValueError``) for a reading that
    is not an int in its range, :class:`csrl.AgentError` (a ``RuntimeError``) for calls out
    of order; an exception raised by a sensor is raised as it is. After an error in a
    sensor the agent stops (its learning would hold a reading never made): every later
    call raises :class:`csrl.AgentError`.

    >>> import csrl
    >>> # A corridor of cells 0..3, the goal right of cell 3; one feature: the cell.
    >>> agent = csrl.CsQlAgent([1.0], [4], num_actions=2, strategy="lazy", seed=1)
    >>> for episode in range(30):
    ...     cell = 0
    ...     for t in range(100):
    ...         a = agent.act(lambda f, c=cell: c)
    ...         nxt = cell + 1 if a == 1 else max(cell - 1, 0)
    ...         goal = nxt == 4
    ...         agent.update(float(goal), goal, t == 99, sensor=lambda f, c=nxt: c)
    ...         if goal:
    ...             break
    ...         cell = nxt
    >>> agent.trials, agent.policy()
    (30, [1, 1, 1, 1])
    >>> agent.descriptions()
    [[(0, 0)], [(0, 1)], [(0, 2)], [(0, 3)]]
    >>> agent.act(lambda f: 9)
    Traceback (most recent call last):
    ...
    csrl.SensorError: the sensor read 9 for feature 0, which reads 0 to 3
    """

    __slots__ = ("_inner",)

    def __init__(
        self,
        feature_costs: Sequence[float],
        feature_values: Sequence[int],
        num_actions: int,
        strategy: Optional[str] = None,
        seed: Optional[int] = None,
        settings: Any = None,
        *,
        refine_from: str = "left",
        initial_value: float = 0.0,
    ) -> None:
        from . import _settings_text

        self._inner = _csrl.CsQlAgent(
            [float(c) for c in _tolist(feature_costs)],
            [int(v) for v in _tolist(feature_values)],
            int(num_actions),
            strategy=strategy,
            seed=seed,
            settings=_settings_text(settings),
            refine_from=refine_from,
            initial_value=float(initial_value),
        )

    @classmethod
    def for_world(
        cls,
        world: Any,
        strategy: Optional[str] = None,
        seed: Optional[int] = None,
        settings: Any = None,
        *,
        refine_from: str = "left",
    ) -> "CsQlAgent":
        """An agent with a world's features, prices, actions and starting value, as
        :func:`csrl.run` would make it for that world (the world itself stays yours to
        step and sense).

        >>> import csrl
        >>> lake = csrl.World("frozenlake4x4", sensing="factors")
        >>> agent = csrl.CsQlAgent.for_world(lake, strategy="lazy", seed=1)
        >>> agent.trials, agent.sensing_cost
        (0, 0.0)
        """
        from . import resolve_settings

        gamma = resolve_settings(strategy=strategy, seed=seed, settings=settings)["gamma"]
        return cls(
            world.prices,
            world.arities,
            world.num_actions,
            strategy,
            seed,
            settings,
            refine_from=refine_from,
            initial_value=_csrl.value_floor(world._inner, gamma),
        )

    def act(self, sensor: Sensor) -> int:
        """Choose an action in the state ``sensor`` reads (asked only for what the agent
        measures: at the start of a trial, or when the last update came without a
        sensor)."""
        return self._inner.act(sensor)

    def update(
        self,
        reward: float,
        terminated: bool,
        truncated: bool,
        sensor: Optional[Sensor] = None,
    ) -> None:
        """The outcome of the action :meth:`act` returned: its reward, whether it
        terminated (reached the goal) and whether it was truncated (your move cap), and a
        sensor of the state reached (needed when truncated and not terminated)."""
        self._inner.update(float(reward), bool(terminated), bool(truncated), sensor)

    @property
    def rng(self) -> "_csrl.Rng":
        """The agent's generator as a :class:`csrl.Rng`: a world that draws its starts
        and outcomes from it (:meth:`csrl.World.sample_start`, :meth:`csrl.World.sample`)
        shares the agent's one stream, in :func:`csrl.run`'s order, and the agent then
        learns what :func:`csrl.run` learns for the same seed."""
        return self._inner.rng

    @property
    def trials(self) -> int:
        """Trials started."""
        return self._inner.trials

    @property
    def moves(self) -> int:
        """Moves learned from."""
        return self._inner.moves

    @property
    def sensing_cost(self) -> float:
        """The sensing cost charged so far."""
        return self._inner.sensing_cost

    @property
    def refine_from(self) -> str:
        """``"left"`` or ``"next"``."""
        return self._inner.refine_from

    def descriptions(self) -> List[List[Tuple[int, int]]]:
        """The descriptions, in id order: ``(feature, value)`` pairs, in the order they
        were added. A description's id is its row of :meth:`q_table`."""
        return self._inner.descriptions()

    def q_table(self) -> List[List[float]]:
        """Q of every description: one row each, one value per action."""
        return self._inner.q_table()

    def values(self) -> List[float]:
        """V of every description."""
        return self._inner.values()

    def policy(self) -> List[int]:
        """The greedy action of every description (the lowest among ties)."""
        return self._inner.policy()

    def last_trial(self, current: bool = False) -> Optional[Mapping[str, Union[int, float, bool]]]:
        """What happened in the last trial that ended (or, with ``current=True``, in the
        trial in progress): ``trial``, ``moves``, ``terminated``, ``cost``,
        ``decreases``, ``refinements``, ``resets``; ``None`` if there is none."""
        t = self._inner.trial(current)
        if t is None:
            return None
        keys = ("trial", "moves", "terminated", "cost", "decreases", "refinements", "resets")
        return dict(zip(keys, t))

    def __repr__(self) -> str:
        return (
            f"csrl.CsQlAgent({self.trials} trials, {self.moves} moves, "
            f"{len(self.descriptions())} descriptions, sensing cost {self.sensing_cost})"
        )
