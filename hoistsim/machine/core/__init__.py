"""The core: bodies, couplings, the restart loop, the ledger.  It names no part of the machine."""

from ... import _jax  # noqa: F401  (float64 before any array of the core exists)
