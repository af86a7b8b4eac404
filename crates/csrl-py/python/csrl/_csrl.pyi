"""Type stubs of the compiled part of csrl (``csrl._csrl``)."""

from os import PathLike
from typing import Any, Callable, Optional, Union

__version__: str

MAX_STATES: int
"""The most states a world may have."""
MAX_ACTIONS: int
"""The most actions a world (or an agent) may have."""
MAX_FEATURES: int
"""The most features a world (or an agent) may have."""
MAX_READING: int
"""The largest reading a feature may have in a state."""
MAX_REWARD: float
"""The largest size a reward may have (so that its sums over a run stay finite)."""
MAX_PRICE: float
"""The largest price a feature may have (so that a run's total cost stays finite)."""
MAX_TOTAL_COST: float
"""The most a classifier's learning may cost in all: the summed prices times the objects."""
MAX_CLASSES: int
"""The most classes a test-cost tree learns (a continuous target has one per object)."""
MAX_LOOKAHEAD_FEATURES: int
"""The most features ACT's sampled lookahead (ACT, and CVT's lookahead grower) runs on."""

class SettingsError(ValueError):
    """Settings that cannot be used (the message names them)."""

class WorldError(ValueError):
    """A world or map that cannot be read or built (the message says what and where)."""

class DataError(ValueError):
    """Data a classifier cannot learn from."""

class AgentError(RuntimeError):
    """A CsQlAgent called out of order, or stopped at an earlier error of its sensor."""

class SensorError(ValueError):
    """A sensor's reading that is not an int in its feature's range."""

def run(
    world: Union[str, World, None] = None,
    strategy: Optional[str] = None,
    seed: Optional[int] = None,
    learner: Optional[str] = None,
    settings: Optional[str] = None,
    max_trials: Optional[int] = None,
    episodes: Optional[int] = None,
    predict_sensing: Optional[str] = None,
    trace: bool = False,
) -> dict[str, Any]: ...
def resolve_settings(
    world: Optional[str] = None,
    strategy: Optional[str] = None,
    seed: Optional[int] = None,
    learner: Optional[str] = None,
    settings: Optional[str] = None,
    max_trials: Optional[int] = None,
    episodes: Optional[int] = None,
    predict_sensing: Optional[str] = None,
) -> dict[str, Any]: ...
def settings_toml(settings: Any) -> str: ...
def dumps(obj: Any) -> str: ...
def map_names() -> list[str]: ...
def world_names() -> list[str]: ...
def value_floor(world: World, gamma: float) -> float: ...

class World:
    @staticmethod
    def load(name: str, settings: Optional[str] = None) -> World: ...
    @staticmethod
    def from_json(text: str) -> World: ...
    @staticmethod
    def from_file(path: Union[str, PathLike[str]]) -> World: ...
    def to_json(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def num_states(self) -> int: ...
    @property
    def num_actions(self) -> int: ...
    @property
    def num_features(self) -> int: ...
    def states(self) -> list[int]: ...
    def terminal(self) -> list[bool]: ...
    def feature_names(self) -> list[str]: ...
    def prices(self) -> list[float]: ...
    def arities(self) -> list[int]: ...
    def action_names(self) -> list[str]: ...
    def state_labels(self) -> list[str]: ...
    def readings(self) -> list[list[int]]: ...
    def outcomes(self, s: int, a: int) -> list[tuple[float, int, float, bool]]: ...
    def start(self) -> list[tuple[float, int]]: ...
    def optimal_values(self, gamma: float) -> list[float]: ...
    def sample_start(self, rng: Rng) -> int: ...
    def sample(self, s: int, a: int, rng: Rng) -> tuple[int, float, bool]: ...

class Rng:
    def __init__(self, seed: int) -> None: ...
    @property
    def shared(self) -> bool: ...

class CsQlAgent:
    def __init__(
        self,
        feature_costs: list[float],
        feature_values: list[int],
        num_actions: int,
        strategy: Optional[str] = None,
        seed: Optional[int] = None,
        settings: Optional[str] = None,
        refine_from: str = "left",
        initial_value: float = 0.0,
    ) -> None: ...
    def act(self, sensor: Callable[[int], int]) -> int: ...
    def update(
        self,
        reward: float,
        terminated: bool,
        truncated: bool,
        sensor: Optional[Callable[[int], int]] = None,
    ) -> None: ...
    @property
    def rng(self) -> Rng: ...
    @property
    def trials(self) -> int: ...
    @property
    def moves(self) -> int: ...
    @property
    def sensing_cost(self) -> float: ...
    @property
    def refine_from(self) -> str: ...
    def descriptions(self) -> list[list[tuple[int, int]]]: ...
    def q_table(self) -> list[list[float]]: ...
    def values(self) -> list[float]: ...
    def policy(self) -> list[int]: ...
    def trial(self, current: bool = False) -> Optional[tuple[int, int, bool, float, int, int, int]]: ...

class Classifier:
    def __init__(self, kind: str, costs: list[float], tolerance: int = 1) -> None: ...
    def learn(self, rows: list[list[Optional[int]]], classes: list[int]) -> tuple[int, float]: ...
    def classify(self, rows: list[list[Optional[int]]]) -> tuple[list[Optional[int]], list[float]]: ...
    def classify_proba(
        self, rows: list[list[Optional[int]]], classes: int
    ) -> tuple[list[Optional[int]], list[float], list[list[float]]]: ...
    @property
    def library_size(self) -> int: ...
    def tree_dot(
        self, feature_names: list[str], value_names: list[list[str]], class_names: list[str]
    ) -> str: ...

# A column for TestCostTree: (None, floats with NaN for missing) for a numeric feature,
# or (value names, codes: an index into them, -1 for missing, len(names) for a value
# never seen) for a nominal one.
_Column = tuple[Optional[list[str]], list[Any]]

class TestCostTree:
    @staticmethod
    def fit(
        learner: str,
        names: list[str],
        columns: list[_Column],
        classes: list[int],
        class_names: list[str],
        prices: list[tuple[float, float, Optional[int]]],
        group_names: list[str],
        misclassification: list[list[float]],
        confidence: float = 0.25,
        w: float = 1.0,
        seed: int = 0,
        population: int = 50,
        generations: int = 20,
        samples: int = 5,
        selection_prices: str = "path",
        icet_pruning: str = "errors",
        search_objects: int = 400,
        folds: int = 5,
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
        threads: int = 1,
        voi_lookahead: Optional[int] = None,
        voi_confidence: Optional[float] = None,
        voi_m: Optional[float] = None,
        cvt_samples: int = 5,
    ) -> TestCostTree: ...
    def classify(
        self,
        columns: list[_Column],
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
    ) -> tuple[list[int], list[float], list[list[int]], list[list[float]]]: ...
    def explain(
        self,
        columns: list[_Column],
        max_test_cost: Optional[float] = None,
        max_tests: Optional[int] = None,
    ) -> list[
        tuple[
            list[tuple[int, float, Optional[int], Optional[list[float]], Optional[float]]],
            Optional[int],
        ]
    ]: ...
    def nodes(
        self,
    ) -> list[tuple[int, list[float], Optional[tuple[int, Optional[float], list[int]]]]]: ...
    @property
    def learner(self) -> str: ...
    @property
    def icet_genome(self) -> Optional[tuple[list[float], float, float, float]]: ...
    @property
    def cvt_choice(self) -> Optional[tuple[str, Optional[float], float]]: ...
    def state(self) -> Any: ...
    @staticmethod
    def from_state(state: Any) -> TestCostTree: ...
