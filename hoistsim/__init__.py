"""hoistsim: time-domain start-up of a winch hoist with a stick-slip cone clutch.

Public names are imported on first use, so the command line pays only for
what a command needs (a run never loads the closed-form solver's scipy parts,
checking a scenario never loads JAX).  Every module that uses JAX imports
:mod:`hoistsim._jax` first (directly, or through ``hoistsim.machine.core`` or
``hoistsim._pytree``), so float64 is set before any array exists.
"""

from importlib import import_module

__version__ = "0.1.0"

_PUBLIC = {
    "load_scenario": "scenario.loading",
    "scenario_from_dict": "scenario.loading",
    "scenario_from_text": "scenario.loading",
    "ScenarioError": "errors",
    "simulate": "running.simulation",
    "SimulationError": "running.simulation",
    "RunResult": "results.run_result",
    "sweep": "running.sweeps",
    "SweepResult": "running.sweeps",
    "sensitivity": "running.sensitivity",
    "Sensitivity": "results.sensitivity_result",
    "SweepSensitivity": "running.sweep_sensitivity",
    "fit": "studies.fit",
    "FitResult": "studies.fit",
    "exact_from_scenario": "references.exact",
    "solve_exact": "references.exact",
    "open_results": "results.reading",
}
__all__ = sorted(_PUBLIC)


def __getattr__(name: str):
    if name in _PUBLIC:
        value = getattr(import_module(f".{_PUBLIC[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'hoistsim' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + __all__)
