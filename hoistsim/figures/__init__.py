"""The figures: a results file drawn as the runs against time, the summary against the swept value, the
periodic regime.

:mod:`.files` writes a file's figures; :mod:`.runs`, :mod:`.summary` and :mod:`.periodic` draw
them from the panels the elements declare, so this layer names no part; :mod:`.base` holds what
they share, :mod:`.placing` lays out a figure of runs from its measured texts, :mod:`.naming` names its
events and wraps its title so that no two texts overlap, :mod:`.marks` puts the dots on its curves and
:mod:`.zoom` enlarges a burst of its events.  matplotlib is imported inside these modules only, never by a
layer below.

May import: the foundation, the displays (:mod:`hoistsim.display`) and the results; nothing here runs the
machine, and nothing here loads JAX.
"""
