"""Every ``hoistsim`` command of the README and the site's pages run as a user runs it: page by page, in the order
written, from a folder that holds the repository's scenarios, each exiting 0 (a command that reads a file an
earlier one wrote finds it there).  docs/check_readme.py runs the same commands, and the install, from a clean
clone; here they run in this process (the command line's own entry point, its compiled programs shared), so a
page whose commands simulate is slow and one that only checks, compares or works out statics is quick.

What is not run here is said, with the reason: what check_readme.py leaves to its flags (the test suite, a
sweep of a million runs, benchmarks), ``hoistsim watch`` (it runs until stopped: tests/cli/test_watch.py runs
it), the environment's commands (venv, pip: this process's environment is the one they make) and the gallery's
pages, whose commands are ``hoistsim run`` of a shipped scenario and ``hoistsim plot`` of its file, exactly as
tests/every_scene.py runs every shipped scenario and Modelica example (the last test holds them to that form).
"""

from __future__ import annotations

import shlex
import subprocess

import pytest
from helpers import ROOT, docs_checker

SIMULATING = {"run", "plot", "flywheel", "sensitivity", "fit", "bench"}


check_readme = docs_checker()
STEPS = check_readme.plan_site(ROOT)
PAGES = [page for page in check_readme.site_pages(ROOT) if not page.startswith("docs/gallery/")]


def _runnable(step) -> bool:
    """A step this test runs: a hoistsim command check_readme.py would run (not watch), or a file copied."""
    if step.handling != "run":
        return False
    return step.program == "hoistsim" or step.words[:1] == ["cp"]


def _page_param(page: str):
    steps = [step for step in STEPS if step.command.page == page and _runnable(step)]
    slow = any(step.subcommand in SIMULATING for step in steps)
    return pytest.param(page, steps, id=page, marks=pytest.mark.slow if slow else ())


@pytest.mark.parametrize("page, steps", [_page_param(page) for page in PAGES])
def test_every_command_of_the_page_runs(page, steps, tmp_path, monkeypatch):
    from click.testing import CliRunner

    from hoistsim.cli import main

    (tmp_path / "scenarios").symlink_to(ROOT / "scenarios")
    monkeypatch.chdir(tmp_path)
    for step in steps:
        if step.program == "cp":
            subprocess.run(step.words, check=True)
            continue
        result = CliRunner().invoke(main, step.words[1:], catch_exceptions=False)
        assert result.exit_code == 0, f"{step.command.where}: `{step.shell}` exited {result.exit_code}:\n" \
                                      f"{result.output[-2000:]}"


def test_what_is_not_run_here_is_said():
    """Every command of a page that is not a gallery's is run here, or left with a reason."""
    for step in STEPS:
        if step.command.page.startswith("docs/gallery/") or _runnable(step):
            continue
        left = step.handling in ("skip", "watch") or step.program in ("python3", "pip", "mkdocs", "python")
        assert left, f"{step.command.where}: `{step.shell}` is neither run here nor left with a reason"


def test_the_gallery_commands_are_the_scenes_every_scene_runs():
    """A gallery page's commands: `hoistsim run` of a shipped scenario or Modelica example to a file, then
    `hoistsim plot` of that file (tests/every_scene.py runs each scene so, and draws its figures)."""
    written = set()
    gallery = [step for step in STEPS if step.command.page.startswith("docs/gallery/") and step.program == "hoistsim"]
    assert len(gallery) >= 2 * 59
    for step in gallery:
        words = step.words[1:]
        if step.subcommand == "run":
            assert len(words) == 4 and words[2] == "-o", f"{step.command.where}: {shlex.join(step.words)}"
            assert words[1].startswith("scenarios/") and (ROOT / words[1]).is_file(), step.command.where
            written.add(words[3])
        else:
            assert step.subcommand == "plot" and words[1] in written and words[2] == "-o", step.command.where
