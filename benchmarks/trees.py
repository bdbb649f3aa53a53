"""This tree beside another commit's, for the benchmarks' ``--against COMMIT``: a git worktree, removed after."""

from __future__ import annotations

import contextlib
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
