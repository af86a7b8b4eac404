"""csrl: cost-sensitive reinforcement learning (Tan, AAAI-91) from Python, at native speed.

The learning runs in Rust; this package gives it Python's shapes:

* :func:`run` -- one CS-QL run (or a baseline), the same JSON object as ``csrl run --json``.
* :class:`CsQlAgent` -- CS-QL stepped from Python, for environments without a published
  model: it asks a sensor for the features it measures and returns an action.
* :class:`World` -- a finite world with priced features: built-in worlds and maps by name,
  world files, your own arrays, and Gymnasium's toy-text environments.
* :mod:`csrl.gym` -- ``SensingEnv``, a Gymnasium environment where sensing has a price
  (registered as ``csrl/Sensing-v0``).
* :mod:`csrl.sklearn` -- scikit-learn estimators that pay for what they measure: the
  paper's ``CsId3Classifier`` and ``CsIblClassifier``, and the test-cost tree family
  (``C45Classifier``, ``Eg2Classifier``, ``IcetClassifier``, ... and
  ``TestCostTreeClassifier``).

Errors are Python exceptions carrying the Rust message: :class:`SettingsError`,
:class:`WorldError` and :class:`SensorError` are ``ValueError``\\ s, :class:`AgentError`
a ``RuntimeError``.

>>> import csrl
>>> report = csrl.run(world="tan3x3", strategy="lazy", seed=1)
>>> report["converged"], report["map"], report["strategy"]
(True, 'tan3x3', 'lazy')
>>> try:
...     csrl.run(world="tan3x3", settings={"temperature": -1.0})
... except csrl.SettingsError as e:
...     print(type(e).__mro__[1].__name__)
ValueError
"""

from __future__ import annotations

import os
from typing import Any, Mapping, Optional, Union

from . import _csrl
from ._csrl import (
    AgentError,
    DataError,
    Rng,
    SensorError,
    SettingsError,
    WorldError,
    dumps,
    map_names,
    world_names,
)
from .world import World

__version__: str = _csrl.__version__

__all__ = [
    "AgentError",
    "CsQlAgent",
    "DataError",
    "Rng",
    "SensorError",
    "SettingsError",
    "World",
    "WorldError",
    "dumps",
    "map_names",
    "resolve_settings",
    "run",
    "run_json",
    "value_floor",
    "world_names",
]

Settings = Union[Mapping[str, Any], str, "os.PathLike[str]", None]


def _settings_text(settings: Settings) -> Optional[str]:
    """The settings as ``_csrl`` takes them: TOML text, or ``@PATH`` for a file."""
    if settings is None:
        return None
    if isinstance(settings, Mapping):
        return _csrl.settings_toml(dict(settings))
    if isinstance(settings, (str, os.PathLike)):
        return "@" + os.fspath(settings)
    raise SettingsError(
        "settings must be a mapping (the tables of a settings file as dicts) or the path "
        f"of a TOML settings file, found {type(settings).__name__}"
    )


def _world_arg(world: Union[str, "os.PathLike[str]", World, None]) -> Any:
    if isinstance(world, World):
        return world._inner
    if isinstance(world, os.PathLike):
        return os.fspath(world)
    return world


def run_json(
    world: Union[str, "os.PathLike[str]", World, None] = None,
    strategy: Optional[str] = None,
    seed: Optional[int] = None,
    learner: Optional[str] = None,
    settings: Settings = None,
    *,
    max_trials: Optional[int] = None,
    episodes: Optional[int] = None,
    predict_sensing: Optional[str] = None,
    trace: bool = False,
) -> str:
    """One run, as the text ``csrl run --json`` prints (without its final newline):
    :func:`dumps` of :func:`run`'s report (see :func:`run` for the arguments).

    >>> import csrl, json
    >>> text = csrl.run_json(world="tan3x3", strategy="eager", seed=2)
    >>> json.loads(text)["seed"]
    2
    """
    return dumps(
        run(
            world,
            strategy,
            seed,
            learner,
            settings,
            max_trials=max_trials,
        episodes=episodes,
            predict_sensing=predict_sensing,
            trace=trace,
        )
    )


def run(
    world: Union[str, "os.PathLike[str]", World, None] = None,
    strategy: Optional[str] = None,
    seed: Optional[int] = None,
    learner: Optional[str] = None,
    settings: Settings = None,
    *,
    max_trials: Optional[int] = None,
    episodes: Optional[int] = None,
    predict_sensing: Optional[str] = None,
    trace: bool = False,
) -> dict:
    """One run of CS-QL (or a baseline), its report as a dict: the JSON object
    ``csrl run --json`` prints for the same arguments, as Python objects (:func:`dumps`
    writes it back as the command's text, byte for byte).

    The arguments are the flags of ``csrl run``: ``world`` (``--world``: a built-in
    world or map, a map or world file, ``random:WxH:DENSITY:SEED``, or a :class:`World`),
    ``strategy``, ``seed``, ``learner``, ``max_trials``, ``episodes``, ``predict_sensing`` and ``trace``;
    ``settings`` is what ``--config`` reads: the path of a TOML settings file, or the same
    tables as a dict (``{"temperature": 0.2, "world": {"slip": 0.1}}``). Arguments left
    at ``None`` take the settings' value, else the paper's, or where ``world`` names a
    built-in world that asks for its own temperature, detector or trial cap (``taxi``,
    ``cliffwalking``, ``frozenlake8x8``), the world's. The learners played on
    episodes of the costed return, ``learner="amrl-q"`` and ``learner="belief"`` (tuned
    by the settings' ``amrl_q`` and ``belief`` tables), play ``episodes`` episodes (not
    ``max_trials``, the cap of a run judged over trials), need ``{"costly": {"price": ...}}``
    and give their report: the costed return of every episode and their summary.

    The GIL is released while the run goes on, and Ctrl-C stops it
    (``KeyboardInterrupt``).

    >>> import csrl
    >>> r = csrl.run(world="frozenlake4x4", strategy="lazy", seed=1)
    >>> r["converged"], r["map"]
    (True, 'frozenlake4x4')
    """
    report: dict = _csrl.run(
        world=_world_arg(world),
        strategy=strategy,
        seed=seed,
        learner=learner,
        settings=_settings_text(settings),
        max_trials=max_trials,
        episodes=episodes,
        predict_sensing=predict_sensing,
        trace=trace,
    )
    return report


def resolve_settings(
    world: Union[str, "os.PathLike[str]", None] = None,
    strategy: Optional[str] = None,
    seed: Optional[int] = None,
    learner: Optional[str] = None,
    settings: Settings = None,
    *,
    max_trials: Optional[int] = None,
    episodes: Optional[int] = None,
    predict_sensing: Optional[str] = None,
) -> dict:
    """The settings a run with these arguments would use (the report's ``settings``),
    checked but not run.

    >>> import csrl
    >>> csrl.resolve_settings(world="tan8x8", settings={"temperature": 0.2})["temperature"]
    0.2
    """
    resolved: dict = _csrl.resolve_settings(
        world=None if world is None else os.fspath(world),
        strategy=strategy,
        seed=seed,
        learner=learner,
        settings=_settings_text(settings),
        max_trials=max_trials,
        episodes=episodes,
        predict_sensing=predict_sensing,
    )
    return resolved


def value_floor(world: World, gamma: float = 0.9) -> float:
    """Where :func:`csrl.run` starts Q and V in ``world`` at discount ``gamma``: the value
    of earning the worst state's best sure reward forever, 0 in worlds without negative
    rewards (``docs/specification.md``, 1.11). ``gamma`` must be at least 0 and below 1
    (:class:`csrl.SettingsError` otherwise).

    >>> import csrl
    >>> csrl.value_floor(csrl.World("frozenlake4x4")), round(csrl.value_floor(csrl.World("taxi")), 6)
    (0.0, -10.0)
    """
    return _csrl.value_floor(world._inner, float(gamma))


# After the names above: the agent's module reads `_settings_text` and `resolve_settings`.
from .agent import CsQlAgent  # noqa: E402
