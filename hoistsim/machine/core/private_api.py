"""The private API of diffrax and equinox that the core uses: each name reached here, and nowhere else.

None of these is promised to stay where it is; an upgrade may move or drop
one.  Each is reached through :func:`reach`, which then fails at once, naming
the package, its version and the name that moved (tests/machine/test_private_api.py
reaches for every one, and checks that no other module of hoistsim uses a
private name of JAX, jaxlib, diffrax or equinox).  Following a move is a change
to this module alone.
"""

from __future__ import annotations

import importlib

REACHED: list[tuple[str, str, str]] = []  # (package, module, name) of every name reached, in order


def reach(package: str, module: str, name: str):
    """``module.name``, a private name of ``package``: an ImportError that names the package, its version
    and the name if an upgrade has moved it."""
    try:
        found = getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError):
        from importlib.metadata import PackageNotFoundError, version

        try:
            installed = f"{package} {version(package)}"
        except PackageNotFoundError:
            installed = f"{package} (not installed)"
        raise ImportError(f"{installed} has no {module}.{name}, which hoistsim uses (hoistsim/machine/core/"
                          f"private_api.py says why): install a version that has it, or follow it to where it "
                          f"moved") from None
    REACHED.append((package, module, name))
    return found


# diffrax: the marker an implicit solver's root finder holds in place of its rtol, atol and norm (its
# default): "the step-size controller's".  diffeqsolve puts the controller's there; the core steps the
# solver itself (stepping.py), so it does the same, finding the marker by identity.
use_stepsize_tol = reach("diffrax", "diffrax._root_finder", "use_stepsize_tol")

# equinox: a while loop whose carry holds buffers written in place.  Under vmap, lax.while_loop selects
# its whole carry lane by lane at each trip: a pass's output rows (the run's whole grid) would be copied
# at every step, and the row loop's block at every trip.
while_loop = reach("equinox", "equinox.internal", "while_loop")

# equinox: any() over the runs of a vmapped batch, outside the batching, so that the lax.cond around a
# crossing's location stays a branch (taken where some run of the batch crossed) instead of both
# branches computed and one selected for every run at every pass.
unvmap_any = reach("equinox", "equinox.internal", "unvmap_any")

# equinox: the float just before x (jnp.nextafter towards -inf; below 0, minus the smallest normal), the
# ulp diffrax counts in: a step that ends within END_ULPS of them short of a pass's end is taken to the end.
prevbefore = reach("equinox", "equinox.internal", "prevbefore")
