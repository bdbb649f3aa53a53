"""Shared set-up: float64 JAX (hoistsim turns it on at import) and scene builders."""

from __future__ import annotations

import os
import re
import sys
import tempfile
from pathlib import Path

# Commands run in-process enable the compilation cache: keep it out of the user's home.
os.environ.setdefault("HOISTSIM_CACHE_DIR", tempfile.mkdtemp(prefix="hoistsim-test-cache-"))

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
