"""The periodic regime of a machine whose torques or inertia vary with angle (the second seed), read off a run.

- :mod:`.regime`: settling and the analysed periods, read from a run's rows;
- :mod:`.tredgold`: the turning-moment diagram at constant speed and Tredgold's answer;
- :mod:`.analysis`: both for a run, with the summary's columns.

The machine's period is :mod:`hoistsim.scenario.period`; the flywheel that meets a degree of
irregularity, :mod:`hoistsim.studies.flywheel`.
"""

from ... import _jax  # noqa: F401  (float64 before any array exists)
