"""A lossy mesh: its tooth load, the phases the wheel drives the pinion, its losses."""

from __future__ import annotations

from .panel import Display, Panel, Phase, SummaryPanel, Trace

PANELS = (Panel("mesh", "mesh [N*m]\n(tooth load at the drum)", 45, (Trace("tooth load", "mesh_torque"),),
                zero_line=True, height=0.8),)


def _headline(summary: dict) -> str | None:
    losses = [float(v) for key, v in summary.items() if key.endswith("mesh_loss_energy")]
    return f"mesh losses {sum(losses) / 1000:.2f} kJ" if losses else None


def _panels_for(run: dict) -> tuple:
    """The hoist's mesh panel, or for a drawn drivetrain one panel of every lossy stage's tooth load."""
    drawn = (run.get("parameters") or {}).get("drivetrain")
    if not drawn:
        return PANELS
    lossy = [name for name, stage in (drawn.get("gears") or {}).items()
             if any(stage.get(key) is not None for key in ("efficiency", "backdrive_efficiency", "loss_table"))]
    traces = tuple(Trace(name, f"{name}_mesh_torque") for name in lossy)
    return (Panel("meshes", "tooth load [N*m]\n(at each stage's output)", 45, traces, zero_line=True,
                  height=0.8),) if traces else ()


MESH_FRICTION = Display(
    panels=PANELS,
    shading=(Phase("wheel drives the pinion", "mesh_mode", 2, "#b2182b", hatch="..."),),
    summary_panels=(SummaryPanel("mesh_loss_energy", "mesh losses [kJ]", 45, scale=1e-3),),
    headline=_headline,
    panels_for=_panels_for,
    reads=lambda column: column.endswith("_mesh_torque"),
)
