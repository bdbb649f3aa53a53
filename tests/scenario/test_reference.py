"""docs/scenario.md, the scenario reference: written from the schema, it has every key, and it is the file the
schema writes now (regenerate with ``python -m hoistsim.scenario.reference``)."""

from __future__ import annotations

import html
import re
import types
import typing
from pathlib import Path

import pytest
from click.testing import CliRunner

from hoistsim.cli import main
from hoistsim.errors import ScenarioError
from hoistsim.scenario.loading import load_scenario
from hoistsim.scenario.reference import COMMAND, PATH, anchor, reference
from hoistsim.scenario.schema import Scenario
from hoistsim.scenario.schema_base import Section

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / PATH


def _sections_of(annotation) -> list[tuple[str, type]]:
    """("" | "<name>" | "[]", model) for each section a key may hold."""
    found = []
    union = typing.get_origin(annotation) in (typing.Union, types.UnionType)
    for member in typing.get_args(annotation) if union else (annotation,):
        origin = typing.get_origin(member)
        inner = typing.get_args(member)[-1] if origin in (dict, list) else member
        if isinstance(inner, type) and issubclass(inner, Section):
            found.append(({dict: ".<name>", list: "[]"}.get(origin, ""), inner))
    return found


def schema_keys(model=Scenario, prefix: str = "") -> list[str]:
    """Every key a scenario may give, dotted from the top (``drivetrain.shafts.<name>.inertia``), walked from the
    schema apart from the generator."""
    keys = []
    for name, field in model.model_fields.items():
        if field.exclude:
            continue
        keys.append(prefix + name)
        for suffix, sub in _sections_of(field.annotation):
            keys += schema_keys(sub, f"{prefix}{name}{suffix}.")
    return keys


def tables_of(text: str) -> dict[str, dict[str, str]]:
    """Each heading's table: key -> its row."""
    found: dict[str, dict[str, str]] = {}
    heading = None
    for line in text.splitlines():
        if line.startswith("#"):
            heading = html.unescape(line.lstrip("#").strip())  # <name> is written as entities
            found[heading] = {}
        elif heading is not None and (match := re.match(r"\| `([A-Za-z_0-9]+)` \|", line)):
            found[heading][match.group(1)] = line
    return found


TOP = "The scenario's top keys"


def table_of(section: str, tables: dict) -> str | None:
    """The heading whose table has a section's keys: its own, or the one its row links to (a section met before:
    a ripple on the drum is the motor's)."""
    if not section:
        return TOP
    if section in tables:
        return section
    holder = section.removesuffix(".<name>").removesuffix("[]")  # the key that holds the section
    parent, _, name = holder.rpartition(".")
    heading = table_of(parent, tables)
    row = tables[heading].get(name, "") if heading is not None else ""
    link = re.search(r"\[keys of `([^`]+)`\]\(#([^)]+)\)", row)
    return link.group(1) if link is not None and link.group(1) in tables else None


def documented(key: str, tables: dict) -> bool:
    section, _, leaf = key.rpartition(".")
    heading = table_of(section, tables)
    return heading is not None and leaf in tables[heading]


def test_the_reference_is_the_schema_now():
    """Stale: run the command this names to write it again."""
    assert DOC.read_text(encoding="utf-8") == reference(), f"docs/scenario.md is stale: run {COMMAND}"


def test_every_key_of_the_schema_has_its_row():
    tables = tables_of(DOC.read_text(encoding="utf-8"))
    missing = [key for key in schema_keys() if not documented(key, tables)]
    assert not missing, missing
    assert len(schema_keys()) > 150  # the walk reached the drivetrain's parts


def test_every_row_says_what_its_key_means():
    """A key added to the schema without a description (``Field(description=...)``) has an empty meaning."""
    rows = [row for table in tables_of(DOC.read_text(encoding="utf-8")).values() for row in table.values()]
    assert not [row for row in rows if row.rstrip().endswith("|  |")]


def test_every_link_reaches_a_heading():
    text = DOC.read_text(encoding="utf-8")
    targets = {anchor(html.unescape(line.lstrip("#").strip())) for line in text.splitlines() if line.startswith("#")}
    links = re.findall(r"\]\(#([^)]+)\)", text)
    assert links and not [link for link in links if link not in targets]


def test_rows_read_as_an_engineer_writes():
    """Units in the user's words, no reST or Python types leaking into the document."""
    text = DOC.read_text(encoding="utf-8")
    for leak in (":class:", "``", "| float |", "| int |", "TimeSignal", "NoneType", "typing."):
        assert leak not in text, leak
    rows = tables_of(text)
    assert "rpm" in rows["motor"]["no_load_speed"] and "N*m" in rows["motor"]["stall_torque"]
    assert "kg*m^2" in rows["drum"]["inertia"] and "> 0 deg, < 90 deg" in rows["clutch"]["half_angle"]
    assert "20 degC" in rows["drivetrain.heat_capacitors.<name>"]["temperature"]
    assert "[[speed, torque], ...]" in rows["motor"]["torque_speed"]
    assert "one of `tsit5`" in rows["simulation"]["solver"]
    assert ("Give one of: `stall_torque` + `no_load_speed`, or `rated_power` + `rated_speed` + `no_load_speed`, or "
            "`breakdown_torque` + `breakdown_slip` + `no_load_speed`") in text


def test_each_way_of_giving_a_thing_names_keys_there_are():
    def visit(model, seen):
        for way in model.alternatives:
            for key in (k.strip() for alternative in way for k in alternative.split("+")):
                assert " " in key or key in model.model_fields, (model.__name__, key)
        for field in model.model_fields.values():
            for _, sub in _sections_of(field.annotation):
                if sub not in seen:
                    seen.add(sub)
                    visit(sub, seen)

    visit(Scenario, {Scenario})


def test_the_readme_links_the_reference_and_nothing_outside_the_repository():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "(docs/scenario.md)" in readme
    assert "../" not in readme and "contract.md" not in readme


def test_run_help_names_the_reference():
    out = CliRunner().invoke(main, ["run", "--help"]).output
    assert PATH in out


@pytest.mark.parametrize("text, key", [("motr:\n  inertia: 1\n", "motr"),
                                       ("drivetrain:\n  shafts: {a: {inertia: 1, sped: 1}}\n", "sped")])
def test_an_unknown_key_names_the_reference_in_one_line(tmp_path, text, key):
    path = tmp_path / "bad.yaml"
    path.write_text("name: bad\nsimulation: {duration: 1 s, output_interval: 0.1 s}\n" + text)
    with pytest.raises(ScenarioError) as caught:
        load_scenario(path)
    message = str(caught.value)
    assert "unknown key" in message and key in message and PATH in message and "\n" not in message
