"""The machine layer: bodies and couplings, the elements that make a scene, and their assembly.

:mod:`.core` is the engine that names no part (bodies, the restart loop, switching, the ledger);
:mod:`.elements` holds one part of the machine a file, each contributing its states, torques,
guards and columns; :mod:`.assemble` turns a validated scenario into the traced plan of
a run (its elements, the scheduled boundaries, the initial state and the output grid).

May import: the foundation, :mod:`hoistsim.components` and :mod:`hoistsim.scenario`.
"""
