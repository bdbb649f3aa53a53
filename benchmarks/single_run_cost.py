"""What one run costs: a step attempt and a pass of each shipped scene against a fused one-lane Dormand-Prince step.

For every single-run scenario (``scenarios/*.yaml`` without a ``sweep:``), every Modelica example
(``scenarios/modelica/*.yaml``), the drawing guide's drivetrain with every kind of part, and a stick-slip
chain (a drive turning a hub through a clutch, a spring from the hub to a block, the block dragged by a
clutch to the ground; 20 s), in this one process:

- warm run: ``hoistsim.simulate`` once compiled (or loaded from the cache), best and median of ``--repeats``;
  "loop" is the compiled call alone (the run's ``stats["wall_time"]``: the program and reading its output
  back), without building the plan and the results;
- step attempts (rejected) and passes of the run (``RunResult.stats``), and the issue's plain ratios: the loop
  over the attempts and over the passes;
- a split of the loop's time into a cost per step attempt and a cost per pass: the same scene at 4 tolerances
  (rtol and atol times 1, 1/10, 1/100, 1/1000, fewer where that would go below 1e-13; a new tolerance is a
  traced number, nothing compiles), and ``loop = a * attempts + b * passes`` fitted by least squares on the
  best time of each (what a run does once, the rows written from the kept steps after the loop, falls in b);
- the yardstick, measured first in the same process: an adaptive Dormand-Prince 5(4) written in plain JAX in
  one ``lax.while_loop`` (stages written out, the state one array, diffrax's PI coefficients), its event guard
  located by bisection on the step's cubic Hermite interpolant inside the loop (a ``lax.cond``), a restart
  after each event; each scene's loop cost per step attempt over it.

``--hlo`` counts the operations of each scene's compiled program (its post-optimisation HLO): the restart
loop's body (a pass) and the nested loops in it (the step loop, the crossing's search, the static check's
searches), and what a pass runs outside its step loop attributed, through each operation's stack of source
frames, to the part of ``loop._step`` it comes from (the decision and its static check, the extremes, the kink
anchors and orientations, the guards read at the start and the end, the crossings found together, ...).

``--profile`` counts the operations (XLA's thunks) one warm run of each scene executes, from a
``jax.profiler`` trace (the scene compiled afresh with every source frame on each operation): per step
attempt, and per pass outside the step loop by nested loop (the crossing's search, the static check's searches) and
by part of ``loop._step``.  ``--variants`` times each scene as it is against two changes patched in at run
time in a fresh process (cache off; no file changes): the crossing's search stopped at a bracket of 1e-9 s
instead of 1e-15 (what its last tries cost), and a table's knots not taken for bends of the rate (steps
not stopped short of them: what stopping short saves).

``--compile`` measures each scene's first run in a fresh process with the cache off (``HOISTSIM_CACHE_DIR``
empty): the first ``simulate`` less a warm one.  ``--chains 1,2,3,4,6,8`` measures the compile of a family of
chains with that many friction couplings (shafts J1..Jn, a clutch between neighbours, a brake from Jn to the
ground; a fresh process each, cache off, 180 s at most each): tracing and lowering, XLA's compile, and the
compiled program's operations by the source function they come from.

    python benchmarks/single_run_cost.py                       # every scene, repeats 3
    python benchmarks/single_run_cost.py --scenes Backlash compliant_hoist --repeats 5
    python benchmarks/single_run_cost.py --hlo --scenes exercise6_direct_start Backlash
    python benchmarks/single_run_cost.py --compile --scenes CoupledClutches
    python benchmarks/single_run_cost.py --profile --no-runs
    python benchmarks/single_run_cost.py --variants --no-runs --repeats 7 --scenes compliant_hoist "stick-slip chain"
    python benchmarks/single_run_cost.py --chains 1,2,3,4,6,8 --no-runs
"""

from __future__ import annotations

import argparse
import collections
import importlib.util
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# the page of the site that draws a drivetrain with every kind of part
EVERY_PART_PAGE = "docs/how-to/draw-a-drivetrain.md"
SCENARIOS = ROOT / "scenarios"

# a drive pulling a block through a clutch and a spring, the block dragged by a clutch to the ground: it sticks
# and slips again and again (the scene a test of a run's room uses too)
STICK_SLIP = (ROOT / "tests" / "data" / "stick_slip_chain.yaml").read_text()


def chain_yaml(n: int) -> str:
    """A chain with ``n`` friction couplings: shafts J1..Jn, clutch<i> between J<i> and J<i+1>, a brake from Jn
    to the ground; a torque in harmonics on J1, the clutches pressed at staggered times, the brake applied
    late: every coupling slips and locks in the run."""
    shafts = "\n".join(f"    J{i}: {{inertia: {1.0 + 0.1 * i} kg*m^2, speed: {10.0 - i} rad/s}}"
                       for i in range(1, n + 1))
    clutches = [f"    clutch{i}: {{between: [J{i}, J{i + 1}], static_friction: 0.55, kinetic_friction: 0.5, "
                f"effective_radius: 1 m, force: [[0 s, 0 N], [{0.05 * i:.2f} s, 0 N], [{0.05 * i:.2f} s, 20 N]]}}"
                for i in range(1, n)]
    clutches.append(f"    brake: {{between: [J{n}, ground], static_friction: 0.55, kinetic_friction: 0.5, "
                    "effective_radius: 1 m, force: [[0 s, 0 N], [0.5 s, 0 N], [0.5 s, 40 N]]}")
    return (f"name: chain{n}\ndrivetrain:\n  shafts:\n{shafts}\n  torques:\n"
            "    - {shaft: J1, torque: {harmonics: [{amplitude: 10 N*m, frequency: 5 Hz}]}}\n"
            "  clutches:\n" + "\n".join(clutches) + "\nsimulation:\n  duration: 1 s\n  output_interval: 0.1 s\n")


def every_part_drivetrain() -> str:
    """The drawing guide's drivetrain with every kind of part (its block that starts ``name: every-drawn-part``)."""
    text = (ROOT / EVERY_PART_PAGE).read_text()
    block = re.search(r"```yaml\n(name: every-drawn-part.*?)```", text, re.DOTALL)
    assert block, f"{EVERY_PART_PAGE} no longer has the every-part drivetrain's block"
    return block.group(1)


def scene_paths(folder: Path) -> dict[str, Path]:
    """Every single-run scene by name: the scenarios without a sweep, the Modelica examples, the stick-slip
    chain and the drawing guide's every-part drivetrain (written to ``folder``)."""
    out = {}
    for path in sorted(SCENARIOS.glob("*.yaml")):
        if not re.search(r"^sweep:", path.read_text(), re.MULTILINE):
            out[path.stem] = path
    for path in sorted((SCENARIOS / "modelica").glob("*.yaml")):
        out[f"modelica/{path.stem}"] = path
    for path in sorted((SCENARIOS / "modelica" / "translational").glob("*.yaml")):
        out[f"modelica/translational/{path.stem}"] = path
    chain = folder / "stick_slip_chain.yaml"
    chain.write_text(STICK_SLIP)
    out["stick-slip chain"] = chain
    every_part = folder / "every_part_drivetrain.yaml"
    every_part.write_text(every_part_drivetrain())
    out["every-part drivetrain"] = every_part
    return out


# ----------------------------------------------------------------------------------------- the yardstick

def yardstick(repeats: int) -> dict:
    """The fused one-lane Dormand-Prince 5(4): a driven, damped oscillator x'' + 0.1 x' + x = sin(1.3 t)
    (state [x, v]), rtol 1e-8, atol 1e-10, its guard x located by bisection (60 halvings on the step's cubic
    Hermite) each time it falls through zero, and the step restarted there; 400 s of it.  Returns the loop's
    wall time over its step attempts (us), the attempts, the rejected ones and the events."""
    import jax
    import jax.numpy as jnp

    a = [[], [1 / 5], [3 / 40, 9 / 40], [44 / 45, -56 / 15, 32 / 9],
         [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729],
         [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
         [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]]
    c = [0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0]
    b = a[6] + [0.0]
    b_hat = [5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100, 1 / 40]
    e = [bi - bh for bi, bh in zip(b, b_hat)]
    rtol, atol, t_end = 1e-8, 1e-10, 400.0

    def f(t, y):
        return jnp.stack([y[1], -0.1 * y[1] - y[0] + jnp.sin(1.3 * t)])

    def hermite(t0, h, y0, y1, f0, f1, t):
        s = (t - t0) / h
        return ((2 * s**3 - 3 * s**2 + 1) * y0 + (s**3 - 2 * s**2 + s) * h * f0 + (-2 * s**3 + 3 * s**2) * y1
                + (s**3 - s**2) * h * f1)

    def body(carry):
        t, h, y, f0, steps, rejected, events, old_ratio = carry
        h = jnp.minimum(h, t_end - t)
        k = [f0]
        for i in range(1, 7):
            k.append(f(t + c[i] * h, y + h * sum(aij * kj for aij, kj in zip(a[i], k) if aij != 0.0)))
        y1 = y + h * sum(bi * ki for bi, ki in zip(b, k) if bi != 0.0)
        err = h * sum(ei * ki for ei, ki in zip(e, k) if ei != 0.0)
        scale = atol + rtol * jnp.maximum(jnp.abs(y), jnp.abs(y1))
        ratio = jnp.sqrt(jnp.mean((err / scale) ** 2))
        keep = ratio <= 1.0
        # PI control (diffrax's PIDController(pcoeff=0.4, icoeff=0.3) form for order 5)
        factor = jnp.where(ratio == 0.0, 10.0, 0.9 * ratio ** (-0.7 / 5) * old_ratio ** (0.4 / 5))
        factor = jnp.clip(factor, 0.2, 10.0)
        crossed = keep & (y[0] > 0.0) & (y1[0] <= 0.0)

        def locate():
            def halve(i, bracket):
                lo, hi = bracket
                mid = 0.5 * (lo + hi)
                below = hermite(t, h, y, y1, f0, k[6], mid)[0] <= 0.0
                return jnp.where(below, lo, mid), jnp.where(below, mid, hi)
            _, hit = jax.lax.fori_loop(0, 60, halve, (t, t + h))
            return hit, hermite(t, h, y, y1, f0, k[6], hit)

        t_new, y_new = jax.lax.cond(crossed, locate, lambda: (t + h, y1))
        y_new = jnp.where(crossed, y_new.at[0].set(0.0), y_new)  # restart on the guard's zero
        t_new = jnp.where(keep, t_new, t)
        y_new = jnp.where(keep, y_new, y)
        f_new = jnp.where(keep, jnp.where(crossed, f(t_new, y_new), k[6]), f0)
        return (t_new, h * factor, y_new, f_new, steps + 1, rejected + ~keep, events + crossed,
                jnp.where(keep, jnp.maximum(ratio, 1e-4), old_ratio))

    @jax.jit
    def run(y0):
        start = (jnp.zeros(()), jnp.full((), 1e-3), y0, f(0.0, y0), jnp.array(0), jnp.array(0), jnp.array(0),
                 jnp.ones(()))
        return jax.lax.while_loop(lambda s: s[0] < t_end, body, start)

    y0 = jnp.asarray([1.0, 0.0])
    out = jax.block_until_ready(run(y0))
    times = []
    for _ in range(max(repeats, 5)):
        started = time.perf_counter()
        out = jax.block_until_ready(run(y0))
        times.append(time.perf_counter() - started)
    steps = int(out[4])
    return {"us": 1e6 * min(times) / steps, "us_median": 1e6 * statistics.median(times) / steps, "steps": steps,
            "rejected": int(out[5]), "events": int(out[6])}


# ------------------------------------------------------------------------------------------- the runs

def timed_runs(path: Path, repeats: int, overrides=()) -> dict:
    from hoistsim import load_scenario, simulate

    scenario = load_scenario(path, overrides=list(overrides))
    result = simulate(scenario)  # compiled (or loaded) first
    whole, loop = [], []
    for _ in range(repeats):
        started = time.perf_counter()
        result = simulate(scenario)
        whole.append(time.perf_counter() - started)
        loop.append(result.stats["wall_time"])
    stats = result.stats
    return {"whole": whole, "loop": loop, "steps": stats["steps"], "rejected": stats["rejected_steps"],
            "passes": stats["segments"], "switches": stats["switches"],
            "rtol": scenario.simulation.rtol, "atol": scenario.simulation.atol}


def split(path: Path, base: dict, repeats: int) -> dict | None:
    """loop = a * attempts + b * passes over the scene at up to 4 tolerances (the best of the loop's times;
    what a run does once, its rows written from the kept steps after the loop, counts in b)."""
    import numpy as np

    points = [(base["steps"], base["passes"], min(base["loop"]))]
    for factor in (0.1, 0.01, 0.001):
        rtol, atol = base["rtol"] * factor, base["atol"] * factor
        if rtol < 1e-13:
            break
        try:
            run = timed_runs(path, repeats, [f"simulation.rtol={rtol!r}", f"simulation.atol={atol!r}"])
        except Exception:  # noqa: BLE001  (a tolerance the run cannot meet)
            break
        points.append((run["steps"], run["passes"], min(run["loop"])))
    if len(points) < 2:
        return None
    x = np.asarray([[s, p] for s, p, _ in points], dtype=float)
    y = np.asarray([w for _, _, w in points])
    (a, b), *_ = np.linalg.lstsq(x, y, rcond=None)
    return {"step_us": 1e6 * a, "pass_us": 1e6 * b, "points": len(points),
            "attempts": [int(s) for s, _, _ in points], "passes": [int(p) for _, p, _ in points],
            "best_s": [w for _, _, w in points]}


# ------------------------------------------------------------------------------------- the program's HLO



def _opcode(line: str) -> str:
    """An instruction's opcode: the word after its result's type (a tuple's parentheses skipped)."""
    rest = line.split(" = ", 1)[1]
    if rest.startswith("("):
        depth = 0
        for i, char in enumerate(rest):
            depth += {"(": 1, ")": -1}.get(char, 0)
            if depth == 0:
                rest = rest[i + 1:]
                break
    else:
        rest = rest.split(" ", 1)[1] if " " in rest else ""
    found = re.match(r"\s*([a-z][\w\-]*)\(", rest)
    return found.group(1) if found else "?"


_CALLED = re.compile(r"(?:condition|body|calls|to_apply|true_computation|false_computation)=%([\w.\-]+)")
_BRANCHES = re.compile(r"branch_computations=\{([^}]*)\}")
_FRAME = re.compile(r"stack_frame_id=(\d+)")
_OP_NAME = re.compile(r'op_name="([^"]*)"')
TRIVIAL = {"parameter", "get-tuple-element", "tuple", "bitcast", "constant"}


class Hlo:
    """A compiled program's HLO text: its computations, their instructions and each one's source frames."""

    def __init__(self, text: str):
        self.computations, self.entry = {}, None
        section, current = None, None
        files, functions, locations, frames = {}, {}, {}, {}
        for line in text.splitlines():
            if line in ("FileNames", "FunctionNames", "FileLocations", "StackFrames"):
                section = line
                continue
            if section and re.match(r"^\d+ ", line):
                number, rest = line.split(" ", 1)
                if section == "FileNames":
                    files[int(number)] = rest.strip('"')
                elif section == "FunctionNames":
                    functions[int(number)] = rest.strip('"')
                elif section == "FileLocations":
                    fields = dict(re.findall(r"(\w+)=(\d+)", rest))
                    locations[int(number)] = (int(fields["file_name_id"]), int(fields["function_name_id"]),
                                              int(fields["line"]))
                elif section == "StackFrames":
                    fields = dict(re.findall(r"(\w+)=(\d+)", rest))
                    # (XLA prints each parent one above its id: 1 for none)
                    frames[int(number)] = (int(fields["file_location_id"]), int(fields.get("parent_frame_id", 1)) - 1)
                continue
            section = None if not line.startswith(" ") and not re.match(r"^\d+ ", line) else section
            header = re.match(r"^(ENTRY )?%([\w.\-]+) .*\{$", line)
            if header:
                current = header.group(2)
                self.computations[current] = []
                if header.group(1):
                    self.entry = current
                continue
            if line == "}":
                current = None
                continue
            if current is not None and " = " in line:
                self.computations[current].append(self._instruction(line))
        self.files, self.functions, self.locations, self.frames = files, functions, locations, frames

    @staticmethod
    def _instruction(line: str) -> dict:
        opcode = _opcode(line)
        called = _CALLED.findall(line)
        branches = _BRANCHES.search(line)
        if branches:
            called += [name.strip().lstrip("%") for name in branches.group(1).split(",")]
        frame = _FRAME.search(line)
        op_name = _OP_NAME.search(line)
        body = re.search(r"body=%([\w.\-]+)", line)
        return {"opcode": opcode, "called": called,
                "frame": int(frame.group(1)) if frame else None, "op_name": op_name.group(1) if op_name else "",
                "body": body.group(1) if body else None, "line": line}

    def stack(self, frame: int | None) -> list[tuple[str, str, int]]:
        """(file, function, line) of each frame, outermost first."""
        out, seen = [], set()
        while frame and frame in self.frames and frame not in seen:
            seen.add(frame)
            location, parent = self.frames[frame]
            file_id, function_id, line = self.locations[location]
            out.append((self.files.get(file_id, "?"), self.functions.get(function_id, "?"), line))
            frame = parent
        return out[::-1]

    def executed(self, name: str, skip_whiles=True) -> collections.Counter:
        """Operations a run of computation ``name`` executes, by opcode (a fusion is one; conditionals' branches
        are not entered; nested loops are counted as one ``while`` each, their bodies apart)."""
        counts = collections.Counter()
        for ins in self.computations.get(name, []):
            if ins["opcode"] in TRIVIAL:
                continue
            counts[ins["opcode"]] += 1
            if ins["opcode"] == "call":
                for called in ins["called"]:
                    counts.update(self.executed(called))
        return counts

    def walk(self, name: str, depth=0):
        """Every instruction run by a trip of ``name``: (instruction, where), where is 'here', 'branch' (inside
        a conditional) or the nested loop's body; fusions are not entered."""
        for ins in self.computations.get(name, []):
            yield ins, depth
            if ins["opcode"] in ("call", "conditional"):
                for called in ins["called"]:
                    yield from self.walk(called, depth + (ins["opcode"] == "conditional"))


def hoistsim_frames(stack) -> list[tuple[str, str]]:
    return [(Path(f).stem, fn) for f, fn, _ in stack if "/hoistsim/" in f]


# The program's parts, by the function an operation was traced in (the innermost of these on its stack).
PARTS = {"solve_response": "response", "response_table": "response", "response": "response",
         "settle": "static check", "_check": "static check", "_giving_way": "static check",
         "margins": "static check (margins)", "candidates_at_boundary": "static check",
         "keep_momentum": "keep_momentum", "guard_values": "guards", "vector_field": "vector field",
         "kink_anchors": "kink anchors", "orients": "orients", "rows_from_steps": "rows", "row_outputs": "rows",
         "_note": "extremes", "record": "event log", "apply_event": "apply_event", "_crossing": "crossing",
         "integrate_pass": "integrate_pass", "crossed_together": "crossed_together", "decide": "decide"}


def part_of(frames) -> str:
    for _, fn in reversed(frames):
        if fn.split(".")[0] in PARTS:
            return PARTS[fn.split(".")[0]]
    return f"{frames[-1][0]}.{frames[-1][1]}" if frames else "(no source)"


# What of loop._step a pass's operation comes from: the function _step (or _solve_segment) called.
ITEMS = {
    "decide": "decision at the pass's start (static check, events recorded)",
    "_note": "running extremes (_note, twice a pass)",
    "segment_from": "segment (next boundary)",
    "response": "the bodies' response for the modes",
    "kink_anchors": "kink anchors (a jvp)",
    "orients": "two-way observations' orientation (a jvp)",
    "guard_values": "guards read outside the step loop (start x2, end)",
    "integrate_pass": "integrate_pass outside its step loop (first step guess, init, crossing's step, locate)",
    "crossed_together": "crossings found together",
    "apply_event": "apply_event (rows, pending switch)",
    "guards": "guard bookkeeping",
}


def item_of(hstack, in_step_loop=False) -> str:
    names = [fn for _, fn in hstack]
    if "_step" not in names:
        return "(outside the pass)"
    deeper = names[names.index("_step") + 1:]
    if deeper[:1] == ["_solve_segment"]:
        deeper = deeper[1:]
    for fn in deeper:
        if fn in ITEMS:
            return fn
    return "_step itself" if not deeper else deeper[0]


def analyse(hlo: Hlo) -> dict:
    """The restart loop's body (a pass) and its nested loops: operations a trip runs, by opcode; the pass's
    operations outside its nested loops by the part of _step they come from."""
    every = [i for instructions in hlo.computations.values() for i in instructions if i["opcode"] == "while"]
    outer = [i for i in every if i["op_name"].endswith("restart_loop)/while")]
    if not outer:  # the restart loop's while, whatever its name: the loop with the largest body
        outer = sorted(every, key=lambda i: -len(hlo.computations.get(i["body"], [])))
    body = outer[0]["body"]
    loops, per_item, per_item_branch = [], collections.Counter(), collections.Counter()
    kinds = collections.Counter()
    for ins, depth in hlo.walk(body):
        if ins["opcode"] in TRIVIAL or ins["opcode"] in ("call",):
            continue
        stack = hoistsim_frames(hlo.stack(ins["frame"]))
        item = item_of(stack)
        if ins["opcode"] == "while":
            fn = stack[-1][1] if stack else "?"
            ops = hlo.executed(ins["body"])
            nested = sum(1 for i, _ in hlo.walk(ins["body"]) if i["opcode"] == "while")
            loops.append({"function": fn, "item": item, "ops": sum(ops.values()), "fusions": ops["fusion"],
                          "whiles": nested, "conditionals": ops["conditional"],
                          "dynamic": ops["dynamic-slice"] + ops["dynamic-update-slice"],
                          "custom_calls": ops["custom-call"], "in_branch": depth > 0})
        (per_item_branch if depth else per_item)[item] += 1
        if not depth:
            kinds[ins["opcode"]] += 1
    top = hlo.executed(body)
    return {"pass_ops": sum(top.values()), "pass_kinds": dict(kinds), "loops": loops, "items": dict(per_item),
            "items_in_branches": dict(per_item_branch), "program_ops": sum(len(v) for v in hlo.computations.values()),
            "computations": len(hlo.computations)}


PROGRAM_TEXT = """
import sys
import jax
jax.config.update("jax_traceback_in_locations_limit", -1)  # every source frame of each operation
from hoistsim import load_scenario
from hoistsim.machine.assemble import build_plan, log_rows, step_room
from hoistsim.machine.core.loop import compiled_run
scenario = load_scenario(sys.argv[1])
plan, _ = build_plan(scenario)
program = compiled_run(scenario.simulation.solver, log_rows(plan), step_room(plan))
open(sys.argv[2], "w").write(program.lower(plan).compile().as_text())
"""


PROFILE = """
import collections, glob, gzip, json, sys, tempfile
import jax
jax.config.update("jax_traceback_in_locations_limit", -1)  # every source frame of each operation
import hoistsim._jax
from hoistsim import load_scenario, simulate
scenario = load_scenario(sys.argv[1], overrides=sys.argv[4:])
simulate(scenario)
program = list(hoistsim._jax.programs._held.values())[-1][0]
open(sys.argv[2], "w").write(program.as_text())
folder = tempfile.mkdtemp()
jax.profiler.start_trace(folder, create_perfetto_trace=True)
result = simulate(scenario)
jax.profiler.stop_trace()
trace = json.load(gzip.open(sorted(glob.glob(folder + "/**/*.trace.json.gz", recursive=True))[-1]))
events = trace["traceEvents"] if isinstance(trace, dict) else trace
counts = collections.Counter(e["name"] for e in events if e.get("ph") == "X")
json.dump({"counts": counts, "stats": result.stats}, open(sys.argv[3], "w"))
"""


def contexts(hlo: Hlo, body: str) -> dict[str, str]:
    """Each computation a pass runs -> the nested loop it is in ('pass' for none): the step loop, the
    bisection, the static check's searches..."""
    out = {}

    def visit(name, context):
        if name in out:
            return
        out[name] = context
        for ins in hlo.computations.get(name, []):
            if ins["opcode"] == "while":
                frames = hoistsim_frames(hlo.stack(ins["frame"]))
                fn = frames[-1][1] if frames else "?"
                inner = "step loop" if fn == "integrate_pass" and len(hlo.computations.get(ins["body"], [])) > 40 \
                    else f"loop in {fn}"
                for called in ins["called"]:
                    visit(called, inner if context == "pass" else context)
            elif ins["opcode"] in ("call", "conditional"):
                for called in ins["called"]:
                    visit(called, context)
    visit(body, "pass")
    return out


def child(program: str, *args: str, timeout: float | None = None, check: bool = False) -> subprocess.CompletedProcess:
    """``program`` run in a fresh process with the cache off, importing hoistsim from the tree this process
    imports it from (``-P``: not from its working directory, so that ``PYTHONPATH`` can pair two trees)."""
    tree = Path(importlib.util.find_spec("hoistsim").origin).resolve().parents[1]
    env = dict(os.environ, HOISTSIM_CACHE_DIR="",
               PYTHONPATH=os.pathsep.join(filter(None, [str(tree), os.environ.get("PYTHONPATH")])))
    return subprocess.run([sys.executable, "-P", "-c", program, *args], capture_output=True, text=True, env=env,
                          cwd=ROOT, timeout=timeout, check=check)


# The profiler keeps some 500 000 events of a trace and drops the rest unsaid: a run that executes more is
# counted short (the engine at 1 s read 146 operations a step where it executes 253).
PROFILE_OVERRIDES = {"engine_hoist_flywheel": ["simulation.duration=0.3 s"]}


def profile_report(paths: dict[str, Path]) -> None:
    """Operations (thunks) each run executes, counted from a profile of one warm run, by where they are."""
    print("\noperations executed by one warm run (XLA's thunks, counted in a jax.profiler trace; fusions, "
          "loops' and conditionals' own thunks each one), per pass and per step attempt")
    for name, path in paths.items():
        with tempfile.TemporaryDirectory() as folder:
            text, counted = Path(folder) / "program.hlo", Path(folder) / "counts.json"
            shorter = PROFILE_OVERRIDES.get(name, [])
            if shorter:
                print(f"({name} profiled with {' '.join(shorter)}: a whole run's trace would be millions of events)")
            done = child(PROFILE, str(path), str(text), str(counted), *shorter)
            if done.returncode != 0:
                print(f"{name}: failed {done.stderr[-500:]}")
                continue
            hlo = Hlo(text.read_text())
            got = json.loads(counted.read_text())
        every = [i for instructions in hlo.computations.values() for i in instructions if i["opcode"] == "while"]
        outer = next(i for i in every if i["op_name"].endswith("restart_loop)/while"))
        where = contexts(hlo, outer["body"])
        instruction = {}
        for computation, instructions in hlo.computations.items():
            for ins in instructions:
                name_of = re.match(r"\s*(?:ROOT )?%([\w.\-]+) =", ins["line"])
                if name_of:
                    instruction[name_of.group(1)] = (computation, ins)
        by = collections.Counter()
        for thunk, count in got["counts"].items():
            if thunk not in instruction:
                continue
            computation, ins = instruction[thunk]
            context = where.get(computation)
            if context is None:
                by["(once a run)"] += count
                continue
            item = item_of(hoistsim_frames(hlo.stack(ins["frame"])))
            by[context if context != "pass" else f"pass: {item}"] += count
        stats = got["stats"]
        passes, steps = stats["segments"], stats["steps"]
        print(f"\n== {name}: {steps} step attempts, {passes} passes; thunks a step attempt "
              f"{by['step loop'] / max(steps, 1):.1f}; thunks a pass outside its step loop "
              f"{sum(v for k, v in by.items() if k not in ('step loop', '(once a run)')) / max(passes, 1):.0f}")
        for key, count in by.most_common():
            per = count / max(steps if key == "step loop" else passes, 1) if key != "(once a run)" else count
            unit = "a step attempt" if key == "step loop" else ("a run" if key == "(once a run)" else "a pass")
            print(f"   {count:9d}  {per:9.1f} {unit:<15} {key}")
        print("JSON " + json.dumps({"scene": name, "stats": stats, "thunks": dict(by)}))


def program_text(path: Path) -> str:
    """The compiled run's HLO as simulate first compiles it (a fresh process, the cache off, so that each
    operation keeps its whole stack of source frames)."""
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "program.hlo"
        child(PROGRAM_TEXT, str(path), str(out), check=True)
        return out.read_text()


def hlo_report(paths: dict[str, Path]) -> None:
    for name, path in paths.items():
        try:
            hlo = Hlo(program_text(path))
        except Exception as error:  # noqa: BLE001
            print(f"{name}: {type(error).__name__}: {error}")
            continue
        a = analyse(hlo)
        print(f"\n== {name}: program {a['program_ops']} instructions in {a['computations']} computations; "
              f"a pass's trip: {a['pass_ops']} operations outside its nested loops")
        print("   by kind: " + ", ".join(f"{k} {v}" for k, v in sorted(a["pass_kinds"].items(), key=lambda kv: -kv[1])))
        print("   by item (operations a pass runs outside its nested loops; + those in conditional branches):")
        for item, count in sorted(a["items"].items(), key=lambda kv: -kv[1]):
            extra = a["items_in_branches"].get(item, 0)
            print(f"     {count:6d} (+{extra:4d})  {item}: {ITEMS.get(item, '')}")
        for item, extra in a["items_in_branches"].items():
            if item not in a["items"]:
                print(f"     {0:6d} (+{extra:4d})  {item}: {ITEMS.get(item, '')}")
        print("   nested loops (ops a trip of its body runs: fusions, whiles inside, conditionals, dynamic slices):")
        for loop in a["loops"]:
            print(f"     {loop['function']:<20} [{loop['item']}]{' (in a branch)' if loop['in_branch'] else ''}: "
                  f"{loop['ops']} ops, {loop['fusions']} fusions, {loop['whiles']} whiles, "
                  f"{loop['conditionals']} conditionals, {loop['dynamic']} dynamic (update-)slices, "
                  f"{loop['custom_calls']} custom calls")
        print("JSON " + json.dumps({"scene": name, **a}))


# ------------------------------------------------------------------------------------ fresh processes

FIRST_RUN = """
import sys, time
started = time.perf_counter()
from hoistsim import load_scenario, simulate
scenario = load_scenario(sys.argv[1])
t0 = time.perf_counter(); simulate(scenario); first = time.perf_counter() - t0
t1 = time.perf_counter(); simulate(scenario); warm = time.perf_counter() - t1
print(t0 - started + first, first - warm)
"""

CHAIN_COMPILE = """
import collections, json, sys, time
sys.path.insert(0, sys.argv[2])
from single_run_cost import Hlo, hoistsim_frames, part_of
from hoistsim import load_scenario
from hoistsim.machine.assemble import build_plan, log_rows, step_room
from hoistsim.machine.core.loop import compiled_run
scenario = load_scenario(sys.argv[1])
plan, _ = build_plan(scenario)
program = compiled_run(scenario.simulation.solver, log_rows(plan), step_room(plan))
t0 = time.perf_counter(); lowered = program.lower(plan); t1 = time.perf_counter()
compiled = lowered.compile(); t2 = time.perf_counter()
hlo = Hlo(compiled.as_text())
by_function = collections.Counter()
for instructions in hlo.computations.values():
    for ins in instructions:
        by_function[part_of(hoistsim_frames(hlo.stack(ins["frame"])))] += 1
stablehlo = lowered.as_text().count(" = ")
print(json.dumps({"trace_s": t1 - t0, "xla_s": t2 - t1, "stablehlo_ops": stablehlo,
                  "hlo_ops": sum(by_function.values()), "by_function": by_function.most_common(40)}))
"""


VARIANT = """
import json, sys, time
variant = sys.argv[2]
from hoistsim.machine.core import crossing, loop
if variant == "crossing-1e-9":
    # the crossing's search stopped at a bracket of 1e-9 s instead of 1e-15: what its last tries cost
    crossing.CROSSING_ATOL = crossing.CROSSING_RTOL = 1e-9
if variant == "no-bends":
    # a table's knots not taken for bends of the rate: the steps run into them blindly, refused in turn
    loop._bends = lambda guards: None
from hoistsim import load_scenario, simulate
scenario = load_scenario(sys.argv[1])
result = simulate(scenario)
loops = []
for _ in range(int(sys.argv[3])):
    result = simulate(scenario)
    loops.append(result.stats["wall_time"])
print(json.dumps({"loops": loops, **{k: v for k, v in result.stats.items() if k != "wall_time"},
                  "lockup": {k: v for k, v in result.values.items() if isinstance(v, float)}}))
"""


def variant_runs(path: Path, variant: str, repeats: int) -> dict | None:
    """The scene's warm loop in a fresh process, the cache off, with ``variant`` patched into the loop."""
    done = child(VARIANT, str(path), variant, str(repeats))
    if done.returncode != 0:
        print(done.stderr[-1500:])
        return None
    return json.loads(done.stdout.strip().splitlines()[-1])


VARIANTS = ("as is", "crossing-1e-9", "no-bends")


def variants_report(paths: dict[str, Path], repeats: int, rounds: int = 1) -> None:
    """Each scene as it is, with a shorter crossing search, and with a table's knots not taken for bends (fresh
    processes, alternating)."""
    print("\nvariants, patched in a fresh process each (cache off): crossing-1e-9, the crossing's search stopped "
          "at 1e-9 s; no-bends, steps not stopped short of a table's knots; "
          f"the loop's best and median of {repeats} warm runs, {rounds} round(s)")
    for name, path in paths.items():
        got = {variant: [] for variant in VARIANTS}
        counts = {}
        for _ in range(rounds):
            for variant in got:
                out = variant_runs(path, variant, repeats)
                if out is None:
                    continue
                got[variant] += out["loops"]
                counts[variant] = (out["steps"], out["rejected_steps"], out["segments"], out["switches"])
        print(f"{name}:")
        for v, t in got.items():
            if t:
                print(f"    {v:<16} best {1e3 * min(t):9.2f} ms  median {1e3 * statistics.median(t):9.2f} ms  "
                      f"(attempts, rejected, passes, switches) {counts.get(v)}")
        print("JSON " + json.dumps({"scene": name, "variants": got, "counts": counts}))


def first_run(path: Path) -> tuple[float, float] | None:
    done = child(FIRST_RUN, str(path))
    if done.returncode != 0:
        return None
    whole, compile_s = (float(v) for v in done.stdout.split()[-2:])
    return whole, compile_s


def chain_compile(path: Path, limit: float) -> dict | None:
    try:
        done = child(CHAIN_COMPILE, str(path), str(Path(__file__).parent), timeout=limit)
    except subprocess.TimeoutExpired:
        return None
    if done.returncode != 0:
        print(done.stderr[-2000:])
        return None
    return json.loads(done.stdout.strip().splitlines()[-1])


def chains_report(counts: list[int], folder: Path, limit: float) -> None:
    print(f"\ncompile of a chain of n friction couplings (fresh process, cache off, {limit:.0f} s at most)")
    print(f"{'n':>3} {'trace+lower [s]':>16} {'XLA [s]':>8} {'StableHLO ops':>14} {'HLO instructions':>17}  "
          "largest sources of HLO instructions")
    for n in counts:
        path = folder / f"chain{n}.yaml"
        path.write_text(chain_yaml(n))
        started = time.perf_counter()
        out = chain_compile(path, limit)
        if out is None:
            print(f"{n:>3}  over {limit:.0f} s (or failed) after {time.perf_counter() - started:.0f} s")
            break
        top = ", ".join(f"{name} {count}" for name, count in out["by_function"][:6])
        print(f"{n:>3} {out['trace_s']:>16.2f} {out['xla_s']:>8.2f} {out['stablehlo_ops']:>14} "
              f"{out['hlo_ops']:>17}  {top}")
        print("JSON " + json.dumps({"n": n, **out}))


# -------------------------------------------------------------------------------------------- main

def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", nargs="*", default=None, help="names (a file's stem; modelica/NAME, "
                        "modelica/translational/NAME or NAME)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--no-split", action="store_true", help="leave out the fit over 4 tolerances")
    parser.add_argument("--no-runs", action="store_true", help="leave out the warm runs' table")
    parser.add_argument("--hlo", action="store_true", help="count the compiled program's operations")
    parser.add_argument("--compile", action="store_true", help="each scene's first run in a fresh process")
    parser.add_argument("--profile", action="store_true",
                        help="count the operations one warm run executes (a profile), per pass and step")
    parser.add_argument("--variants", action="store_true",
                        help="each scene as it is and with the decision taken only when due (fresh processes)")
    parser.add_argument("--rounds", type=int, default=1, help="alternating rounds of --variants")
    parser.add_argument("--chains", default="", help="compile of chains of these many couplings, e.g. 1,2,3,4,6,8")
    parser.add_argument("--chain-limit", type=float, default=180.0)
    options = parser.parse_args()
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; load average "
          f"{' '.join(f'{v:.2f}' for v in os.getloadavg())}; {os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        paths = scene_paths(folder)
        if options.scenes:
            wanted = set(options.scenes)
            paths = {k: v for k, v in paths.items() if k in wanted or k.split("/")[-1] in wanted or v.stem in wanted}
        if not options.no_runs:
            runs_report(paths, options)
        if options.hlo:
            hlo_report(paths)
        if options.compile:
            print("\nfirst run in a fresh process, cache off (HOISTSIM_CACHE_DIR empty)")
            print(f"{'scene':<40} {'imports, load and first simulate [s]':>36} {'compile: first less warm [s]':>29}")
            for name, path in paths.items():
                out = first_run(path)
                print(f"{name:<40} " + ("failed" if out is None else f"{out[0]:>36.2f} {out[1]:>29.2f}"))
        if options.profile:
            profile_report(paths)
        if options.variants:
            variants_report(paths, options.repeats, options.rounds)
        if options.chains:
            chains_report([int(n) for n in options.chains.split(",")], folder, options.chain_limit)


def runs_report(paths: dict[str, Path], options) -> None:
    from hoistsim.results.report import table

    stick = yardstick(options.repeats)
    print(f"yardstick, fused one-lane DP5(4) with a bisection event guard in one while_loop: "
          f"{stick['us']:.3f} us a step attempt (median {stick['us_median']:.3f}; {stick['steps']} attempts, "
          f"{stick['rejected']} rejected, {stick['events']} events)")
    rows = []
    for name, path in paths.items():
        try:
            run = timed_runs(path, options.repeats)
        except Exception as error:  # noqa: BLE001
            print(f"{name}: {type(error).__name__}: {str(error)[:200]}")
            continue
        loop = statistics.median(run["loop"])
        fit = None if options.no_split else split(path, run, options.repeats)
        steps, passes = run["steps"], run["passes"]
        row = [name, f"{1e3 * min(run['whole']):.1f}", f"{1e3 * statistics.median(run['whole']):.1f}",
               f"{1e3 * loop:.1f}", f"{steps} ({run['rejected']})", f"{100 * run['rejected'] / max(steps, 1):.0f}",
               str(passes), str(run["switches"]), f"{1e6 * loop / max(steps, 1):.1f}",
               f"{1e6 * loop / max(passes, 1):.0f}", f"{1e6 * loop / max(steps, 1) / stick['us']:.1f}"]
        if fit is not None:
            row += [f"{fit['step_us']:.2f}", f"{fit['pass_us']:.0f}", f"{fit['step_us'] / stick['us']:.1f}"]
        else:
            row += ["-"] * 3
        rows.append(row)
        print("JSON " + json.dumps({"scene": name, **run, "fit": fit}), flush=True)
    print(table(["scene", "warm best [ms]", "warm median [ms]", "loop median [ms]", "attempts (rejected)",
                 "rejected [%]", "passes", "switches", "loop/attempt [us]", "loop/pass [us]", "over DP5",
                 "fit: a step [us]", "fit: a pass [us]", "fit step over DP5"], rows))


if __name__ == "__main__":
    main()
