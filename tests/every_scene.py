"""Every scene the project shows a user, as a user runs it: ``hoistsim run SCENE -o OUT.h5`` (a sweep's every
run), the file opened with h5py and as the README says (``hoistsim.open_results``), then ``hoistsim plot``'s
figures drawn from that file and held to what every figure must be (legible.py).

The scenes are the shipped scenarios (``scenarios/*.yaml``), the Modelica examples (``scenarios/modelica``) and
every ``yaml`` block of README.md and the site's pages (docs/, every folder) that is a whole scene; each has a test
module of its own, so the two test processes share them out.  A scene that simulates but cannot be written (a bearing friction
once named its heat ``<name>_energy`` both as a series and as a summary) fails here, a block a user would copy
that does not load at all fails here, and so does a figure whose names run over each other or its curves.

A block that is not a whole scene is said so in :data:`FRAGMENTS`, with the reason; none is skipped unsaid.
"""

from __future__ import annotations

import re

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from click.testing import CliRunner  # noqa: E402
from helpers import ROOT  # noqa: E402
from legible import event_names_apart, legible, panels  # noqa: E402

import hoistsim  # noqa: E402
from hoistsim.cli import main  # noqa: E402
from hoistsim.figures.files import draw_figures  # noqa: E402
from hoistsim.figures.frames import FreshFrames  # noqa: E402
from hoistsim.scenario.sweep_runs import SweepRuns  # noqa: E402

DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
_YAML_BLOCK = re.compile(r"^```ya?ml[ \t]*\n(.*?)^```", re.S | re.M)

# Blocks of the documents that are not a whole scene, by their file and first line: why each is not.
FRAGMENTS = {
    ("docs/scenario-files.md", "name: exercise6-direct-start"):
        "the reference of every key of a hoist scene: alternatives side by side (`gears:` given twice), "
        "not one scene",
    ("docs/how-to/buffer.md", "buffer:"): "the buffer's section alone, as it stands in scenarios/load_onto_a_buffer.yaml "
                                          "(run whole by the shipped scenarios' test)",
}

# The cheap ones, run by the quick loop too (`-m "not slow"`): a hoist and a Modelica example, seconds each.
QUICK = {"scenarios/first_scenario.yaml", "scenarios/modelica/First.yaml"}


def blocks() -> list[tuple[str, int, str]]:
    """Every yaml block of the documents: (its file, relative to the repository; its first line; its text)."""
    found = []
    for document in DOCUMENTS:
        text = document.read_text(encoding="utf-8")
        for match in _YAML_BLOCK.finditer(text):
            found.append((document.relative_to(ROOT).as_posix(), text[: match.start()].count("\n") + 2,
                          match.group(1)))
    return found


def fragment(path: str, text: str) -> tuple[str, str] | None:
    """The key of :data:`FRAGMENTS` that says a block is no whole scene; None for a scene."""
    first = text.lstrip().splitlines()[0] if text.strip() else ""
    return next((key for key in FRAGMENTS if key[0] == path and first.startswith(key[1])), None)


def _param(name, path, text):
    return pytest.param(name, path, text, id=name, marks=() if name in QUICK else pytest.mark.slow)


def files_in(folder) -> list:
    """A test case for each scenario file of ``folder``: (its name, its path, None)."""
    return [_param(path.relative_to(ROOT).as_posix(), path, None) for path in sorted(folder.glob("*.yaml"))]


def document_scenes() -> list:
    """A test case for each yaml block of the documents that is a whole scene: ("FILE:LINE", None, its text)."""
    return [_param(f"{path}:{line}", None, text) for path, line, text in blocks() if fragment(path, text) is None]


# ---------------------------------------------------------------- what some figures must say, by the scene's file
def _compliant_hoist(figures):
    """The load ran back to -0.152 m by the end of the run: marked there, once; the first 30 ms enlarged."""
    fig = figures[""]
    load = next(ax for ax in panels(fig) if ax.get_ylabel().startswith("load height"))
    (time, height), = next(c for c in load.collections if c.get_label() == "lowest point").get_offsets()
    assert time == 1.0 and height == pytest.approx(-0.152, abs=5e-4)
    zooms = [ax for ax in panels(fig) if not ax.get_ylabel()]
    assert zooms and zooms[0].get_xlim()[1] < 0.05
    enlarged = [t.get_text() for t in zooms[0].texts if t.get_gid() == "event name"]
    assert len(enlarged) == 7 and not [name for name in enlarged if "/" in name]  # each switch named


def _backlash(figures):
    assert figures[""]._suptitle.get_text().startswith("Backlash: Modelica.Mechanics.Rotational.Examples.Backlash")


def _drawn_drivetrain(says):
    """CoupledClutches (a lock as another clutch engages, 6.6 ms apart) and the two-speed shift (three switches
    within 41 ms): every switch named, each clutch's story in the title, capacities and heat drawn."""
    def check(figures):
        fig = figures[""]
        assert sum(len(name.split(" / ")) for name in event_names_apart(fig)) >= 4
        assert says in fig._suptitle.get_text().replace("\n    ", " ").replace(";\n", "; ")
        labels = [ax.get_ylabel() for ax in panels(fig)]
        assert any(label.startswith("clutch heat") for label in labels)
        for ax in panels(fig):
            if ax.get_ylabel().endswith("torque [N*m]") and "\n" in ax.get_ylabel():
                assert "static capacity" in [t.get_text() for t in ax.get_legend().get_texts()]

    return check


NAMED = {
    "scenarios/compliant_hoist.yaml": _compliant_hoist,
    "scenarios/modelica/Backlash.yaml": _backlash,
    "scenarios/coupled_clutches.yaml": _drawn_drivetrain(
        "clutch1 locks at 0.791 s, lets go 0.831 s, locks 0.907 s, lets go 1.000 s, opens 1.251 s"),
    "scenarios/two_speed_hoist.yaml": _drawn_drivetrain("low_clutch locked from the start, lets go at 1.263 s, "
                                                        "opens 1.300 s"),
}


def never_twice(events, name) -> None:
    """No instant found twice: a restart never fires again on the root it stopped at (the same kind of instant of
    the same element of one run, within 1e-12 s of the last)."""
    run, time = events["run"][()], events["time"][()]
    kind, element = events["kind"].asstr()[()], events["element"].asstr()[()]
    order = np.lexsort((time, element, kind, run))
    same = ((run[order][1:] == run[order][:-1]) & (kind[order][1:] == kind[order][:-1])
            & (element[order][1:] == element[order][:-1]))
    close = np.diff(time[order]) <= 1e-12
    twice = order[1:][same & close]
    assert not twice.size, (name, [(kind[i], element[i], float(time[i])) for i in twice[:5]])


def runs_to_a_legible_file(name, path, text, tmp_path, monkeypatch) -> None:
    """The scene run through the command line to a file with rows in every series, and its figures legible."""
    monkeypatch.chdir(tmp_path)  # anything a scene writes beside the file stays here
    if path is None:  # a block of a document, saved as a user would save it
        path = tmp_path / "scene.yaml"
        path.write_text(text, encoding="utf-8")
    runs = len(SweepRuns(hoistsim.load_scenario(path)))
    out = tmp_path / "out.h5"
    result = CliRunner().invoke(main, ["run", str(path), "-o", str(out)])
    assert result.exit_code == 0, (name, result.output, result.exception)
    assert f"wrote {out}" in result.output
    with h5py.File(out, "r") as f:
        assert "scenario" in f and f["runs/time"].shape[0] > 1
        if "events" in f["runs"]:
            never_twice(f["runs/events"], name)
    with hoistsim.open_results(out) as ds:
        assert ds.sizes["run"] == runs and ds.sizes["time"] > 1
        series = [key for key, values in ds.data_vars.items() if values.dims == ("run", "time")]
        summaries = [key for key, values in ds.data_vars.items() if values.dims == ("run",)]
        assert series and "label" in summaries and "energy_residual" in summaries
        for key in series:  # every run has its row at t = 0 and at the end, in every series
            values = ds[key].isel(time=[0, -1]).values
            assert np.isfinite(values).all(), (name, key)
    figures, frames = {}, FreshFrames()
    for suffix, fig in draw_figures(out, plt, frames):  # as `hoistsim plot OUT.h5` draws them
        legible(fig)
        figures[suffix] = fig
    assert figures
    if name in NAMED:
        NAMED[name](figures)
    for fig in figures.values():
        frames.done(plt, fig)
