"""What a part's outputs are called: patterns filled in with its name."""

from __future__ import annotations


class NamedOutputs:
    """A part whose outputs (columns, summaries, ledger terms, events) are named by patterns filled in with its
    name (``{name}_torque``).  A scenario that names them otherwise (a hoist's ``slip_speed``) does so where its
    results are written (:func:`hoistsim.scenario.lowering.output_names`): the machine runs under these."""

    @property
    def part_name(self) -> str:
        """The name its patterns are filled in with: its own, or the part's it belongs to (a clutch's heating)."""
        return self.section

    def named(self, pattern: str) -> str:
        return pattern.format(name=self.part_name)


def called(kind: str, name: str) -> str:
    """How a description names a part: "clutch c1", or "the clutch" where the part is named by its kind's own word
    (the hoist's ``clutch``, ``motor``), which would otherwise read twice."""
    return f"the {kind}" if name == kind else f"{kind} {name}"
