"""The scenario layer: a YAML file read into a validated scenario in SI units, and a sweep's runs.

Reading YAML with its line numbers (:mod:`.yamlsource`), quantities and units (:mod:`.units`),
tables and time signals (:mod:`.tables`, :mod:`.signals`), the schema of every section
(:mod:`.schema` and its ``schema_*`` parts), a key's checks, unit and one-line error
(:mod:`.keys`), loading a file with ``--set`` overrides (:mod:`.loading`) and what it learns
beyond the values, the scenario's text, source and sweep (:mod:`.provenance`), a sweep's values and
its runs as scenarios (:mod:`.sweep_spec`, :mod:`.swept_values`, :mod:`.sweep_runs`), and the
machine's period in whole turns (:mod:`.period`).  Nothing here imports JAX.

May import: the foundation (errors) and :mod:`hoistsim.components`.
"""
