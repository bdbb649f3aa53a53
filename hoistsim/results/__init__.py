"""The results layer: what a run's records become, the file format written and read, and the tables.

A run's result and its summary (:mod:`.run_result`, :mod:`.summaries`), the periodic regime and
Tredgold's diagram read off a run's rows (:mod:`.periodic`), the HDF5 file written atomically
(:mod:`.output`, :mod:`.output_periodic`, :mod:`.atomic`) and read back (:mod:`.reading`), and
the tables a terminal shows (:mod:`.report`).

May import: the foundation, components, the displays, the scenario and the machine (never the references:
the tests' oracles are no part of a result).
"""
