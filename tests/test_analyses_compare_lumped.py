"""Closed-form against lumped modes (dynstiff.analyses.compare_lumped.compare_modes): matched by
frequency and platform-shape MAC, unmatched rows kept, bad inputs named."""

import numpy as np
import pytest
from conftest import linearised, point_mass_robot

import dynstiff as ds
from dynstiff.errors import InvalidParameterError
from dynstiff.lumped import compare_modes


def test_compare_modes_keeps_unmatched_rows():
    rob = point_mass_robot()
    eq = rob.equilibrium(pose=[0.2, -0.1, 1.0])
    model = ds.FrequencyModel(eq)
    cf = ds.modes(model, 10)
    lm = ds.modes(linearised(rob, eq.unstretched_lengths, 40), 13)
    df = compare_modes(cf, lm)
    assert len(df) == 13 and df["closed-form freq [Hz]"].isna().sum() == 3
    matched = df.dropna(subset=["closed-form freq [Hz]"])
    assert list(matched["closed-form mode"]) == list(range(1, 11))
    # measured at N = 40: global -2e-4 ... -1.2e-4, local down to -1.1e-3 (6.2 Hz family)
    assert np.abs(matched["relative difference [-]"]).max() < 2e-3
    assert set(matched.loc[matched["kind (closed form)"] == "global", "matched by"]) == {"MAC"}
    with pytest.raises(InvalidParameterError, match="lumped_modes"):
        compare_modes(cf, lm.freq_hz)
    with pytest.raises(InvalidParameterError, match="mass_matrix"):
        compare_modes(cf, lm, np.eye(3))
