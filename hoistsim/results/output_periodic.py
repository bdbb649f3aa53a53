"""The periodic regime of a run in the HDF5 file: its periods (a row a period) and Tredgold's diagram."""

from __future__ import annotations

import h5py


def write_diagram(group: h5py.Group, diagram) -> None:
    """Tredgold's turning-moment diagram of the analysed regime, on the dimension ``angle``."""
    angle = group.create_dataset("angle", data=diagram.angle)
    angle.attrs["units"] = "rad"
    angle.attrs["long_name"] = "motor angle from the start of the first analysed period"
    angle.make_scale("angle")
    for name, values, units, text in (
            ("driving_torque", diagram.driving, "N*m", "driving torque M'_m at the motor shaft, at the mean speed"),
            ("resisting_torque", diagram.resisting, "N*m",
             "resisting torque M'_r at the motor shaft (inertia torques of reciprocating parts at the mean speed)"),
            ("energy", diagram.energy, "J", "integral of (M'_m - M'_r) over the angle from the period's start")):
        data = group.create_dataset(name, data=values)
        data.attrs["units"] = units
        data.attrs["long_name"] = text
        data.dims[0].attach_scale(angle)
    for key in ("mean_speed", "inertia", "energy_fluctuation", "min_speed_angle", "max_speed_angle",
                "work_residual", "irregularity"):
        group.attrs[key] = getattr(diagram, key)


def write_periods(group: h5py.Group, regime) -> None:
    """The periodic regime, one row per whole period: a dataset per column on the dimension ``period``."""
    from .periodic.regime import PERIOD_DESCRIPTIONS

    table = regime.table
    group.attrs["period"] = regime.period
    group.attrs["period_units"] = "rad"
    group.attrs["settling_tolerance"] = regime.tolerance
    group.attrs["settled"] = regime.settled
    group.attrs["message"] = regime.message
    index = group.create_dataset("period", data=table["period"])
    index.attrs["units"] = "1"
    index.attrs["long_name"] = PERIOD_DESCRIPTIONS["period"]
    index.make_scale("period")
    for name, values in table.items():
        if name == "period":
            continue
        data = group.create_dataset(name, data=values)
        data.attrs["units"] = regime.units[name]
        data.attrs["long_name"] = PERIOD_DESCRIPTIONS.get(name, f"{name.removesuffix('_per_period')} "
                                                                "gained in the period (J)")
        data.dims[0].attach_scale(index)
