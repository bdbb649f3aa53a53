"""Each unit's SI factor as pint worked it out in an earlier process: a scenario read without pint.

:func:`hoistsim.scenario.units.to_si` reads "3201 N" as 3201 times what one newton is in the key's SI
unit; that factor comes from pint once, and is kept here for later processes.
"""

from __future__ import annotations

import json
import os
from functools import lru_cache
from pathlib import Path

from ..cache_folders import cache_folder, keep


class KnownFactors:
    """Each unit's SI factor as pint worked it out in an earlier process, kept in the cache folder.

    Importing pint and building its registry is some 0.15 s of a command's start (more than reading
    the rest of the scenario); a scenario whose units were all read before is read without pint.  The
    file is named by what decides the factors: pint's installed files, :mod:`.units` (where the
    registry is defined) and this module, so a new pint or an edit of either module starts a new file.
    It is rewritten whole (a temporary file renamed): two processes learning at once lose at most a
    factor, read again later.  A factor read from it is the one pint gave: the same number to the bit.
    """

    def __init__(self, folder: str | None):
        self.path = None
        self.factors: dict[str, float] = {}
        if folder is None:
            return
        self.path = os.path.join(folder, f"factors-{_factors_origin()}.json")
        try:
            with open(self.path, encoding="utf-8") as file:
                read = json.load(file)
            self.factors = {k: float(v) for k, v in read.items() if isinstance(v, (int, float))}
        except (OSError, ValueError, AttributeError):  # none yet, or unreadable: pint reads again
            self.factors = {}

    @staticmethod
    def key(unit: str, si_unit: str, radians: int) -> str:
        """A unit read as a quantity whose SI unit is ``si_unit`` with the angle to the power ``radians``."""
        return f"{unit} as {si_unit or '1'} (rad^{radians})"

    def learn(self, key: str, factor: float) -> None:
        self.factors[key] = factor
        if self.path is None:
            return
        try:
            keep(self.path, json.dumps(self.factors, sort_keys=True).encode())
        except OSError:  # a read-only cache: learnt for this process only
            pass


@lru_cache(maxsize=1)
def known_factors() -> KnownFactors:
    """This process's factors, read from the cache folder once."""
    return KnownFactors(cache_folder("units"))


def _factors_origin() -> str:
    """A digest of what the factors come from: pint's files as installed, the registry's definition
    (:mod:`.units`) and this module."""
    import hashlib
    from importlib.util import find_spec

    here = Path(__file__).resolve().parent
    digest = hashlib.sha256((here / "units.py").read_bytes() + Path(__file__).read_bytes())
    spec = find_spec("pint")
    if spec is not None and spec.origin:
        for path in sorted(Path(spec.origin).parent.glob("*.txt")) + [Path(spec.origin)]:  # its definitions
            stat = path.stat()
            digest.update(f"{path.name} {stat.st_size} {stat.st_mtime_ns}".encode())
    return digest.hexdigest()[:16]
