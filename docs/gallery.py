"""The documentation site's gallery, generated from the runs: every shipped scenario and every Modelica example.

    python docs/gallery.py                            # every page (some 17 minutes on 2 cores), the index, the nav
    python docs/gallery.py --only modelica-Friction   # these pages (the rest of the index kept); --list: the pages

Each scene is run by the command line in this process (`hoistsim run`, a sweep whole, then the figures `hoistsim
plot` draws), its compiled solver shared with its comparison.  Its page, docs/gallery/<slug>.md, says what the scene
is (its file's leading comment, else its description), the commands that reproduce it, its figures and its summary;
a Modelica example's also draws hoistsim's trajectories over Dymola's (tests/data/modelica/) with each signal's
worst deviation, as the tests measure it.  docs/gallery/index.md lists the pages, mkdocs.yml's nav between its two
gallery markers (nothing else there touched).  Pages and figures are written atomically.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

# a run as the site's figures make theirs: the command line in this process (the script's own folder is on the path)
from figures import hoistsim_command  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = ROOT / "scenarios"
GALLERY = ROOT / "docs" / "gallery"
REFERENCES = ROOT / "tests" / "data" / "modelica"
MKDOCS = ROOT / "mkdocs.yml"
NAV_START, NAV_END = "# the gallery's pages: written by docs/gallery.py", "# end of the gallery's pages"
GROUPS = {"hoist": "The hoist's scenarios", "rotational": "Modelica Rotational",
          "translational": "Modelica Translational"}
# (group, folder, its pages' slugs' prefix, its examples' keys' prefix among the comparisons)
FOLDERS = (("hoist", SCENARIOS, "", ""), ("rotational", SCENARIOS / "modelica", "modelica-", ""),
           ("translational", SCENARIOS / "modelica" / "translational", "modelica-translational-", "translational/"))
DPI = 100  # the figures as `hoistsim plot` draws them, at a page's width
PALETTES, MOST_BYTES = (128, 64, 32), 140_000  # a figure's colours, fewer for a busy one until it fits
DYMOLA = dict(color="#9ecae1", linewidth=5.0, solid_capstyle="butt", label="Dymola")  # thick, light
HOISTSIM = dict(color="#08306b", linewidth=1.1, linestyle=(0, (4, 2)), label="hoistsim")  # thin, dark, dashed
CAPTIONS = {"": "the runs", "_summary": "the summary against the swept value",
            "_periodic": "the periodic regime: the turning-moment diagram and the speed over a period"}
UNITS = {"phi": "rad", "phi_rel": "rad", "w": "rad/s", "w_rel": "rad/s", "s": "m", "s_rel": "m", "v": "m/s",
         "v_rel": "m/s", "T": "K", "lossPower": "W", "i": "A"}  # a Modelica signal's unit, by its last name


@dataclass(frozen=True)
class Scene:
    slug: str
    path: Path
    scenario: str  # its path from the repository's root, as a command names it there
    group: str
    example: str | None = None  # its key in hoistsim.references.modelica_signals.COMPARISONS, where it has one


def scenes() -> list[Scene]:
    from hoistsim.references.modelica_signals import COMPARISONS

    found = []
    for group, folder, prefix, key in FOLDERS:
        for path in sorted(folder.glob("*.yaml")):
            example = key + path.stem if group != "hoist" and key + path.stem in COMPARISONS else None
            found.append(Scene(prefix + path.stem, path, path.relative_to(ROOT).as_posix(), group, example))
    return found


# ------------------------------------------------------------------------------------------ what the scene is
def about(path: Path) -> tuple[str, list[str]]:
    """The scene's title (its ``name``) and what it is: the sentences of its file's leading comment, up to its
    first command or blank comment line, else its description."""
    from ruamel.yaml import YAML

    text = path.read_text(encoding="utf-8")
    data = YAML(typ="safe").load(text)
    lines = []
    for line in text.splitlines():
        if not line.startswith("#") or line.strip() == "#" or re.match(r"#\s{3,}\S", line):
            break  # the prose ends where the file's commands (indented) or its keys begin
        lines.append(line[1:].strip())
    prose = "\n".join(lines) or str(data.get("description") or "")
    return str(data["name"]), sentences(prose)


def sentences(prose: str) -> list[str]:
    """The prose's whole sentences: each ends at a stop (a quoted question's too) followed by two spaces or a
    line's end, the files' style; a sentence cut short by a command line is left out."""
    parts = re.split(r"(?:(?<=[.?!])|(?<=[.?!]\"))(?:\s*\n\s*|\s{2,})", prose.strip())
    return [" ".join(part.split()) for part in parts if re.search(r"[.?!]\"?$", part.strip())]


def gist(said: list[str]) -> str:
    """What the scene shows, in a few words for the index: its first sentence, after the Modelica example's name
    that opens it ("The Modelica Standard Library's X (MSL 4.0): ..."), without its asides in parentheses, cut at
    its first clause past eight words."""
    first = said[0] if said else ""
    while (start := first.find(" (")) >= 0:  # an aside, to its matching parenthesis: sin(2 pi t) is no aside
        depth = 0
        for end in range(start + 1, len(first)):
            depth += {"(": 1, ")": -1}.get(first[end], 0)
            if depth == 0:
                break
        first = first[:start] + first[end + 1:]
    head, colon, rest = first.partition(": ")
    if colon and rest and head.startswith(("The Modelica Standard Library's", "Modelica.")):
        first = rest[0].upper() + rest[1:]
    words = first.split()
    for i, word in enumerate(words):
        if i >= 8 and word.endswith((",", ";", ":")) and i + 1 < len(words):
            return " ".join(words[:i + 1])[:-1] + " ..."
    return first


def markdown(text: str) -> str:
    """Prose as Markdown shows it as written (a scenario's N*m and kg*m^2 no emphasis, its <name> no tag), its code
    spans kept and the files it names put in code spans."""
    parts = re.split(r"(`[^`]+`|(?<![\w/.-])(?:[\w.-]+/)*[\w-]+\.(?:yaml|csv|py|md)\b)", text)
    return "".join(part if part.startswith("`") else f"`{part}`" if i % 2 else
                   re.sub(r"([\\`*_\[\]|])", r"\\\1", part).replace("<", "&lt;") for i, part in enumerate(parts))


# ------------------------------------------------------------------------------------------------- the run
def pyplot():
    import matplotlib

    matplotlib.use("Agg")  # files only, never a window
    import matplotlib.pyplot as plt

    return plt


def save_png(fig, target: Path) -> None:
    """The figure at the gallery's resolution, in a palette (a third of the bytes, the same look), atomically."""
    import io

    from PIL import Image

    from hoistsim.results.atomic import atomic_path

    drawn = io.BytesIO()
    fig.savefig(drawn, dpi=DPI, format="png")
    image = Image.open(io.BytesIO(drawn.getvalue())).convert("RGB")
    for colours in PALETTES:
        packed = io.BytesIO()
        image.quantize(colors=colours, method=Image.Quantize.MEDIANCUT).save(packed, format="png", optimize=True)
        if packed.tell() < MOST_BYTES:
            break
    with atomic_path(target) as partial:
        partial.write_bytes(packed.getvalue())


def plot_figures(results: Path, slug: str) -> list[str]:
    """The figures `hoistsim plot` draws of the file, as <slug>.png, <slug>_summary.png, <slug>_periodic.png;
    returns their suffixes."""
    from hoistsim.figures.files import draw_figures
    from hoistsim.figures.frames import FreshFrames

    plt, frames, suffixes = pyplot(), FreshFrames(), []
    for suffix, fig in draw_figures(results, plt, frames):
        save_png(fig, GALLERY / f"{slug}{suffix}.png")
        frames.done(plt, fig)
        suffixes.append(suffix)
    return suffixes


# ------------------------------------------------------------------------------------------ what the run says
def summary_table(results: Path) -> list[str]:
    """The summary's values with their words and units (the package's: summary_meanings, summary_display): one
    run's, or a sweep's least and most over its runs, its swept keys first."""
    from hoistsim.results.reading import read_summary, read_summary_units, read_swept_keys
    from hoistsim.results.report import column_cells
    from hoistsim.results.summary_display import scaled, summary_header
    from hoistsim.results.summary_meanings import summary_meaning

    rows, units, swept = read_summary(results), read_summary_units(results), read_swept_keys(results)
    keys = swept + [k for k in rows[0] if k not in swept and k not in ("label", "energy_residual")]
    lines = (["| quantity | value | unit |", "|---|---:|---|"] if len(rows) == 1 else
             [f"| quantity, over the {len(rows)} runs | least | most | unit |", "|---|---:|---:|---|"])
    for key in keys:
        header, scale = (f"{key} [{units[key]}]", 1.0) if key in swept else summary_header(key, units.get(key, ""))
        words, unit = re.fullmatch(r"(.*?)(?: \[(.*)\])?", header).groups()
        words, unit = f"swept: {key}" if key in swept else summary_meaning(key)[0] or words, unit or ""
        values = [float(scaled(row[key], scale)) for row in rows]
        finite = [v for v in values if math.isfinite(v)] or [math.nan]
        shown = values if len(rows) == 1 else [min(finite), max(finite)]
        cells = [_said(value, cell, key) for value, cell in zip(shown, column_cells(shown, 2 if scale is None else 4))]
        lines.append(f"| {markdown(words)} | {' | '.join(cells)} | {markdown(unit if unit != '1' else '')} |")
    return lines


def _said(value: float, cell: str, key: str) -> str:
    """A value's cell, with what its 0 or NaN stands for where the summary's words say."""
    from hoistsim.results.summary_meanings import summary_meaning

    # the comment's clauses, "0: never slipped; NaN: never locked in the run", "1: yes, 0: no"
    said = dict(re.findall(r"(NaN|-?\d+): (.*?)(?=(?:; |, )(?:NaN|-?\d+): |$)", summary_meaning(key)[1]))
    meaning = said.get("NaN" if math.isnan(value) else f"{value:.0f}" if value == round(value) else "")
    if meaning:  # NaN: the meaning alone ("never locked in the run")
        return markdown(meaning) if math.isnan(value) else f"{cell}: {markdown(meaning)}"
    return cell


def headline(results: Path) -> str:
    """What the runs' figure's title says of the run (each part's few words: when the clutch locks, its heat, the
    load's travel), or a sweep's extent."""
    from hoistsim.display import headline as parts_headline
    from hoistsim.figures.read_back import prepared
    from hoistsim.results.reading import read_runs, read_summary, read_summary_units, read_swept_keys
    from hoistsim.results.report import column_cells

    swept = read_swept_keys(results)
    if swept:
        values = [float(row[swept[0]]) for row in read_summary(results)]
        least, most = column_cells([min(values), max(values)])
        unit = read_summary_units(results).get(swept[0], "")
        return f"{len(values)} runs, {swept[0]} from {least} to {most} {unit}".rstrip()
    (run,) = read_runs(results, columns={"time"})
    prepared(run)
    said = parts_headline({**run["attrs"], "events": run["events"]})
    return "; ".join(said) or f"energy residual {float(run['attrs']['energy_relative_residual']):.1e}"


# ------------------------------------------------------------------------------------------ against Dymola
def compare(scene: Scene):
    """The example run again (its solver compiled: loaded) and held to Dymola's trajectories as the tests hold
    it: (its comparison, the reference table, the run, our comparison signals, each one's worst deviation)."""
    from hoistsim import load_scenario, simulate
    from hoistsim.references.dymola import deviations, read_reference
    from hoistsim.references.modelica_signals import COMPARISONS

    comparison = COMPARISONS[scene.example]
    table = read_reference(REFERENCES, scene.example)
    run = simulate(load_scenario(scene.path))
    ours = comparison.signals(run)
    return comparison, table, run, ours, deviations(run.time, table, ours, comparison.until)


def dymola_figure(title: str, comparison, table: dict, time, ours: dict, worst: dict, target: Path) -> None:
    """Each comparison signal a panel: Dymola's trajectory thick and light, hoistsim's over it thin, dark and
    dashed; the time past the comparison's end shaded."""
    plt = pyplot()
    columns = 1 if len(ours) <= 3 else 2
    rows = math.ceil(len(ours) / columns)
    fig, axes = plt.subplots(rows, columns, sharex=True, squeeze=False, figsize=(10, 0.9 + 1.9 * rows),
                             layout="constrained")
    for ax, (signal, series) in zip(axes.flat, ours.items()):
        ax.plot(table["time"], table[signal], **DYMOLA)
        ax.plot(time, series, **HOISTSIM)
        unit = UNITS.get(signal.rsplit(".", 1)[-1])
        named = f"{signal} [{unit}]" if unit else signal
        ax.set_title(f"{named}: worst {worst[signal]:.1e} of its range", fontsize=9, loc="left")
        ax.grid(alpha=0.3)
        if np.isfinite(comparison.until):
            ax.axvspan(comparison.until, table["time"][-1], color="0.85", zorder=0, label="not compared")
    for ax in axes.flat[len(ours):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
        ax.xaxis.set_tick_params(labelbottom=True)
    axes[0][0].legend(fontsize=8, loc="best")
    fig.suptitle(title, fontsize=10, x=0.01, horizontalalignment="left")
    save_png(fig, target)
    plt.close(fig)


def dymola_section(scene: Scene, name: str) -> tuple[list[str], str]:
    """The page's comparison with Dymola, and the index's few words of it."""
    comparison, table, run, ours, worst = compare(scene)
    signal = max(worst, key=worst.get)
    title = f"{name}: hoistsim (dashed) over Dymola's trajectories; worst {worst[signal]:.1e} of its range, {signal}"
    dymola_figure(title, comparison, table, run.time, ours, worst, GALLERY / f"{scene.slug}_dymola.png")
    source = next(REFERENCES.glob(f"{scene.example}.csv*")).relative_to(ROOT).as_posix()
    lines = ["## Against Dymola", "",
             f"Dymola's published trajectories of the example (`{source}`, from modelica/MAP-LIB_ReferenceResults), "
             "each comparison signal's worst deviation taken at every reference row more than 1 ms from one of its "
             "events, as a fraction of the signal's range: the measure the tests hold the example to.", "",
             f"Worst deviation: **{worst[signal]:.1e}** of its range, `{signal}`; the tests' tolerance: "
             f"**{comparison.tolerance:.0e}**.", ""]
    if np.isfinite(comparison.until):
        lines += [f"Compared until {comparison.until:g} s (shaded after): {markdown(comparison.why_until)}.", ""]
    lines += [f"![{markdown(name)}: hoistsim's trajectories over Dymola's]({scene.slug}_dymola.png)", "",
              "| signal | worst deviation, of its range |", "|---|---:|"]
    lines += [f"| `{s}` | {value:.1e} |" for s, value in worst.items()]
    return lines, f"worst {worst[signal]:.1e} of range vs Dymola ({signal})"


# ------------------------------------------------------------------------------------------------ the pages
def write_text(path: Path, text: str) -> None:
    from hoistsim.results.atomic import atomic_path

    with atomic_path(path) as partial:
        partial.write_text(text, encoding="utf-8")


def make_page(scene: Scene, work: Path) -> str:
    """Run the scene, draw its figures and write its page; returns its index row."""
    name, said = about(scene.path)
    results = work / f"{scene.slug}.h5"
    hoistsim_command("run", str(scene.path), "-o", str(results))
    suffixes = plot_figures(results, scene.slug)
    lines = [f"# {markdown(name)}", "", markdown(" ".join(said[:2])), "", "```sh",
             f"hoistsim run {scene.scenario} -o {scene.slug}.h5", f"hoistsim plot {scene.slug}.h5 -o {scene.slug}.png",
             "```", ""]
    for suffix in suffixes:
        lines += [f"![{markdown(name)}: {CAPTIONS[suffix]}]({scene.slug}{suffix}.png)", ""]
    lines += ["## What the runs say" if "_summary" in suffixes else "## What the run says", ""]
    lines += summary_table(results) + [""]
    said_of_it = headline(results)
    if scene.example:
        compared, said_of_it = dymola_section(scene, name)
        lines += compared + ["", f"The comparison drawn again: `python docs/gallery.py --only {scene.slug}`.", ""]
    elif scene.group != "hoist":
        lines += ["The repository keeps no Dymola trajectories of this example: it is not drawn over them.", ""]
    write_text(GALLERY / f"{scene.slug}.md", "\n".join(lines))
    return f"| [{markdown(name)}]({scene.slug}.md) | {markdown(gist(said))} | {markdown(said_of_it)} |"


def write_index(all_scenes: list[Scene], rows: dict[str, str]) -> None:
    """docs/gallery/index.md: a table of the pages, a group each; rows not made now are kept as they were."""
    index = GALLERY / "index.md"
    old = index.read_text(encoding="utf-8").splitlines() if index.exists() else []
    rows = {**{found.group(1): line for line in old if (found := re.search(r"\]\(([^)]+)\.md\)", line))}, **rows}
    lines = ["# Gallery", "",
             "Every shipped scenario (`scenarios/`) and every Modelica example (`scenarios/modelica/`) run, each "
             "page with what the scene is, the commands that make it again, its figures and its summary; a Modelica "
             "example's page also draws hoistsim's trajectories over Dymola's and gives the worst deviation. "
             "`python docs/gallery.py` writes them all.", ""]
    for group, heading in GROUPS.items():
        members = [s for s in all_scenes if s.group == group and s.slug in rows]
        lines += [f"## {heading}", "", "| scene | what it shows | what the run says |", "|---|---|---|"]
        lines += [rows[s.slug] for s in members] + [""]
    write_text(index, "\n".join(lines))


def write_nav(all_scenes: list[Scene]) -> None:
    """The pages that exist, between mkdocs.yml's gallery markers (put at the end of its nav: when absent)."""
    text = MKDOCS.read_text(encoding="utf-8")
    lines = text.splitlines()
    if NAV_START not in text:
        start = lines.index("nav:")
        end = next((i for i in range(start + 1, len(lines)) if lines[i] and not lines[i].startswith(" ")), len(lines))
        lines[end:end] = ["  - Gallery:", f"      {NAV_START}", f"      {NAV_END}"]
    first, last = (next(i for i, line in enumerate(lines) if line.strip() == mark) for mark in (NAV_START, NAV_END))
    indent = lines[first][:len(lines[first]) - len(lines[first].lstrip())]
    entries = [f"{indent}- gallery/index.md"]
    for group, heading in GROUPS.items():
        pages = [s for s in all_scenes if s.group == group and (GALLERY / f"{s.slug}.md").exists()]
        entries += [f"{indent}- {json.dumps(heading)}:"] if pages else []
        entries += [f"{indent}    - {json.dumps(about(s.path)[0])}: gallery/{s.slug}.md" for s in pages]
    lines[first + 1:last] = entries
    write_text(MKDOCS, "\n".join(lines) + "\n")


def generate(only: list[str] | None = None, progress=print) -> None:
    every = scenes()
    chosen = [s for s in every if not only or s.slug in only]
    unknown = sorted(set(only or ()) - {s.slug for s in every})
    if unknown:
        raise KeyError(f"no page {', '.join(unknown)}: see --list")
    GALLERY.mkdir(exist_ok=True)
    rows, failed, started = {}, [], time.perf_counter()
    for scene in chosen:  # one scene failing costs its page alone: the others are made, the failure said at the end
        began = time.perf_counter()
        try:
            with tempfile.TemporaryDirectory() as work:
                rows[scene.slug] = make_page(scene, Path(work))
        except Exception as exc:
            failed.append(f"{scene.slug} ({type(exc).__name__}: {exc})")
        progress(f"{scene.slug}: {time.perf_counter() - began:.1f} s{' FAILED' if scene.slug not in rows else ''}")
    write_index(every, rows)
    write_nav(every)
    progress(f"{len(rows)} pages in {time.perf_counter() - started:.0f} s")
    if failed:
        raise RuntimeError("not made: " + "; ".join(failed))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="+", metavar="NAME", help="make only these pages (their slugs)")
    parser.add_argument("--list", action="store_true", help="list the pages and the scenario each runs")
    args = parser.parse_args()
    if args.list:
        print("\n".join(f"{scene.slug:44s} {scene.scenario}" for scene in scenes()))
        sys.exit(0)
    try:
        generate(args.only)
    except (KeyError, RuntimeError) as exc:
        print(f"gallery: {exc.args[0]}", file=sys.stderr)
        sys.exit(2)
