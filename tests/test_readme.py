"""The commands of the README and the site's pages as docs/check_readme.py reads them: all found, every file and
option real; the README short, its first screen a quick-start and its ten-line scenario the shipped template's;
the walk-through's numbers the runs'.

No command is run here (docs/check_readme.py runs them from a clean clone, minutes): the commands are
read, and each one's subcommand and options are looked up in the command line itself. The template and
its fix are run once each, in process (two compiles of a few seconds).
"""

from __future__ import annotations

import re
import shlex

import pytest
from helpers import ROOT, docs_checker

README = (ROOT / "README.md").read_text(encoding="utf-8")
GETTING_STARTED = (ROOT / "docs" / "getting-started.md").read_text(encoding="utf-8")


check_readme = docs_checker()
PAGES = check_readme.site_pages(ROOT)
STEPS = check_readme.plan_site(ROOT)


def _options(subcommand: str | None) -> set[str]:
    """The options `hoistsim SUBCOMMAND --help` lists (the group's own for None)."""
    from hoistsim.cli import main

    command = main if subcommand is None else main.commands[subcommand]
    return {name for parameter in command.params for name in (*parameter.opts, *parameter.secondary_opts)
            if name.startswith("-")} | {"--help", "-h"}


def test_the_pages_are_the_readme_and_every_page_of_the_site():
    assert PAGES[0] == "README.md"
    assert set(PAGES[1:]) == {f"docs/{path.relative_to(ROOT / 'docs').as_posix()}"
                              for path in (ROOT / "docs").rglob("*.md")}
    assert PAGES.index("docs/index.md") < PAGES.index("docs/getting-started.md") < PAGES.index("docs/scenario.md")


@pytest.mark.parametrize("page", PAGES)
def test_every_line_of_every_sh_block_is_in_a_command(page):
    """A line of a ```sh block is blank, a comment of its own, or part of one command found."""
    text = (ROOT / page).read_text(encoding="utf-8")
    found = check_readme.block_commands(text, page)
    covered = {command.line + offset for command in found for offset in range(command.text.count("\n") + 1)}
    for start, body in check_readme.sh_blocks(text):
        for number, line in enumerate(body, start):
            if line.strip() and not line.startswith("#"):
                assert number in covered, f"{page} line {number} is in no command: {line!r}"
    assert all(command.words for command in found)
    assert all(not command.text[:1].isspace() for command in found)


def test_the_opening_commands_are_read_whole():
    first = check_readme.block_commands(README)[:2]
    assert [command.line for command in first] == [7, 10]
    assert [[step[0] for step in command.steps()] for command in first] == [
        ["python3", ".venv/bin/pip", ".venv/bin/hoistsim"], ["python3", ".venv/bin/pip", ".venv/bin/python"]]


def test_inline_commands_are_found_and_mentions_left():
    inline = [step.command.text for step in STEPS if step.command.inline]
    assert "hoistsim check scenarios/lift_off_the_ground.yaml" in inline
    assert "hoistsim statics scenarios/exercise6_constant_speed.yaml" in inline
    assert not [text for text in inline if re.fullmatch(r"(\.venv/bin/)?hoistsim \w+", text)]


@pytest.mark.parametrize("step", [s for s in STEPS if s.subcommand], ids=lambda s: s.command.where)
def test_every_subcommand_and_option_exists(step):
    from hoistsim.cli import main

    assert step.subcommand in main.commands, f"{step.command.where}: no `hoistsim {step.subcommand}`"
    known = _options(step.subcommand)
    for word in step.words[2:] + step.optional:
        option = word.split("=", 1)[0]
        if option.startswith("-") and not re.fullmatch(r"-\d.*", option):
            assert option in known, f"{step.command.where}: `hoistsim {step.subcommand}` has no {option}"


def test_required_options_are_given():
    """What `--help` marks [required] (-o for run and plot, --irregularity for flywheel) is on every line."""
    from hoistsim.cli import main

    for step in STEPS:
        if step.subcommand:
            for parameter in main.commands[step.subcommand].params:
                if parameter.required and parameter.opts[0].startswith("-"):
                    assert set(parameter.opts) & set(step.words), \
                        f"{step.command.where}: `{step.shell}` lacks {parameter.opts[0]}"


def test_every_file_a_command_names_exists():
    for step in STEPS:
        for word in step.words + step.optional:
            if re.match(r"(scenarios|benchmarks|docs|tests)/", word):
                assert (ROOT / word).exists(), f"{step.command.where}: {word} is not in the repository"


def test_every_placeholder_is_filled_in():
    for step in STEPS:
        if step.handling != "skip":
            left = [word for word in step.words if check_readme._PLACEHOLDER.match(word) and word != "...."]
            assert not left, f"{step.command.where}: {left} not in check_readme.PLACEHOLDERS"
            assert "..." not in step.words, f"{step.command.where}: `...` with no command above to stand for"


def test_long_commands_are_handled_deliberately():
    by_text = {step.shell: step for step in STEPS}
    suite = by_text[".venv/bin/python -m pytest"]
    assert suite.handling == "skip" and "--tests" in suite.reason
    watch = next(step for step in STEPS if step.subcommand == "watch")
    assert watch.handling == "watch"
    million = [step for step in STEPS if "1000000" in step.shell]
    assert million and all(step.handling == "skip" and "--long" in step.reason for step in million)
    assert all(step.handling == "skip" for step in STEPS if step.words[1:2] and step.words[1].startswith("benchmarks/"))
    assert check_readme.plan_site(ROOT, tests="all", long=True)  # the flags that run them do not break the plan
    assert {step.handling for step in check_readme.plan_site(ROOT, venv=True) if step.program == "pip"} == {"skip"}
    suites = [step for step in check_readme.plan_site(ROOT, tests="all") if step.shell == ".venv/bin/python -m pytest"]
    assert [step.handling for step in suites] == ["run"] + ["skip"] * (len(suites) - 1)  # the suite run once


def test_the_list_mode_runs_nothing(capsys):
    assert check_readme.main(["--list", str(ROOT)]) == 0
    listed = capsys.readouterr().out.splitlines()
    assert len(listed) == len(STEPS)
    assert shlex.split(listed[0])[2:] == ["python3", "-m", "venv", ".venv"]


def test_a_clone_runs_the_commands_and_a_failure_fails(tmp_path, capsys):
    """The runner on a repository of its own: each command run from the clone, a failing one exits 1."""
    import subprocess

    repo = tmp_path / "repo"
    repo.mkdir()
    (repo / "README.md").write_text("# x\n\n```sh\npython3 -m venv .venv\necho made > made.txt && cat made.txt  # two\n"
                                    "test -f README.md\nfalse\n```\n")
    for command in (["init", "-q", "-b", "main"], ["add", "README.md"],
                    ["-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "readme"]):
        subprocess.run(["git", "-C", str(repo), *command], check=True)
    venv = tmp_path / "venv"
    (venv / "bin").mkdir(parents=True)
    assert check_readme.main([str(repo), "--venv", str(venv)]) == 1
    table = capsys.readouterr().out.split("#  where")[1].split("\n\n")[0].splitlines()[2:]
    assert [row.split()[2] for row in table if row.split()[:1] and row.split()[0].isdigit()] == ["skip", "0", "0", "0", "1"]
    assert "the environment given with --venv" in "\n".join(table)


# --- the first screen and the first scenario --------------------------------------------------------

FIRST_SCENARIO = ROOT / "scenarios" / "first_scenario.yaml"
FIRST_SCREEN = "\n".join(README.splitlines()[:40])


def _section(title: str, text: str = GETTING_STARTED) -> str:
    """A page's ``## title`` section (getting-started.md's by default), up to the next ``## `` heading."""
    start = text.index(f"\n## {title}\n")
    end = text.find("\n## ", start + 1)
    return text[start:end if end > 0 else None]


def _fenced(text: str, language: str) -> list[str]:
    return re.findall(rf"^```{language}\n(.*?)^```$", text, flags=re.S | re.M)


def _with_the_brake(text: str) -> str:
    """The template with the `#` of its two brake lines deleted, as the walk-through says."""
    fixed = text.replace("\n#brake:", "\nbrake:").replace("\n#  release_time:", "\n  release_time:")
    assert fixed.count("\nbrake:") == 1 and fixed.count("\n  release_time:") == 1
    return fixed


def test_the_first_screen_is_the_quick_start():
    """The two commands, what a first and a later run cost (the first compiles), and the way to the walk-through."""
    first = check_readme.block_commands(README)[:2]
    assert all(command.text in FIRST_SCREEN for command in first)
    assert "the first run of a scene: it compiles the scene's solver first" in FIRST_SCREEN
    assert "a later run of the same structure" in FIRST_SCREEN and "0.9 s" in FIRST_SCREEN
    assert "compiles again" in FIRST_SCREEN
    assert FIRST_SCREEN.count("\n## ") <= 1  # the quick-start, then at most the next heading
    assert "benchmarks/README.md" in FIRST_SCREEN  # where the measurements' history went


def test_the_readme_fits_on_two_screens_and_leads_into_the_site():
    """At most 200 lines: what it is, a figure, the two commands, a ten-line scenario, and every page of the
    site's navigation linked (the pages read as Markdown on the repository's host too)."""
    assert len(README.splitlines()) <= 200
    assert README.count("![") == 1
    linked = set(re.findall(r"\]\((docs/[^)#\s]+)", README))
    for target in linked:
        assert (ROOT / target).exists(), f"README links {target}, which is not there"
    nav = set(re.findall(r":\s+([\w./-]+\.md)\s*$", check_readme._nav_text(ROOT), flags=re.M))
    assert {f"docs/{page}" for page in nav if not page.startswith("gallery/") and page != "index.md"} <= linked
    assert "docs/gallery/index.md" in linked


def test_the_readme_scenario_in_ten_lines_is_the_template():
    """The README's scenario is scenarios/first_scenario.yaml without its comments: the same keys and values."""
    from ruamel.yaml import YAML

    block = _fenced(_section("Your first scenario, in ten lines", README), "yaml")[0]
    assert len(block.splitlines()) <= 10
    assert YAML(typ="safe").load(block) == YAML(typ="safe").load(FIRST_SCENARIO.read_text(encoding="utf-8"))


def test_the_readme_shows_the_first_scenario_whole():
    assert _fenced(_section("Your first scenario"), "yaml")[0] == FIRST_SCENARIO.read_text(encoding="utf-8")


def test_every_line_of_the_first_scenario_says_what_it_is():
    for number, line in enumerate(FIRST_SCENARIO.read_text(encoding="utf-8").splitlines(), 1):
        assert "#" in line, f"scenarios/first_scenario.yaml line {number} has no comment: {line!r}"


def test_the_walk_through_runs_the_template_and_its_fix():
    commands = [step.shell for step in check_readme.plan(_section("Your first scenario"))]
    assert "hoistsim run scenarios/first_scenario.yaml -o first.h5" in commands
    assert "hoistsim plot first.h5 -o first.png" in commands
    assert any("scenarios/first_scenario.yaml" in c and "brake.release_time=" in c for c in commands)


@pytest.fixture(scope="module")
def template_run():
    from hoistsim import load_scenario, simulate

    return simulate(load_scenario(FIRST_SCENARIO)).summary


@pytest.fixture(scope="module")
def fixed_run(tmp_path_factory):
    """The template with its brake lines' `#` deleted: a new structure (a brake), compiled once here."""
    from hoistsim import load_scenario, simulate

    path = tmp_path_factory.mktemp("first") / "first_scenario.yaml"
    path.write_text(_with_the_brake(FIRST_SCENARIO.read_text(encoding="utf-8")), encoding="utf-8")
    return simulate(load_scenario(path)).summary


def _quoted(number: str) -> None:
    assert number in _section("Your first scenario"), f"the walk-through does not say {number}"


def test_the_first_scenario_lets_the_unbraked_load_fall_first(template_run):
    assert template_run["lowest_load_position"] < -0.1  # the clutch ramped from rest: the load runs back
    assert template_run["final_load_position"] > 0  # then the clutch catches it and lifts it
    _quoted(f"**−{-template_run['lowest_load_position']:.3f} m**")
    _quoted(f"**{template_run['lockup_time']:.3f} s**")
    _quoted(f"**{template_run['slip_energy'] / 1e3:.2f} kJ**")
    _quoted(f"+{template_run['final_load_position']:.2f} m at 3 s")


def test_its_brake_lines_keep_the_load_from_falling(template_run, fixed_run):
    from hoistsim import load_scenario, simulate

    assert fixed_run["lowest_load_position"] >= 0.0
    assert fixed_run["lockup_time"] < template_run["lockup_time"]
    assert fixed_run["slip_energy"] < template_run["slip_energy"]
    _quoted("**0 m**")
    _quoted(f"**{fixed_run['lockup_time']:.3f} s**")
    _quoted(f"**{fixed_run['slip_energy'] / 1e3:.2f} kJ**")
    _quoted(f"+{fixed_run['final_load_position']:.2f} m instead of")
    # the README's command-line fix is the same scene (and runs on the program just compiled)
    given = simulate(load_scenario(FIRST_SCENARIO, overrides=["brake.release_time=0.5 s"])).summary
    assert given["lockup_time"] == fixed_run["lockup_time"]
