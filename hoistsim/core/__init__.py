"""The core: bodies, couplings, the restart loop, the ledger.  It names no part of the machine."""
