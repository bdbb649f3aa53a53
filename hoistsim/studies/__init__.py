"""The studies: answers computed from a scenario by many runs or none.

What accuracy costs in time (:mod:`.work_precision`, ``hoistsim bench``), the exercise's static
answers (:mod:`.statics`, ``hoistsim statics``) and the flywheel that meets a degree of
irregularity (:mod:`.flywheel`, ``hoistsim flywheel``).

May import: every layer below it, the command line excepted.
"""
