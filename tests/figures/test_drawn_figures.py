"""The run figure of a drawn drivetrain answers like the hoist's: event names that never overlap, each clutch's
story and heat in the title, its torque against its static capacity, its heat, one legend entry a kind of mark;
legends that show only what the run has.

Drawn from runs made here (columns and events as a results file gives them back), so no solver is compiled;
the shipped CoupledClutches and two-speed hoist are run in test_shipped_figures.py.
"""

from __future__ import annotations

import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from legible import event_names_apart, markers_inside, panels  # noqa: E402

from hoistsim.display import headline  # noqa: E402
from hoistsim.display.holding_brake import HOLDING_BRAKE  # noqa: E402
from hoistsim.display.rope import ROPE  # noqa: E402
from hoistsim.figures.naming import wrap_title  # noqa: E402
from hoistsim.figures.runs import _shade, runs_figure  # noqa: E402
from hoistsim.results.reading import events_table  # noqa: E402
from hoistsim.scenario.lowering import output_names  # noqa: E402

T = np.linspace(0.0, 2.5, 2501)
ONE = ("run", np.zeros(1), "")
# a shift as the two-speed hoist's, then a burst of switches within 20 ms, then a lock as another engages
EVENTS = [(1.2, "engage", "high", "switch"), (1.2632, "unlock", "low", "switch"), (1.3, "disengage", "low", "switch"),
          (1.304, "lock", "high", "switch"), (1.6, "lock", "low", "switch"), (1.605, "unlock", "low", "switch"),
          (1.61, "lock", "low", "switch"), (1.615, "unlock", "low", "switch"), (1.62, "lock", "low", "switch"),
          (2.0, "engage", "third", "switch"), (2.0066, "lock", "high", "switch"), (2.2, "slip_peak", "high",
                                                                                     "observation")]


def _run(events=EVENTS, summary=None):
    """A drawn run read back: three shafts, three clutches (the low one locked from the start, its torque both
    ways), every clutch's columns, the events given."""
    clutches = {"low": {"between": ["a", "b"]}, "high": {"between": ["a", "c"]}, "third": {"between": ["c", "b"]}}
    run = {"time": T, "a_speed": 10 * (1 - np.exp(-T)), "b_speed": 5 * (1 - np.exp(-T)), "c_speed": 2 * T}
    for i, name in enumerate(clutches):
        run[f"{name}_slip"] = np.sin((i + 1) * T)
        run[f"{name}_torque"] = 300 * np.cos((i + 1) * T) + (0 if name == "low" else 300)  # only low's goes below 0
        run[f"{name}_capacity"] = np.full_like(T, 700.0)
        run[f"{name}_energy"] = 200 * (i + 1) * T  # low 0.5 kJ, third 1.5 kJ at the end: drawn in kJ
    table = events_table({"time": np.array([e[0] for e in events]), "kind": np.array([e[1] for e in events]),
                          "element": np.array([e[2] for e in events]), "torque_margin": np.full(len(events), np.nan),
                          "mode_after": np.array(["locked"] * len(events)), "category": np.array([e[3] for e in events])})
    summary = summary if summary is not None else {
        "low_lockup_time": 0.0, "low_slip_energy": 4.14, "high_lockup_time": 1.304, "high_slip_energy": 236.6,
        "third_lockup_time": np.nan, "third_slip_energy": 1500.0}
    run["events"] = table
    run["attrs"] = {"name": "drawn", "parameters": json.dumps({"drivetrain": {
        "shafts": {"a": {}, "b": {}, "c": {}}, "clutches": clutches}}), **summary}
    return run


def _panels(fig):
    return [ax for ax in fig.axes if ax.get_ylabel()]


def _event_names_apart(fig):
    """No two event names on each other, each above the top panel (off its curves) or the enlarged burst's
    top panel: their texts."""
    names = event_names_apart(fig)
    tops = [_panels(fig)[0], *_zooms(fig)[:1]]
    assert not [t.get_text() for ax in fig.axes if ax not in tops for t in ax.texts if t.get_gid() == "event name"]
    return names


def _zooms(fig):
    """The enlarged burst's panels, beside the run's (no label of their own: they share the run's scales)."""
    return [ax for ax in panels(fig) if not ax.get_ylabel()]


def test_event_names_never_overlap_and_name_every_switch():
    fig = runs_figure([_run()], plt, ONE)
    names = _event_names_apart(fig)
    said = " / ".join(names)
    for text in ("high engage", "low unlock", "low disengage", "high lock", "third engage"):
        assert text in said
    assert "slip peak" not in said  # an observation is a row, not a line
    plt.close(fig)


def test_event_names_of_a_burst_share_a_name_and_stay_inside_the_panel():
    """Twenty switches within 40 ms, one at the panel's very start and one at its end: enlarged beside the run,
    where they are still too many to name one by one."""
    burst = [(0.0, "lock", "low", "switch"), (2.5, "unlock", "high", "switch")]
    burst += [(1.0 + 0.002 * i, "lock" if i % 2 else "unlock", "low", "switch") for i in range(20)]
    fig = runs_figure([_run(burst)], plt, ONE)
    names = _event_names_apart(fig)
    assert len(names) < 22 and any(name.endswith("events)") for name in names)
    assert markers_inside(fig) >= 2  # the locks at the run's first instant and in the burst
    plt.close(fig)


def test_a_burst_of_events_in_a_sliver_of_the_run_is_enlarged_beside_it_each_event_named():
    """A compliant shaft's ringing: the clutch lets go and relocks seven times in the first 30 ms of a 2.5 s run.
    A column of panels beside the run's shows those 30 ms, each switch named; the run's panel names them once."""
    times = [0.0074, 0.0118, 0.0150, 0.0200, 0.0221, 0.0276, 0.0290]
    burst = [(t, "unlock" if i % 2 == 0 else "lock", "low", "switch") for i, t in enumerate(times)]
    fig = runs_figure([_run(burst + [(1.6, "engage", "third", "switch")])], plt, ONE)
    zooms = _zooms(fig)
    assert len(zooms) == len(_panels(fig)) > 0
    low, high = zooms[0].get_xlim()
    assert low <= times[0] and times[-1] <= high and high - low < 0.05 * 2.5  # the burst, and the run's start
    event_names_apart(fig)
    enlarged = [t.get_text() for t in zooms[0].texts if t.get_gid() == "event name"]
    assert sorted(enlarged) == sorted(["low unlock"] * 4 + ["low lock"] * 3)  # each named, none merged
    said = [t.get_text() for t in _panels(fig)[0].texts if t.get_gid() == "event name"]
    assert said == ["7 events, enlarged \u2192", "third engage"]
    plt.close(fig)


def test_two_names_either_side_of_two_close_lines_stand_a_name_apart():
    """CoupledClutches: clutch3 engages at 0.900 s and clutch1 locks at 0.907 s; their names, on either side of
    the two lines, must not touch: a name's width apart, or one name for both."""
    fig = runs_figure([_run([(0.4, "engage", "high", "switch"), (0.900, "engage", "third", "switch"),
                             (0.907, "lock", "low", "switch")])], plt, ONE)
    said = " / ".join(_event_names_apart(fig))
    assert all(name in said for name in ("high engage", "third engage", "low lock"))
    plt.close(fig)


def test_the_lowest_point_is_the_runs_lowest_not_a_turn_of_a_ringing():
    """A load that rings 40 um below its start in the first 30 ms (three turns, each an observation), then runs
    back to -0.152 m at the end of the run, still falling: one lowest point, at the end, inside the panel."""
    turns = [0.007, 0.015, 0.021]
    run = _run([(t, "load_lowest", "load", "observation") for t in turns])
    ringing = -40e-6 * np.abs(np.sin(np.pi * T / 0.0075)) * (T < 0.03)
    run["load_position"] = ringing - 0.152 * (T / T[-1]) ** 2
    fig = runs_figure([run], plt, ONE)
    load = next(ax for ax in _panels(fig) if ax.get_ylabel().startswith("load height"))
    marked = [c for c in load.collections if c.get_label() == "lowest point"]
    assert len(marked) == 1 and len(marked[0].get_offsets()) == 1
    (time, height), = marked[0].get_offsets()
    assert (time, height) == (T[-1], pytest.approx(-0.152))
    assert markers_inside(fig) >= 1
    plt.close(fig)


def test_a_scene_whose_parts_tell_nothing_is_titled_by_what_it_is():
    """Modelica's Backlash: two inertias on springs, no clutch, no load: the title says the scene's description,
    not its bare name."""
    run = {"time": T, "a_speed": np.sin(T), "b_speed": np.cos(T)}
    run["events"] = events_table({"time": np.array([]), "kind": np.array([], str), "element": np.array([], str),
                                  "torque_margin": np.array([]), "mode_after": np.array([], str),
                                  "category": np.array([], str)})
    run["attrs"] = {"name": "Backlash", "parameters": json.dumps({
        "description": "two inertias on springs,\n  the second's with play",  # as YAML's folded text keeps it
        "drivetrain": {"shafts": {"a": {}, "b": {}}}})}
    fig = runs_figure([run], plt, ONE)
    assert fig._suptitle.get_text() == "Backlash: two inertias on springs, the second's with play"
    plt.close(fig)


def test_the_title_tells_each_clutchs_story_and_its_heat():
    run = _run()
    said = headline({**run["attrs"], "events": run["events"]})
    stories = dict(part.split(" ", 1) for text in said for part in text.split("; "))
    # seven switches: told by their counts
    assert stories["low"] == "locked from the start, locks 3 times (first at 1.600 s), lets go 3 times, opens " \
                             "once, 4.14 J of heat"
    assert stories["high"] == "engages at 1.200 s, locks 1.304 s, locks 2.007 s, 237 J of heat"
    assert stories["third"] == "engages at 2.000 s, 1.50 kJ of heat"
    # the summary alone (hoistsim watch): the first lock, never "locks at 0"
    alone = headline(run["attrs"])[0]
    assert alone.startswith("low locked from the start, 4.14 J of heat; high first locks at 1.304 s")
    assert "third never locks (1.50 kJ of heat up to the end)" in alone


def test_the_hoists_clutch_tells_its_story_as_a_drawn_one_under_the_names_its_file_keeps():
    """The hoist's summary keeps its clutch's lock-up time as lockup_time: its names table gives the clutch's
    own, and one display tells a hoist's clutch's story as a drawn one's."""
    events = _run([(1.821, "lock", "clutch", "switch"), (2.5, "unlock", "clutch", "switch"),
                   (4.9, "lock", "clutch", "switch")])["events"]
    names = output_names({"clutch": {}})
    summary = {"lockup_time": 1.821, "slip_energy": 13230.0, "slip_duration": 6.4}
    said = headline({**summary, "events": events}, names)
    assert said[0] == "clutch locks at 1.821 s, lets go 2.500 s, locks 4.900 s, 13.23 kJ of heat"
    assert headline(summary, names)[0] == "clutch first locks at 1.821 s, 13.23 kJ of heat"
    assert headline(summary) == []  # without its names table: no part of the hoist's names is a coupling's


def test_a_long_title_is_wrapped_between_clutches_and_stays_above_the_panels():
    fig = runs_figure([_run()], plt, ONE)
    title = fig._suptitle.get_text()
    assert "\n" in title and all(len(line) <= 125 for line in title.splitlines())
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    assert fig._suptitle.get_window_extent(renderer).y0 >= _panels(fig)[0].get_window_extent(renderer).y1
    assert fig._suptitle.get_window_extent(renderer).y1 <= fig.bbox.y1 + 1
    plt.close(fig)
    assert wrap_title("n", ["a; b"]) == "n: a; b" and wrap_title("n", []) == "n"


def test_each_clutch_torque_against_its_capacity_and_every_clutchs_heat():
    fig = runs_figure([_run()], plt, ONE)
    panels = {ax.get_ylabel(): ax for ax in _panels(fig)}
    for name in ("low", "high", "third"):
        legend = [t.get_text() for t in panels[f"{name}\ntorque [N*m]"].get_legend().get_texts()]
        # the capacity's other side only where the torque goes there
        assert legend == ["transmitted", "static capacity"] + (["- static capacity"] if name == "low" else [])
    heat = panels["clutch heat [kJ]\n(so far)"]
    assert [t.get_text() for t in heat.get_legend().get_texts()] == ["low", "high", "third"]
    assert max(np.max(line.get_ydata()) for line in heat.get_lines()) == pytest.approx(1.5)  # kJ
    plt.close(fig)


def test_one_legend_entry_a_kind_of_mark():
    events = [(0.5, "lock", "low", "switch"), (0.7, "lock", "high", "switch"), (0.9, "lock", "third", "switch")]
    fig = runs_figure([_run(events)], plt, ONE)
    slips = next(ax for ax in _panels(fig) if ax.get_ylabel().startswith("clutch slip"))
    legend = [t.get_text() for t in slips.get_legend().get_texts()]
    assert legend.count("clutch locks") == 1 and len([c for c in slips.collections if c.get_label()]) == 3
    plt.close(fig)


def test_legends_show_only_what_the_run_has():
    """A rope slack only at the first instant shades nothing and has no legend entry; a brake whose torque goes
    negative is not "holding the load up"."""
    fig, ax = plt.subplots()
    _shade([ax], {"time": T, "rope_taut": np.r_[0, np.ones(len(T) - 1)]}, ROPE.shading)
    assert not ax.get_legend_handles_labels()[1]
    _shade([ax], {"time": T, "rope_taut": (T > 1).astype(int)}, ROPE.shading)
    assert ax.get_legend_handles_labels()[1] == ["rope slack"]
    plt.close(fig)
    up = HOLDING_BRAKE.panels_of({"brake_torque": np.array([0.0, 900.0])})[0].traces[0].label
    both = HOLDING_BRAKE.panels_of({"brake_torque": np.array([900.0, -900.0])})[0].traces[0].label
    assert up == "holding the load up" and "holding the load up" not in both


def test_the_summary_legend_shows_the_markers_it_draws():
    from hoistsim.figures.summary import summary_figure

    rows = [{"label": str(i), "lockup_time": np.nan if i < 2 else 0.5, "slip_duration": 0.5, "slip_energy": 1.0,
             "peak_clutch_torque": 1.0} for i in range(5)]
    fig = summary_figure(rows, ("clutch.engagement_force", np.arange(5.0), "N"), plt, "demo", {"clutch": {}})
    legend = fig.legends[0]
    index = [t.get_text() for t in legend.get_texts()].index("never locks (2 of 5 runs)")
    from matplotlib.lines import Line2D

    assert index == 0 and "^" in [line.get_marker() for line in legend.findobj(Line2D)]
    assert markers_inside(fig) >= 2  # "never locks" at the top of each panel with no value for it: not cut off
    plt.close(fig)


def test_a_kept_frame_with_an_enlarged_burst_draws_the_same_figure_as_a_new_one():
    """`watch` keeps the frame: its enlarged column emptied and redrawn for the next run's burst, pixel for pixel
    the figure drawn afresh (and the figure's height, grown for the last names, set back)."""
    from hoistsim.figures.frames import FreshFrames, KeptFrames

    first = [(0.0074 + 0.003 * i, "unlock" if i % 2 == 0 else "lock", "low", "switch") for i in range(7)]
    second = [(1.0 + 0.004 * i, "lock" if i % 2 == 0 else "unlock", "high", "switch") for i in range(5)]
    kept = KeptFrames()
    frames = [runs_figure([_run(first)], plt, ONE, kept)]
    fig = runs_figure([_run(second)], plt, ONE, kept)
    assert fig is frames[0] and any(not ax.get_ylabel() for ax in panels(fig))  # the same frame, enlarged
    fig.canvas.draw()
    again = np.asarray(fig.canvas.buffer_rgba()).copy()
    fresh = runs_figure([_run(second)], plt, ONE, FreshFrames())
    fresh.canvas.draw()
    drawn = np.asarray(fresh.canvas.buffer_rgba())
    assert again.shape == drawn.shape
    assert np.any(again != drawn, axis=2).mean() < 1e-4
    plt.close(fig)
    plt.close(fresh)
