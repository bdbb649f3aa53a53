"""What a part's outputs are called: patterns filled in with its name, or the names its drawing gives them."""

from __future__ import annotations


class NamedOutputs:
    """A part whose outputs (columns, summaries, ledger terms, events) are named by patterns filled in with its
    name (``{name}_torque``), save those its drawing names otherwise (``names``: the hoist's template's)."""

    @property
    def part_name(self) -> str:
        """The name its patterns are filled in with: its own, or the part's it belongs to (a clutch's heating)."""
        return self.section

    def named(self, pattern: str) -> str:
        return dict(self.names).get(pattern, pattern.format(name=self.part_name))


def names_of(spec) -> tuple:
    """The output names a part's spec gives otherwise than its patterns, as a static field holds them."""
    return tuple(sorted(spec.output_names().items()))
