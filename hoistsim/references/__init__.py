"""The references: what the tests trust, computed without the elements or the restart loop.

The two-shaft reduced model of exercise 6 (:mod:`.model`), its closed-form piecewise solution
(:mod:`.exact`, with :mod:`.exppoly` for its exponential-polynomial phases), the elastic rope's
exact phases (:mod:`.rope_exact`), and two independent peers: scipy's event-restart integration
of the same equations (:mod:`.scipy_reference`) and the regularised (smoothed-friction) ODE
(:mod:`.regularised`).  Dymola's published trajectories of Modelica's examples, how far a run is from them
(:mod:`.dymola`) and what each example compares (:mod:`.modelica_signals`), which the tests and the documentation's
gallery share.  The engine, the results and the figures never import these; the tests and the studies read them.

May import: the foundation, :mod:`hoistsim.components`, :mod:`hoistsim.scenario` and
:mod:`hoistsim.machine` (the regularised peer drives the assembled machine's smooth right-hand side).
"""
