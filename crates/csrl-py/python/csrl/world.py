"""Finite worlds with priced features: :class:`World`."""

from __future__ import annotations

import json
import math
import numbers
import os
from typing import Any, Callable, Iterable, Mapping, Optional, Sequence, Union

from . import _csrl
from ._csrl import WorldError

__all__ = ["World"]


def _tolist(x: Any) -> Any:
    """Lists (and numbers) from numpy arrays, or ``x`` itself."""
    tolist = getattr(x, "tolist", None)
    return tolist() if callable(tolist) else x


def _is_bool(x: Any) -> bool:
    return isinstance(x, bool) or type(x).__name__ == "bool_"


def _integer(x: Any, at: str, what: str, below: int) -> int:
    """``x`` as an int in ``range(below)``: an int or a numpy integer, never a float that
    would be truncated nor a bool."""
    if _is_bool(x) or not isinstance(x, numbers.Integral):
        raise WorldError(f"{at}: {what} {x!r} is not an integer")
    v = int(x)
    if not 0 <= v < below:
        raise WorldError(f"{at}: {what} {v} is not in 0 to {below - 1}")
    return v


def _real(x: Any, at: str, what: str) -> float:
    """``x`` as a finite float (an int, a float or a numpy number, not a bool)."""
    if _is_bool(x) or not isinstance(x, numbers.Real):
        raise WorldError(f"{at}: {what} {x!r} is not a number")
    v = float(x)
    if not math.isfinite(v):
        raise WorldError(f"{at}: {what} {v} is not finite")
    return v


def _probability(x: Any, at: str) -> float:
    """``x`` as a probability: a finite number in [0, 1]."""
    p = _real(x, at, "probability")
    if not 0.0 <= p <= 1.0:
        raise WorldError(f"{at}: probability {p} is not in [0, 1]")
    return p


def _at_most(count: int, limit: int, what: str) -> None:
    """Refuse a size beyond a world's limit before anything is built."""
    if count > limit:
        raise WorldError(f"{what}: {count}, more than the limit of {limit}")


def _generator(rng: Any, method: str) -> "_csrl.Rng":
    """``rng`` if it is a :class:`csrl.Rng`; a ``TypeError`` that says what to pass
    otherwise (an agent itself is not a generator: its ``rng`` is)."""
    if isinstance(rng, _csrl.Rng):
        return rng
    if isinstance(rng, _csrl.CsQlAgent) or isinstance(getattr(rng, "_inner", None), _csrl.CsQlAgent):
        raise TypeError(
            f"World.{method} takes a csrl.Rng, not a CsQlAgent: pass agent.rng to draw from "
            "the agent's own generator (as csrl.run does), or csrl.Rng(seed) for a generator of its own"
        )
    raise TypeError(
        f"World.{method} takes a csrl.Rng (csrl.Rng(seed), or a CsQlAgent's agent.rng), "
        f"not {type(rng).__name__}"
    )


class World:
    """A finite world whose states are sensed through priced features.

    Every world CS-QL runs in is one of these: its states and actions, where trials
    start, the outcomes of every action with their probabilities and rewards, which
    states are terminal, and its features, each with a price and a small-integer reading
    in every state. Features are kept cheapest first (ties in the given order).

    Build one by name (``World("taxi")``, ``World("tan8x8")``, a map or world file), from
    arrays (:meth:`from_arrays`), or from a Gymnasium environment that publishes its model
    (:meth:`from_gymnasium`). :func:`csrl.run` runs CS-QL in it at native speed, measured
    against the oracle of its true model.

    >>> import csrl
    >>> lake = csrl.World("frozenlake4x4", sensing="factors", factor_costs=[1.0, 2.0])
    >>> lake.name, lake.num_states, lake.num_actions, lake.feature_names
    ('frozenlake4x4', 16, 4, ['row', 'col'])
    >>> lake.prices
    [1.0, 2.0]
    >>> csrl.World("no-such-world")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    csrl.WorldError: no built-in map and no file named `no-such-world` (built-in maps: tan3x3, ...)
    """

    __slots__ = ("_inner",)

    def __init__(
        self,
        name: Union[str, "os.PathLike[str]"],
        *,
        sensing: Optional[str] = None,
        slip: Optional[float] = None,
        slide: Optional[float] = None,
        factor_costs: Optional[Sequence[float]] = None,
    ) -> None:
        """A world by name, as ``csrl run --world`` takes it: a built-in world
        (:func:`csrl.world_names`), a built-in map (:func:`csrl.map_names`), a map file
        (TOML), a world file (``.json``) or ``random:WxH:DENSITY:SEED``. ``sensing``
        (``"local"`` or ``"factors"``), ``slip``, ``slide`` and ``factor_costs`` are the
        ``[world]`` settings of the built-in worlds. A grid map becomes the finite world
        ``csrl world export`` writes for it.
        """
        options: dict = {}
        if sensing is not None:
            options["sensing"] = sensing
        if slip is not None:
            options["slip"] = float(slip)
        if slide is not None:
            options["slide"] = float(slide)
        if factor_costs is not None:
            options["factor_costs"] = [float(c) for c in _tolist(factor_costs)]
        text = _csrl.settings_toml({"world": options}) if options else None
        self._inner = _csrl.World.load(os.fspath(name), text)

    @classmethod
    def _wrap(cls, inner: "_csrl.World") -> "World":
        w = cls.__new__(cls)
        w._inner = inner
        return w

    # -- building ------------------------------------------------------------------

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "World":
        """A world file (format ``csrl-world``, version 1; ``docs/specification.md``)."""
        return cls._wrap(_csrl.World.from_file(os.fspath(path)))

    @classmethod
    def from_json(cls, text: str) -> "World":
        """A world from the JSON text of a world file."""
        return cls._wrap(_csrl.World.from_json(text))

    @classmethod
    def from_spec(cls, spec: Mapping[str, Any]) -> "World":
        """A world from a world file's contents as a dict (the JSON object)."""
        return cls.from_json(json.dumps(spec))

    @classmethod
    def from_arrays(
        cls,
        transitions: Any,
        rewards: Any,
        terminal: Sequence[bool],
        readings: Any,
        feature_costs: Sequence[float],
        *,
        start: Union[int, Sequence[Any]] = 0,
        name: str = "arrays",
        feature_names: Optional[Sequence[str]] = None,
        action_names: Optional[Sequence[str]] = None,
        state_labels: Optional[Sequence[str]] = None,
    ) -> "World":
        """A world from a tabular model of your own.

        * ``transitions[s][a]``: the outcomes of action ``a`` in state ``s``, a list of
          ``(probability, next_state)`` pairs (or a row of ``num_states`` probabilities);
          ignored for terminal states.
        * ``rewards[s][a]``: the reward of taking ``a`` in ``s``, one number for every
          outcome or a list with one per outcome.
        * ``terminal[s]``: whether ``s`` ends a trial; an outcome ends the trial exactly
          when it enters a terminal state.
        * ``readings[s][f]``: what feature ``f`` reads in state ``s`` (a small integer),
          for every state; a ``num_states x num_features`` array.
        * ``feature_costs[f]``: the price of measuring feature ``f``.
        * ``start``: a start state, or ``(probability, state)`` pairs.

        Arrays may be numpy arrays. Nothing is coerced: probabilities are finite numbers
        in [0, 1], rewards and prices finite numbers, states and readings integers (a
        float such as ``1.7`` is refused, not truncated), names distinct, and sizes within
        a world's limits (checked before anything is built). Errors name the argument
        and the index, or the state, action or feature at fault.

        >>> import csrl
        >>> # A corridor 0 - 1 - 2 where 2 is the goal; one feature (the position) at price 1.
        >>> T = [[[(1.0, 0)], [(1.0, 1)]], [[(1.0, 0)], [(1.0, 2)]], [[], []]]
        >>> R = [[0.0, 0.0], [0.0, 1.0], [0.0, 0.0]]
        >>> w = csrl.World.from_arrays(T, R, [False, False, True], [[0], [1], [2]], [1.0])
        >>> w.states(), w.outcomes(1, 1)
        ([0, 1], [(1.0, 2, 1.0, True)])
        """
        # Sizes first, before anything is built.
        n = len(terminal)
        _at_most(n, _csrl.MAX_STATES, "states")
        nf = len(feature_costs)
        _at_most(nf, _csrl.MAX_FEATURES, "features")
        terminal = [bool(t) for t in _tolist(terminal)]
        transitions = _tolist(transitions)
        rewards = _tolist(rewards)
        readings = [
            [
                _integer(v, f"readings[{s}][{f}]", "reading", _csrl.MAX_READING + 1)
                for f, v in enumerate(_tolist(row))
            ]
            for s, row in enumerate(_tolist(readings))
        ]
        costs = [_real(c, f"feature_costs[{f}]", "price") for f, c in enumerate(_tolist(feature_costs))]
        if len(transitions) != n or len(rewards) != n or len(readings) != n:
            raise WorldError(
                f"terminal has {n} states but transitions has {len(transitions)}, "
                f"rewards {len(rewards)} and readings {len(readings)}: one entry per state each"
            )
        num_actions = None
        spec_transitions = []
        for s in range(n):
            if terminal[s]:
                continue
            row = transitions[s]
            if num_actions is None:
                num_actions = len(row)
                _at_most(num_actions, _csrl.MAX_ACTIONS, "actions")
            if len(row) != num_actions:
                raise WorldError(
                    f"state {s} has {len(row)} actions in transitions, state "
                    f"{next(i for i in range(n) if not terminal[i])} has {num_actions}"
                )
            for a, outs in enumerate(row):
                outs = _tolist(outs)
                at = f"transitions[{s}][{a}]"
                if outs and not isinstance(outs[0], (list, tuple)):
                    # A row of probabilities over the next states.
                    if len(outs) != n:
                        raise WorldError(
                            f"{at}: a row of {len(outs)} probabilities, but there are {n} states"
                        )
                    outs = [(p, t) for t, p in enumerate(outs) if _probability(p, f"{at}[{t}]") > 0]
                else:
                    for j, o in enumerate(outs):
                        if len(o) != 2:
                            raise WorldError(f"{at}[{j}]: {o!r} is not a (probability, next_state) pair")
                r = rewards[s][a] if a < len(rewards[s]) else None
                if r is None:
                    raise WorldError(f"state {s}, action {a}: rewards has no entry")
                r = _tolist(r)
                per = r if isinstance(r, list) else [r] * len(outs)
                if len(per) != len(outs):
                    raise WorldError(
                        f"state {s}, action {a}: {len(outs)} outcomes but {len(per)} rewards"
                    )
                out = []
                for j, ((p, t), rew) in enumerate(zip(outs, per)):
                    p = _probability(p, f"{at}, outcome {j}")
                    t = _integer(t, f"state {s}, action {a}, outcome {j}", "next state", n)
                    rew = _real(rew, f"rewards[{s}][{a}], outcome {j}", "reward")
                    out.append([p, t, rew, terminal[t]])
                spec_transitions.append([s, a, out])
        if num_actions is None:
            num_actions = 1
        if isinstance(start, numbers.Number) or hasattr(start, "__index__"):
            start_pairs = [[1.0, _integer(start, "start", "state", n)]]
        else:
            start_pairs = [
                [_probability(p, f"start[{i}]"), _integer(s, f"start[{i}]", "state", n)]
                for i, (p, s) in enumerate(_tolist(start))
            ]
        names = list(feature_names) if feature_names is not None else [f"f{i}" for i in range(nf)]
        if len(names) != nf:
            raise WorldError(f"{len(names)} feature names for {nf} features")
        spec = {
            "format": "csrl-world",
            "version": 1,
            "name": name,
            "states": list(state_labels) if state_labels is not None else n,
            "actions": list(action_names)
            if action_names is not None
            else [str(a) for a in range(num_actions)],
            "start": start_pairs,
            "terminal": [s for s in range(n) if terminal[s]],
            "transitions": spec_transitions,
            "features": [{"name": names[f], "price": costs[f]} for f in range(nf)],
            "readings": readings,
        }
        return cls.from_spec(spec)

    @classmethod
    def from_gymnasium(
        cls,
        env: Any,
        features: Callable[[int], Iterable[int]],
        feature_costs: Sequence[float],
        *,
        feature_names: Optional[Sequence[str]] = None,
        name: Optional[str] = None,
    ) -> "World":
        """A world from a Gymnasium environment that publishes its model as the toy-text
        environments do (``env.unwrapped.P[s][a] = [(p, next, reward, terminated), ...]``
        with ``Discrete`` spaces: FrozenLake, Taxi, CliffWalking).

        ``features(s)`` gives the readings of observation ``s`` (small integers, the same
        number for every state), ``feature_costs`` their prices. Trials start as the
        environment's ``initial_state_distrib`` says. A state is terminal when an outcome
        enters it with ``terminated`` set; the world then checks that every outcome into
        it says so.

        >>> import gymnasium as gym, csrl
        >>> env = gym.make("FrozenLake-v1", is_slippery=False)
        >>> w = csrl.World.from_gymnasium(env, lambda s: divmod(s, 4), [1.0, 1.0],
        ...                               feature_names=["row", "col"])
        >>> w.num_states, w.num_actions, len(w.states())
        (16, 4, 11)
        """
        u = env.unwrapped
        P = getattr(u, "P", None)
        if P is None:
            raise WorldError(
                f"{type(u).__name__} publishes no model (env.unwrapped.P); "
                "use csrl.World.from_arrays with a model of your own"
            )
        try:
            n = int(u.observation_space.n)
            na = int(u.action_space.n)
        except AttributeError:
            raise WorldError(
                "from_gymnasium needs Discrete observation and action spaces"
            ) from None
        # Sizes first, before anything is built.
        _at_most(n, _csrl.MAX_STATES, "states")
        _at_most(na, _csrl.MAX_ACTIONS, "actions")
        terminal = [False] * n
        model = []
        for s in range(n):
            row = []
            for a in range(na):
                outs = []
                for j, (p, t, r, done) in enumerate(P[s][a]):
                    at = f"P[{s}][{a}][{j}]"
                    p = _probability(p, at)
                    t = _integer(t, at, "next state", n)
                    outs.append((p, t, _real(r, at, "reward"), bool(done)))
                    if done and p > 0:
                        terminal[t] = True
                row.append(outs)
            model.append(row)
        start_dist = getattr(u, "initial_state_distrib", None)
        if start_dist is None:
            raise WorldError(
                f"{type(u).__name__} has no initial_state_distrib: build the world with "
                "csrl.World.from_arrays and a start of your own"
            )
        start_dist = _tolist(start_dist)
        if len(start_dist) != n:
            raise WorldError(
                f"initial_state_distrib has {len(start_dist)} entries, but there are {n} states"
            )
        start: list[list[Any]] = [
            [p, s]
            for s, p in enumerate(
                _probability(p, f"initial_state_distrib[{s}]") for s, p in enumerate(start_dist)
            )
            if p > 0
        ]
        # The states a trial can reach: there an outcome must say `terminated` exactly
        # when it enters a terminal state. Elsewhere (Taxi's states with the passenger
        # already delivered, for instance) the flag is taken from the state entered:
        # no trial ever takes those outcomes.
        reachable = [False] * n
        todo = [s for _p, s in start]
        for s in todo:
            reachable[s] = True
        while todo:
            s = todo.pop()
            if terminal[s]:
                continue
            for a in range(na):
                for p, t, _r, _d in model[s][a]:
                    if p > 0 and not reachable[t]:
                        reachable[t] = True
                        todo.append(t)
        transitions = []
        for s in range(n):
            if terminal[s]:
                continue
            for a in range(na):
                out = []
                for p, t, r, done in model[s][a]:
                    if reachable[s] and done != terminal[t]:
                        raise WorldError(
                            f"P[{s}][{a}]: an outcome enters state {t} with terminated={bool(done)}, "
                            f"but another outcome enters it with terminated={not done}: "
                            "a csrl world ends a trial by the state entered"
                        )
                    out.append([p, t, r, terminal[t]])
                transitions.append([s, a, out])
        readings: list[list[int]] = []
        for s in range(n):
            sensed = [
                _integer(v, f"features({s})[{f}]", "reading", _csrl.MAX_READING + 1)
                for f, v in enumerate(_tolist(features(s)))
            ]
            if not readings:
                _at_most(len(sensed), _csrl.MAX_FEATURES, "features")
            if readings and len(sensed) != len(readings[0]):
                raise WorldError(
                    f"features({s}) gave {len(sensed)} readings, features(0) gave {len(readings[0])}"
                )
            readings.append(sensed)
        costs = [_real(c, f"feature_costs[{f}]", "price") for f, c in enumerate(_tolist(feature_costs))]
        nf = len(readings[0]) if readings else 0
        if len(costs) != nf:
            raise WorldError(f"features gives {nf} readings per state but feature_costs has {len(costs)} prices")
        names = list(feature_names) if feature_names is not None else [f"f{i}" for i in range(nf)]
        if len(names) != nf:
            raise WorldError(f"{len(names)} feature names for {nf} features")
        if name is None:
            spec_id = getattr(getattr(env, "spec", None), "id", None)
            name = spec_id or type(u).__name__
        spec = {
            "format": "csrl-world",
            "version": 1,
            "name": name,
            "states": n,
            "actions": [str(a) for a in range(na)],
            "start": start,
            "terminal": [s for s in range(n) if terminal[s]],
            "transitions": transitions,
            "features": [{"name": names[f], "price": costs[f]} for f in range(nf)],
            "readings": readings,
        }
        return cls.from_spec(spec)

    # -- reading -------------------------------------------------------------------

    @property
    def name(self) -> str:
        """The world's name (a run's report names it)."""
        return self._inner.name

    @property
    def num_states(self) -> int:
        """The number of states, terminal ones included."""
        return self._inner.num_states

    @property
    def num_actions(self) -> int:
        """The number of actions."""
        return self._inner.num_actions

    @property
    def num_features(self) -> int:
        """The number of features."""
        return self._inner.num_features

    @property
    def feature_names(self) -> list:
        """The features' names, cheapest first."""
        return self._inner.feature_names()

    @property
    def prices(self) -> list:
        """The features' prices, cheapest first."""
        return self._inner.prices()

    @property
    def arities(self) -> list:
        """How many readings each feature has (it reads ``0..arity``)."""
        return self._inner.arities()

    @property
    def action_names(self) -> list:
        """The actions' names."""
        return self._inner.action_names()

    @property
    def state_labels(self) -> list:
        """The states' labels."""
        return self._inner.state_labels()

    def states(self) -> list:
        """The non-terminal states a trial can reach, in id order."""
        return self._inner.states()

    def terminal(self) -> list:
        """Whether each state is terminal."""
        return self._inner.terminal()

    def readings(self) -> list:
        """What each feature reads in each state: one row per state."""
        return self._inner.readings()

    def outcomes(self, state: int, action: int) -> list:
        """The outcomes of ``action`` in ``state``: ``(probability, next, reward,
        terminated)`` tuples (none for a terminal state)."""
        return self._inner.outcomes(state, action)

    def start(self) -> list:
        """Where trials start: ``(probability, state)`` pairs."""
        return self._inner.start()

    def sample_start(self, rng: "_csrl.Rng") -> int:
        """Draw a trial's start state from ``rng``, a :class:`csrl.Rng`: ``csrl.Rng(seed)``
        for a generator of its own, or a :class:`csrl.CsQlAgent`'s ``agent.rng``, with
        which the world's draws and the agent's come from one stream in :func:`csrl.run`'s
        order (one draw for the start, then per move the agent's draw and the outcome's),
        so that the agent learns what :func:`csrl.run` learns for the same seed.

        >>> import csrl
        >>> w = csrl.World("tan3x3")
        >>> w.sample_start(csrl.Rng(1)) in w.states()
        True
        >>> agent = csrl.CsQlAgent.for_world(w, seed=1)
        >>> w.sample_start(agent.rng) in w.states()
        True
        """
        return self._inner.sample_start(_generator(rng, "sample_start"))

    def sample(self, state: int, action: int, rng: "_csrl.Rng") -> tuple:
        """Draw an outcome of ``action`` in the non-terminal ``state`` from ``rng``, a
        :class:`csrl.Rng` (see :meth:`sample_start`): ``(next, reward, terminated)``.

        >>> import csrl
        >>> w = csrl.World("frozenlake4x4")
        >>> w.sample(0, 2, csrl.Rng(1))  # right, on ice that does not slip
        (1, 0.0, False)
        """
        return self._inner.sample(state, action, _generator(rng, "sample"))

    def optimal_values(self, gamma: float = 0.9) -> list:
        """The optimal value of every state at discount ``gamma``."""
        return self._inner.optimal_values(gamma)

    def to_json(self) -> str:
        """The world as the JSON text of a world file."""
        return self._inner.to_json()

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Write the world as a world file (``csrl run --world PATH.json`` runs it)."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.to_json())

    def __repr__(self) -> str:
        return repr(self._inner)

    def __reduce__(self) -> Any:
        return (World.from_json, (self.to_json(),))
