"""A sweep's validated values kept as columns: each one as validated, in a few bytes."""

from __future__ import annotations

import pickle

from helpers import SWEEP_FILE

from hoistsim import load_scenario
from hoistsim.scenario.sweep_spec import held_at, with_swept_value
from hoistsim.scenario.swept_values import BATCH, SweptValues, collect


def test_a_force_range_is_kept_as_columns_and_gives_back_each_value_as_validated():
    count = 2 * BATCH + 3  # batches and a partial one
    s = load_scenario(SWEEP_FILE, sweeps=[f"clutch.engagement_force=3 kN:12 kN:{count}"])
    kept = s.provenance.swept["clutch.engagement_force"].validated
    assert isinstance(kept, SweptValues) and len(kept) == count
    assert kept.stacked.forces.shape == (count, 1) and kept.stacked.forces.nbytes == 8 * count
    values = s.provenance.swept["clutch.engagement_force"].values
    for i in (0, 1, BATCH - 1, BATCH, count // 2, count - 1, -1):
        alone = held_at(with_swept_value(s, "clutch.engagement_force", values[i]), "clutch.engagement_force")
        assert kept[i] == alone and type(kept[i]) is type(alone)
        assert type(kept[i].forces) is tuple and type(kept[i].forces[0]) is float
    assert pickle.loads(pickle.dumps(kept))[count // 2] == kept[count // 2]  # as sent to a cluster's workers


def test_values_of_one_shape_stack_and_others_stay_as_they_came():
    tables = [((0.0, 1.0), (2.0, float(k))) for k in range(BATCH + 5)]
    stacked = collect(tables)
    assert isinstance(stacked, SweptValues) and stacked[-1] == tables[-1] and stacked[3:5] == tables[3:5]
    teeth = collect([17, 90])  # whole numbers: stacked as floats, given back as they came
    assert teeth.stacked.dtype == float and list(teeth) == [17, 90] and type(teeth[0]) is int
    for values in ([1.0, 2.0, "slow"], [(1.0, 2.0), (3.0,)], [True, False], [None, 1.0],
                   [1.0] * BATCH + [2],  # a later batch of another type
                   tables + [((0.0, 1.0),)]):  # a later value of another shape
        kept = collect(iter(values))
        assert list(kept) == values and [type(v) for v in kept] == [type(v) for v in values]
