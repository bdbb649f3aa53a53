"""The documentation site's gallery (docs/gallery/, written by docs/gallery.py from the runs; nothing is run here):
every shipped scenario and every Modelica example has its page and its figures, every page is in mkdocs.yml's
navigation between the gallery's markers and nothing else is, each page's commands run a scenario that is there,
and each Modelica example's page states a worst deviation from Dymola below the tolerance its tests hold it to."""

from __future__ import annotations

import re

import pytest
from helpers import ROOT, SCENARIOS

from hoistsim.references.modelica_signals import COMPARISONS

GALLERY = ROOT / "docs" / "gallery"
NAV_START, NAV_END = "# the gallery's pages: written by docs/gallery.py", "# end of the gallery's pages"
FIGURE_BYTES, GALLERY_BYTES = 150_000, 12_000_000  # a figure's, the whole gallery's


def _scenes() -> dict[str, tuple[str, str | None]]:
    """Each page's slug -> (its scenario, relative to the repository; its example's key among the comparisons)."""
    scenes = {p.stem: (p, None) for p in SCENARIOS.glob("*.yaml")}
    scenes |= {f"modelica-{p.stem}": (p, p.stem) for p in (SCENARIOS / "modelica").glob("*.yaml")}
    scenes |= {f"modelica-translational-{p.stem}": (p, f"translational/{p.stem}")
               for p in (SCENARIOS / "modelica" / "translational").glob("*.yaml")}
    return {slug: (path.relative_to(ROOT).as_posix(), example) for slug, (path, example) in scenes.items()}


SCENES = _scenes()


def _page(slug: str) -> str:
    return (GALLERY / f"{slug}.md").read_text(encoding="utf-8")


def _nav_pages() -> list[str]:
    """The pages listed between mkdocs.yml's gallery markers."""
    text = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    assert NAV_START in text and NAV_END in text, "mkdocs.yml has no gallery markers"
    between = text[text.index(NAV_START) + len(NAV_START):text.index(NAV_END)]
    return re.findall(r"(gallery/\S+\.md)\s*$", between, re.MULTILINE)


@pytest.mark.parametrize("slug", sorted(SCENES))
def test_every_scene_has_its_page_and_its_figures(slug):
    page = _page(slug)
    assert page.startswith("# "), slug
    figures = re.findall(r"!\[[^\]]*\]\(([^)]+\.png)\)", page)
    assert f"{slug}.png" in figures or f"{slug}_summary.png" in figures, figures
    if SCENES[slug][1] in COMPARISONS:
        assert f"{slug}_dymola.png" in figures, figures
    for figure in figures:
        assert (GALLERY / figure).is_file(), figure


@pytest.mark.parametrize("slug", sorted(SCENES))
def test_a_pages_commands_run_its_scenario_and_plot_what_it_wrote(slug):
    (commands,) = re.findall(r"```sh\n(.*?)```", _page(slug), re.DOTALL)
    run, plot = commands.strip().splitlines()
    found = re.fullmatch(r"hoistsim run (\S+\.yaml) -o (\S+\.h5)", run)
    assert found and found.group(1) == SCENES[slug][0] and (ROOT / found.group(1)).is_file(), run
    assert plot == f"hoistsim plot {found.group(2)} -o {slug}.png", plot


def test_the_navigation_lists_every_gallery_page_and_nothing_else():
    listed = _nav_pages()
    assert listed[0] == "gallery/index.md"
    assert sorted(listed) == sorted(f"gallery/{path.name}" for path in GALLERY.glob("*.md"))
    assert len(listed) == len(set(listed))


def test_the_index_links_every_page():
    index = (GALLERY / "index.md").read_text(encoding="utf-8")
    assert sorted(re.findall(r"\]\(([^)]+)\.md\)", index)) == sorted(SCENES)


@pytest.mark.parametrize("slug", sorted(s for s, (_, example) in SCENES.items() if example in COMPARISONS))
def test_a_modelica_page_states_a_worst_deviation_below_the_tests_tolerance(slug):
    page = _page(slug)
    found = re.search(r"Worst deviation: \*\*([0-9.e+-]+)\*\* of its range, `([^`]+)`; the tests' tolerance: "
                      r"\*\*([0-9.e+-]+)\*\*", page)
    assert found, slug
    worst, signal, tolerance = float(found.group(1)), found.group(2), float(found.group(3))
    assert tolerance == COMPARISONS[SCENES[slug][1]].tolerance <= 1e-3
    assert worst < tolerance, (slug, signal, worst)
    # the worst is the largest of the signals' table
    table = dict(re.findall(r"^\| `([^`]+)` \| ([0-9.e+-]+) \|$", page, re.MULTILINE))
    assert signal in table and max(float(v) for v in table.values()) == worst, table


def test_the_figures_are_small():
    sizes = {path.name: path.stat().st_size for path in GALLERY.glob("*.png")}
    assert all(size < FIGURE_BYTES for size in sizes.values()), {n: s for n, s in sizes.items() if s >= FIGURE_BYTES}
    assert sum(path.stat().st_size for path in GALLERY.iterdir()) < GALLERY_BYTES
