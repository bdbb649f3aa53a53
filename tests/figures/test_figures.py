"""The figures answer the questions: panels from the elements present, phases, events, legends, families, summaries."""

from __future__ import annotations

import importlib.util
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from click.testing import CliRunner  # noqa: E402
from helpers import ROOT, SCENARIOS  # noqa: E402
from legible import event_names_apart, markers_inside  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

from hoistsim.cli import main  # noqa: E402
from hoistsim.figures.files import runs_columns  # noqa: E402
from hoistsim.figures.runs import THIN_TO, runs_figure  # noqa: E402
from hoistsim.figures.summary import summary_figure  # noqa: E402
from hoistsim.results.reading import read_runs  # noqa: E402


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """Results files: brake and engage at speed; direct start with bearings; the same at 2 kN, where it runs back."""
    folder = tmp_path_factory.mktemp("figures")
    files = {}
    for name, scenario, options in (
            ("engage_at_speed_with_brake", "engage_at_speed_with_brake", []),
            ("exercise6_direct_start", "exercise6_direct_start", []),
            # question 2's case, with the direct start's structure (no new compilation): it slips and runs back
            ("runback", "exercise6_direct_start", ["--set", "clutch.engagement_force=2000 N"]),
            # the brake lets go before the clutch closes: the load falls, turns round and is lifted
            ("turnaround", "engage_at_speed_with_brake", ["--set", "brake.release_time=0.3 s"])):
        files[name] = folder / f"{name}.h5"
        result = CliRunner().invoke(main, ["run", str(SCENARIOS / f"{scenario}.yaml"), "-o", str(files[name]),
                                           *options])
        assert result.exit_code == 0, result.output
    return files


def _figure(path, swept=("run", np.zeros(1), "")):
    runs = read_runs(path, columns=runs_columns())
    return runs_figure(runs, plt, swept), runs


def _panels(fig):
    return [ax for ax in fig.axes if ax.get_ylabel() and ax.get_label() != "<colorbar>"]


def _ylabels(fig):
    return [ax.get_ylabel().split(" [")[0] for ax in _panels(fig)]


def _vertical_lines(ax):
    return [line for line in ax.get_lines()
            if len(line.get_xdata()) == 2 and line.get_xdata()[0] == line.get_xdata()[1]]


def test_each_element_present_brings_its_panel_and_none_other(results):
    fig, _ = _figure(results["engage_at_speed_with_brake"])
    labels = _ylabels(fig)
    assert labels == ["shaft speed", "clutch slip", "clutch torque", "clutch heat", "load height", "load speed",
                      "brake torque"]
    plt.close(fig)
    fig, _ = _figure(results["exercise6_direct_start"])
    assert _ylabels(fig) == ["shaft speed", "clutch slip", "clutch torque", "clutch heat", "load height",
                             "load speed", "drum-shaft loads"]
    legend = [t.get_text() for t in _panels(fig)[-1].get_legend().get_texts()]
    assert legend == ["bearing A", "bearing B", "tooth force", "rope tension"]
    plt.close(fig)


def test_one_run_shades_its_phases_and_marks_every_event_in_every_panel(results):
    fig, runs = _figure(results["engage_at_speed_with_brake"])
    panels = _panels(fig)
    top = [t.get_text() for t in panels[0].get_legend().get_texts()]
    for phase in ("clutch open", "clutch locked", "brake holding"):
        assert phase in top
    events = {row["kind"]: float(row["time"]) for row in runs[0]["events"]
              if row["category"] in ("switch", "scheduled")}
    assert set(events) == {"engage", "brake_release", "lock"}
    for ax in panels:
        assert sorted(line.get_xdata()[0] for line in _vertical_lines(ax)) == sorted(events.values())
    names = [t.get_text() for t in panels[0].texts]
    assert sorted(names) == ["brake release", "clutch engage", "clutch lock"]  # named once, at the top, by element
    assert all(not ax.texts for ax in panels[1:])
    plt.close(fig)


@pytest.mark.parametrize("name, says", [
    ("exercise6_direct_start", "clutch never slips; load +2.1 m"),
    ("engage_at_speed_with_brake", "clutch engages at 0.500 s, locks 1.030 s, 1.30 kJ of heat; load +1.56 m"),
    ("runback", "clutch never locks (25.39 kJ of heat up to the end); load runs back 6.45 m"),
])
def test_the_title_says_what_happened(results, name, says):
    fig, _ = _figure(results[name])
    assert fig._suptitle.get_text().endswith(says)
    plt.close(fig)


def test_legends_sit_beside_the_panels_not_on_the_data(results):
    fig, _ = _figure(results["runback"])
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    for ax in _panels(fig):
        legend = ax.get_legend()
        if legend is not None:
            assert legend.get_window_extent(renderer).x0 >= ax.get_window_extent(renderer).x1 - 1
    plt.close(fig)


def test_every_text_lies_inside_the_figure_and_the_panels_keep_apart(results):
    """A run's figure and a few runs' are placed from their measured texts: nothing past the figure's
    edges, the title above the panels, no panel or legend on the next one, the y labels in one column, no
    event's name on another's nor on a curve, no marker cut by a panel's edge."""
    one = read_runs(results["engage_at_speed_with_brake"], columns=runs_columns())
    two = read_runs(results["runback"], columns=runs_columns()) + read_runs(results["exercise6_direct_start"],
                                                                             columns=runs_columns())
    for runs, swept in ((one, ("run", np.zeros(1), "")), (two, ("run", np.arange(2.0), ""))):
        fig = runs_figure(runs, plt, swept)
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        edge, panels = fig.bbox, _panels(fig)
        for ax in panels:
            tight = ax.get_tightbbox(renderer)  # ticks, labels, the right-hand scale and the legend
            assert tight.x0 >= edge.x0 - 1 and tight.x1 <= edge.x1 + 1, ax.get_ylabel()
            assert tight.y0 >= edge.y0 - 1 and tight.y1 <= edge.y1 + 1, ax.get_ylabel()
        title = fig._suptitle.get_window_extent(renderer)
        assert title.y1 <= edge.y1 + 1 and title.y0 >= panels[0].get_window_extent(renderer).y1
        for upper, lower in zip(panels, panels[1:]):
            below = lower.get_window_extent(renderer).y1
            assert upper.get_window_extent(renderer).y0 > below
            if upper.get_legend() is not None:
                assert upper.get_legend().get_window_extent(renderer).y0 >= below - 1, upper.get_ylabel()
        event_names_apart(fig)  # see also test_drawn_figures.py (events a few milliseconds apart) and
        markers_inside(fig)  # test_shipped_figures.py (every shipped scenario's figures)
        sides = [ax.yaxis.label.get_window_extent(renderer).x1 for ax in panels]  # the side facing the axes
        assert max(sides) - min(sides) < 1
        plt.close(fig)


def test_a_kept_frame_draws_the_same_figure_as_a_new_one(results, tmp_path):
    """`watch` keeps the last figure's panels and redraws on them: each figure is the one drawn afresh (to the
    anti-aliasing of a line's end: the panels' places agree to round-off), a new structure gets a new frame,
    and no figure is left open."""
    from PIL import Image

    from hoistsim.figures.files import plot_file
    from hoistsim.figures.frames import KeptFrames

    kept, open_before, frames_seen = KeptFrames(), set(plt.get_fignums()), []
    order = ["exercise6_direct_start", "runback", "engage_at_speed_with_brake", "turnaround", "exercise6_direct_start"]
    for name in order:
        plot_file(results[name], tmp_path / "fresh.png")
        plot_file(results[name], tmp_path / "kept.png", frames=kept, png_compression=1)
        frames_seen.append(kept._frame)
        fresh = np.asarray(Image.open(tmp_path / "fresh.png"), dtype=int)
        again = np.asarray(Image.open(tmp_path / "kept.png"), dtype=int)
        assert fresh.shape == again.shape, name
        differ = np.any(fresh != again, axis=2)
        assert differ.mean() < 1e-4, (name, int(differ.sum()))  # a dashed line's last dash, at most
    assert frames_seen[1] is frames_seen[0]  # another force: the same panels
    assert frames_seen[2] is not frames_seen[1]  # a brake: another panel, another frame
    assert frames_seen[3] is frames_seen[2] and frames_seen[4] is not frames_seen[3]
    assert set(plt.get_fignums()) - open_before == {frames_seen[-1].fig.number}  # only the kept one
    plt.close(frames_seen[-1].fig)


def test_the_load_position_panel_marks_where_a_load_that_ran_back_was_lowest(results):
    fig, runs = _figure(results["turnaround"])
    load = next(ax for ax in _panels(fig) if ax.get_ylabel().startswith("load height"))
    marked = [c for c in load.collections if c.get_label() == "lowest point"]
    (time, height), = marked[0].get_offsets()
    assert height == pytest.approx(runs[0]["attrs"]["lowest_load_position"], rel=1e-12) and height < -0.3
    assert time == pytest.approx(1.1678, abs=1e-4)  # where the rope speed goes through zero
    assert "load dips 0.353 m, ends +0.783 m" in fig._suptitle.get_text()
    plt.close(fig)
    fig, runs = _figure(results["runback"])  # a load that never turns round is lowest at the end of the run
    load = next(ax for ax in _panels(fig) if ax.get_ylabel().startswith("load height"))
    (time, height), = next(c for c in load.collections if c.get_label() == "lowest point").get_offsets()
    assert time == runs[0]["time"][-1] and height == pytest.approx(runs[0]["attrs"]["lowest_load_position"], rel=1e-12)
    assert _panels(fig)[3].get_xlim()[1] > time  # the time axis widened: the dot is whole
    plt.close(fig)
    fig, _ = _figure(results["engage_at_speed_with_brake"])  # a load that never goes below its start: no mark
    assert not [c for c in _panels(fig)[3].collections if c.get_label() == "lowest point"]
    plt.close(fig)


def _family(run, count):
    """count copies of a run, each a little faster and longer-slipping: a stand-in for a sweep's runs."""
    runs = []
    for i in range(count):
        copy = {k: (v * (1 + 0.01 * i) if isinstance(v, np.ndarray) and v.dtype.kind == "f" and k != "time" else v)
                for k, v in run.items()}
        copy["time"] = np.linspace(0.0, float(run["time"][-1]), 5000)
        for key in list(copy):
            if isinstance(copy[key], np.ndarray) and key not in ("time", "events") and len(copy[key]) == len(run["time"]):
                copy[key] = np.interp(copy["time"], run["time"], copy[key].astype(float))
        copy["attrs"] = dict(run["attrs"], label=f"clutch.engagement_force={1000 + i} N")
        runs.append(copy)
    return runs


def test_a_family_of_runs_is_colour_mapped_thinned_and_has_no_event_lines(results):
    base = read_runs(results["engage_at_speed_with_brake"], columns=runs_columns())[0]
    runs = _family(base, 300)
    fig = runs_figure(runs, plt, ("clutch.engagement_force", np.arange(300.0) + 1000, "N"))
    panels = _panels(fig)
    assert any(ax.get_label() == "<colorbar>" for ax in fig.axes)  # the swept value's colour bar
    for ax in panels:
        assert not _vertical_lines(ax)
        families = [c for c in ax.collections if isinstance(c, LineCollection)]
        assert families and all(len(s) <= 2 * THIN_TO + 2 for c in families for s in c.get_segments())
        assert len(families[0].get_segments()) == 300
    # peaks survive the thinning: the highest motor speed drawn is the highest there is
    speed = [c for c in panels[0].collections if isinstance(c, LineCollection)][0]
    drawn = max(s[:, 1].max() for s in speed.get_segments())
    assert drawn == pytest.approx(max(r["motor_speed"].max() for r in runs) * 30 / math.pi, rel=1e-12)
    # the lock instants are dots on the slip curves, one a run
    dots = [c for c in panels[1].collections if c.get_label() == "clutch locks"]
    assert len(dots[0].get_offsets()) == 300
    plt.close(fig)


HOIST = {"clutch": {}}  # a hoist's scenario (its values as a file keeps them): its summaries under its names


def _summaries(count):
    """Summary rows over a swept force: never locks below 30 %, never slips above 80 %, a lock-up between."""
    x = np.linspace(1000.0, 10000.0, count)
    rows = []
    for i, force in enumerate(x):
        share = i / max(count - 1, 1)
        lockup = math.nan if share < 0.3 else 0.0 if share > 0.8 else 1.0 - share
        rows.append({"label": f"f={force}", "lockup_time": lockup, "slip_duration": 0.0 if share > 0.8 else 0.5,
                     "slip_energy": 1000.0 * (1 - share), "peak_clutch_torque": force / 10,
                     "lowest_load_position": -1.0 if share < 0.3 else 0.0, "final_load_position": share})
    return x, rows


def test_never_locks_and_never_slips_are_marked_apart(results):
    x, rows = _summaries(12)
    fig = summary_figure(rows, ("clutch.engagement_force", x, "N"), plt, "demo", HOIST)
    lockup = fig.axes[0]
    assert lockup.get_ylabel() == "lock-up time [s]"
    never_locks = [line for line in lockup.get_lines() if line.get_marker() == "^"]
    never_slips = [line for line in lockup.get_lines() if line.get_marker() == "D"]
    assert len(never_locks[0].get_xdata()) == sum(math.isnan(r["lockup_time"]) for r in rows) == 4
    assert list(never_locks[0].get_ydata()) == [1.0] * 4  # at the panel's top edge, not at 0 s
    assert list(never_slips[0].get_ydata()) == [0.0] * 3
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "never locks (4 of 12 runs)" in legend and "never slips (locked from the start) (3 of 12 runs)" in legend
    assert any("clutch heat of a run that never locks: heat up to the end of the run" == t for t in legend)
    plt.close(fig)


def test_ten_thousand_runs_draw_as_bands_not_a_wall_of_marks():
    x, rows = _summaries(10_000)
    fig = summary_figure(rows, ("clutch.engagement_force", x, "N"), plt, "demo", HOIST)
    lockup = fig.axes[0]
    assert not [line for line in lockup.get_lines() if line.get_marker() in ("^", "D", "o")]
    assert len(lockup.patches) == 2  # one band a kind of run
    plt.close(fig)


def _figures_script():
    spec = importlib.util.spec_from_file_location("hoistsim_docs_figures", ROOT / "docs" / "figures.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.slow
def test_the_script_regenerates_the_readme_figures(tmp_path):
    script = _figures_script()
    written = script.regenerate(["engage_at_speed_with_brake", "force_sweep", "work_precision"], tmp_path,
                                progress=lambda text: None)
    assert sorted(p.name for p in written) == ["engage_at_speed_with_brake.png", "force_sweep.png",
                                                "force_sweep_summary.png", "work_precision.png"]
    for path in written:
        assert path.stat().st_size > 30_000
    pages = "\n".join(page.read_text() for page in [ROOT / "README.md", *(ROOT / "docs").rglob("*.md")])
    shown = {name for name in script.FIGURES if f"{name}.png" in pages}
    assert shown >= {"engage_at_speed_with_brake", "force_sweep", "engine_periodic", "engine_flywheel",
                     "work_precision"}


@pytest.mark.slow
def test_the_script_makes_the_periodic_figures(tmp_path):
    """The engine's and the press's periodic figures (the engine's flywheel sizing, ~4 min, is left to the script)."""
    written = _figures_script().regenerate(["slider_crank_periodic", "engine_periodic"], tmp_path,
                                           progress=lambda text: None)
    assert [p.name for p in written] == ["slider_crank_periodic.png", "engine_periodic.png"]


def test_round_off_is_drawn_flat_not_zoomed_into(results):
    """A clutch locked throughout has a slip of zero to round-off: its panel shows a flat line at 0 on a
    sensible scale, not 1e-14 rpm wiggles."""
    fig, _ = _figure(results["exercise6_direct_start"])
    assert _panels(fig)[1].get_ylim() == (-1.0, 1.0)
    plt.close(fig)


def test_the_clutch_temperature_against_its_limit_run_by_run_and_across_the_sweep(tmp_path):
    """Three forces of the force-window scenario: the temperature panel draws the limit and marks where each
    run overheats; the summary figure's peak-temperature panel draws the limit and bands the runs that
    overheat, the picture of the force window."""
    path = tmp_path / "window.h5"
    result = CliRunner().invoke(main, ["run", str(SCENARIOS / "clutch_force_window.yaml"), "-o", str(path),
                                       "--sweep", "clutch.engagement_force=4 kN,4.4 kN,6 kN"])
    assert result.exit_code == 0, result.output
    fig, runs = _figure(path, ("clutch.engagement_force", np.array([4000.0, 4400.0, 6000.0]), "N"))
    panel = next(ax for ax in _panels(fig) if ax.get_ylabel().startswith("clutch temperature"))
    limit = [line for line in panel.get_lines() if line.get_linestyle() == ":"]
    assert limit and np.allclose(limit[0].get_ydata(), 80.0)  # degC, across the run
    overheats = [c for c in panel.collections if c.get_label() == "overheat"]
    assert len(overheats) == 1 and len(overheats[0].get_offsets()) == 2  # the 4 and 4.4 kN runs
    plt.close(fig)
    from hoistsim.figures.files import plot_file

    written = plot_file(path, tmp_path / "window.png")
    assert [p.rsplit("/", 1)[-1] for p in written] == ["window.png", "window_summary.png"]
    from hoistsim.figures.files import scenario_parameters, swept_axis
    from hoistsim.results.reading import read_summary

    rows = read_summary(path)
    fig = summary_figure(rows, swept_axis(path, rows), plt, "window", scenario_parameters(path))
    peak = next(ax for ax in fig.axes if ax.get_ylabel() == "peak clutch temperature [degC]")
    assert [line.get_ydata()[0] for line in peak.get_lines() if line.get_linestyle() == ":"] == [80.0]
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "overheats (2 of 3 runs)" in legend and "max temperature (80 degC)" in legend
    plt.close(fig)
