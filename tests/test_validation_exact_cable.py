"""Headline numbers of validation/exact_cable.py (quick grid: d/L = 1e-3, 1e-2, 0.1 at 0, 60
and 85 deg): the closed form, the lumped chain and the exact cable (theory.md §11) against
each other."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

PATH = Path(__file__).resolve().parents[1] / "validation" / "exact_cable.py"


@pytest.fixture(scope="module")
def quick():
    spec = importlib.util.spec_from_file_location("exact_cable", PATH)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod, mod.run(quick=True)


@pytest.mark.slow
def test_exact_agrees_with_richardson_chain(quick):
    """The exact cable against the independent lumped chain (N = 400, 800, Richardson,
    theory.md §7.2): <= 1e-6 on every cable, slack U's included (measured 3e-7 there,
    ~1e-9 on taut ones)."""
    _, df = quick
    assert len(df) == 9
    assert df["Richardson freq err"].max() < 1e-6
    assert df["Richardson static err"].max() < 1e-6
    taut = df["T_min/T_max"] > 0.1
    assert df.loc[taut, "Richardson freq err"].max() < 5e-8


@pytest.mark.slow
def test_closed_form_error_grows_as_sag_squared(quick):
    """Horizontal chord: the closed form's frequency error grows as (d/L)^2 (theory.md
    §3.6), 5e-6 at d/L = 1e-3; steeper chords are worse at equal sag."""
    _, df = quick
    flat = df[df["inclination [deg]"] == 0].sort_values("sag/chord")
    slope = np.polyfit(np.log(flat["sag/chord"]), np.log(flat["closed form freq err"]), 1)[0]
    assert 1.9 < slope < 2.1
    assert flat["closed form freq err"].iloc[0] < 1e-5
    err = df.pivot(index="sag/chord", columns="inclination [deg]", values="closed form freq err")
    assert (err[85.0] > 10 * err[0.0]).all()


@pytest.mark.slow
def test_closed_form_guard_bounds_its_frequency_error(quick):
    """closed_form_validity(...).error (theory.md §11.5) is at least the measured frequency
    error on every cable (measured ratio <= 0.35), and inf exactly on the slack ones."""
    _, df = quick
    guard = df["closed form guard"]
    slack = df["T_min/T_max"] < 0.1
    assert slack.sum() >= 1
    assert np.isinf(guard[slack]).all() and np.isfinite(guard[~slack]).all()
    assert (df.loc[~slack, "closed form freq err"] <= guard[~slack]).all()


@pytest.mark.slow
def test_lumped_chain_converges_as_n_minus_2(quick):
    """Lumped chain, first 10 frequencies: N = 10 -> 40 divides the error by ~16
    (theory.md §7.2) on the taut cables."""
    _, df = quick
    taut = df["T_min/T_max"] > 0.1
    ratio = df.loc[taut, "lumped N=10 freq err"] / df.loc[taut, "lumped N=40 freq err"]
    assert ratio.between(12.0, 17.0).all()


@pytest.mark.slow
def test_model_map(quick):
    """Where each model is enough: at 1e-2 the closed form serves a flat cable up to d/L =
    1e-2 but not an 85-degree one; the slack 85-degree cable needs the exact cable; at 1e-4
    nothing but the exact cable serves d/L >= 1e-2."""
    mod, df = quick
    loose, tight = mod.sufficient(df, 1e-2), mod.sufficient(df, 1e-4)
    assert "CF" in loose.loc[0.0, 0.01] and "CF" not in loose.loc[85.0, 0.01]
    assert loose.loc[85.0, 0.1] == "exact"
    assert (tight[[0.01, 0.1]] == "exact").all().all()
    assert tight.loc[0.0, 0.001] == "CF"
