"""The base of every section of the scenario schema: frozen, no unknown keys, finite numbers."""

from __future__ import annotations

from typing import ClassVar

from pydantic import BaseModel, ConfigDict

from ..errors import ScenarioError


class Section(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)
    # the ways of giving one thing, one of each group ("a + b": keys given together), for the scenario reference
    # (the section's validators hold them)
    alternatives: ClassVar[tuple[tuple[str, ...], ...]] = ()

    def _one_value_or_group(self, section: str, single: str, group: tuple, both: str, required: str) -> bool:
        """Check that the section gives ``single`` or every key of ``group``, not both (one-line errors
        naming the key; ``both`` and ``required`` say what to give); True where the group is given."""
        given = [name for name in group if getattr(self, name) is not None]
        if getattr(self, single) is not None and given:
            raise ScenarioError(f"{section}.{given[0]}", f"give either {both}, not both")
        if getattr(self, single) is None:
            missing = [name for name in group if getattr(self, name) is None]
            if missing:
                raise ScenarioError(f"{section}.{missing[0] if given else single}", f"required: {required}")
        return bool(given)
