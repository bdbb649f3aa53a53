"""The work-precision study in its smoke mode: accuracy and cost (in steps, which are repeatable) are held.

The full study is a manual command (benchmarks/work_precision.py); this keeps a
regression in accuracy or in work per run from slipping in unseen.  Times are
printed by the study, never asserted here.
"""

from __future__ import annotations

import math

import pytest

from hoistsim.studies.work_precision import study


@pytest.fixture(scope="module")
def rows():
    return {(r.method, r.setting): r for r in study(smoke=True, progress=lambda _: None)}


def test_hybrid_accuracy_follows_the_tolerance(rows):
    loose, tight = rows[("tsit5", "1e-05")], rows[("tsit5", "1e-09")]
    assert loose.switches_match and tight.switches_match
    assert loose.speed_error < 1e-3 and tight.speed_error < 1e-7
    assert tight.switch_time_error < 1e-9 and tight.clutch_energy_error < 1e-9


def test_work_per_run_has_not_grown(rows):
    # steps measured when the study was written: 21 at rtol 1e-5, 107 at 1e-9 (Tsit5)
    assert rows[("tsit5", "1e-05")].steps <= 30
    assert rows[("tsit5", "1e-09")].steps <= 140


def test_scipy_peer_and_regularised_model_behave_as_documented(rows):
    rk45 = rows[("RK45", "1e-08")]
    assert rk45.switches_match and rk45.speed_error < 1e-6
    tanh = rows[("tanh tsit5", "width 0.1")]
    # the smoothing width, not the tolerance, sets the regularised model's error
    assert 0.01 < tanh.speed_error < 1.0 and math.isnan(tanh.switch_time_error)
    assert tanh.steps > 10 * rows[("tsit5", "1e-09")].steps
    assert rows[("closed form", "-")].speed_error == 0.0
