"""The documentation site (mkdocs.yml, docs/): it builds with ``mkdocs build --strict``, offline, so a dead link, an
anchor that is not there, or a page left out of the navigation fails; every page of docs/ is in its navigation, and
no page points outside the repository."""

from __future__ import annotations

import re
import subprocess
import sys

from helpers import ROOT
from ruamel.yaml import YAML

DOCS = ROOT / "docs"


def _nav_pages(entries) -> list[str]:
    pages = []
    for entry in entries:
        for value in entry.values() if isinstance(entry, dict) else [entry]:
            pages += _nav_pages(value) if isinstance(value, list) else [value]
    return pages


def test_the_site_builds_strictly_and_every_page_is_there(tmp_path):
    built = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path)],
                           cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert built.returncode == 0, built.stderr[-3000:]
    pages = _nav_pages(YAML(typ="safe").load((ROOT / "mkdocs.yml").read_text(encoding="utf-8"))["nav"])
    assert sorted(pages) == sorted(path.relative_to(DOCS).as_posix() for path in DOCS.rglob("*.md"))
    for page in pages:
        html = (tmp_path / page.replace(".md", ".html")).read_text(encoding="utf-8")
        assert "<h1" in html, page
    # the reference's section headings keep their <name> (taken for an HTML tag, it was dropped)
    assert 'id="drivetrainbearing_frictionsname"' in (tmp_path / "scenario.html").read_text(encoding="utf-8")
    # the generated references are there: every command's options from its help, every public name's docstring
    commands = (tmp_path / "commands.html").read_text(encoding="utf-8")
    assert all(f"hoistsim {name}" in commands for name in ("run", "plot", "watch", "sensitivity", "fit"))
    assert "--summary-only" in commands and "--irregularity" in commands
    import hoistsim

    python = (tmp_path / "python.html").read_text(encoding="utf-8")
    for name in hoistsim.__all__:
        assert f'id="hoistsim.{hoistsim._PUBLIC[name]}.{name}"' in python, name


def test_no_page_points_outside_the_repository():
    for path in DOCS.rglob("*.md"):
        text = path.read_text(encoding="utf-8")
        assert "../shared" not in text and "shared/" not in text, path.name
        for target in re.findall(r"\]\(([^)#\s]+)", text):
            assert target.startswith("http") or (path.parent / target).resolve().is_relative_to(DOCS), \
                f"{path.name} links {target} outside the site"
