"""The gas torque of a single-cylinder four-stroke engine over its 720 deg cycle, as a ripple table.

An idealised indicator diagram (an air-standard dual cycle with polytropic
compression and expansion) times the slider-crank's lever arm:

- intake, 0-180 deg (TDC at 0): the cylinder at 0.95 bar;
- compression, 180-360 deg: p V^1.35 constant from 0.95 bar at BDC, compression ratio 16;
- combustion at TDC (360 deg): the pressure rises 1.6 times at constant volume, then stays
  constant while the volume grows by 1.3 (the cut-off ratio);
- expansion to BDC (540 deg): p V^1.30 constant;
- exhaust, 540-720 deg: 1.1 bar.

The gas force (p - 1 bar) A on the piston turns the crank with the torque
-F dx/dangle, x = r cos(a) + sqrt(l^2 - r^2 sin^2 a) (TDC at a = 0).  The
table is that torque less its mean over the cycle (the engine's
characteristic gives the mean), every 5 deg: a ripple that starts and ends at
the same value, as motor.ripple.table needs.  Run it to print the YAML rows:

    python scenarios/tools/engine_torque_table.py
"""

from __future__ import annotations

import math

import numpy as np

BORE, CRANK, ROD = 0.130, 0.075, 0.300  # m: a 2-litre stationary engine
COMPRESSION_RATIO, PRESSURE_RATIO, CUTOFF_RATIO = 16.0, 1.6, 1.3
N_COMPRESSION, N_EXPANSION = 1.35, 1.30
INTAKE, EXHAUST, AMBIENT = 0.95e5, 1.1e5, 1.0e5  # Pa
STEP = 5.0  # deg


def position(a):
    return CRANK * np.cos(a) + np.sqrt(ROD**2 - (CRANK * np.sin(a)) ** 2)


def lever(a):
    """dx/da (m/rad)."""
    s = np.sin(a)
    return -CRANK * s * (1 + CRANK * np.cos(a) / np.sqrt(ROD**2 - (CRANK * s) ** 2))


def pressure(angle_deg):
    """Cylinder pressure (Pa) at a crank angle of the 720 deg cycle."""
    area = math.pi * BORE**2 / 4
    swept = area * 2 * CRANK
    clearance = swept / (COMPRESSION_RATIO - 1)
    top = position(0.0)

    def volume(a):
        return clearance + area * (top - position(a))

    a = math.radians(angle_deg)
    bottom = volume(math.pi)
    if angle_deg < 180.0:
        return INTAKE
    if angle_deg < 360.0:
        return INTAKE * (bottom / volume(a)) ** N_COMPRESSION
    if angle_deg >= 540.0:
        return EXHAUST
    peak = INTAKE * (bottom / clearance) ** N_COMPRESSION * PRESSURE_RATIO
    if volume(a) <= CUTOFF_RATIO * clearance:
        return peak
    return peak * (CUTOFF_RATIO * clearance / volume(a)) ** N_EXPANSION


def table():
    angles = np.arange(0.0, 720.0 + STEP / 2, STEP)
    area = math.pi * BORE**2 / 4
    torque = np.array([-(pressure(d % 720.0 if d < 720.0 else 0.0) - AMBIENT) * area * lever(math.radians(d))
                       for d in angles])
    torque[-1] = torque[0]
    # the mean over the cycle (trapezoids, the integral of the table itself) goes to the characteristic
    mean = np.sum(0.5 * (torque[1:] + torque[:-1]) * np.diff(angles)) / 720.0
    return angles, torque - mean, mean


if __name__ == "__main__":
    angles, ripple, mean = table()
    print(f"# mean gas torque {mean:.1f} N*m (given by the characteristic); ripple {ripple.min():.0f} .. "
          f"{ripple.max():.0f} N*m")
    print("    table:")
    for a, m in zip(angles, ripple):
        print(f"      - [{a:g} deg, {m:.1f} N*m]")
