"""Save to figure under `hoistsim watch`: from writing a new value into the scenario to the new figure in place.

A `hoistsim watch SCENARIO -o OUT.h5 --plot FIG.png` process is started on a copy of a shipped
scenario and left to compile; then a value is changed and saved `--saves` times, each time
waiting for the figure file to be replaced (its inode changes: the figure is moved into place
whole).  Median and spread of the seconds from the save to the replaced figure, and to the
headline on stdout.

    python benchmarks/watch_latency.py [--saves 15] [--scenario exercise6_direct_start.yaml]
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
KEY = re.compile(r"^(\s*engagement_force:\s*).*$", re.MULTILINE)


def _inode(path: Path) -> int:
    try:
        return path.stat().st_ino
    except FileNotFoundError:
        return -1


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--saves", type=int, default=15)
    parser.add_argument("--scenario", default="exercise6_direct_start.yaml")
    options = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        scenario, figure = folder / "scene.yaml", folder / "scene.png"
        text = (ROOT / "scenarios" / options.scenario).read_text(encoding="utf-8")
        assert KEY.search(text), "the scenario needs a clutch.engagement_force line"
        scenario.write_text(text, encoding="utf-8")
        env = dict(os.environ, HOISTSIM_CACHE_DIR=str(folder / "cache"), PYTHONUNBUFFERED="1")
        errors = open(folder / "stderr.txt", "w+", encoding="utf-8")
        proc = subprocess.Popen([sys.executable, "-m", "hoistsim.cli", "watch", str(scenario), "-o",
                                 str(folder / "scene.h5"), "--plot", str(figure)], cwd=ROOT, env=env,
                                stdout=subprocess.PIPE, stderr=errors, text=True)

        def waiting(done) -> None:
            """Until ``done()``; a watch that stopped is an error, with what it said on stderr."""
            while not done():
                if proc.poll() is not None:
                    errors.seek(0)
                    raise SystemExit(f"the watch stopped (exit {proc.returncode}): {errors.read().strip()}")
                time.sleep(0.001)

        lines: list[tuple[float, str]] = []
        reader = threading.Thread(target=lambda: [lines.append((time.perf_counter(), line)) for line in proc.stdout],
                                  daemon=True)
        reader.start()
        try:
            waiting(lambda: _inode(figure) != -1 and len(lines) >= 1)  # the first run: its headline and figure
            to_figure, to_headline = [], []
            for i in range(options.saves):
                time.sleep(0.3)  # the watch at rest, as between a user's saves
                before, seen = _inode(figure), len(lines)
                force = 2600 + 100 * (i % 8)  # a new value each save: the clutch slips, locks or not
                edited = KEY.sub(lambda m: f"{m.group(1)}{force} N", text)
                started = time.perf_counter()
                scenario.write_text(edited, encoding="utf-8")
                waiting(lambda: _inode(figure) != before)
                to_figure.append(time.perf_counter() - started)
                waiting(lambda: len(lines) > seen)
                to_headline.append(lines[seen][0] - started)
        finally:
            proc.terminate()
            proc.wait(10)
    print(f"scenario: {options.scenario}, {options.saves} saves of a new engagement force")
    print(f"save -> figure replaced:   median {statistics.median(to_figure):.3f} s "
          f"(min {min(to_figure):.3f}, max {max(to_figure):.3f})")
    print(f"save -> headline printed:  median {statistics.median(to_headline):.3f} s")


if __name__ == "__main__":
    main()
