"""The kinds of event the core itself records: a coupling's mode changes.

Here, apart from the core, so that what reads a results file (a figure, a table) knows them without loading the
machine and JAX.  A part may rename them (a rope's ``rope_taut``, a stop's ``stop_reached``): the renamed kinds
are switches too, listed by each machine's layout (``Layout.switch_kinds``).
"""

SWITCH_KINDS = ("lock", "unlock", "reversal", "engage", "disengage")
