"""Shared set-up: float64 JAX (hoistsim turns it on at import) and scene builders."""

from __future__ import annotations

import sys
from pathlib import Path

import hoistsim  # noqa: F401  (enables float64 before any test creates an array)

sys.path.insert(0, str(Path(__file__).parent))

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = ROOT / "scenarios"
