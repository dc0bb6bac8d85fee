"""Platform participation and receptance amplification (dynstiff/analyses/participation.py,
theory.md §12.1)."""

import dataclasses

import numpy as np
import pytest

import dynstiff as ds
from dynstiff.analyses.participation import (
    GLOBAL_SHARE,
    PLATFORM_SHARE_THRESHOLD,
    categories,
    platform_participation,
    receptance_amplification,
)
from dynstiff.errors import InvalidParameterError


def with_mass(robot, mass):
    return ds.Robot(robot.anchors, robot.attachments, robot.cables,
                    dataclasses.replace(robot.platform, mass=mass), g=robot.g,
                    tension_limits=robot.tension_limits)


@pytest.fixture(scope="module")
def cogiro50():
    sc = ds.load_scene("cogiro")
    eq = with_mass(sc.robot, 50.0).equilibrium(pose=sc.pose)
    m = ds.FrequencyModel(eq)
    return m, ds.modes(m, fmax_hz=3.0)


def test_shares_sum_and_categories(cogiro50):
    """Per-DOF shares are >= 0 and sum to the platform share 1 - cable fraction; the
    50 kg CoGiRo's 2.216 Hz mode holds 42 % of its energy in the platform: "mixed"."""
    m, mo = cogiro50
    p = platform_participation(m, mo)
    assert np.allclose(p.platform_share, 1 - mo.cable_energy_fraction, atol=1e-15)
    assert np.allclose(p.dof_share.sum(axis=1), p.platform_share, rtol=1e-12, atol=1e-15)
    assert np.all(p.dof_share >= 0)
    k = int(np.argmin(np.abs(p.freq_hz - 2.216)))
    assert abs(p.freq_hz[k] - 2.216) < 5e-4
    assert 0.40 < p.platform_share[k] < 0.44 and p.category[k] == "mixed"
    assert mo.kind[k] == "local"                   # the binary label missed it
    assert p.checked[k] and "global" in p.category
    df = p.to_frame()
    assert list(df["category"]) == list(p.category) and "share y [-]" in df


def test_categories_thresholds():
    assert categories([0.0, 0.0499, 0.05, 0.4999, 0.5, 1.0]) == (
        "local", "local", "mixed", "mixed", "global", "global")
    assert categories([0.05], threshold=0.01) == ("mixed",)
    assert PLATFORM_SHARE_THRESHOLD < GLOBAL_SHARE
    with pytest.raises(InvalidParameterError, match="threshold"):
        categories([0.2], threshold=0.6)


def test_receptance_amplification_of_a_massless_model():
    """Point mass on 3 CoGiRo cables (closed-form model) with the platform ratio applied as
    i 2 zeta K_s: every mode peaks at 1 / (2 zeta) times its own static value; for the
    direct receptance of the mode's DOF the ratio is >= that in a band around the mode and
    about 1 far below it."""
    from conftest import point_mass_robot
    eq = point_mass_robot().equilibrium(pose=[0.2, -0.1, 1.0, 0, 0, 0])
    m = ds.build_model(eq, "dsm", platform_damping_ratio=0.02)
    f = ds.eigenfrequencies(m.undamped(), 3)
    r, f_at, dof = receptance_amplification(m, (0.0, 0.3 * f[0]), f)
    assert 1.0 <= r < 1.11                          # 1 / (1 - 0.09) plus the cables
    r, f_at, dof = receptance_amplification(m, (0.9 * f[0], 1.1 * f[0]), f)
    assert r > 0.6 / (2 * 0.02) and abs(f_at / f[0] - 1) < 0.01
