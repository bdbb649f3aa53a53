"""The terminal's tables: within the width they are given (stacked blocks, each repeating the row's label, or the
columns that fit), every value still shown, aligned, units under the names."""

from __future__ import annotations

import math

import pytest

from hoistsim.results.report import (OPTIONAL_COLUMNS, PERIODIC_COLUMNS, SUMMARY_COLUMNS, compare_table, csv_text,
                                     fitted_table, periodic_table, summary_table)
from hoistsim.results.summary_display import summary_header


def _summary(label: str, i: int) -> dict:
    """A run with every column the summary table knows, drawn clutches' too (values that differ run by run)."""
    keys = [key for key, _, _ in SUMMARY_COLUMNS + PERIODIC_COLUMNS]
    keys += [key for extra in OPTIONAL_COLUMNS.values() for key, _, _ in extra]
    summary = {"label": label, "clutch1_lockup_time": 0.7913 + i, "clutch2_slip_energy": 6.138 * (i + 1)}
    summary.update({key: (n + 1) * 1.2345 + 10 * i for n, key in enumerate(keys)})
    summary["lockup_time"] = math.nan if i == 0 else 0.25 * i  # a clutch that never locks: "-"
    return summary


RUNS = [_summary(f"clutch.engagement_force={3 + i} kN", i) for i in range(4)]


def _blocks(text: str) -> list[list[str]]:
    return [block.splitlines() for block in text.split("\n\n")]


def _values(block: list[str], label_width: int) -> list[list[str]]:
    """A block's rows below its rule, each as its cells after the label."""
    rule = next(i for i, line in enumerate(block) if line.startswith("---"))
    return [line[label_width:].split() for line in block[rule + 1:]]


@pytest.mark.parametrize("width", [80, 120])
@pytest.mark.parametrize("table", [summary_table, periodic_table])
def test_a_run_table_fits_the_width_in_blocks_and_keeps_every_value(table, width):
    wide = table(RUNS, width=None)
    fitted = table(RUNS, width=width)
    assert max(len(line) for line in fitted.splitlines()) <= width
    label_width = max(len(s["label"]) for s in RUNS)
    [whole], blocks = _blocks(wide), _blocks(fitted)
    assert len(blocks) > 1 or table is periodic_table  # the whole summary is 200 characters or more
    for block in blocks:  # each block repeats the label column, every run in its order
        rule = next(i for i, line in enumerate(block) if line.startswith("---"))
        assert [line[:label_width].strip() for line in block[rule + 1:]] == [s["label"] for s in RUNS]
    # every value of the wide table, in the same order, once the blocks are read side by side
    side_by_side = [sum(cells, []) for cells in zip(*(_values(block, label_width) for block in blocks))]
    assert side_by_side == _values(whole, label_width)


def test_a_block_is_aligned_with_its_units_under_the_names():
    text = summary_table(RUNS[:1], width=80)
    block = _blocks(text)[0]
    rule = next(i for i, line in enumerate(block) if line.startswith("---"))
    names, units, row = block[:rule - 1], block[rule - 1], block[rule + 1]
    assert "[s]" in units and "[kJ]" in units and "lock-up" in names[-1]  # each clutch's heat as the hoist's
    spans = [(m.start(), m.end()) for m in __import__("re").finditer("-+", block[rule])]
    for line in [*names, units, row]:  # every cell inside its column's rule, numbers right-aligned to its end
        for start, end in spans[1:]:
            cell = line[start:end]
            assert line[end:end + 1] in ("", " ") and (not cell.strip() or cell.endswith(cell.strip()))
    assert "clutch1" in names[0] and "heat" in names[1]  # a name wider than its values wraps at its space


def test_wide_is_one_block_with_whole_names():
    text = summary_table(RUNS, width=None)
    assert "\n\n" not in text and "clutch heat" in text.splitlines()[0]


def test_a_long_sweep_shows_its_ends_and_says_how_to_see_all():
    runs = [_summary(f"run {i}", i) for i in range(30)]
    text = summary_table(runs, width=80)
    assert max(len(line) for line in text.splitlines()) <= 80
    assert "run 0 " in text and "run 29" in text and "run 15" not in text and "..." in text
    assert text.splitlines()[-1] == "(30 runs; all of them: hoistsim compare OUT.h5 [--csv])"


def _file_rows():
    rows = [{"label": s["label"], "clutch.engagement_force": 3000.0 + 1000 * i,
             **{k: v for k, v in s.items() if k != "label"}} for i, s in enumerate(RUNS)]
    units = {name: "s" if name.endswith("time") else "N" if name == "clutch.engagement_force" else "1"
             for name in rows[0] if name != "label"}
    return rows, units


@pytest.mark.parametrize("width", [80, 120])
def test_compare_shows_the_columns_that_fit(width):
    rows, units = _file_rows()
    text = compare_table(rows, units, width=width)
    lines = text.splitlines()
    assert max(len(line) for line in lines) <= width and "\n\n" not in text
    assert lines[-1].startswith("(") and "--wide" in lines[-1] and "--columns" in lines[-1]
    rule = next(i for i, line in enumerate(lines) if line.startswith("---"))
    assert lines[rule - 1].split()[:2] == ["[N]", "[s]"]  # the swept key, then the lock-up time
    # the labels only say the swept values: the values name the runs, in one format (never 3000 then 1e+04)
    assert [line.split()[0] for line in lines[rule + 1:-1]] == ["3000", "4000", "5000", "6000"]
    assert "clutch.engagement_force=" not in text
    # the questions first: when the clutch locks, its heat, where the load went; headed as the run's table is
    heads = " ".join(lines[:rule])
    for name in ("lock-up", "heat", "lowest", "final"):
        assert name in heads, (name, text)
    assert heads.index("lowest") < heads.index("peak") and "_" not in heads.replace("engagement_", "")
    wider = compare_table(rows, units, width=width + 40)
    assert len(wider.splitlines()[rule + 1]) > len(lines[rule + 1])  # a wider terminal: more columns


@pytest.mark.parametrize("width", [None, 80])
def test_compare_shows_a_summary_as_the_run_table_does(width):
    """One formatter: a file's summary (SI, its units row) compared, the columns the run's table shows, prints
    that table, header, unit, scale and number format alike (clutch heat in kJ, speeds in rpm, never
    slip_energy [J])."""
    rows, _ = _file_rows()
    si = {"lockup_time": "s", "slip_duration": "s", "slip_energy": "J", "peak_clutch_torque": "N*m",
          "peak_slip_speed": "rad/s", "final_motor_speed": "rad/s", "peak_clutch_temperature": "K",
          "peak_rope_force": "N", "clutch2_slip_energy": "J", "clutch1_lockup_time": "s"}
    run_table = summary_table(RUNS, width=width)
    shown = ["clutch1_lockup_time", "clutch2_slip_energy"]
    for key, _, _ in SUMMARY_COLUMNS:
        shown += [key] + [extra for extra, _, _ in OPTIONAL_COLUMNS.get(key, ())]
    assert compare_table(rows, si, ["label", *shown], width=width) == run_table
    assert "[kJ]" in run_table and "[rpm]" in run_table and "slip_energy" not in run_table


@pytest.mark.parametrize("width", [80, 120])
def test_compare_of_chosen_columns_stacks_them(width):
    rows, units = _file_rows()
    chosen = ["label", *[n for n in rows[0] if n != "label"]]
    text = compare_table(rows, units, chosen, width=width)
    assert max(len(line) for line in text.splitlines()) <= width and "more column" not in text
    whole = compare_table(rows, units, chosen, width=None)
    label_width = max(len(r["label"]) for r in rows)
    side_by_side = [sum(cells, []) for cells in zip(*(_values(block, label_width) for block in _blocks(text)))]
    assert side_by_side == _values(whole.splitlines(), label_width)


def test_compare_wide_has_every_column_unwrapped():
    rows, units = _file_rows()
    text = compare_table(rows, units, width=None)
    head = text.splitlines()[0]
    assert head.split()[:3] == ["run", "clutch.engagement_force", "lock-up"] and "more column" not in text
    for name in rows[0]:  # every column, under the header the run's table gives it
        assert summary_header(name)[0].partition(" [")[0] in head or name == "label", name


def test_a_name_wraps_at_its_underscores_and_dots():
    text = fitted_table(["label", "clutch.engagement_force [N]", "peak_clutch_torque [N*m]"],
                        [["a", "3000", "156.2"]], width=80)
    lines = text.splitlines()
    assert [line.split() for line in lines[:4]] == [["clutch.", "peak_"], ["engagement_", "clutch_"],
                                                      ["label", "force", "torque"], ["[N]", "[N*m]"]]


def test_csv_has_a_units_row():
    rows, units = _file_rows()
    lines = csv_text(rows, units).splitlines()
    assert lines[0].split(",")[:2] == ["label", "clutch.engagement_force"] and lines[1].split(",")[:2] == ["", "N"]
    assert len(lines) == 2 + len(rows) and lines[2].startswith("clutch.engagement_force=3 kN,3000.0,")


def test_a_label_wider_than_the_width_still_gives_a_table():
    text = fitted_table(["run", "lock-up [s]", "heat [J]"], [["x" * 50, "0.5", "12"]], width=40)
    assert [line.split()[-1] for line in text.splitlines() if line.startswith("x")] == ["0.5", "12"]


def test_a_column_reads_in_one_number_format():
    from hoistsim.results.report import column_cells

    assert column_cells([3000.0, 6000.0, 9000.0, 12000.0]) == ["3000", "6000", "9000", "12000"]
    assert column_cells([0.35, 1.0301, math.nan, None]) == ["0.350", "1.030", "-", "-"]
    assert column_cells([406.9, 12.26]) == ["406.9", "12.3"]
    assert column_cells([3.5e-10, 1e-12]) == ["3.500e-10", "1.000e-12"]  # very small: scientific
    assert column_cells([2.5e5, 1.5]) == ["2.500e+05", "1.500e+00"]  # very large: scientific, all of them
    assert column_cells([2.5e5, 1.0]) == ["250000", "1"]  # whole numbers as such
    assert column_cells([5e-4, 40.0]) == ["5.000e-04", "4.000e+01"]  # decimals would print the small one as 0
    assert column_cells(["3 kN", True, 2]) == ["3 kN", "yes", "2"]


def test_a_sweep_file_compares_with_one_format_per_column_at_120():
    """A force swept past 10 kN prints as 9000 then 12000; where the load went is in view at 120 columns."""
    rows, units = _file_rows()
    for row, force in zip(rows, (3000.0, 6000.0, 9000.0, 12000.0)):
        row["clutch.engagement_force"] = force
    text = compare_table(rows, units, width=120)
    lines = text.splitlines()
    rule = next(i for i, line in enumerate(lines) if line.startswith("---"))
    assert [line.split()[0] for line in lines[rule + 1:-1]] == ["3000", "6000", "9000", "12000"]
    for column in zip(*(line.split() for line in lines[rule + 1:-1])):  # each column: one count of decimals
        assert len({len(cell.partition(".")[2]) for cell in column if cell != "-"}) == 1, column


def _sensitivity():
    from hoistsim.results.sensitivity_result import Sensitivity

    keys = {"clutch.engagement_force": 5000.0, "clutch.kinetic_friction": 0.1, "load.mass": 500.0}
    return Sensitivity(
        name="engage-at-speed-with-brake", keys=keys,
        key_units={"clutch.engagement_force": "N", "clutch.kinetic_friction": "1", "load.mass": "kg"},
        values={"lockup_time": 1.03013, "slip_energy": 1302.41, "lowest_load_position": 0.0},
        units={"lockup_time": "s", "slip_energy": "J", "lowest_load_position": "m"},
        derivatives={"lockup_time": dict(zip(keys, (-3.9122e-4, -19.561, 0.002408))),
                     "slip_energy": dict(zip(keys, (-0.68105, -34052.0, 4.7304))),
                     "lowest_load_position": dict(zip(keys, (0.0, math.nan, 0.0)))},
        tables=("clutch.engagement_force",))


@pytest.mark.parametrize("width", [60, 80])
def test_a_sensitivity_table_and_its_notes_fit_the_width(width):
    """The notes wrap at their words (the elasticity's was 101 characters, whatever the width)."""
    from hoistsim.results.report import sensitivity_table

    text = sensitivity_table(_sensitivity(), width)
    assert max(len(line) for line in text.splitlines()) <= width, text
    words = " ".join(text.split())
    assert "per relative change of the key" in words and "every force scaled with it)" in words
    assert "1.03013 s" in text and "1302.41 J" in text


def test_a_sensitivity_as_json_has_each_summary_value_and_unit():
    """`sensitivity --json`: each summary's value (the one its table prints) and unit beside its derivatives."""
    import json

    result = _sensitivity()
    printed = json.loads(json.dumps(result.to_dict()))
    assert printed["lockup_time"]["value"] == 1.03013 and printed["lockup_time"]["unit"] == "s"
    assert printed["slip_energy"]["value"] == 1302.41 and printed["slip_energy"]["unit"] == "J"
    assert printed["lockup_time"]["load.mass"] == {"derivative": 0.002408, "unit": "s/kg",
                                                   "elasticity": pytest.approx(500 / 1.03013 * 0.002408)}
    assert printed["lowest_load_position"]["value"] == 0.0
    assert printed["lowest_load_position"]["clutch.kinetic_friction"]["derivative"] is None  # none exists


def test_the_flywheel_answers_fit_the_width_every_word_kept():
    """`flywheel`'s answers (102 characters however narrow the terminal): the quantities wrapped at their words."""
    import types

    from hoistsim.results.report import flywheel_table

    numbers = dict.fromkeys(["mean_speed", "energy_fluctuation", "flywheel_as_given", "irregularity_as_given",
                             "irregularity_tredgold_as_given", "machine_inertia", "required_inertia_tredgold",
                             "flywheel_inertia_tredgold", "irregularity_with_tredgold_flywheel",
                             "flywheel_inertia", "irregularity_with_flywheel"], 12.345678)
    rim = {"outer_diameter": 0.6, "inner_diameter": 0.0, "width": 0.08, "mass": 180.0, "density": 7200.0}
    sizing = types.SimpleNamespace(irregularity=0.01, shaft="motor", candidates=[1] * 7, rim=rim, **numbers)
    whole, fitted = flywheel_table("engine-hoist-flywheel", sizing, 1.5), flywheel_table(
        "engine-hoist-flywheel", sizing, 1.5, width=80)
    assert max(len(line) for line in whole.splitlines()) > 80 >= max(len(line) for line in fitted.splitlines())
    assert sorted(whole.replace("-", " ").split()) == sorted(fitted.replace("-", " ").split())
