"""Save to figure under `hoistsim watch`: from writing a new value into the scenario to the new figure in place.

A `hoistsim watch SCENARIO -o OUT.h5 --plot FIG.png` process is started on a copy of a shipped
scenario and left to compile; then a value is changed and saved `--saves` times, each time
waiting for the figure file to be replaced (its inode changes: the figure is moved into place
whole).  Median and spread of the seconds from the save to the replaced figure, and to the
headline on stdout.  With ``--against COMMIT`` that commit's watch (a git worktree) runs beside
this tree's and the saves alternate between them.

    python benchmarks/watch_latency.py [--saves 15] [--scenario exercise6_direct_start.yaml] [--against COMMIT]
"""

from __future__ import annotations

import argparse
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from trees import trees, user_environment

ROOT = Path(__file__).resolve().parents[1]
KEY = re.compile(r"^(\s*engagement_force:\s*).*$", re.MULTILINE)


def _inode(path: Path) -> int:
    try:
        return path.stat().st_ino
    except FileNotFoundError:
        return -1


class Watching:
    """A `hoistsim watch` process of one tree on its own copy of the scenario; :meth:`save` times one save."""

    def __init__(self, root: Path, folder: Path, text: str):
        folder.mkdir()
        self.text, self.scenario, self.figure = text, folder / "scene.yaml", folder / "scene.png"
        self.scenario.write_text(text, encoding="utf-8")
        env = user_environment(HOISTSIM_CACHE_DIR=str(folder / "cache"), PYTHONUNBUFFERED="1", PYTHONPATH=str(root))
        self.errors = open(folder / "stderr.txt", "w+", encoding="utf-8")
        self.proc = subprocess.Popen([sys.executable, "-m", "hoistsim.cli", "watch", str(self.scenario), "-o",
                                      str(folder / "scene.h5"), "--plot", str(self.figure)], cwd=root, env=env,
                                     stdout=subprocess.PIPE, stderr=self.errors, text=True)
        self.lines: list[tuple[float, str]] = []
        threading.Thread(target=lambda: [self.lines.append((time.perf_counter(), line)) for line in self.proc.stdout],
                         daemon=True).start()

    def waiting(self, done) -> None:
        """Until ``done()``; a watch that stopped is an error, with what it said on stderr."""
        while not done():
            if self.proc.poll() is not None:
                self.errors.seek(0)
                raise SystemExit(f"the watch stopped (exit {self.proc.returncode}): {self.errors.read().strip()}")
            time.sleep(0.001)

    def started(self) -> None:
        """The first run (it compiles): its headline and figure."""
        self.waiting(lambda: _inode(self.figure) != -1 and len(self.lines) >= 1)

    def save(self, force: float) -> tuple[float, float]:
        """Seconds from a save of a new force to the figure replaced, and to the headline printed."""
        before, seen = _inode(self.figure), len(self.lines)
        edited = KEY.sub(lambda m: f"{m.group(1)}{force} N", self.text)
        started = time.perf_counter()
        self.scenario.write_text(edited, encoding="utf-8")
        self.waiting(lambda: _inode(self.figure) != before)
        to_figure = time.perf_counter() - started
        self.waiting(lambda: len(self.lines) > seen)
        return to_figure, self.lines[seen][0] - started

    def stop(self) -> None:
        self.proc.terminate()
        self.proc.wait(10)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--saves", type=int, default=15)
    parser.add_argument("--scenario", default="exercise6_direct_start.yaml")
    parser.add_argument("--against", default=None, help="a commit whose watch is timed beside this tree's, "
                                                        "save by save")
    options = parser.parse_args()
    text = (ROOT / "scenarios" / options.scenario).read_text(encoding="utf-8")
    assert KEY.search(text), "the scenario needs a clutch.engagement_force line"
    with tempfile.TemporaryDirectory() as folder, trees(folder, options.against) as roots:
        folder = Path(folder)
        watches, times = {}, {label: [] for label in roots}
        try:
            for label, root in roots.items():  # one at a time: each compiles its first run
                watches[label] = Watching(root, folder / f"watch-{label}", text)
                watches[label].started()
            for i in range(options.saves):
                for label, watched in watches.items():  # alternating: both trees in the same minutes
                    time.sleep(0.3)  # the watches at rest, as between a user's saves
                    times[label].append(watched.save(2600 + 100 * (i % 8)))  # slips, locks or not
        finally:
            for watched in watches.values():
                watched.stop()
    print(f"scenario: {options.scenario}, {options.saves} saves of a new engagement force"
          + (" to each tree, alternating" if options.against else ""))
    for label, pairs in times.items():
        to_figure, to_headline = [p[0] for p in pairs], [p[1] for p in pairs]
        print(f"{label:<10} save -> figure replaced: median {statistics.median(to_figure):.3f} s "
              f"(min {min(to_figure):.3f}, max {max(to_figure):.3f}); "
              f"save -> headline printed: median {statistics.median(to_headline):.3f} s")


if __name__ == "__main__":
    main()
