"""docs/output.md, the results file's reference: it is what the code that writes the files writes now (regenerate
with ``python -m hoistsim.results.file_reference``), it names every series, summary, ledger term and event kind of
every shipped scenario's machine, and it reads as Markdown on the site: no <name> taken for a tag, no link that
leaves docs/ or misses its heading."""

from __future__ import annotations

import html
import re
import types

import pytest

from hoistsim.machine.assemble import machine_elements
from hoistsim.machine.core.layout import Layout
from hoistsim.results import file_reference
from hoistsim.results.file_reference import COMMAND, PATH, ROOT, SCENARIOS, Page, main
from hoistsim.results.output import summary_units
from hoistsim.scenario.loading import load_scenario
from hoistsim.scenario.lowering import output_names
from hoistsim.scenario.reference import anchor

DOC = ROOT / PATH
SHIPPED = sorted(SCENARIOS.rglob("*.yaml"))


@pytest.fixture(scope="module")
def page() -> str:
    return Page().text()


def test_the_page_is_what_the_code_writes_now(page):
    """Stale: run the command this names to write it again."""
    assert DOC.read_text(encoding="utf-8") == page, f"{PATH} is stale: run {COMMAND}"


def test_check_exits_1_where_the_page_is_stale(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(file_reference, "Page", lambda: types.SimpleNamespace(text=lambda: "the page\n"))
    written = tmp_path / "output.md"
    assert main(["--check", str(written)]) == 1 and "stale" in capsys.readouterr().out
    assert main([str(written)]) == 0 and written.read_text(encoding="utf-8") == "the page\n"
    assert main(["--check", str(written)]) == 0


def _names(page: str, section: str) -> set[str]:
    """The names in the first column of every table of a section (``## Series`` to the next ``## ``)."""
    text = page.split(f"\n## {section}\n", 1)[1].split("\n## ", 1)[0]
    return set(re.findall(r"^\| `([^`]+)` \|", text, flags=re.MULTILINE))


def _strings(value) -> set[str]:
    """Every key and text of a scenario's resolved values: the names its parts, shafts and blocks go by."""
    if isinstance(value, dict):
        return set(value) | {s for v in value.values() for s in _strings(v)}
    if isinstance(value, list | tuple):
        return {s for v in value for s in _strings(v)}
    return {value} if isinstance(value, str) else set()


def _pattern(patterns: set[str], names: set[str], columns: set[str]) -> re.Pattern:
    """The page's names as one pattern, each word in them standing for one of a machine's names (``<loss>`` for
    one of its series)."""
    def alternatives(words: set[str]) -> str:
        return "(?:" + "|".join(map(re.escape, sorted(words, key=len, reverse=True))) + ")"

    def regex(name: str) -> str:
        return "".join(alternatives(columns if part == "<loss>" else names) if re.fullmatch(r"<[\w ]+>", part)
                       else re.escape(part) for part in re.split(r"(<[\w ]+>)", name))

    return re.compile("|".join(f"(?:{regex(name)})" for name in sorted(patterns)))


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: str(p.relative_to(SCENARIOS)))
def test_every_output_of_every_shipped_machine_is_on_the_page(page, path):
    scenario = load_scenario(path)
    built = Layout(machine_elements(scenario))
    layout = built.named(output_names(scenario))
    names = set(built.shafts) | set(built.sections) | _strings(scenario.resolved())
    columns = set(layout.columns())
    outputs = {"Series": columns, "Summaries": set(summary_units(layout)), "Events": set(layout.event_kinds),
               "Run variables": set(layout.ledger_kinds) - {"kinetic_energy"}}
    for section, found in outputs.items():
        pattern = _pattern(_names(page, section), names, columns)
        missing = [name for name in found if not pattern.fullmatch(name)]
        assert not missing, f"{section} of {path.name} not on the page: {missing}"


def test_every_summary_and_series_says_what_it_is(page):
    """A part's output without words (a series' description, a summary's pattern in summary_meanings) shows as an
    empty meaning; those that have none yet are named here, so that a new one fails."""
    rows = re.findall(r"^\| `([^`]+)` \| [^|]* \|  \|", page, flags=re.MULTILINE)
    assert set(rows) <= {"<name>_lower_impact_loss", "<name>_upper_impact_loss", "<name>_peak_friction"}, rows


def test_it_reads_as_markdown_on_the_site(page):
    prose = re.sub(r"```.*?```", "", page, flags=re.DOTALL)  # fenced blocks keep their <i> as text
    assert not re.search(r"<[A-Za-z]", re.sub(r"`[^`\n]*`", "", prose)), "a <word> outside code: write &lt;word&gt;"
    targets = {anchor(html.unescape(line.lstrip("#").strip())) for line in page.splitlines() if line.startswith("#")}
    links = re.findall(r"\]\(([^)]*)\)", prose)
    assert links and all(link.startswith("#") or link.startswith("scenario.md#") for link in links), links
    assert not [link for link in links if link.startswith("#") and link[1:] not in targets]
    scenario_targets = {anchor(html.unescape(line.lstrip("#").strip())) for line in (ROOT / "docs" / "scenario.md")
                        .read_text(encoding="utf-8").splitlines() if line.startswith("#")}
    assert not [link for link in links if link.startswith("scenario.md#") and link[12:] not in scenario_targets]
    for table in (block for block in prose.split("\n\n") if block.startswith("| ")):
        cells = [len(re.findall(r"(?<!\\)\|", row)) for row in table.splitlines()]
        assert set(cells) == {cells[0]}, table  # every row as many cells as its header
