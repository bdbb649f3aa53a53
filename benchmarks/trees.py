"""This tree beside another commit's, for the benchmarks' ``--against COMMIT``: a git worktree, removed after."""

from __future__ import annotations

import contextlib
import os
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


@contextlib.contextmanager
def trees(folder, against: str | None):
    """``{label: root}`` in the order to measure them: ``against``'s worktree (made in ``folder``) first where
    one is asked for, then this tree as "now"."""
    if not against:
        yield {"now": ROOT}
        return
    other = Path(folder) / "against"
    subprocess.run(["git", "worktree", "add", "--detach", str(other), against], cwd=ROOT, check=True,
                   capture_output=True)
    try:
        yield {against: other, "now": ROOT}
    finally:
        subprocess.run(["git", "worktree", "remove", "--force", str(other)], cwd=ROOT, capture_output=True)


def user_environment(**settings) -> dict:
    """This process's environment with ``settings``, as a user's shell starts Python: keeping each module's
    bytecode.  A container may set PYTHONDONTWRITEBYTECODE, which has every start of a command compile
    hoistsim's hundred modules from source again (0.1 s of a warm run on 2 cores): set ``KEEP_ENVIRONMENT=1``
    to measure with the environment as it is."""
    environment = dict(os.environ, **settings)
    if os.environ.get("KEEP_ENVIRONMENT") != "1":
        environment.pop("PYTHONDONTWRITEBYTECODE", None)
    return environment
