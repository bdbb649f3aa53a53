"""The running layer: a run, a sweep in blocks of compiled calls, streaming to chunk files, a cluster.

:mod:`.simulation` runs one scenario; a sweep (:mod:`.sweeps`) splits its runs into blocks of one
structure (:mod:`.block_plans`, :mod:`.blocks`), streams them to chunk files that survive a kill
(:mod:`.streaming`) and may spread them over a Dask cluster (:mod:`.cluster`).

May import: every layer below it (foundation, components, display, scenario, machine, results).
"""
