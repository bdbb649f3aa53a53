"""Shared set-up: float64 JAX (hoistsim turns it on at import) and scene builders."""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

# The on-disk caches serve fresh `hoistsim` processes; in the test session, commands
# run in-process and share jit's in-memory cache instead, and nothing is written to
# the user's home.  Tests of the caches give their subprocesses a folder of their own.
os.environ["HOISTSIM_CACHE_DIR"] = ""

import hoistsim  # noqa: E402,F401  (enables float64 before any test creates an array)

sys.path.insert(0, str(Path(__file__).parent))

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = ROOT / "scenarios"


def core(text: str) -> str:
    """A scenario text without its optional sections (they may come and go in the shipped files)."""
    kept, skipping = [], False
    for line in text.splitlines(keepends=True):
        top = re.match(r"([A-Za-z_]\w*)[ \t]*:", line)
        if top:
            skipping = top.group(1) in ("initial", "brake", "bearings", "sweep")
        if not skipping:
            kept.append(line)
    return "".join(kept)
