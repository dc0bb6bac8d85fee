"""Headline numbers of the validation studies (validation/*.py, each exposing run())."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

VALIDATION = Path(__file__).resolve().parents[1] / "validation"


def load(name):
    spec = importlib.util.spec_from_file_location(name, VALIDATION / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_chordwise_inertia_quick():
    """theory.md §3.6: the closed form misses ~ -omega^2 m L/3 on K_uu; the consistent axial
    mass closes the gap to the lumped-mass reference by more than 10x."""
    df = load("chordwise_inertia").run(quick=True)
    assert df["reference error"].max() < 1e-4            # the reference is converged
    assert df["K_uu err without"].abs().max() > 2e-2     # the effect is real (~4 % at 8 Hz)
    assert df["K_uu err with"].abs().max() < 1.5e-3
    assert df["matrix err with"].max() < 2e-3
    # where the chordwise effect stands above the static shallow-cable floor (~1e-4 here),
    # the correction removes most of it
    visible = df["K_uu err without"].abs() > 1e-3
    assert visible.sum() >= 4
    assert (df["K_uu err with"].abs()[visible] * 5 < df["K_uu err without"].abs()[visible]).all()


@pytest.mark.slow
def test_chordwise_inertia_full():
    mod = load("chordwise_inertia")
    s = mod.summary(mod.run())
    assert (s["max |K_uu err| with"] < 2.5e-3).all()
    assert (s["max |K_uu err| with"] * 5 < s["max |K_uu err| without"]).all()


def test_float64_matches_mpmath_quick():
    """Stable float64 forms against the 50-digit naive forms (validation/float64_vs_mpmath.py):
    <= 1e-9 away from poles (measured ~1e-13); near a pole the error is the pole's own
    conditioning, eps / (relative distance)."""
    df = load("float64_vs_mpmath").run(quick=True)
    assert len(df) > 1000
    assert df.loc[df["away"], "err_entry"].max() <= 1e-9
    near = df[df["near_pole"]]
    assert len(near) > 50
    assert (near["err_entry"] * near["pole_dist"] / np.finfo(float).eps).max() <= 10
