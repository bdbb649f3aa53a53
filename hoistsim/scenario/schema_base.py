"""The base of every section of the scenario schema: frozen, no unknown keys, finite numbers."""

from __future__ import annotations

from typing import ClassVar

from pydantic import BaseModel, ConfigDict, PrivateAttr

from ..errors import ScenarioError


class Section(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)
    # the ways of giving one thing, one of each group ("a + b": keys given together), for the scenario reference
    # (the section's validators hold them)
    alternatives: ClassVar[tuple[tuple[str, ...], ...]] = ()
    _derived: tuple = PrivateAttr(default=())  # the keys set from others
    # What a drawn part's element reads beside its own keys (the scene's gravity, a shaft's gear train), written
    # into a copy where the scenario is lowered (:mod:`.lowering`): no file gives them, and no element reads the
    # scenario for them.
    _resolved: dict = PrivateAttr(default_factory=dict)

    def lowered(self, scenario) -> "Section":
        """The spec as its element reads it, standing alone (one that needs nothing beyond its keys: itself)."""
        return self

    def with_resolved(self, **values) -> "Section":
        """A copy with ``values`` written in (see :meth:`lowered`)."""
        out = self.model_copy()
        out._resolved = {**self._resolved, **values}
        return out

    def resolved(self, name: str):
        """What :meth:`with_resolved` wrote in as ``name``."""
        if name not in self._resolved:  # a part built from a spec not lowered: the program's error, not the user's
            raise RuntimeError(f"{type(self).__name__}.{name} is written in where the scenario is lowered "
                               "(hoistsim/scenario/lowering.py)")
        return self._resolved[name]

    def _derive(self, key: str, value) -> None:
        """Set ``key`` from the keys given (a stall torque from the nameplate, a ratio from teeth): read as such
        from here on, and never written back into a scenario beside the keys it came from."""
        object.__setattr__(self, key, value)
        self._derived = self._derived + (key,)

    def derived(self) -> tuple[str, ...]:
        """The keys set from others (:meth:`_derive`)."""
        return self._derived

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
