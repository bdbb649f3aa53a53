"""The command line, the top layer: each command a thin wrapper over the layers below, errors one line.

:mod:`.group` holds the ``hoistsim`` group and its one-line errors; the commands register on it
from their modules (:mod:`.run_commands`, :mod:`.study_commands`, :mod:`.file_commands`), each
importing what it uses when it runs, so that ``hoistsim --help`` loads no JAX, matplotlib or
Dask.  :mod:`.watching` is ``hoistsim watch``'s loop, :mod:`.terminal` its notices and progress.
It may import every layer.
"""

from . import file_commands, run_commands, sensitivity_commands, study_commands  # noqa: F401  (each registers its commands on main)
from .group import main as main
