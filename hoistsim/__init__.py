"""hoistsim: time-domain start-up of a winch hoist with a stick-slip cone clutch."""

from . import _jax  # noqa: F401  (float64 before any array exists)
from .exact import exact_from_scenario as exact_from_scenario
from .exact import solve_exact as solve_exact
from .results import RunResult as RunResult
from .scenario import ScenarioError as ScenarioError
from .scenario import load_scenario as load_scenario
from .scenario import scenario_from_dict as scenario_from_dict
from .scenario import scenario_from_text as scenario_from_text
from .simulation import SimulationError as SimulationError
from .simulation import simulate as simulate
from .sweeps import SweepResult as SweepResult
from .sweeps import sweep as sweep

__version__ = "0.1.0"
