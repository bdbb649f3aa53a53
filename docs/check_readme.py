"""Run every command of the README and the documentation site from a clean clone, as a newcomer would: a
maintainer's check before a release.

    python docs/check_readme.py [REPO] [--venv PATH] [--tests quick|all] [--long] [--keep] [--list] [--pages P,..]

The pages are README.md, then the site's (docs/) in the order of mkdocs.yml's navigation, then any other page of
docs/ (``--pages`` names some of them instead).  The commands are read from each page's ```sh blocks (a line
that starts with a space, or follows one ending in a backslash, goes on the command above; ``# ...`` is a
comment) and from its inline code that begins with ``hoistsim``, ``python`` or ``pip`` (with or without ``.venv/bin/``) and says more
than a bare subcommand.  REPO (default: the repository this file sits in, its checked-out branch) is
cloned into a temporary folder, the environment made there as the README says (or ``--venv`` linked
in as ``.venv``, skipping the install), and each command run in the pages' order from the clone's root, with
``.venv/bin`` first on PATH (the README's "activate it") and an empty folder of compiled programs
(the first run compiles, as a newcomer's does).  A table gives each command's exit status and wall
time; any failure makes the exit status 1.

The README's reference lines are run too, their placeholders filled in (:data:`PLACEHOLDERS`),
optional ``[...]`` parts left out and ``...`` read as the arguments of the command of the same
kind above it.  What takes long is handled deliberately, the reason printed beside it:

- the test suite (``pytest``) runs only with ``--tests quick`` (the quick loop) or ``--tests all``;
- ``hoistsim watch``, which runs until stopped, is run until its first results are written, the
  scenario is saved once (a comment added), and it is stopped with Ctrl-C once it has written again;
- sweeps of more than :data:`BIG_SWEEP` runs run only with ``--long``;
- benchmarks and the figures script (minutes each, and their numbers are the README's) are listed,
  never run: run them alone on a quiet machine.
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent

# What a reference line's placeholder stands for when it is run (by subcommand, then for every command).
PLACEHOLDERS = {
    None: {"SCENARIO.yaml": "scenarios/exercise6_direct_start.yaml",
           "SCENARIO": "scenarios/exercise6_direct_start.yaml",
           "OUT.h5": "reference_out.h5", "FIG.png": "reference_fig.png"},
    # a flywheel is sized for a machine with a periodic regime: the README's own example
    "flywheel": {"SCENARIO.yaml": "scenarios/motor_ripple_tredgold.yaml"},
    # a sensitivity of every run of a sweep: the sensitivities guide's own (one program for both)
    "sensitivity": {"SCENARIO.yaml": "scenarios/force_sweep_engage_at_speed.yaml",
                    "KEY,KEY": "clutch.kinetic_friction,load.mass"},
    # a fit needs a trace of its scene: the README's own rig
    "fit": {"SCENARIO.yaml": "scenarios/clutch_rig.yaml", "TRACE.csv": "scenarios/clutch_rig_trace.csv",
            "SERIES,..": "motor_speed,drum_speed", "KEY,..": "clutch.static_friction,clutch.kinetic_friction",
            "FITTED.yaml": "reference_fitted.yaml"},
}
# a sweep of more runs than this runs only with --long
BIG_SWEEP = 10_000
# a command that runs until stopped: seconds allowed for the first results, then for the run after the save
WATCH_FIRST_S, WATCH_SAVE_S = 300.0, 60.0
SAVE_MARK = "\n# saved by docs/check_readme.py\n"
# words the shell reads as redirections and pipes, never quoted
SHELL_OPERATORS = {">", ">>", "<", "2>", "2>&1", "&>", "|", "||", ";"}

_INLINE_START = re.compile(r"^(?:\.venv/bin/)?(?:hoistsim|python3?|pip)\s")
_PLACEHOLDER = re.compile(r"^[A-Z][A-Z0-9_]*(?:\.[a-z0-9]+)?$")


@dataclass
class Command:
    """One command of the README: where it is written and its words (comments dropped)."""

    line: int  # the page's line (1-based) where it starts
    text: str  # as written, continuation lines joined
    inline: bool  # written in a sentence, not in a ```sh block
    words: list[str] = field(default_factory=list)
    page: str = "README.md"  # the page it is written on, relative to the repository

    @property
    def where(self) -> str:
        return f"{self.page}:{self.line}"

    def steps(self) -> list[list[str]]:
        """The commands of an ``a && b`` chain, each a list of words."""
        found, current = [], []
        for word in self.words:
            if word == "&&":
                found.append(current)
                current = []
            else:
                current.append(word)
        return found + [current]


@dataclass
class Step:
    """One command as it is run: its words with placeholders filled and optional parts left out."""

    command: Command
    words: list[str]  # as run
    optional: list[str]  # the words of its [...] parts (checked against --help, not run)
    handling: str = "run"  # run, watch or skip
    reason: str = ""

    @property
    def shell(self) -> str:
        return " ".join(word if word in SHELL_OPERATORS else shlex.quote(word) for word in self.words)

    @property
    def program(self) -> str:
        return Path(self.words[0]).name if self.words else ""

    @property
    def subcommand(self) -> str | None:
        return self.words[1] if self.program == "hoistsim" and len(self.words) > 1 else None


# --- reading the README ----------------------------------------------------------------------------

def sh_blocks(text: str) -> list[tuple[int, list[str]]]:
    """Each ```sh block: the page's line of its first line (1-based) and its lines."""
    blocks, lines, start, inside = [], text.splitlines(), 0, None
    for number, line in enumerate(lines, 1):
        fence = line.strip()
        if inside is None and fence.startswith("```"):
            inside = fence[3:].strip()
            start = number + 1
            body = []
        elif inside is not None and fence == "```":
            if inside == "sh":
                blocks.append((start, body))
            inside = None
        elif inside is not None:
            body.append(line)
    return blocks


def block_commands(text: str, page: str = "README.md") -> list[Command]:
    """Every command of every ```sh block."""
    found = []
    for start, body in sh_blocks(text):
        continues = False
        for offset, line in enumerate(body):
            stripped = line.strip()
            if not stripped or (line.startswith("#") and not continues):  # a comment of its own
                continue
            if found and (continues or line[:1].isspace()) and found[-1].line >= start:
                found[-1].text += "\n" + line
            else:
                found.append(Command(start + offset, line, inline=False, page=page))
            continues = line.rstrip().endswith("\\")
    for command in found:
        command.words = shlex.split(command.text.replace("\\\n", " "), comments=True)
    return found


def inline_commands(text: str, page: str = "README.md") -> list[Command]:
    """Commands written inline (`hoistsim run scenarios/x.yaml -o x.h5`), outside fenced blocks.

    A bare subcommand (`hoistsim plot`) names the command and is not one.
    """
    lines, outside, inside = text.splitlines(), [], False
    for line in lines:  # fenced blocks blanked, so that line numbers stay
        if line.strip().startswith("```"):
            inside = not inside
            outside.append("")
        else:
            outside.append("" if inside else line)
    prose = "\n".join(outside)
    found = []
    for match in re.finditer(r"(?<!`)`([^`]+)`(?!`)", prose):
        span = " ".join(match.group(1).split())
        if not _INLINE_START.match(span):
            continue
        words = shlex.split(span)
        program = Path(words[0]).name
        if program == "hoistsim" and len(words) < 3:
            continue
        found.append(Command(prose.count("\n", 0, match.start()) + 1, span, inline=True, words=words, page=page))
    return found


def commands(text: str, page: str = "README.md") -> list[Command]:
    """Every command of a page in the order it is written."""
    return sorted(block_commands(text, page) + inline_commands(text, page), key=lambda command: command.line)


def site_pages(repo: Path) -> list[str]:
    """README.md, then the site's pages in the order of mkdocs.yml's navigation, then any other page of docs/."""
    listed = re.findall(r"^\s*-\s*(?:[^\n]*?:\s+)?([\w./-]+\.md)\s*$", _nav_text(repo), flags=re.M)
    others = sorted(path.relative_to(repo / "docs").as_posix() for path in (repo / "docs").rglob("*.md"))
    ordered = list(dict.fromkeys(listed + others))
    return ["README.md", *(f"docs/{page}" for page in ordered if (repo / "docs" / page).exists())]


def _nav_text(repo: Path) -> str:
    config = repo / "mkdocs.yml"
    text = config.read_text(encoding="utf-8") if config.exists() else ""
    return text[text.find("\nnav:"):] if "\nnav:" in text else ""


def _without_optional(words: list[str]) -> tuple[list[str], list[str]]:
    kept, optional, depth = [], [], 0
    for word in words:
        if word.startswith("[") or depth:
            depth += word.count("[") - word.count("]")
            optional.extend(w for w in word.strip("[]").split("|") if w)
        else:
            kept.append(word)
    return kept, optional


def _sweep_runs(words: list[str]) -> int:
    runs = 1
    for before, word in zip(words, words[1:]):
        if before == "--sweep":
            values = word.split("=", 1)[-1]
            parts = values.split(":")
            runs *= int(parts[-1]) if len(parts) == 3 and parts[-1].strip().isdigit() else len(values.split(","))
    return runs


def plan(text: str, *, page: str = "README.md", tests: str = "none", long: bool = False, venv: bool = False,
         earlier_steps: list[Step] | None = None) -> list[Step]:
    """A page's commands as steps to run, each with what is done with it and why (``earlier_steps``: the
    pages' before it, whose test suite is not run twice)."""
    steps, previous, before = [], {}, earlier_steps or []
    for command in commands(text, page):
        for words in command.steps():
            words, optional = _without_optional(words)
            step = Step(command, words, optional)
            sub = step.subcommand
            if "..." in words and sub in previous:  # `hoistsim flywheel ... --density`: the one above's arguments
                at = words.index("...")
                words[at:at + 1] = previous[sub]
            fill = {**PLACEHOLDERS[None], **PLACEHOLDERS.get(sub, {})}
            step.words = [fill.get(word, word) for word in words]
            if sub:
                previous[sub] = step.words[2:]
            _decide(step, tests=tests, long=long, venv=venv)
            earlier = [s for s in before + steps if s.shell == step.shell and s.handling == step.handling == "run"]
            if earlier and "pytest" in step.words:  # the suite written twice is run once
                step.handling, step.reason = "skip", f"run above, {earlier[0].command.where}"
            steps.append(step)
    return steps


def plan_site(repo: Path, pages: list[str] | None = None, **options) -> list[Step]:
    """Every page's steps, README.md first (``pages``: these only, in this order)."""
    steps = []
    for page in pages or site_pages(repo):
        text = (repo / page).read_text(encoding="utf-8")
        steps += plan(text, page=page, earlier_steps=steps, **options)
    return steps


def _decide(step: Step, *, tests: str, long: bool, venv: bool) -> None:
    words, program = step.words, step.program
    if program.startswith("python") and "pytest" in words:
        quick = "not slow" in words
        if tests == "all" or (tests == "quick" and quick):
            step.reason = "the quick test loop" if quick else "the whole test suite"
        else:
            step.handling = "skip"
            step.reason = ("the quick test loop, minutes: --tests quick runs it" if quick
                           else "the whole test suite, tens of minutes: --tests all runs it")
    elif venv and (words[:3] == ["python3", "-m", "venv"] or program == "pip"):
        step.handling, step.reason = "skip", "the environment given with --venv"
    elif program.startswith("python") and words[1:2] == ["docs/check_readme.py"]:
        step.handling, step.reason = "skip", "this check itself"
    elif program.startswith("python") and len(words) > 1 and words[1].startswith(("benchmarks/", "docs/")):
        step.handling, step.reason = "skip", "a benchmark or the figures, minutes: run it alone on a quiet machine"
    elif step.subcommand == "watch":
        step.handling, step.reason = "watch", "runs until stopped: first results, one save, Ctrl-C"
    elif step.subcommand == "run" and _sweep_runs(words) > BIG_SWEEP and not long:
        step.handling, step.reason = "skip", f"a sweep of {_sweep_runs(words):,} runs: --long runs it"


# --- running ---------------------------------------------------------------------------------------

@dataclass
class Outcome:
    status: int | None  # None: skipped
    wall: float
    note: str = ""
    tail: str = ""


def _environment(clone: Path, cache: Path) -> dict:
    env = {key: value for key, value in os.environ.items() if key not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PATH"] = f"{clone / '.venv' / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["VIRTUAL_ENV"] = str(clone / ".venv")
    env["HOISTSIM_CACHE_DIR"] = str(cache)
    return env


def run_step(step: Step, clone: Path, env: dict, timeout: float) -> Outcome:
    if step.handling == "skip":
        return Outcome(None, 0.0, step.reason)
    if step.handling == "watch":
        return watch_step(step, clone, env)
    started = time.perf_counter()
    try:
        done = subprocess.run(step.shell, shell=True, cwd=clone, env=env, capture_output=True, text=True,
                              timeout=timeout, executable="/bin/bash")
        status, output = done.returncode, done.stdout + done.stderr
    except subprocess.TimeoutExpired as exc:
        status, output = 124, f"timed out after {timeout:.0f} s\n{exc.stdout or ''}{exc.stderr or ''}"
    wall = time.perf_counter() - started
    return Outcome(status, wall, step.reason, "\n".join(str(output).splitlines()[-12:]))


def _stamp(path: Path):
    try:
        stat = path.stat()
        return stat.st_ino, stat.st_mtime_ns
    except OSError:
        return None


def _wait_for_change(paths: list[Path], before: dict, until: float, process) -> bool:
    while time.perf_counter() < until:
        if all(_stamp(path) not in (None, before[path]) for path in paths):
            return True
        if process.poll() is not None:
            return False
        time.sleep(0.05)
    return False


def _ctrl_c_as_in_a_terminal():
    # a process started in the background (`... &`) inherits SIGINT ignored, and Python then never raises
    # KeyboardInterrupt: the watch would not stop at Ctrl-C as it does in a terminal
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def watch_step(step: Step, clone: Path, env: dict) -> Outcome:
    """Start the watch, wait for its results, save the scenario once, wait for them again, press Ctrl-C."""
    words = step.words
    written = [clone / words[i + 1] for i, word in enumerate(words[:-1]) if word in ("-o", "--output", "--plot")]
    scenario = clone / next(word for word in words[2:] if word.endswith((".yaml", ".yml")))
    original = scenario.read_text()
    started = time.perf_counter()
    process = subprocess.Popen(step.shell, shell=True, cwd=clone, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, executable="/bin/bash", start_new_session=True,
                               preexec_fn=_ctrl_c_as_in_a_terminal)
    note = ""
    try:
        before = {path: _stamp(path) for path in written}
        if not _wait_for_change(written, before, started + WATCH_FIRST_S, process):
            note = "no first results"
        else:
            first = time.perf_counter() - started
            before = {path: _stamp(path) for path in written}
            saved = time.perf_counter()
            scenario.write_text(original + SAVE_MARK)
            if _wait_for_change(written, before, saved + WATCH_SAVE_S, process):
                note = f"first results {first:.1f} s, after the save {time.perf_counter() - saved:.2f} s"
            else:
                note = "no results after the save"
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGINT)  # Ctrl-C, to the shell and the watch alike
        try:
            output, _ = process.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            output, _ = process.communicate()
        scenario.write_text(original)
    status = process.returncode if note.startswith("first") else 1
    return Outcome(status, time.perf_counter() - started, f"{note}; {step.reason}",
                   "\n".join(output.splitlines()[-12:]))


def clone_repository(repo: Path, into: Path) -> str:
    branch = subprocess.run(["git", "-C", str(repo), "rev-parse", "--abbrev-ref", "HEAD"],
                            capture_output=True, text=True, check=True).stdout.strip()
    chosen = [] if branch == "HEAD" else ["--branch", branch]
    subprocess.run(["git", "clone", "--quiet", *chosen, str(repo), str(into)], check=True)
    return subprocess.run(["git", "-C", str(into), "log", "-1", "--format=%h %s"], capture_output=True,
                          text=True, check=True).stdout.strip()


def _short(text: str, width: int) -> str:
    return text if len(text) <= width else text[: width - 1] + "…"


def table(rows: list[tuple[Step, Outcome]]) -> str:
    width = max([len(step.command.where) for step, _ in rows] + [5])
    out = [f"{'#':>3}  {'where':<{width}}  {'exit':>4}  {'wall s':>7}  command", "-" * (width + 100)]
    for number, (step, outcome) in enumerate(rows, 1):
        status = "skip" if outcome.status is None else str(outcome.status)
        wall = "" if outcome.status is None else f"{outcome.wall:7.1f}"
        out.append(f"{number:>3}  {step.command.where:<{width}}  {status:>4}  {wall:>7}  {_short(step.shell, 78)}")
        if outcome.note:
            out.append(f"{'':>{width + 22}}({outcome.note})")
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("repo", nargs="?", default=str(HERE), help="repository to clone (default: this one)")
    parser.add_argument("--venv", help="an environment to use as the clone's .venv instead of installing one")
    parser.add_argument("--tests", choices=("none", "quick", "all"), default="none",
                        help="run the README's test commands: none (default), the quick loop, or all")
    parser.add_argument("--long", action="store_true", help=f"also run sweeps of more than {BIG_SWEEP:,} runs")
    parser.add_argument("--keep", action="store_true", help="keep the clone (its path is printed)")
    parser.add_argument("--list", action="store_true", help="print the commands and what is done with each; run none")
    parser.add_argument("--timeout", type=float, default=1800.0, help="seconds one command may take")
    parser.add_argument("--pages", help="only these pages, comma-separated (README.md, docs/how-to/lift-off.md, ...)")
    args = parser.parse_args(argv)

    pages = args.pages.split(",") if args.pages else None
    options = dict(tests=args.tests, long=args.long, venv=bool(args.venv))
    steps = plan_site(Path(args.repo), pages, **options)
    if args.list:
        for step in steps:
            reason = f"   ({step.reason})" if step.reason else ""
            print(f"{step.command.where}  {step.handling:<5}  {step.shell}{reason}")
        return 0

    folder = Path(tempfile.mkdtemp(prefix="check_readme_"))
    clone, cache = folder / "hoistsim", folder / "compiled"
    cache.mkdir()
    print(f"cloning {args.repo} into {clone}: {clone_repository(Path(args.repo), clone)}", flush=True)
    steps = plan_site(clone, pages, **options)  # the clone's pages, which is what is run
    if args.venv:
        (clone / ".venv").symlink_to(Path(args.venv).resolve())
    env = _environment(clone, cache)
    rows = []
    try:
        for step in steps:
            outcome = run_step(step, clone, env, args.timeout)
            rows.append((step, outcome))
            status = "skip" if outcome.status is None else f"exit {outcome.status}, {outcome.wall:.1f} s"
            print(f"{step.command.where}: {status}: {step.shell}", flush=True)
            if outcome.status:
                print("    " + outcome.tail.replace("\n", "\n    "), flush=True)
    finally:
        print()
        print(table(rows))
        if args.keep:
            print(f"\nthe clone is kept: {clone}")
        else:
            shutil.rmtree(folder, ignore_errors=True)
    failed = [step for step, outcome in rows if outcome.status not in (None, 0)]
    ran = sum(outcome.status is not None for _, outcome in rows)
    print(f"\n{ran} commands run, {len(rows) - ran} skipped, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
