"""The results file's reference, ``docs/output.md``, written from the code that writes the files: what every file
holds read back from the file :func:`.output.write_runs` writes for a run of placeholders (``<series>``), what a
machine adds from the elements of every shipped scenario, built (never compiled) and built again with words for the
names they hold (their own ``<name>``, another part's ``<driving>``); the opening and the attributes' meanings are
fixed text here.  ``python -m hoistsim.results.file_reference [PATH]`` writes it (default ``docs/output.md``);
``--check`` writes nothing and exits 1 where the page is stale."""

from __future__ import annotations

import dataclasses
import html
import json
import re
import sys
import tempfile
import types
from pathlib import Path

import h5py
import numpy as np

from ..machine.core.element import MODE_NAMES
from ..machine.core.layout import SWITCH_KINDS, Layout
from ..machine.core.ledger import HEAT_OF
from ..machine.elements import REGISTRY, element_class
from ..scenario.loading import load_scenario
from ..scenario.lowering import lower, output_names
from ..scenario.reference import anchor, reference
from .chunk_records import SOLVER_COUNTS, instant_categories
from .output import FORMAT_VERSION, summary_units, write_runs
from .periodic.analysis import Periodic, loss_columns
from .periodic.regime import PERIOD_UNITS, Regime
from .periodic.tredgold import Diagram
from .run_result import RunResult
from .summary_meanings import summary_meaning

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "scenarios"
PATH = "docs/output.md"
COMMAND = "python -m hoistsim.results.file_reference"
WORD = re.compile(r"<[\w ]+>")  # a placeholder: <name>, <driving>, <swept key>

_OPENING = """\
# Results files (HDF5)

Every group, variable and attribute of a results file, written from the code that writes the files (`hoistsim/results/`,
`hoistsim/machine/elements/`) by `{command}`: do not edit it by hand (a test compares it with the code).

Format {version} (root attribute `format_version` = {version}): one layout for one run or a million, the runs stacked.

```text
/                   attrs format (hoistsim-runs), format_version ({version}), summary_only
/runs               a group that opens as one xarray Dataset, dims (run, time)
    run             (run)        0 … n-1 in sweep order; a dimension scale
    time            (time)  s    the output grid (every run's, merged when runs differ); a dimension scale
    motor_speed     (run, time) rad/s   drum_speed rad/s (up positive)   slip_speed rad/s (motor - pinion)
    clutch_torque   (run, time) N*m     positive when the motor drives the load
    clutch_locked   (run, time) 0/1     clutch_mode (0 locked, 1 slipping forwards, 2 backwards, 3 open)
    clutch_capacity, engagement_force, load_position, load_velocity, clutch_energy, motor_torque,
    motor_work, and each present part's own (brake_torque, bearing_A, …): NaN where a run has no row
    label           (run)        the run's swept values (or the scenario's name)
    <swept key>     (run)        each swept key's SI value by its dotted name (NaN for a table), with units
    lockup_time, slip_duration, slip_energy, peak_clutch_torque, peak_slip_speed, lowest_load_position,
    final speeds and position, load_lifted, lock/unlock counts, energy_residual, … (run): the summary;
                    with a periodic regime also period, settling_periods, mean/max/min_speed and their
                    angles, irregularity, irregularity_tredgold, energy_fluctuation(_tredgold), …
    energy_*, solver_* (run)     the energy ledger's terms; the solver's counts (steps, ...) and wall time
    attrs           name, parameters (the resolved scenario as JSON, SI), solver, rtol, atol,
                    swept_keys, summary_columns
/runs/events        every exact instant of every run, one row each, dim (event): run, time,
                    kind (lock, unlock, reversal, engage, disengage, brake_release, slip_peak,
                    load_lowest, speed_max, …, period), category (switch, scheduled, observation,
                    limit, cycle), element, torque_margin (the coupling's static capacity minus the torque it
                    would carry stuck, N*m), mode_after, and the value of every series just after it
/periodic/<i>/      run i's periodic regime: periods/ (a row a whole period: its number, start and end time,
                    start angle and speed, mean/max/min speed and their angles, irregularity, energy_fluctuation,
                    switches_per_period, clutch_energy_per_period, analysed 0/1; attrs period (rad), period_units,
                    settling_tolerance, settled, message) and turning_moment/ (Tredgold's diagram on `angle`)
/scenario           the scenario text as read (and any --set), with provenance: source, command, solver,
                    tolerances, date (created), python, hoistsim, jax, diffrax, numpy and h5py versions
```

A `--summary-only` file has the (run) variables of the summary and the swept keys, and no (run, time) ones: no
`time`, no `energy_*` or `solver_*`, no events and no periodic groups. Series are chunked along run and compressed.
Every dataset has a `units` attribute, and every variable of /runs and /runs/events a `long_name` (what it is, in
words); a summary whose 0 or NaN stands for something also has a `comment` saying what (`lockup_time`:
"{lockup}"). The exact instants are in the events table, not interleaved into the grid;
`hoistsim.results.reading.read_runs` merges them back per run.

```python
import hoistsim, xarray as xr
ds = hoistsim.open_results("forces.h5")                     # = xr.open_dataset(..., group="runs", engine="h5netcdf")
ds["slip_speed"].sel(run=3)                                   # one run
ds["lockup_time"].to_series()                                 # one value a run
events = xr.open_dataset("forces.h5", group="runs/events", engine="h5netcdf")
periods = xr.open_dataset("engine.h5", group="periodic/0/periods", engine="h5netcdf")
```

Files written in format 1 (a group per run and a /summary table) are still read by `plot` and `compare`."""

# What each attribute says, by its name (a package's version, <package>_version, says so by its name).
_ATTRIBUTES = {
    "format": "what the file is: `hoistsim-runs`", "name": "the scenario's name",
    "format_version": "its layout: 2 (1: a group per run and a /summary table, as written before)",
    "summary_only": "1 for a `--summary-only` file: the (run) variables of the summary alone",
    "parameters": "the resolved scenario as JSON, SI", "solver": "the solver (`simulation.solver`)",
    "rtol": "its relative tolerance (`simulation.rtol`)", "atol": "its absolute tolerance (`simulation.atol`)",
    "swept_keys": "the swept keys, dotted, as a JSON list", "created": "when the file was written (UTC, ISO 8601)",
    "summary_columns": "the summary's columns in order, as a JSON list: label, the swept keys, the summary values",
    "source": "the scenario file it was read from", "command": "the command line that wrote the file",
    "period": "the angle of the machine's cycle, a period of the motor shaft", "period_units": "`period`'s: rad",
    "settling_tolerance": "how closely successive periods agree once settled (relative to the mean speed)",
    "settled": "whether the regime settled within the run", "message": "why there is no analysis, where there is none",
    "mean_speed": "the speed the diagram is taken at (rad/s)", "inertia": "the machine's inertia at the motor (kg*m^2)",
    "energy_fluctuation": "the largest fluctuation of the energy in the period, Delta E_max (J)",
    "min_speed_angle": "where the energy is least, from the period's start (rad)",
    "max_speed_angle": "where the energy is greatest, from the period's start (rad)",
    "work_residual": "the energy at the period's end: zero where the mean torques balance (J)",
    "irregularity": "Tredgold's degree of irregularity, Delta E_max / (I mean_speed^2)",
    # every variable's
    "units": "the unit (`1`: a number, a flag, a mode or a text)", "long_name": "what it is, in words",
    "comment": "a summary's: what its 0 or NaN stand for",
}
_EACH_VARIABLE = ("units", "long_name", "comment")  # said once, for every variable
_UNITS_SAID = {"<swept key>": "the key's SI unit"}  # a placeholder's units, which the specimen cannot have


def _cell(text) -> str:
    """Text in a table's cell: its pipes kept from splitting the row, its <name> from being taken for a tag."""
    return str(text).replace("|", "\\|").replace("*", "\\*").replace("<", "&lt;").replace(">", "&gt;")


def _table(header: tuple, rows) -> list[str]:
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header), *("| " + " | ".join(r) + " |" for r in rows)]


def _link(cls: str) -> str:
    return f"[{cls}](#{anchor(cls)})"


def _mention(name: str) -> re.Pattern:
    """``name`` as a word of its own (``clutch`` in ``clutch_hub``, not in ``clutch1``)."""
    return re.compile(rf"(?<![A-Za-z0-9]){re.escape(name)}(?![A-Za-z0-9])")


def _held(element, name: str | None, known: set) -> tuple[object, dict]:
    """``element`` built again with a word for each name it holds: its own <name> (in a name made of it too:
    <name>_lower), another part's the field's holding it (<driving>); a part of a fixed name (the load) keeps it."""
    words, changes = {}, {}
    for field in dataclasses.fields(element):
        value = getattr(element, field.name)
        if not (field.init and isinstance(value, str) and value) or (name is None and field.name == "section"):
            continue
        if name and value != name and value not in known and _mention(name).search(value):
            changes[field.name] = _mention(name).sub("<name>", value, count=1)
        else:
            changes[field.name] = f"<{field.name}>"
            words[f"<{field.name}>"] = value
    held = dataclasses.replace(element, **changes)
    own = getattr(held, "part_name", None) or getattr(held, "name", None) or getattr(held, "section", "")
    if name and own in words:  # its own name, in the field it is known by
        held = dataclasses.replace(held, **{own[1:-1]: "<name>"})
        del words[own]
    return held, {**words, **({"<name>": name} if name else {})}


def _pairs(built, worded, words: dict):
    """(name as built, name in words) of each output, checked: the words filled in give the name as built."""
    for real, word in zip(list(built), list(worded), strict=True):
        if WORD.sub(lambda m: words.get(m.group(), m.group()), word) != real:
            raise ValueError(f"{word!r} does not fill in as {real!r}: the reference cannot name it")
        yield real, word


def _kinds_of(element) -> list[str]:
    """The event kinds an element names, gathered as :class:`.Layout` does (switches, crossings, observations)."""
    crossings = element.crossing_events
    return [*getattr(element, "switch_names", {}).values(), *(k for pair in crossings.values() for k in pair),
            *element.event_kinds, *element.cycles.values(),
            *(k for k in element.observation_kinds if k not in crossings)]


def machines():
    """Each shipped scenario's machine, built, not compiled: its layout, its files' names for its outputs, and its
    parts: each one's path in the registry (``place``), the hoist's section it stands for (``hoist``, "" for a
    drawn part), its element as built and built again with words (``held``), and what each word stands for."""
    for path in sorted(SCENARIOS.rglob("*.yaml")):
        scenario = load_scenario(path)
        lowered = lower(scenario, REGISTRY).parts
        elements = [element_class(part).from_spec(part.spec) for part in lowered]
        layout, parts = Layout(tuple(elements)), []
        for part, element in zip(lowered, elements):
            known = set(layout.shafts) | {getattr(e, "section", "") for e in elements if e is not element}
            held, words = _held(element, getattr(part.spec, "name", "") or None, known)
            parts.append(types.SimpleNamespace(place=part.path, hoist=part.section if part.template else "",
                                               element=element, held=held, words=words))
        yield layout, output_names(scenario), parts


class Catalogue:
    """What the shipped machines write: by part kind in words, and a hoist's under its template's names."""

    def __init__(self):
        classes = [c for entry in REGISTRY.values() for c in (entry.values() if isinstance(entry, dict) else [entry])]
        # in the machine's order; places and hoist ordered sets, series (name, units) -> the meanings met
        self.kinds = {c.__name__: types.SimpleNamespace(places={}, hoist={}, series={}, summaries={}, terms={})
                      for c in classes}
        self.hoist = types.SimpleNamespace(series={}, summaries={})  # name -> (units, meaning), name -> units
        self.run_summaries: dict = {}  # the periodic regime's and every run's: name -> units
        self.events: dict = {}  # kind -> (category, {what writes it})
        for layout, names, parts in machines():
            self._machine(layout, names, parts)

    def _machine(self, built, names: dict, parts) -> None:
        layout, hoist = built.named(names), any(part.hoist for part in parts)  # a hoist: its template's names
        units, own_units, own = summary_units(layout), summary_units(built), set()
        category = dict(zip(layout.event_kinds, instant_categories(layout, layout.event_kinds)))
        for core in (kind for kind in ("slip_peak", *SWITCH_KINDS) if kind in category):  # the core's own
            self.events.setdefault(core, (category[core], {}))[1]["every coupling"] = None
        for part in parts:
            cls, element, held = type(part.element).__name__, part.element, part.held
            kind = self.kinds[cls]
            kind.places[part.place] = None
            kind.hoist.update(dict.fromkeys([part.hoist] if part.hoist else []))
            for real, word in _pairs(element.columns, held.columns, part.words):
                kind.series.setdefault((word, element.columns[real][0]), []).append(held.columns[word][1])
            for real, word in _pairs(element.summaries, held.summaries, part.words):
                kind.summaries[word] = own_units[real]
                own.add(names.get(real, real))
            for real, word in _pairs(element.ledger_kinds, held.ledger_kinds, part.words):
                kind.terms.update(dict.fromkeys((word, names.get(real, real) if hoist else word),  # a hoist's too
                                                held.ledger_kinds[word]))
            for real, word in _pairs(_kinds_of(element), _kinds_of(held), part.words):
                for shown in dict.fromkeys((word, names.get(real, real) if hoist else word)):
                    self.events.setdefault(shown, (category[names.get(real, real)], {}))[1][cls] = None
        self._angles(layout, parts)
        if hoist:
            self.hoist.series.update(layout.columns())
            self.hoist.summaries.update({name: unit for name, unit in units.items() if name in own})
        losses = loss_columns(layout)  # each one's growth a period is a summary: <loss>_per_period
        for name, unit in ((n, u) for n, u in units.items() if n not in own):
            loss = next((loss for loss in losses if name.startswith(loss) and name != loss), "")
            self.run_summaries[name.replace(loss, "<loss>", 1) if loss else name] = unit

    def _angles(self, layout, parts) -> None:
        """The angles some part reads: each a series of the shaft (or mass) it is the angle of."""
        for shaft, (column, units, text) in layout.angle_columns.items():
            part = next(p for p in parts if shaft in p.element.bodies() or shaft in p.element.shafts())
            held = part.held.angle_columns()  # keyed <name>, or by the fixed name a part keeps (the load)
            said = held.get("<name>") or held.get(shaft) or tuple(
                _mention(shaft).sub("<name>", t, count=1) for t in (column, units, text))
            self.kinds[type(part.element).__name__].series.setdefault((said[0], units), []).append(  # a mass: always
                said[2] if shaft in part.element.angles() else f"{said[2]}; written where a part reads it")


def specimen() -> dict:
    """The file :func:`.output.write_runs` writes for one run of placeholders, read back: each group's and dataset's
    path (/periodic/<i> for run i's) -> (its dims, None for a group; its attributes but HDF5's own)."""
    loss = "<loss>_per_period"
    regime = Regime(period=1.0, table={name: np.zeros(1) for name in (*PERIOD_UNITS, loss)}, settled_at=None,
                    analysed=slice(0, 0), tolerance=0.0, units={**PERIOD_UNITS, loss: "J"})
    diagram = Diagram(*[np.zeros(2)] * 4, mean_speed=1.0, inertia=1.0, energy_fluctuation=0.0, min_speed_angle=0.0,
                      max_speed_angle=0.0, work_residual=0.0)
    text, grid = np.asarray(["<kind>"], dtype=object), np.array([0.0, 1.0])
    terms = {"kinetic_energy": "potential", "<work>": "work", "<loss>": "loss", "<stored>": "potential",
             "<heat>": HEAT_OF + "<loss>"}
    run = RunResult(
        scenario=load_scenario(SCENARIOS / "first_scenario.yaml"), label="", time=grid, grid=grid,
        series={"<series>": np.zeros(2)}, units={"<series>": "(the series')"}, events={"kind": text[:0]},
        ledger={name: (kind, 0.0, 0.0) for name, kind in terms.items()}, periodic=Periodic(regime, diagram),
        stats={**dict.fromkeys(SOLVER_COUNTS, 0), "wall_time": 0.0},
        instants={"time": np.array([0.5]), "kind": text, "element": text, "torque_margin": np.zeros(1),
                  "mode_after": text, "category": text})
    found = {}

    def note(name: str, item) -> None:
        dims = [(list(d.keys()) or [name.rsplit("/", 1)[-1]])[0] for d in item.dims] if hasattr(item, "dims") else None
        attrs = {k: item.attrs[k] for k in item.attrs if not (k.isupper() or k.startswith("_"))}
        found[re.sub(r"^/periodic/\d+", "/periodic/<i>", "/" + name)] = (dims, attrs)

    with tempfile.TemporaryDirectory() as folder:
        write_runs(Path(folder) / "specimen.h5", [run], parameters={"<swept key>": [0.0]})
        with h5py.File(Path(folder) / "specimen.h5", "r") as f:
            note("", f)
            f.visititems(note)
    return found


class Page:
    """The reference: the opening, then a section of a table or a few each, from the specimen and the catalogue."""

    def __init__(self):
        self.catalogue, self.entries = Catalogue(), specimen()
        self.headings = {html.unescape(line.lstrip("#").strip()) for line in reference().splitlines()
                         if line.startswith("#")}  # the scenario reference's, which the parts' places link to

    def text(self) -> str:
        lines = [_OPENING.format(command=COMMAND, version=FORMAT_VERSION, lockup=summary_meaning("lockup_time")[1])]
        for section in (self.attributes, self.run_variables, self.series, self.summaries, self.events):
            lines += ["", *section()]
        for group in ("/periodic/<i>/periods", "/periodic/<i>/turning_moment"):
            lines += ["", f"## {_cell(group)}", "", *self.variables(group)]
        return "\n".join(lines) + "\n"

    def attributes(self) -> list[str]:
        """Each group's (and the scenario's) attributes, and those every variable has."""
        def meaning(name: str) -> str:
            if name.endswith("_version") and name != "format_version":
                return f"the version of {name.removesuffix('_version')} that wrote the file"
            if name not in _ATTRIBUTES:
                raise KeyError(f"the results file's attribute {name!r} has no meaning: add it to _ATTRIBUTES")
            return _ATTRIBUTES[name]

        rows = [(f"`{where}`", f"`{name}`", _cell(meaning(name))) for where, (dims, attrs) in self.entries.items()
                for name in attrs if dims is None or name not in _EACH_VARIABLE]
        rows += [("every variable", f"`{name}`", _cell(meaning(name))) for name in _EACH_VARIABLE]
        return ["## Groups and attributes", "", *_table(("where", "attribute", "meaning"), rows)]

    def variables(self, group: str, leave=()) -> list[str]:
        """The variables right in a group: its dimension scales first, then by name."""
        found = {p.rsplit("/", 1)[1]: entry for p, entry in self.entries.items()
                 if entry[0] is not None and p.rsplit("/", 1)[0] == group and p.rsplit("/", 1)[1] not in leave}
        order = sorted(found, key=lambda name: (found[name][0] != [name], name.strip("<>")))
        return _table(("variable", "dims", "units", "meaning"), [
            (f"`{name}`", _cell(", ".join(found[name][0])), _cell(_UNITS_SAID.get(name, found[name][1]["units"])),
             _cell(found[name][1].get("long_name", ""))) for name in order])

    def run_variables(self) -> list[str]:
        attrs, heat = self.entries["/runs"][1], HEAT_OF + "another part's loss"  # a heat whose loss is not its own
        summary = set(json.loads(attrs["summary_columns"])) - {"label", *json.loads(attrs["swept_keys"])}
        terms = [(f"`{t}`", _cell(k if WORD.search(k) or not k.startswith(HEAT_OF) else heat), _link(cls))
                 for cls, kind in self.catalogue.kinds.items() for t, k in kind.terms.items()]
        return ["## Run variables", "", "Beside the series and the summary: the run, its swept values, the energy "
                "ledger's terms over the run and the solver's counts.", "",
                *self.variables("/runs", leave={"<series>", *summary}), "", "Each part's ledger terms, by kind (a "
                "work done on the machine, a loss, a stored energy, or where a loss's heat went):", "",
                *_table(("term", "kind", "part kind"), terms)]

    def place(self, path: str) -> str:
        """A part's place in a scenario, linked to the scenario reference's table of its keys (or its holder's)."""
        shown, listed = path.replace(".*", ".<name>"), path.replace(".*", "[]")
        shown = listed if listed in self.headings - {shown} else shown
        found = next((h for h in (shown.rsplit(".", cut)[0] for cut in range(shown.count(".") + 1))
                      if h in self.headings), "")
        return f"[`{shown}`](scenario.md#{anchor(found)})" if found else f"`{shown}`"

    def series(self) -> list[str]:
        hoist = [(f"`{n}`", _cell(u), _cell(t)) for n, (u, t) in self.catalogue.hoist.series.items()]
        lines = ["## Series", "", "On (run, time). A hoist's, under the names its template gives them:", "",
                 *_table(("series", "units", "meaning"), hoist), "", "### Series by part kind", "",
                 "What each kind of part adds, named after the part: `<name>` stands for its name (its key in the "
                 "scenario; a hoist's parts are named by its template: `motor`, `clutch`, `brake`, …), other words "
                 "in angle brackets for the shafts, masses or parts it names (`<driving>`, `<shaft>`). A series in "
                 "units `1` is a flag or a mode, stored as a small integer."]
        for cls, kind in ((c, k) for c, k in self.catalogue.kinds.items() if k.places):
            hoist = f"; in a hoist, by {', '.join(map(self.place, kind.hoist))}" if kind.hoist else ""
            # the meaning naming most: a spring's between two shafts, over one's on the ground
            rows = [(f"`{n}`", _cell(u), _cell(max(t, key=lambda m: len(WORD.findall(m)))))
                    for (n, u), t in kind.series.items()]
            lines += ["", f"#### {cls}", "", f"Given by {', '.join(map(self.place, kind.places))}{hoist}.", "",
                      *(_table(("series", "units", "meaning"), rows) if rows else ["No series of its own."])]
        absent = ", ".join(cls for cls, kind in self.catalogue.kinds.items() if not kind.places)
        return lines + ["", f"No shipped scenario has a part of these kinds, whose series are not listed: {absent}."]

    def summaries(self) -> list[str]:
        def row(name, units, *more):
            return (f"`{name}`", _cell(units), *map(_cell, summary_meaning(name)), *more)

        head, found = ("summary", "units", "meaning", "0 or NaN"), self.catalogue
        return ["## Summaries", "", "On (run): one value a run. A hoist's, under its template's names:", "",
                *_table(head, [row(n, u) for n, u in found.hoist.summaries.items()]), "",
                "### Every run's, and a periodic regime's", "",
                *_table(head, [row(n, u) for n, u in found.run_summaries.items()]), "", "### Summaries by part kind",
                "", *_table((*head, "part kind"), [row(n, u, _link(cls)) for cls, kind in found.kinds.items()
                                                   for n, u in kind.summaries.items()])]

    def events(self) -> list[str]:
        rows = [(f"`{kind}`", category, ", ".join(w if w == "every coupling" else _link(w) for w in writers))
                for kind, (category, writers) in self.catalogue.events.items()]
        return ["## Events", "", "`/runs/events`: every exact instant of every run, one row each.", "",
                *self.variables("/runs/events"), "", "`mode_after` is one of "
                f"{', '.join(f'`{mode}`' for mode in MODE_NAMES.values())}; empty for an element that is no coupling.",
                "", "### Kinds of instant", "",
                "A hoist's under its template's names too.", "", *_table(("kind", "category", "written by"), rows)]


def main(argv: list[str] | None = None) -> int:
    """Write the reference to PATH (default docs/output.md); with ``--check``, exit 1 where it is stale."""
    args = sys.argv[1:] if argv is None else argv
    target, text = Path(next((a for a in args if a != "--check"), ROOT / PATH)), Page().text()
    if "--check" not in args:
        target.write_text(text, encoding="utf-8")
        return 0
    stale = not target.exists() or target.read_text(encoding="utf-8") != text
    print(f"{target} is stale: run {COMMAND}" if stale else f"{target} is up to date")
    return int(stale)


if __name__ == "__main__":
    sys.exit(main())
