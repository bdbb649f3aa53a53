"""Every shipped scenario's figures, as `hoistsim run` then `hoistsim plot` make them, are legible: the events'
names apart and off the curves, under the title; every marker whole inside its panel (tests/figures/legible.py).
And the figures a user reads most closely answer: the compliant hoist's lowest point where the load is
lowest (the end of the run, not a ringing's turn), its burst of switches enlarged; Backlash titled by what it
is; CoupledClutches and the two-speed hoist with every switch named and each clutch's story in the title.

A run of each scene: a program of its own to compile for most (in this one process, so scenes of one
structure share theirs).  About 5 min on 2 cores: slow.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402
from click.testing import CliRunner  # noqa: E402
from helpers import SCENARIOS  # noqa: E402
from legible import event_names_apart, legible, panels  # noqa: E402

from hoistsim.cli import main  # noqa: E402
from hoistsim.figures.files import draw_figures  # noqa: E402
from hoistsim.figures.frames import FreshFrames  # noqa: E402

SHIPPED = sorted(SCENARIOS.glob("*.yaml")) + sorted((SCENARIOS / "modelica").glob("*.yaml"))


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
    "compliant_hoist": _compliant_hoist, "Backlash": _backlash,
    "coupled_clutches": _drawn_drivetrain("clutch1 locks 0.791 s, lets go 0.831 s, locks 0.907 s, lets go 1.000 s, "
                                          "opens 1.251 s"),
    "two_speed_hoist": _drawn_drivetrain("low_clutch locked from the start, lets go 1.263 s, opens 1.300 s"),
}


@pytest.mark.slow
@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: str(p.relative_to(SCENARIOS)))
def test_every_figure_of_a_shipped_scenario_is_legible(path, tmp_path):
    results = tmp_path / "run.h5"
    ran = CliRunner().invoke(main, ["run", str(path), "-o", str(results)])
    assert ran.exit_code == 0, ran.output
    figures, frames = {}, FreshFrames()
    for suffix, fig in draw_figures(results, plt, frames):
        legible(fig)
        figures[suffix] = fig
    assert figures
    if path.stem in NAMED:
        NAMED[path.stem](figures)
    for fig in figures.values():
        frames.done(plt, fig)
