"""Results of a time-domain run (dynstiff.timedomain.response): TimeResponse and its
Spectrum as tables and figures, the recorded history read-only."""

import numpy as np
import pytest

from dynstiff.errors import InvalidParameterError
from dynstiff.lumped import simulate


def test_results_convert_and_plot(robot_model):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    m = robot_model(3)
    r = simulate(m, 0.5, 0.01, initial=[1e-4, 0, 0, 0, 0, 0], record_nodes=True)
    n_t = r.times.size
    assert n_t == 51 and r.pose.shape == (n_t, 6) and r.velocity.shape == (n_t, 6)
    assert [a.shape for a in r.nodes] == [(n_t, 4, 3)] * 3
    np.testing.assert_allclose(r.nodes[0][:, -1], r.pose[:, :3], atol=1e-12)  # B = P
    df = r.to_frame()
    assert len(df) == n_t and "z [m]" in df and "residual [J]" in df and "T_B2 [N]" in df
    sp = r.spectrum("x")
    assert len(sp.to_frame()) == sp.freq_hz.size
    with pytest.raises(InvalidParameterError, match="channel"):
        r.spectrum("q")
    for fig in (r.plot(), sp.plot()):
        assert fig.axes
        plt.close(fig)
    with pytest.raises(ValueError):
        r.pose[0, 0] = 1.0                                    # read-only history
