"""The periodic regime of a machine whose torques or inertia vary with angle (the second seed).

- :mod:`.period`: the machine's period, a common multiple of its parts' periods;
- :mod:`.regime`: settling and the analysed periods, read from a run's rows;
- :mod:`.tredgold`: the turning-moment diagram at constant speed and Tredgold's answer;
- :mod:`.flywheel`: the flywheel that meets a degree of irregularity.
"""

from .. import _jax  # noqa: F401  (float64 before any array exists)
