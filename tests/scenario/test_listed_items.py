"""A sweep's long lists read as a template and its numbers: the same data as YAML's, or YAML reads them."""

from __future__ import annotations

import io

import pytest
from helpers import SCENARIOS
from ruamel.yaml import YAML

from hoistsim import load_scenario
from hoistsim.errors import ScenarioError
from hoistsim.scenario import listed_items
from hoistsim.scenario.listed_items import LONG, cut_long_lists
from hoistsim.scenario.yamlsource import read_yaml

BASE = (SCENARIOS / "engage_at_speed_with_brake.yaml").read_text()
COUNT = LONG + 9


def _yaml(text: str):
    return YAML(typ="safe", pure=False).load(io.StringIO(text))


def _same(a, b) -> bool:
    """Equal, and of the same types all the way down (an int is not a float)."""
    if isinstance(a, dict):
        return isinstance(b, dict) and list(a) == list(b) and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(map(_same, a, b))
    return type(a) is type(b) and a == b


def _listed(items: list[str], key: str = "clutch.engagement_force", after: str = "") -> str:
    return BASE + "sweep:\n  " + key + ":" + "".join(f"\n    - {item}" for item in items) + "\n" + after


READ_AS_COLUMNS = {
    "force tables": [f"[[0 s, 0 N], [0.5 s, 0 N], [0.6 s, {3000 + 7.25 * k:.3f} N]]" for k in range(COUNT)],
    "forces, units": [f"{k + 1} kN" for k in range(COUNT)],
    # whole numbers and decimals mixed: YAML's int and float, item by item
    "bare numbers": [f"{k}" if k % 3 else f"{k}.5" for k in range(COUNT)],
    "signs and exponents": [f"[[0 s, {-k}e-3 N*m], [1.5e0 s, +{k}.0 N*m]]" for k in range(COUNT)],
    "inertias": [f"{0.01 * (k + 1):.4f} kg*m^2" for k in range(COUNT)],
}


@pytest.mark.parametrize("name", READ_AS_COLUMNS)
def test_a_long_list_read_as_columns_is_what_yaml_reads(name):
    text = _listed(READ_AS_COLUMNS[name], after="  load.mass: [400 kg, 500 kg]\n")
    assert cut_long_lists(text, _yaml) is not None  # read as columns, not by YAML
    assert _same(read_yaml(text, "s.yaml").data, _yaml(text))


LEFT_TO_YAML = {
    "quoted": [f"'{k} kN'" for k in range(COUNT)],
    "a comment after an item": [f"{k} kN  # note" for k in range(COUNT)],
    "words that are not strings": ["true" if k % 2 else "false" for k in range(COUNT)],
    "hexadecimal": [f"0x{k:x}1" for k in range(COUNT)],
    "leading zeros": [f"0{k + 1}" for k in range(COUNT)],
    "another form midway": [f"{k} kN" if k != COUNT // 3 else f"[{k} kN]" for k in range(COUNT)],
    "an alias": ["&a 1 kN"] + ["*a" for _ in range(COUNT - 1)],
    "a mapping": [f"{{force: {k} kN}}" for k in range(COUNT)],
}


@pytest.mark.parametrize("name", LEFT_TO_YAML)
def test_a_list_not_of_one_plain_form_is_left_to_yaml(name):
    text = _listed(LEFT_TO_YAML[name])
    assert _same(read_yaml(text, "s.yaml").data, _yaml(text))


@pytest.mark.parametrize("tail", [
    "    # a comment, then more items\n    - 1 kN\n",  # the list goes on after a comment: all of it is YAML's
    "      - 1 kN\n",  # an item indented further (a nested list: YAML's to say)
    "    - [1 kN,\n       2 kN]\n",  # an item over two lines
])
def test_a_list_that_goes_on_past_its_one_line_items_is_left_to_yaml(tail):
    text = _listed([f"{k} kN" for k in range(COUNT)]) + tail
    try:
        expected = _yaml(text)
    except Exception:  # noqa: BLE001  (YAML refuses it: so must the reading)
        with pytest.raises(ScenarioError):
            read_yaml(text, "s.yaml")
        return
    assert cut_long_lists(text, _yaml) is None
    assert _same(read_yaml(text, "s.yaml").data, expected)


def test_a_short_list_is_yamls():
    assert cut_long_lists(_listed([f"{k} kN" for k in range(LONG - 1)]), _yaml) is None


def test_a_bad_value_in_a_long_list_is_named_by_its_line(tmp_path):
    items = [f"{k + 1} kN" for k in range(COUNT)]
    items[LONG + 2] = "5 kg"
    path = tmp_path / "s.yaml"
    path.write_text(_listed(items))
    with pytest.raises(ScenarioError) as caught:
        load_scenario(path)
    line = path.read_text().splitlines().index(f"    - {items[LONG + 2]}") + 1
    assert caught.value.line == line and caught.value.key == "sweep.clutch.engagement_force"
    assert f"value {LONG + 3} (5 kg)" in caught.value.message


def test_a_long_listed_sweep_gives_the_runs_yaml_alone_gives(tmp_path, monkeypatch):
    path = tmp_path / "s.yaml"
    path.write_text(_listed(READ_AS_COLUMNS["force tables"]))
    fast = load_scenario(path)
    monkeypatch.setattr(listed_items, "LONG", 10**9)
    slow = load_scenario(path)
    key = "clutch.engagement_force"
    assert fast.provenance.raw == slow.provenance.raw
    assert list(fast.provenance.swept[key].validated) == list(slow.provenance.swept[key].validated)
    assert fast.provenance.swept[key].labels == slow.provenance.swept[key].labels
